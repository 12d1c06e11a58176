// whitted.frag: Turner Whitted's ray tracer (1980) as one GLSL Sandbox shader,
// following the lecture's pseudocode and the project's rendering model:
//
//   trace(ray, depth):
//       hit = nearest intersection          (two spheres, a checkered floor)
//       if no hit: return background
//       color = ambient + for each light not in shadow: diffuse + specular
//       if depth < max_depth:
//           color += (kr + kt F) * trace(reflected ray, depth + 1)
//           color += kt (1 - F) * albedo * trace(refracted ray, depth + 1)
//       return color
//
// GLSL has no recursion, so the rays still to trace wait on a small stack,
// each with the weight it contributes with; the sum is the same.
//
//   raysandbox shader assets/shaders/whitted.frag
//
// The uniforms below the first three are parameters: the comment after each
// one makes a control in the window's panel (see docs/sandbox.md).

#ifdef GL_ES
precision highp float;
#endif

uniform float time;
uniform vec2 mouse;
uniform vec2 resolution;

uniform int max_depth = 5;     // @slider(0, 8) bounces of reflection and refraction
uniform float glass_ior = 1.5; // @slider(1.0, 2.5, 0.01) index of refraction of the glass sphere
uniform float spin = 0.15;     // @slider(0.0, 1.0, 0.01) camera orbit, radians per second
uniform vec3 sky = vec3(0.25, 0.55, 0.95); // @color(linear) the background
uniform bool shadows = true;   // @checkbox trace shadow rays
uniform float exposure = 1.0;  // @log(0.1, 10) multiplies the radiance

const float FAR = 1e30;
const float EPS = 1e-4;        // how far secondary rays start off the surface
const int STACK = 12;          // rays waiting to be traced (depth + 2 suffice)

// Materials: color, kd, ks, shininess, kr (mirror), kt (transparency), ior.
// 0 = floor (checkered), 1 = glass, 2 = mirror: the scene of
// assets/scenes/whitted.toml, so at time 0 this shader draws what
// `raysandbox render assets/scenes/whitted.toml` draws.
struct Material {
    vec3 color;
    float kd;
    float ks;
    float shininess;
    float kr;
    float kt;
    float ior;
};

Material material(int id, vec3 p, vec3 n) {
    if (id == 0) {
        // The checker of the rendering model: step into the surface, count the cells.
        vec3 q = floor((p - 0.001 * 0.8 * n) / 0.8);
        bool even = mod(q.x + q.y + q.z, 2.0) == 0.0;
        vec3 c = even ? vec3(0.95, 0.85, 0.1) : vec3(0.85, 0.08, 0.05);
        return Material(c, 0.9, 0.0, 32.0, 0.0, 0.0, 1.5);
    }
    if (id == 1) return Material(vec3(1.0), 0.0, 0.7, 250.0, 0.0, 0.92, glass_ior);
    return Material(vec3(0.9), 0.12, 0.8, 300.0, 0.85, 0.0, 1.5);
}

// The nearest hit so far: distance, outward normal, material, closed shape.
struct Hit {
    float t;
    vec3 n;
    int id;
    bool closed;
};

void sphere(vec3 o, vec3 d, vec3 c, float r, int id, inout Hit h) {
    vec3 oc = o - c;
    float b = dot(oc, d);
    float disc = b * b - (dot(oc, oc) - r * r);
    if (disc < 0.0) return;
    float s = sqrt(disc);
    float t = -b - s;             // the near root, else the far one (inside)
    if (t <= 0.0) t = -b + s;
    if (t > 0.0 && t < h.t) {
        h = Hit(t, (o + t * d - c) / r, id, true);
    }
}

void floor_plane(vec3 o, vec3 d, inout Hit h) {
    if (abs(d.y) < 1e-12) return; // parallel: no hit
    float t = -o.y / d.y;
    if (t > 0.0 && t < h.t) {
        h = Hit(t, vec3(0.0, 1.0, 0.0), 0, false);
    }
}

Hit intersect(vec3 o, vec3 d) {
    Hit h = Hit(FAR, vec3(0.0), -1, false);
    floor_plane(o, d, h);
    sphere(o, d, vec3(0.5, 1.0, 1.2), 0.8, 1, h);
    sphere(o, d, vec3(-0.9, 1.25, -1.4), 1.05, 2, h);
    return h;
}

bool in_shadow(vec3 p, vec3 l, float dist) {
    return intersect(p, l).t < dist;
}

