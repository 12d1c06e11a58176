// expect: error 2:14: error: `resolution` is a vec2 in the GLSL (GLSL Sandbox style), not a vec3
uniform vec3 resolution;
void main() { gl_FragColor = vec4(gl_FragCoord.xy / resolution.xy, 0.0, 1.0); }
