// expect: pass 128 64 255
// Local names that hide a built-in function (`float cos = cos(a)`,
// `distance`), a Shadertoy shader's own `time` and `mouse` (GLSL Sandbox
// names), and a name declared again in an inner block.
vec2 turn(vec2 v, float a) {
    float cos = cos(a);
    float sin = sin(a);
    return vec2(cos * v.x - sin * v.y, sin * v.x + cos * v.y);
}
void mainImage(out vec4 c, in vec2 p) {
    float time = 0.5;
    vec2 mouse = iMouse.z > 0.0 ? iMouse.xy : vec2(0.25);
    {
        float time = 1.0;
        mouse *= time;
    }
    float distance = length(turn(vec2(0.25, 0.0), 0.0));
    c = vec4(time, mouse.x + distance - 0.25, 1.0, 1.0);
}
