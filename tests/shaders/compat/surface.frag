// expect: pass
precision mediump float;
uniform float time;
varying vec2 surfacePosition;
uniform vec2 surfaceSize;
void main() {
    vec2 p = surfacePosition * 8.0 / surfaceSize.y;
    float c = mod(floor(p.x) + floor(p.y), 2.0);
    gl_FragColor = vec4(vec3(c), 1.0);
}
