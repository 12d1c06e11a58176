// expect: pass
#ifdef GL_ES
precision highp float;
precision lowp sampler2D;
#endif
uniform float time;
uniform vec2 mouse;
uniform vec2 resolution;
void main() {
    vec2 p = gl_FragCoord.xy / resolution - mouse;
    gl_FragColor = vec4(0.5 + 0.5 * sin(time + p.xyx * 6.0), 1.0);
}
