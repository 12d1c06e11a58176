// expect: pass 64 128 255
// A Shadertoy shader ported to GLSL Sandbox: its `mainImage` opens in a
// macro (`#define Main void mainImage(...) {`, then `Main ... }`, as some
// Shadertoy authors write it), and a `main` of the port's own calls it.
precision mediump float;
uniform float time;
uniform vec2 resolution;
#define Main void mainImage(out vec4 colour, in vec2 at) { float x = at.x / resolution.x;
Main colour = vec4(0.25, 0.5, 1.0, 1.0) + 0.0 * x; }
void main(void) {
    mainImage(gl_FragColor, gl_FragCoord.xy);
}
