// whitted.wgsl: Turner Whitted's ray tracer (1980) as one WGSL sandbox
// shader: the same scene and the same algorithm as whitted.frag, written the
// WGSL way. The sandbox calls `main_image` for every pixel and provides `u`
// (time, mouse, resolution, ...); the annotated fields of `Params` become
// controls in the window's panel (see docs/sandbox.md).
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
// WGSL has no recursion, so the rays still to trace wait on a small stack,
// each with the weight it contributes with; the sum is the same.
//
//   raysandbox shader assets/shaders/whitted.wgsl

struct Params {
    max_depth: u32,  // @slider(0, 8) @default(5) bounces of reflection and refraction
    glass_ior: f32,  // @slider(1.0, 2.5, 0.01) @default(1.5) index of refraction of the glass sphere
    spin: f32,       // @slider(0.0, 1.0, 0.01) @default(0.15) camera orbit, radians per second
    shadows: u32,    // @checkbox @default(true) trace shadow rays
    sky: vec3<f32>,  // @color(linear) @default(0.25, 0.55, 0.95) the background
    exposure: f32,   // @log(0.1, 10) @default(1) multiplies the radiance
}

const FAR: f32 = 1e30;
const EPS: f32 = 1e-4;     // how far secondary rays start off the surface
const STACK: u32 = 12u;    // rays waiting to be traced (depth + 2 suffice)

// 0 = floor (checkered), 1 = glass, 2 = mirror: the scene of
// assets/scenes/whitted.toml.
struct Material {
    color: vec3<f32>,
    kd: f32,
    ks: f32,
    shininess: f32,
    kr: f32,
    kt: f32,
    ior: f32,
}

fn material(id: i32, p: vec3<f32>, n: vec3<f32>) -> Material {
    if id == 0 {
        // The checker of the rendering model: step into the surface, count the cells.
        let q = floor((p - 0.001 * 0.8 * n) / 0.8);
        let even = (q.x + q.y + q.z) - 2.0 * floor((q.x + q.y + q.z) / 2.0) == 0.0;
        let c = select(vec3(0.85, 0.08, 0.05), vec3(0.95, 0.85, 0.1), even);
        return Material(c, 0.9, 0.0, 32.0, 0.0, 0.0, 1.5);
    }
    if id == 1 {
        return Material(vec3(1.0), 0.0, 0.7, 250.0, 0.0, 0.92, params.glass_ior);
    }
    return Material(vec3(0.9), 0.12, 0.8, 300.0, 0.85, 0.0, 1.5);
}

// The nearest hit so far: distance, outward normal, material, closed shape.
struct Hit {
    t: f32,
    n: vec3<f32>,
    id: i32,
    closed: bool,
}

fn sphere(o: vec3<f32>, d: vec3<f32>, c: vec3<f32>, r: f32, id: i32, h: ptr<function, Hit>) {
    let oc = o - c;
    let b = dot(oc, d);
    let disc = b * b - (dot(oc, oc) - r * r);
    if disc < 0.0 {
        return;
    }
    let s = sqrt(disc);
    var t = -b - s;          // the near root, else the far one (inside)
    if t <= 0.0 {
        t = -b + s;
    }
    if t > 0.0 && t < (*h).t {
        *h = Hit(t, (o + t * d - c) / r, id, true);
    }
}

fn floor_plane(o: vec3<f32>, d: vec3<f32>, h: ptr<function, Hit>) {
    if abs(d.y) < 1e-12 {
        return;              // parallel: no hit
    }
    let t = -o.y / d.y;
    if t > 0.0 && t < (*h).t {
        *h = Hit(t, vec3(0.0, 1.0, 0.0), 0, false);
    }
}

fn intersect(o: vec3<f32>, d: vec3<f32>) -> Hit {
    var h = Hit(FAR, vec3(0.0), -1, false);
    floor_plane(o, d, &h);
    sphere(o, d, vec3(0.5, 1.0, 1.2), 0.8, 1, &h);
    sphere(o, d, vec3(-0.9, 1.25, -1.4), 1.05, 2, &h);
    return h;
}

fn in_shadow(p: vec3<f32>, l: vec3<f32>, dist: f32) -> bool {
    return intersect(p, l).t < dist;
}

