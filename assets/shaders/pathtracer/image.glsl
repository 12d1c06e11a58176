// Shows Buffer A's mean: clamped to [0, 1] and encoded with gamma 2.2.
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec3 mean = texelFetch(iChannel0, ivec2(fragCoord), 0).rgb;
    fragColor = vec4(pow(clamp(mean, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
