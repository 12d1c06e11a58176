// expect: pass 128 64 191
// Constant expressions: global constants from other constants, a global
// variable from constants and `sqrt`, local constants from `sqrt` and from
// other local constants, a constant vector indexed in a function.
const float ROOT_TWO = 1.41421356;
const float HALF_ROOT = ROOT_TWO * 0.5;
const vec4 WEIGHTS = vec4(0.25, 0.5, 0.75, 1.0);
float unit = 1.0 / sqrt(ROOT_TWO * ROOT_TWO * 0.5);
float weight(int i) { return WEIGHTS[i]; }
void mainImage(out vec4 c, in vec2 p) {
    const float three = sqrt(9.0);
    const float k = three / 6.0;
    const vec3 shade = vec3(k, k * 0.5, three * 0.25);
    c = vec4(shade * unit * (HALF_ROOT * ROOT_TWO), weight(3));
}
