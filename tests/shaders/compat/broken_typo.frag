// expect: error 6:15: error: Unknown function 'lenght'
uniform float time;
uniform vec2 resolution;
void main() {
    vec2 p = gl_FragCoord.xy / resolution;
    float r = lenght(p - vec2(0.5));
    gl_FragColor = vec4(r, p, 1.0);
}
