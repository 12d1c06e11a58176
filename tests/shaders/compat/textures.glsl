// expect: pass
uniform sampler2D iChannel0;
uniform vec3 iChannelResolution[4];
vec4 blur(sampler2D image, vec2 uv, float radius) {
    vec2 texel = radius / iChannelResolution[0].xy;
    return 0.25 * (texture2D(image, uv + texel) + texture2D(image, uv - texel)
        + texture2DLod(image, uv + vec2(texel.x, -texel.y), 0.0)
        + texture(image, uv - vec2(texel.x, -texel.y), -100.0));
}
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = fragCoord / iResolution.xy;
    vec4 noise = texelFetch(iChannel1, ivec2(fragCoord) % textureSize(iChannel1, 0), 0);
    fragColor = mix(blur(iChannel0, uv, 2.0), noise, 0.5);
}
