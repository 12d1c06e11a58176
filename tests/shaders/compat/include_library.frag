// expect: pass 51 102 153
// glslViewer's `#include "file"`: a library in a folder next to the shader
// that includes a file of its own folder (found relative to the library,
// not to this file), and a second include of the same file left out.
#ifdef GL_ES
precision mediump float;
#endif

#include "lib/palette.glsl"
#include "lib/shapes.glsl"

uniform vec2 u_resolution;

void main() {
    vec2 st = gl_FragCoord.xy / u_resolution;
    gl_FragColor = vec4(palette(inside_box(st)), 1.0);
}
