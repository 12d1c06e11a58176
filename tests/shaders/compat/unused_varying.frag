// expect: pass 128 128 64
// GLSL Sandbox files as people saved them: a `varying` declared and never
// read (WebGL links it), a uniform declared under a macro's name
// (`#define res resolution`), and words after `#endif`.
#ifdef GL_ES
precision mediump float;
#endif GL_ES
#define res resolution
uniform vec2 mouse, res;
uniform float time;
varying vec2 vUv;
void main(void) {
    gl_FragColor = vec4(res.x / 64.0, res.y / 36.0, 0.25, 1.0);
}
// A macro defined after a declaration does not rename it (`time` stays
// the clock, not a parameter nothing sets).
#define time t_later
