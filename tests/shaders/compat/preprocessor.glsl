// expect: pass 255 128 64
// The preprocessor in function bodies: `#if` with arithmetic, a loop opened
// in one branch and a plain block in the other, a loop whose header and
// closing brace are in two `#if`s, `#if 0` around a `return`, `#ifdef`
// and `#ifndef`, a `discard` that is never compiled.
#define QUALITY 0
#if QUALITY == 0
#define SAMPLES 1
#else
#define SAMPLES 3
#endif
#define SOFT
float level() {
#if 0
    return 0.0;
#endif
#ifdef SOFT
    return 0.5;
#else
    return 1.0;
#endif
}
float total() {
    float t = 0.0;
#if SAMPLES > 1
    for (int k = 0; k < SAMPLES; k++) {
#endif
        t += 1.0;
#if SAMPLES > 1
    }
#endif
#ifndef SOFT
    discard;
#endif
    return t;
}
void mainImage(out vec4 c, in vec2 p) {
    vec3 sum = vec3(0.0);
#if SAMPLES > 1
    for (int k = 0; k < SAMPLES; k++) {
        float w = float(k) / float(SAMPLES);
#else
    {
        float w = 0.0;
#endif
        sum += vec3(total(), level(), 0.25 + w);
    }
    c = vec4(sum / float(SAMPLES), 1.0);
}
