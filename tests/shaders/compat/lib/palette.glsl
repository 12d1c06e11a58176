// Part of tests/shaders/compat/include_library.frag: includes a file of its
// own folder.
#include "shapes.glsl"

vec3 palette(float t) {
    return mix(vec3(0.0), vec3(0.2, 0.4, 0.6), t);
}
