// expect: error 2:21: error: uniform `sky`: a samplerCube cannot be a parameter here
uniform samplerCube sky;
void mainImage(out vec4 c, in vec2 p) {
    c = vec4(1.0);
}
