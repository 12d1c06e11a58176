// expect: pass 0 0 0
// A uniform no convention sets and no annotation asks a control for
// (`u_speed`): it stays 0, so this draws black, and the sandbox warns
// about it. The annotated and initialised ones next to it do not warn.
#ifdef GL_ES
precision mediump float;
#endif

uniform vec2 u_resolution;
uniform float u_speed;
uniform float u_gain = 1.0;
uniform float u_bias; // @slider(0, 1)
uniform mat3 u_rotation;

void main() {
    vec2 st = gl_FragCoord.xy / u_resolution;
    vec3 rotated = u_rotation * vec3(st, 1.0);
    gl_FragColor = vec4(vec3(u_speed * u_gain) + u_bias + rotated, 1.0);
}