// Blinn-Phong from two white lights, ambient, and shadow rays.
vec3 local_light(vec3 p, vec3 d, vec3 ns, Material m) {
    vec3 color = vec3(0.12) * m.color * m.kd;
    vec3 lights[2] = vec3[2](vec3(-4.0, 7.0, 6.0), vec3(5.0, 5.0, 3.0));
    float power[2] = float[2](0.9, 0.35);
    for (int i = 0; i < 2; i++) {
        vec3 to_light = lights[i] - p;
        float dist = length(to_light);
        vec3 l = to_light / dist;
        float ndl = dot(ns, l);
        if (ndl <= 0.0) continue;
        if (shadows && in_shadow(p + EPS * ns, l, dist)) continue;
        vec3 h = normalize(l - d);
        float spec = m.ks * pow(max(0.0, dot(ns, h)), m.shininess);
        color += power[i] * (m.kd * m.color * ndl + spec);
    }
    return color;
}

// The exact unpolarised Fresnel reflectance for cos_i > 0 (1 = total reflection).
float fresnel(float cos_i, float eta_i, float eta_t) {
    float sin_t = eta_i / eta_t * sqrt(max(0.0, 1.0 - cos_i * cos_i));
    if (sin_t >= 1.0 || cos_i <= 0.0) return 1.0;
    float cos_t = sqrt(max(0.0, 1.0 - sin_t * sin_t));
    float rs = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
    float rp = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

vec3 trace(vec3 origin, vec3 direction) {
    vec3 stack_o[STACK];
    vec3 stack_d[STACK];
    vec3 stack_w[STACK];
    int stack_depth[STACK];
    int top = 0;
    stack_o[0] = origin;
    stack_d[0] = direction;
    stack_w[0] = vec3(1.0);
    stack_depth[0] = 0;
    top = 1;
    vec3 color = vec3(0.0);
    for (int guard = 0; guard < 64; guard++) {
        if (top == 0) break;
        top -= 1;
        vec3 o = stack_o[top];
        vec3 d = stack_d[top];
        vec3 w = stack_w[top];
        int depth = stack_depth[top];

        Hit h = intersect(o, d);
        if (h.id < 0) {
            color += w * sky;
            continue;
        }
        vec3 p = o + h.t * d;
        bool entering = dot(d, h.n) < 0.0;
        vec3 ns = entering ? h.n : -h.n;  // the normal facing the ray
        Material m = material(h.id, p, h.n);
        color += w * local_light(p, d, ns, m);
        if (depth >= max_depth) continue;

        float f = 0.0;
        if (m.kt > 0.0) {
            float eta_i = 1.0;
            float eta_t = m.ior;
            if (h.closed && !entering) { eta_i = m.ior; eta_t = 1.0; }
            if (!h.closed) { eta_i = 1.0; eta_t = m.ior; }
            f = fresnel(-dot(d, ns), eta_i, eta_t);
            float wt = m.kt * (1.0 - f);
            if (wt > 0.0 && top < STACK) {
                // Thin planes let the ray through unbent; closed shapes bend it.
                vec3 t_dir = h.closed ? refract(d, ns, eta_i / eta_t) : d;
                stack_o[top] = p - EPS * ns;
                stack_d[top] = normalize(t_dir);
                stack_w[top] = w * wt * m.color;
                stack_depth[top] = depth + 1;
                top += 1;
            }
        }
        float wr = m.kr + m.kt * f;
        if (wr > 0.0 && top < STACK) {
            stack_o[top] = p + EPS * ns;
            stack_d[top] = reflect(d, ns);
            stack_w[top] = w * wr;
            stack_depth[top] = depth + 1;
            top += 1;
        }
    }
    return color;
}

// The lecture's pinhole camera, film one unit in front of the eye.
vec3 camera_ray(vec2 pixel, vec3 eye, vec3 target) {
    vec3 w = normalize(eye - target);
    vec3 u = normalize(cross(vec3(0.0, 1.0, 0.0), w));
    vec3 v = cross(w, u);
    float h = 2.0 * tan(radians(40.0) / 2.0);
    float x = h * resolution.x / resolution.y * (pixel.x / resolution.x - 0.5);
    float y = h * (pixel.y / resolution.y - 0.5);
    return normalize(x * u + y * v - w);
}

vec3 srgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, 12.92 * c, lessThan(c, vec3(0.0031308)));
}

void main() {
    vec3 target = vec3(0.1, 0.8, 0.0);
    vec3 offset = vec3(0.1, 0.6, 5.8);  // the eye of whitted.toml, relative to the target
    float a = time * spin;
    vec3 eye = target + vec3(offset.x * cos(a) + offset.z * sin(a), offset.y,
                             -offset.x * sin(a) + offset.z * cos(a));
    vec3 d = camera_ray(gl_FragCoord.xy, eye, target);
    gl_FragColor = vec4(srgb(exposure * trace(eye, d)), 1.0);
}
