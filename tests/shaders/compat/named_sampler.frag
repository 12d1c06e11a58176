// expect: pass
// GLSL Sandbox textures of the shader's own names, read by a helper
// function (`buffer` is a keyword of GLSL 4.50, renamed where it is used),
// and `backbuffer` declared but never read.
precision highp float;
uniform float time;
uniform vec2 resolution;
uniform sampler2D memory;
uniform sampler2D buffer;
uniform sampler2D backbuffer;
vec4 recall(vec2 at) { return 0.5 * (texture2D(memory, at) + texture2D(buffer, at)); }
void main() {
    vec2 uv = gl_FragCoord.xy / resolution;
    gl_FragColor = vec4(recall(uv).rgb * 0.5 + recall(vec2(0.0)).a * 0.5, 1.0);
}
