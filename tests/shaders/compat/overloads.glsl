// expect: pass 64 128 191
// One name, several functions: by parameter type, by parameter count (one
// with an `out` parameter), and names GLSL does not define (`saturate`,
// `noise`, `hash`).
float saturate(float x) { return clamp(x, 0.0, 1.0); }
vec2 saturate(vec2 x) { return clamp(x, 0.0, 1.0); }
vec3 saturate(vec3 x) { return clamp(x, 0.0, 1.0); }
float noise(float x) { return x * 0.5; }
float hash(vec2 p, out float spare) { spare = p.y; return p.x; }
float hash(vec2 p) { float unused; return hash(p, unused); }
void mainImage(out vec4 c, in vec2 p) {
    float spare;
    float r = hash(vec2(noise(0.5), 2.0), spare);
    vec2 g = saturate(vec2(0.5, -1.0));
    vec3 b = saturate(vec3(0.75 * spare) - 0.75);
    c = vec4(r + hash(vec2(0.0, 1.0)), g.x + g.y, b.z, 1.0);
}
