// expect: pass 64 128 255
// gl_FragColor written by a helper function, in parts (a swizzle), and read
// back; gl_FragCoord read by another helper.
uniform vec2 resolution;
float column() { return gl_FragCoord.x / resolution.x; }
void paint() {
    gl_FragColor = vec4(0.5);
    gl_FragColor.yz = vec2(0.5, 1.0) + step(2.0, column());
    gl_FragColor.x *= gl_FragColor.x;
}
void main() {
    paint();
    gl_FragColor.a = 1.0;
}
