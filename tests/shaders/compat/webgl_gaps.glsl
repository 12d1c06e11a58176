// expect: pass
float shade(const in float x, float);
void mainImage(out vec4 c, in vec2 fragCoord) {
    vec2 p = fragCoord / iResolution.xy - 0.5;
    p *= mat2(cos(iTime + vec4(0.0, 11.0, 33.0, 0.0)));
    c = vec4(shade(p.x, 0.5), shade(p.y, 0.5), 0.5, 1.0);
}
float bias(float x) { return x * 0.5; }
float shade(const in float x, float k) { return bias(x) + k; }
