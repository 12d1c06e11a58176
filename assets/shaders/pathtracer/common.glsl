// A small path tracer in Buffer A (docs/sandbox.md,
// "A path tracer that accumulates, against WebGL2"): a Cornell box with
// two diffuse spheres, lit by a square lamp in the ceiling. Buffer A adds
// one sample per pixel each frame to the running mean of the frames
// before; Image shows it. Common holds the scene and the tracer, Buffer A
// the camera and the average.

const float PI = 3.14159265;

#include "random.glsl"

// The box is [-1, 1] x [0, 2] x [-1, 1], open towards the camera (+z).
const vec3 BOX_MIN = vec3(-1.0, 0.0, -1.0);
const vec3 BOX_MAX = vec3(1.0, 2.0, 1.0);

// The lamp: a square in the ceiling, facing down.
const vec2 LAMP_MIN = vec2(-0.3, -0.3);
const vec2 LAMP_MAX = vec2(0.3, 0.3);
const vec3 LAMP_RADIANCE = vec3(16.0, 13.0, 9.0);

struct Hit {
    float t;
    vec3 normal;
    vec3 albedo;
    bool lamp;
};

// Nearest hit of the ray o + t d with t in (0, best.t): a box wall, the
// plane with `normal` at offset `d0` along it (points inside the box only).
void hit_wall(vec3 o, vec3 d, vec3 normal, float d0, vec3 albedo, inout Hit best) {
    float denom = dot(normal, d);
    if (denom >= 0.0) return; // seen from behind: walls face inwards
    float t = (d0 - dot(normal, o)) / denom;
    if (t <= 0.0 || t >= best.t) return;
    vec3 p = o + t * d;
    if (any(lessThan(p, BOX_MIN - 1e-3)) || any(greaterThan(p, BOX_MAX + 1e-3))) return;
    best = Hit(t, normal, albedo, false);
}

// The smaller root of |o + t d - c|^2 = r^2 that is positive.
void hit_sphere(vec3 o, vec3 d, vec3 c, float r, vec3 albedo, inout Hit best) {
    vec3 oc = o - c;
    float b = dot(oc, d);
    float disc = b * b - (dot(oc, oc) - r * r);
    if (disc < 0.0) return;
    float t = -b - sqrt(disc);
    if (t <= 0.0 || t >= best.t) return;
    best = Hit(t, (o + t * d - c) / r, albedo, false);
}

Hit trace(vec3 o, vec3 d) {
    Hit best = Hit(1e30, vec3(0.0), vec3(0.0), false);
    vec3 white = vec3(0.73);
    hit_wall(o, d, vec3(0.0, 1.0, 0.0), 0.0, white, best);                   // floor
    hit_wall(o, d, vec3(0.0, -1.0, 0.0), -2.0, white, best);                 // ceiling
    hit_wall(o, d, vec3(0.0, 0.0, 1.0), -1.0, white, best);                  // back
    hit_wall(o, d, vec3(1.0, 0.0, 0.0), -1.0, vec3(0.65, 0.05, 0.05), best); // left, red
    hit_wall(o, d, vec3(-1.0, 0.0, 0.0), -1.0, vec3(0.12, 0.45, 0.15), best); // right, green
    hit_sphere(o, d, vec3(-0.4, 0.45, -0.35), 0.45, white, best);
    hit_sphere(o, d, vec3(0.45, 0.3, 0.3), 0.3, vec3(0.8, 0.75, 0.5), best);
    vec3 p = o + best.t * d;
    bool ceiling = best.normal.y < -0.5 && p.y > BOX_MAX.y - 1e-3;
    best.lamp = ceiling && all(greaterThan(p.xz, LAMP_MIN)) && all(lessThan(p.xz, LAMP_MAX));
    return best;
}

// A direction about `n` with density cos(theta) / pi (Malley's method: a
// uniform point of the unit disc lifted onto the hemisphere).
vec3 cosine_direction(vec3 n, inout uint state) {
    float r = sqrt(random(state));
    float phi = 2.0 * PI * random(state);
    vec3 a = abs(n.x) > 0.5 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 u = normalize(cross(a, n));
    vec3 v = cross(n, u);
    return normalize(r * cos(phi) * u + r * sin(phi) * v + sqrt(max(0.0, 1.0 - r * r)) * n);
}

// Light arriving along the ray: the lamp when a camera ray sees it, and at
// each diffuse bounce the lamp sampled directly (next event estimation: a
// uniform point of its area, weighted by the geometry term); the bounced
// rays do not count the lamp again, so nothing is counted twice.
vec3 radiance(vec3 o, vec3 d, inout uint state) {
    vec3 color = vec3(0.0);
    vec3 throughput = vec3(1.0);
    for (int bounce = 0; bounce < 5; bounce++) {
        Hit hit = trace(o, d);
        if (hit.t >= 1e30) break; // out of the open front: black
        if (hit.lamp) {
            if (bounce == 0) color += LAMP_RADIANCE;
            break;
        }
        vec3 p = o + hit.t * d + 1e-4 * hit.normal;
        vec2 s = mix(LAMP_MIN, LAMP_MAX, vec2(random(state), random(state)));
        vec3 to_lamp = vec3(s.x, 2.0, s.y) - p;
        float dist2 = dot(to_lamp, to_lamp);
        vec3 l = to_lamp / sqrt(dist2);
        float cos_surface = dot(hit.normal, l);
        float cos_lamp = l.y; // the lamp faces down, (0, -1, 0)
        if (cos_surface > 0.0 && cos_lamp > 0.0) {
            Hit blocker = trace(p, l);
            if (blocker.lamp) {
                vec2 size = LAMP_MAX - LAMP_MIN;
                color += throughput * hit.albedo / PI * LAMP_RADIANCE
                    * cos_surface * cos_lamp * size.x * size.y / dist2;
            }
        }
        throughput *= hit.albedo; // cosine-weighted: cos / pdf = pi cancels 1 / pi
        o = p;
        d = cosine_direction(hit.normal, state);
    }
    return color;
}
