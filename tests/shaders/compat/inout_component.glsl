// expect: pass
void rotate(inout vec2 p, float a) { p = cos(a) * p + sin(a) * vec2(p.y, -p.x); }
void fold(inout float x) { x = abs(x); }
void mainImage(out vec4 c, in vec2 fragCoord) {
    vec3 p = vec3(fragCoord / iResolution.y - 0.5, 0.0);
    rotate(p.xy, iTime);
    fold(p.x);
    c = vec4(p * 2.0 + 0.5, 1.0);
}
