// expect: pass
#ifdef STANDALONE
uniform float time;
void main() {
    gl_FragColor = vec4(time);
#else
void mainImage(out vec4 c, in vec2 p) {
    c = vec4(p / iResolution.xy, 0.0, 1.0);
#endif
}
