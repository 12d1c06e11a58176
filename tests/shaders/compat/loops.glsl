// expect: pass 128 64 255
// Loop forms: a float counter with a bound that is not constant, a
// condition of two tests, the counter declared before the loop, nested
// loops without braces, `continue` and `break`, a start of `min(iFrame, 0)`
// (a zero the compiler cannot see), `++i`, a `const int` bound.
#define ZERO min(iFrame, 0)
const int STEPS = 4;
float count_to(float n) {
    float total = 0.0;
    for (float i = 0.0; i < n; i++) total += 1.0;
    return total;
}
void mainImage(out vec4 c, in vec2 p) {
    float t = 0.0;
    for (int i = ZERO; i < 70 && t < 0.5; ++i) t += 0.125;
    int k;
    for (k = 0; k < STEPS; k++) {
        if (k == 1) continue;
        if (k == 3) break;
    }
    float grid = 0.0;
    for (int j = 0; j < 2; j++)
    for (int i = 0; i < 2; i++)
        grid += 0.0625;
    c = vec4(t, grid, count_to(float(k)) / 3.0, 1.0);
}
