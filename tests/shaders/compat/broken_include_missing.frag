// expect: error 6:1: error: cannot read
// An `#include` of a file that is not there: an error at the `#include`.
uniform vec2 u_resolution;
uniform float u_time;

#include "lib/no_such_file.glsl"

void main() {
    gl_FragColor = vec4(u_time);
}
