// expect: error 3:33: error: Expected Comma or Semicolon
void mainImage(out vec4 c, in vec2 p) {
    vec2 uv = p / iResolution.xy
    c = vec4(uv, 0.0, 1.0);
}
