// expect: pass 128 64 191
// Statement forms: an assignment inside a declaration (`a, b = a = 0.0`),
// chained assignments, an empty statement, an empty block, a block as a
// statement, an if/else-if chain of single statements, and a ternary over
// several lines choosing vectors.
vec3 pick(float n) {
    return n < 1.0 ? vec3(0.5, 0.0, 0.0) :
           n < 2.0 ? vec3(0.0, 0.25, 0.0) :
                     vec3(0.0, 0.0, 0.75);
}
void mainImage(out vec4 c, in vec2 p) {
    float a, b = a = 0.0;;
    a = b = 1.0;
    vec3 sum = vec3(0.0);
    if (a > 2.0) {
    } else {
        sum += pick(0.0);
    }
    {
        float index = 1.0;
        sum += pick(index);
    }
         if (b < 0.0) sum += vec3(1.0);
    else if (b < 2.0) sum += pick(2.0);
    else sum = vec3(0.0);
    c = vec4(sum, a * b);
}
