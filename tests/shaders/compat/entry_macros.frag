// expect: pass 64 128 255
// Code golf: the declarations and the whole `main` inside macros used at
// the top level, and a Shadertoy-looking `mainImage` that a macro makes
// GLSL Sandbox's `main`.
#define init precision highp float; uniform float time; uniform vec2 resolution;
#define mainImage main
#define colour vec4(resolution.x / 128.0, resolution.y / 36.0, time, 1.0)
init
#define body void helper() { gl_FragColor = colour; }
body
void mainImage(void) { helper(); }
