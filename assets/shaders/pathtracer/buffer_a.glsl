// One path per pixel per frame, jittered inside the pixel, added to the
// running mean of the frames before (its own previous frame in
// iChannel0). Alpha counts the samples; frame 0 starts afresh.
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    uint state = hash(uint(fragCoord.x) + hash(uint(fragCoord.y) + hash(uint(iFrame))));
    vec2 jitter = vec2(random(state), random(state)) - 0.5;
    vec2 p = (2.0 * (fragCoord + jitter) - iResolution.xy) / iResolution.y;
    float tan_half_fov = 0.36; // about 40 degrees vertically
    vec3 d = normalize(vec3(p * tan_half_fov, -1.0));
    vec3 color = radiance(vec3(0.0, 1.0, 3.9), d, state);

    vec4 previous = texelFetch(iChannel0, ivec2(fragCoord), 0);
    if (iFrame == 0) previous = vec4(0.0);
    float n = previous.a;
    fragColor = vec4(mix(previous.rgb, color, 1.0 / (n + 1.0)), n + 1.0);
}
