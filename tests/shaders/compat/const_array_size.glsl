// expect: pass 191 64 255
// A local `const int` as an array size (naga knows only global constants
// as such), a larger value than the name is long, and a global one.
const int G = 2;
void mainImage(out vec4 c, in vec2 p) {
    const int N = 4;
    const int M = 16;
    float a[N];
    float b[M];
    float g[G];
    for (int i = 0; i < N; i++) { a[i] = float(i) / 4.0; }
    b[15] = 1.0;
    g[1] = 0.25;
    c = vec4(a[3], g[1], b[15], 1.0);
}
