// mirror_cube.frag: in the spirit of the lecture's GLSL Sandbox example, a
// mirror cube spins over a checkered floor and reflects the floor, the sky and
// the coloured balls around it, and itself in the balls' shine. A mirror
// sends a ray on in one direction only, so one loop follows the ray from
// bounce to bounce and multiplies the reflectances up (no stack needed).
//
//   raysandbox shader assets/shaders/mirror_cube.frag
//
// The annotated uniforms are controls in the panel: one of each kind.

#ifdef GL_ES
precision highp float;
#endif

uniform float time;
uniform vec2 mouse;
uniform vec2 resolution;

uniform float spin = 0.5;          // @slider(0.0, 3.0, 0.05) turns of the cube, radians per second
uniform float size = 1.6;          // @slider(0.5, 2.4, 0.01) edge length of the cube
uniform int shape = 0;             // @select(cube, sphere, slab) what the mirror is
uniform vec3 tint = vec3(0.85, 0.9, 1.0); // @color the mirror's reflectance
uniform int bounces = 4;           // @slider(0, 8) reflections followed
uniform bool light_follows_mouse;  // @checkbox move the light with the mouse
uniform float haze = 0.002;        // @log(0.0001, 0.1) density of the haze

const float FAR = 1e30;
const float EPS = 1e-4;

// The mirror's rotation: about x and z by fixed angles, about y with time.
mat3 rotation() {
    float a = radians(25.0), b = time * spin + radians(40.0), c = radians(10.0);
    mat3 rx = mat3(1.0, 0.0, 0.0, 0.0, cos(a), sin(a), 0.0, -sin(a), cos(a));
    mat3 ry = mat3(cos(b), 0.0, -sin(b), 0.0, 1.0, 0.0, sin(b), 0.0, cos(b));
    mat3 rz = mat3(cos(c), sin(c), 0.0, -sin(c), cos(c), 0.0, 0.0, 0.0, 1.0);
    return rz * ry * rx;
}

// Hit: t, outward normal, what (0 floor, 1 mirror, 2.. balls).
struct Hit { float t; vec3 n; int id; };

void ball(vec3 o, vec3 d, vec3 c, float r, int id, inout Hit h) {
    vec3 oc = o - c;
    float b = dot(oc, d);
    float disc = b * b - dot(oc, oc) + r * r;
    if (disc < 0.0) return;
    float t = -b - sqrt(disc);
    if (t > 0.0 && t < h.t) h = Hit(t, (o + t * d - c) / r, id);
}

// A box of half size `half_size` centred at `c`, rotated by `rot`: the slab
// method in the box's own frame.
void box(vec3 o, vec3 d, vec3 c, vec3 half_size, mat3 rot, int id, inout Hit h) {
    mat3 inv = transpose(rot);
    vec3 lo = inv * (o - c);
    vec3 ld = inv * d;
    vec3 inv_d = 1.0 / ld;
    vec3 t1 = (-half_size - lo) * inv_d;
    vec3 t2 = (half_size - lo) * inv_d;
    vec3 tmin = min(t1, t2);
    vec3 tmax = max(t1, t2);
    float t_near = max(max(tmin.x, tmin.y), tmin.z);
    float t_far = min(min(tmax.x, tmax.y), tmax.z);
    if (t_near > t_far || t_near <= 0.0 || t_near >= h.t) return;
    // The face of the last slab entered.
    vec3 n = vec3(0.0);
    if (t_near == tmin.x) n.x = -sign(ld.x);
    else if (t_near == tmin.y) n.y = -sign(ld.y);
    else n.z = -sign(ld.z);
    h = Hit(t_near, rot * n, id);
}

Hit intersect(vec3 o, vec3 d) {
    Hit h = Hit(FAR, vec3(0.0), -1);
    if (d.y < 0.0) h = Hit(-o.y / d.y, vec3(0.0, 1.0, 0.0), 0);
    vec3 center = vec3(0.0, 1.4, 0.0);
    if (shape == 0) box(o, d, center, vec3(0.5 * size), rotation(), 1, h);
    if (shape == 1) ball(o, d, center, 0.6 * size, 1, h);
    if (shape == 2) box(o, d, center, vec3(0.5, 0.12, 0.5) * size, rotation(), 1, h);
    ball(o, d, vec3(-2.2, 0.5, 0.6), 0.5, 2, h);
    ball(o, d, vec3(1.6, 0.4, -1.9), 0.4, 3, h);
    ball(o, d, vec3(0.4, 0.3, 2.3), 0.3, 4, h);
    return h;
}

vec3 sky(vec3 d) {
    return mix(vec3(0.75, 0.82, 0.92), vec3(0.35, 0.55, 0.9), clamp(d.y * 1.5, 0.0, 1.0));
}

vec3 albedo(int id, vec3 p) {
    if (id == 0) {
        vec2 cell = floor(p.xz);
        return mod(cell.x + cell.y, 2.0) == 0.0 ? vec3(0.92, 0.92, 0.9) : vec3(0.2, 0.22, 0.28);
    }
    if (id == 2) return vec3(0.85, 0.15, 0.1);
    if (id == 3) return vec3(0.1, 0.3, 0.85);
    return vec3(0.95, 0.7, 0.2);
}

void main() {
    vec2 uv = (2.0 * gl_FragCoord.xy - resolution) / resolution.y;
    vec3 eye = vec3(3.4, 3.0, 5.0);
    vec3 w = normalize(eye - vec3(0.0, 1.15, 0.0));
    vec3 u = normalize(cross(vec3(0.0, 1.0, 0.0), w));
    vec3 v = cross(w, u);
    vec3 d = normalize(uv.x * u + uv.y * v - 2.414 * w);  // 45 degrees field of view

    vec3 light = vec3(6.0, 9.0, 4.0);
    if (light_follows_mouse) light = vec3(16.0 * mouse.x - 8.0, 9.0, 8.0 - 16.0 * mouse.y);

    vec3 o = eye;
    vec3 color = vec3(0.0);
    vec3 weight = vec3(1.0);
    for (int bounce = 0; bounce <= 8; bounce++) {
        Hit h = intersect(o, d);
        if (h.id < 0) {
            color += weight * sky(d);
            break;
        }
        vec3 p = o + h.t * d;
        vec3 n = dot(h.n, d) < 0.0 ? h.n : -h.n;
        float fog = exp(-haze * h.t * h.t);
        if (h.id == 1) {
            // The mirror: a little diffuse, mostly reflection.
            weight *= fog;
            color += weight * 0.08 * tint * max(dot(n, normalize(light - p)), 0.0);
            if (bounce >= bounces) break;
            weight *= tint;
            o = p + EPS * n;
            d = reflect(d, n);
            continue;
        }
        vec3 l = normalize(light - p);
        float lit = max(dot(n, l), 0.0);
        if (intersect(p + EPS * n, l).t < length(light - p)) lit = 0.0;
        vec3 shine = vec3(pow(max(dot(reflect(d, n), l), 0.0), 60.0)) * (h.id == 0 ? 0.0 : 0.5);
        vec3 c = albedo(h.id, p) * (0.15 + 0.95 * lit) + shine * lit;
        color += weight * mix(sky(d), c, fog);
        break;
    }
    gl_FragColor = vec4(pow(color, vec3(1.0 / 2.2)), 1.0);
}
