// expect: pass 64 128 191
// Structs: a member of struct type, values built member by member, passed
// and returned by value, a member named like a built-in function.
struct Ray { vec3 origin; vec3 direction; };
struct Hit { Ray ray; float distance; };
Ray make_ray(vec3 origin, vec3 direction) {
    Ray r;
    r.origin = origin;
    r.direction = direction;
    return r;
}
vec3 point_at(Ray r, float t) { return r.origin + t * r.direction; }
Hit intersect(Ray r) {
    Hit h;
    h.ray = r;
    h.distance = 0.5;
    return h;
}
void mainImage(out vec4 c, in vec2 p) {
    Hit h = intersect(make_ray(vec3(0.25, 0.0, 0.5), vec3(0.0, 0.25, 0.5)));
    h.ray.origin.y += 0.375;
    c = vec4(point_at(h.ray, h.distance), 1.0);
}