// Blinn-Phong from two white lights, ambient, and shadow rays.
fn local_light(p: vec3<f32>, d: vec3<f32>, ns: vec3<f32>, m: Material) -> vec3<f32> {
    var color = vec3(0.12) * m.color * m.kd;
    let lights = array(vec3(-4.0, 7.0, 6.0), vec3(5.0, 5.0, 3.0));
    let power = array(0.9, 0.35);
    for (var i = 0; i < 2; i++) {
        let to_light = lights[i] - p;
        let dist = length(to_light);
        let l = to_light / dist;
        let ndl = dot(ns, l);
        if ndl <= 0.0 {
            continue;
        }
        if params.shadows != 0u && in_shadow(p + EPS * ns, l, dist) {
            continue;
        }
        let h = normalize(l - d);
        let spec = m.ks * pow(max(0.0, dot(ns, h)), m.shininess);
        color += power[i] * (m.kd * m.color * ndl + spec);
    }
    return color;
}

// The exact unpolarised Fresnel reflectance for cos_i > 0 (1 = total reflection).
fn fresnel(cos_i: f32, eta_i: f32, eta_t: f32) -> f32 {
    let sin_t = eta_i / eta_t * sqrt(max(0.0, 1.0 - cos_i * cos_i));
    if sin_t >= 1.0 || cos_i <= 0.0 {
        return 1.0;
    }
    let cos_t = sqrt(max(0.0, 1.0 - sin_t * sin_t));
    let rs = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
    let rp = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

struct Pending {
    o: vec3<f32>,
    d: vec3<f32>,
    w: vec3<f32>,
    depth: u32,
}

fn trace(origin: vec3<f32>, direction: vec3<f32>) -> vec3<f32> {
    var stack: array<Pending, STACK>;
    stack[0] = Pending(origin, direction, vec3(1.0), 0u);
    var top = 1u;
    var color = vec3(0.0);
    for (var guard = 0; guard < 64 && top > 0u; guard++) {
        top -= 1u;
        let ray = stack[top];
        let h = intersect(ray.o, ray.d);
        if h.id < 0 {
            color += ray.w * params.sky;
            continue;
        }
        let d = ray.d;
        let p = ray.o + h.t * d;
        let entering = dot(d, h.n) < 0.0;
        let ns = select(-h.n, h.n, entering);   // the normal facing the ray
        let m = material(h.id, p, h.n);
        color += ray.w * local_light(p, d, ns, m);
        if ray.depth >= params.max_depth {
            continue;
        }
        var f = 0.0;
        if m.kt > 0.0 {
            var eta_i = 1.0;
            var eta_t = m.ior;
            if h.closed && !entering {
                eta_i = m.ior;
                eta_t = 1.0;
            }
            f = fresnel(-dot(d, ns), eta_i, eta_t);
            let wt = m.kt * (1.0 - f);
            if wt > 0.0 && top < STACK {
                // Thin planes let the ray through unbent; closed shapes bend it.
                let t_dir = select(d, refract(d, ns, eta_i / eta_t), h.closed);
                stack[top] = Pending(p - EPS * ns, normalize(t_dir), ray.w * wt * m.color, ray.depth + 1u);
                top += 1u;
            }
        }
        let wr = m.kr + m.kt * f;
        if wr > 0.0 && top < STACK {
            stack[top] = Pending(p + EPS * ns, reflect(d, ns), ray.w * wr, ray.depth + 1u);
            top += 1u;
        }
    }
    return color;
}

// The lecture's pinhole camera, film one unit in front of the eye.
fn camera_ray(pixel: vec2<f32>, eye: vec3<f32>, look_at: vec3<f32>) -> vec3<f32> {
    let w = normalize(eye - look_at);
    let u_axis = normalize(cross(vec3(0.0, 1.0, 0.0), w));
    let v_axis = cross(w, u_axis);
    let h = 2.0 * tan(radians(40.0) / 2.0);
    let x = h * u.resolution.x / u.resolution.y * (pixel.x / u.resolution.x - 0.5);
    let y = h * (pixel.y / u.resolution.y - 0.5);
    return normalize(x * u_axis + y * v_axis - w);
}

fn srgb(linear: vec3<f32>) -> vec3<f32> {
    let c = clamp(linear, vec3(0.0), vec3(1.0));
    return select(1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, 12.92 * c, c < vec3(0.0031308));
}

// frag_coord: the pixel centre, y up (Shadertoy's convention).
fn main_image(frag_coord: vec2<f32>) -> vec4<f32> {
    let look_at = vec3(0.1, 0.8, 0.0);
    let offset = vec3(0.1, 0.6, 5.8);   // the eye of whitted.toml, relative to the look_at
    let a = u.time * params.spin;
    let eye = look_at + vec3(offset.x * cos(a) + offset.z * sin(a), offset.y,
                            -offset.x * sin(a) + offset.z * cos(a));
    let d = camera_ray(frag_coord, eye, look_at);
    return vec4(srgb(params.exposure * trace(eye, d)), 1.0);
}
