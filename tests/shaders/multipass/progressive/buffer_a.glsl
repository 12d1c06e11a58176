// A progressive Monte Carlo estimate of pi / 4, per pixel: each frame one
// random point of the unit square, 1 if it falls inside the quarter disc;
// the average over the frames is kept in Buffer A, which reads its own
// previous frame in iChannel0. Alpha counts the frames.
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    uint state = hash(uint(fragCoord.x) + hash(uint(fragCoord.y) + hash(uint(iFrame))));
    float x = random(state);
    float y = random(state);
    float inside = x * x + y * y < 1.0 ? 1.0 : 0.0;
    vec4 previous = texelFetch(iChannel0, ivec2(fragCoord), 0);
    float n = float(iFrame);
    fragColor = vec4(mix(previous.rgb, vec3(inside), 1.0 / (n + 1.0)), n + 1.0);
}
