// expect: pass 255 128 64
// The WebGL rewrites inside `#define` bodies: `mat2(vec4)` with one
// argument, `texture2D`, a name that is a GLSL 4.50 keyword (`sample`),
// and `dot` of vectors in a global constant (left a call naga evaluates).
#define R2(v) mat2(v)
#define TEX(uv) texture2D(iChannel0, uv)
#define sample 0.5
const vec2 A = vec2(1.0, 2.0);
const float D = dot(A, A);
void mainImage(out vec4 c, in vec2 p) {
    vec2 q = R2(vec4(1.0, 0.0, 0.0, 1.0)) * vec2(0.25, 0.5);
    float t = TEX(q).a;
    c = vec4(D / 5.0, sample, q.x + 0.0 * t, 1.0);
}
