// Shows Buffer A: the running average, which tends to pi / 4 = 0.785 in
// every pixel as the frames add up.
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    fragColor = texture(iChannel0, fragCoord / iResolution.xy);
}
