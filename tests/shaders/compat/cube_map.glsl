// expect: pass 255 255 0
// A Shadertoy shader that declares its channels a cube map and a volume,
// as exports for other players do, and reads them in helpers: the built-in
// cube map is the direction's colour, so +x is red 1, +y green 1, -z blue 0
// (docs/sandbox.md, "Cube maps and volumes").
uniform samplerCube iChannel0;
uniform sampler3D iChannel1;
float along(samplerCube sky, vec3 d, int k) { return textureLod(sky, d, 0.0)[k]; }
float density(sampler3D v, vec3 p) { return texture(v, p).r; }
void mainImage(out vec4 c, in vec2 p) {
    float v = step(0.0, density(iChannel1, vec3(p / iResolution.xy, 0.5)));
    c = vec4(along(iChannel0, vec3(1.0, 0.0, 0.0), 0),
             texture(iChannel0, vec3(0.0, 1.0, 0.0)).g,
             along(iChannel0, vec3(0.0, 0.0, -1.0), 2),
             1.0) * v;
}
