// expect: pass
// A GLSL Sandbox texture of the shader's own name, read by a helper
// function, and `backbuffer` declared but never read.
precision highp float;
uniform float time;
uniform vec2 resolution;
uniform sampler2D memory;
uniform sampler2D backbuffer;
vec4 recall(vec2 at) { return texture2D(memory, at); }
void main() {
    vec2 uv = gl_FragCoord.xy / resolution;
    gl_FragColor = vec4(recall(uv).rgb * 0.5 + recall(vec2(0.0)).a * 0.5, 1.0);
}
