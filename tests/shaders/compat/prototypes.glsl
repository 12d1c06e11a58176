// expect: pass 64 128 255
// Prototypes with named parameters: functions called before their
// definitions (one after mainImage), one declared and defined but never
// called, statements after a `return`, and `return;` ending mainImage.
vec3 shade(vec2 p);
float unused(float x);
float quarter();
void mainImage(out vec4 c, in vec2 p) {
    c = vec4(shade(p), 1.0);
    return;
}
vec3 shade(vec2 p) { return vec3(quarter(), 2.0 * quarter(), 1.0); }
float never() {
    return 0.0;
    float after = 1.0;
    return after;
}
float quarter() { return 0.25 + never(); }
float unused(float x) { return x; }
