// expect: pass 128 64 191
// Matrix forms: mat2 of four numbers times and divided by a number, a
// vector times a matrix and a matrix times a vector, `*=` on a swizzle,
// mat3 of three columns, mat3 of one number (a diagonal) minus another, a
// column by index, mat4 of sixteen numbers times a vec4.
void mainImage(out vec4 c, in vec2 p) {
    mat2 m = 2.0 * mat2(0.0, 1.0, -1.0, 0.0) / 4.0;
    vec2 a = vec2(1.0, 0.0) * m;
    vec2 b = m * vec2(1.0, 0.0);
    vec3 v = vec3(0.0, 0.0, 1.0);
    v.xz *= mat2(0.0, 1.0, -1.0, 0.0);
    mat3 basis = mat3(vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), vec3(0.0, 0.0, 1.0));
    mat3 k = basis * (mat3(0.5) - mat3(0.25));
    mat4 f = mat4(0.5, 0.0, 0.0, 0.0,  0.0, 0.5, 0.0, 0.0,
                  0.0, 0.0, 0.5, 0.0,  0.0, 0.0, 0.0, 0.5);
    c = vec4(b.y - a.y - 0.5, k[1].y, (f * vec4(1.5)).z * v.x, 1.0);
}
