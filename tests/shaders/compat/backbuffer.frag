// expect: pass
#ifdef GL_ES
precision mediump float;
#endif
uniform float time;
uniform vec2 resolution;
uniform sampler2D backbuffer;
void main() {
    vec2 uv = gl_FragCoord.xy / resolution;
    vec4 previous = texture2D(backbuffer, uv + vec2(0.0, 1.0 / resolution.y));
    float spark = step(0.99, fract(sin(dot(uv + time, vec2(12.9898, 78.233))) * 43758.5453));
    gl_FragColor = vec4(previous.rgb * 0.98 + spark, 1.0);
}
