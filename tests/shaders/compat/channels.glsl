// expect: pass
// Channels read by helper functions: two channels, the size of the second
// (iChannelResolution[1]), textureLod, texture with a bias, coordinates
// outside 0..1 (the textures repeat), texture2D in a Shadertoy shader.
vec4 grain(vec2 uv) {
    return texture(iChannel1, floor(uv * 8.0) / iChannelResolution[1].xy);
}
float height(vec2 uv) { return textureLod(iChannel0, uv, 0.0).r; }
void mainImage(out vec4 c, in vec2 fragCoord) {
    vec2 uv = fragCoord / iResolution.xy;
    float h = height(uv * vec2(1.0, -1.0) - 3.0);
    vec3 base = texture(iChannel0, uv * 3.0, -16.0).rgb;
    c = vec4(mix(base, grain(uv).rgb, h) + texture2D(iChannel1, uv).rgb * 0.1, 1.0);
}
