// expect: pass 128 64 191
// Number forms: upper-case exponents (1E6, 1E-2), small and large
// exponents within the float range (1e-6, 1.0e-10, 1e20), a leading zero
// (03.900), no digits on one side of the point (.5, 2.).
void mainImage(out vec4 c, in vec2 p) {
    float one = 1E6 * 1E-2 * 1e-4;
    float tiny = 1e-6 + 1.0e-10;
    float huge = 1e20 / 1e20;
    float r = .5 * one * huge;
    float g = 03.900 / 15.6;
    float b = 2. * 0.375 + tiny;
    c = vec4(r, g, b, 1.0);
}
