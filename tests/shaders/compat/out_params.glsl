// expect: pass 128 64 191
// `out` parameters as shaders pass them: several whole variables, two
// components of a vector (a swizzle), an `out int`, from a function that
// returns a bool; and `fragColor` written in parts and read back.
bool split(float x, out float whole, out float part, out int count) {
    whole = floor(x);
    part = x - whole;
    count = int(whole);
    return part > 0.0;
}
void halves(out vec2 pair) { pair = vec2(0.5, 0.25); }
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    float whole, part;
    int count;
    vec3 v = vec3(0.0);
    halves(v.yz);
    bool fractional = split(2.75, whole, part, count);
    fragColor.rg = vec2(v.y, v.z);
    fragColor.b = fractional ? part : 0.0;
    fragColor.a = 1.0;
    fragColor.r *= float(count) * 0.5;
}
