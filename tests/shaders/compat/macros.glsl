// expect: pass 128 64 191
// Macros as shaders use them: function-like ones, one built on another,
// one that makes a matrix, another shading language's names mapped to
// GLSL's, and one that holds statements.
#define HALF 0.5
#define SAT(x) clamp(x, 0.0, 1.0)
#define RAMP(a, b, t) SAT(((t) - (a)) / ((b) - (a)))
#define SPIN(a) mat2(cos(a), sin(a), -sin(a), cos(a))
#define float2 vec2
#define lerp mix
#define BUMP(v) v += 0.25; v = SAT(v);
void mainImage(out vec4 c, in vec2 p) {
    float2 q = float2(1.0, 0.0) * SPIN(0.0);
    float r = RAMP(0.0, 2.0, q.x);
    float g = lerp(0.0, HALF, HALF);
    float b = 0.5;
    BUMP(b)
    c = vec4(r, g, b, 1.0);
}
