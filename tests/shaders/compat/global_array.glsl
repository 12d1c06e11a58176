// expect: pass 64 128 191
// A global array sized by a macro, filled in mainImage (a swizzle of each
// element) and read by a function.
#define COUNT 3
vec4 spots[COUNT];
vec3 total() {
    vec3 sum = vec3(0.0);
    for (int i = 0; i < COUNT; i++) sum += spots[i].xyz * spots[i].w;
    return sum;
}
void mainImage(out vec4 c, in vec2 p) {
    for (int i = 0; i < COUNT; i++) {
        spots[i].xyz = vec3(0.25 * float(i == 0), 0.5 * float(i == 1), 0.75 * float(i == 2));
        spots[i].w = 1.0;
    }
    c = vec4(total(), 1.0);
}
