// expect: pass
// GLSL Sandbox's `surfacePosition` shadowed: a local of that name made
// from the varying, then a macro of that name whose body uses it.
precision mediump float;
uniform float time;
varying vec2 surfacePosition;
float checker() {
    vec2 surfacePosition = surfacePosition * 8.0;
    return mod(floor(surfacePosition.x) + floor(surfacePosition.y), 2.0);
}
#define surfacePosition (surfacePosition * 0.5)
void main() {
    gl_FragColor = vec4(checker(), length(surfacePosition), 0.0, 1.0);
}
