// expect: pass 128 64 191
// Precision qualifiers on parameters, locals and a loop variable
// (`highp vec2 p`), which naga rejects in a parameter list.
float half_of(highp float x, in mediump float k) { return x * k; }
void mainImage(out vec4 c, in highp vec2 p) {
    lowp float s = half_of(1.0, 0.5);
    for (highp int i = 0; i < 1; i++) { s *= 1.0; }
    c = vec4(s, s * 0.5, s * 1.5, 1.0);
}
