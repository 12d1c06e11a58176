// expect: pass 128 64 191
// Built-in functions shaders call: tanh, round, exp2, log2, atan of two
// arguments, vector comparisons with all and any, mod of a vector by a
// number, smoothstep with vector edges, reflect, sign, step, and dFdx,
// dFdy and fwidth.
void mainImage(out vec4 c, in vec2 p) {
    float r = tanh(0.0) + round(0.4) + exp2(-1.0) * log2(2.0);
    float quarter = atan(1.0, 1.0) / 3.14159265;
    bool inside = all(lessThan(vec2(0.1), vec2(0.2)))
        && any(greaterThan(vec2(0.0, 1.0), vec2(0.5)))
        && all(greaterThanEqual(vec2(1.0), vec2(1.0)));
    vec3 m = mod(vec3(2.75), 1.0);
    vec3 s = smoothstep(vec3(0.0), vec3(1.0), vec3(0.5));
    vec3 bounce = reflect(vec3(0.0, -1.0, 0.0), vec3(0.0, 1.0, 0.0));
    float slope = fwidth(1.0) + dFdx(2.0) + dFdy(3.0);
    float g = inside ? quarter : 0.0;
    float b = m.z * sign(bounce.y) * step(0.5, s.x) + slope;
    c = vec4(r, g, b, 1.0);
}
