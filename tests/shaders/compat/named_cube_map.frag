// expect: pass 0 255 255
// GLSL Sandbox textures of the shader's own names that are a cube map and
// a volume: the built-in ones (docs/sandbox.md, "Cube maps and volumes");
// -x is red 0, +y green 1, +z blue 1.
precision highp float;
uniform vec2 resolution;
uniform samplerCube sky;
uniform sampler3D fog;
void main() {
    vec3 d = vec3(-1.0, 0.0, 0.0);
    float a = step(0.0, texture3D(fog, vec3(gl_FragCoord.xy / resolution, 0.25)).g);
    gl_FragColor = vec4(textureCube(sky, d).r, textureCube(sky, vec3(0.0, 1.0, 0.0)).g,
                        textureCube(sky, vec3(0.0, 0.0, 1.0)).b, 1.0) * a;
}
