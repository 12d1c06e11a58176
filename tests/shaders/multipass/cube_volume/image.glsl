// Samples the built-in cube map and noise volume where the test can
// compute what they hold (tests/sandbox_multipass.rs), at 64x49:
// rows 0..15 (from the bottom): the cube map in the direction of
// longitude 2 pi x / 64 and latitude 0.9 pi (y / 16 - 0.5) (pixel
// centres), with texture() in even columns and textureLod() in odd ones;
// rows 16..47: the volume's texel (x, y - 16, 0) by texelFetch() for
// x < 32, the centre of texel (x - 32, y - 16, 1) by texture() for the
// others; row 48: iChannelResolution[0] and [1] in pixels 0 and 1.
const float PI = 3.14159265;

vec3 direction(vec2 p) {
    float longitude = 2.0 * PI * p.x / 64.0;
    float latitude = 0.9 * PI * (p.y / 16.0 - 0.5);
    return vec3(cos(longitude) * cos(latitude), sin(latitude), sin(longitude) * cos(latitude));
}

void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    ivec2 at = ivec2(fragCoord);
    if (at.y < 16) {
        vec3 d = direction(fragCoord);
        fragColor = (at.x % 2 == 0) ? texture(iChannel0, d) : textureLod(iChannel0, d, 0.0);
    } else if (at.y < 48) {
        int y = at.y - 16;
        if (at.x < 32) {
            fragColor = texelFetch(iChannel1, ivec3(at.x, y, 0), 0);
        } else {
            fragColor = texture(iChannel1, (vec3(at.x - 32, y, 1) + 0.5) / 32.0);
        }
    } else if (at.x == 0) {
        fragColor = vec4(iChannelResolution[0].xyz, iChannelResolution[1].z);
    } else {
        fragColor = vec4(iChannelResolution[1].xyz, 0.0);
    }
}
