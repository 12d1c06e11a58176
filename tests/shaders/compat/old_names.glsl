// expect: pass
uniform vec3 iResolution;
uniform float iGlobalTime;
uniform float iChannelTime[4];
uniform vec4 iDate;
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = fragCoord / iResolution.xy;
    fragColor = vec4(uv, 0.5 + 0.5 * sin(iGlobalTime + iChannelTime[0] + iDate.w), 1.0);
}
void main(void) { mainImage(gl_FragColor, gl_FragCoord.xy); }
