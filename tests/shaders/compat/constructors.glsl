// expect: pass 255 64 128
// Constructors: integers in float vectors, bits of a loop counter (`>>`,
// `&`), `vec2(5 & 1, 5 >> 1)`, integers and a float mixed in one, and a
// number beside a vec2 in a vec3.
void mainImage(out vec4 c, in vec2 p) {
    vec3 corners = vec3(0.0);
    for (int i = 0; i < 4; i++) {
        corners += vec3(((i + 3) >> 1) & 1, (i >> 1) & 1, i & 1);
    }
    vec2 uv = vec2(5 & 1, 5 >> 1);
    vec3 mixed = vec3(0, 1, 0.5);
    vec3 joined = vec3(0.25, uv * 0.5);
    c = vec4(corners.x * 0.25 * uv.y * uv.x, mixed.y * joined.x, mixed.z * joined.z, 1.0);
}
