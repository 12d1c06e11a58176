// shade.wgsl: Whitted shading (docs/rendering-model.md, "Materials" and "Whitted shading").

/// Moves p off the surface along n by 8 units in the last place of the
/// scale of the numbers involved: max(|p|_max, the shape's error_scale, 1/32).
/// A computed hit point is off the surface by a few rounding errors of that
/// scale, and so is the next ray's test against the same surface; starting
/// the new ray well beyond both keeps it from hitting its own surface at
/// t ~ 0 ("shadow acne"), in scenes of any size. The idea is Wachter and
/// Binder's (Ray Tracing Gems ch. 6: a fixed number of ulps, a floor near the
/// origin), with the ulps measured at the shape's scale rather than at each
/// coordinate of p: on a huge ground sphere the error near y = 0 comes from
/// the centre's magnitude, not from p.y. 8: the property tests find 2 the
/// smallest that never self-intersects (tests/intersect_props.rs), and 8
/// leaves room for GPU division and square roots a few ulps off
/// (docs/accuracy.md). docs/implementation.md has the f64 twin.
fn offset_ray(p: vec3<f32>, n: vec3<f32>, error_scale: f32) -> vec3<f32> {
    if !ROBUST {
        return p + NAIVE_OFFSET * n;
    }
    const MIN_SCALE: f32 = 1.0 / 32.0;
    let scale = max(max3(abs(p)), max(error_scale, MIN_SCALE));
    return p + (OFFSET_ULPS * scale) * n;
}

/// 8 units in the last place of f32: 8 * 2^-23.
const OFFSET_ULPS: f32 = 8.0 * 1.1920929e-7;

/// The error_scale for which offset_ray moves a point (at least) `distance`
/// off its surface: for shapes whose rule names the distance (the Julia
/// set's 2 epsilon, an implicit surface's root tolerance).
fn offset_scale_for(distance: f32) -> f32 {
    return distance / OFFSET_ULPS;
}

/// The textbook offset of secondary and shadow rays (ROBUST = false): a
/// fixed distance, too large for a scene a thousand times smaller and too
/// small for one a thousand times larger.
const NAIVE_OFFSET: f32 = 1e-3;

/// Albedo at p: the material colour, or the checker's second colour on odd
/// cells. The rendering model looks the cell up at q = p - 0.001 s n, a small step into
/// the surface, so that a plane lying on a cell boundary does not flicker
/// between two cells. Far from the origin that step is smaller than the f32
/// spacing of p (at 1e5 it is 0.0005 against an ulp of 0.008), p - 0.001 s n
/// rounds back to p, and a floor on a boundary takes the cell on the wrong
/// side everywhere. `checker_cell` evaluates floor(p / s - 0.001 n) exactly
/// from p / s instead. p is relative to the frame origin (scene.wgsl): the
/// material's checker_phase puts back what that origin adds to p / s.
fn albedo_at(m: Material, p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    if !HAS_CHECKER || m.checker_size <= 0.0 {
        return m.color;
    }
    let s = m.checker_size;
    var cell: vec3<i32>;
    if ROBUST {
        cell = checker_cell(p / s + m.checker_phase, 0.001 * n);
    } else {
        cell = vec3<i32>(floor((p - 0.001 * s * n) / s + m.checker_phase));
    }
    if ((cell.x + cell.y + cell.z) & 1) == 0 {
        return m.color;
    }
    return m.checker_color;
}

/// floor(x - step) for |step| < 1, without forming x - step: with
/// k = floor(x) and f = x - k (exact: x and k are close, Sterbenz), it is k,
/// minus 1 when f < step (step > 0), plus 1 when f >= 1 + step (step < 0).
fn checker_cell(x: vec3<f32>, step: vec3<f32>) -> vec3<i32> {
    let k = floor(x);
    let f = x - k;
    let down = (step > vec3(0.0)) & (f < step);
    let up = (step < vec3(0.0)) & (f >= vec3(1.0) + step);
    return vec3<i32>(k) - select(vec3(0), vec3(1), down) + select(vec3(0), vec3(1), up);
}

/// The exact unpolarised Fresnel reflectance of a dielectric interface from
/// index n1 into n2, for cos_i = cos of the angle of incidence. Total internal
/// reflection and grazing incidence (cos_i = 0) reflect everything.
fn fresnel(cos_i: f32, n1: f32, n2: f32) -> f32 {
    if cos_i <= 0.0 {
        return 1.0;
    }
    let eta = n1 / n2;
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = sqrt(1.0 - sin2_t);
    let r_s = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let r_p = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    return 0.5 * (r_s * r_s + r_p * r_p);
}

/// Mirror direction of d about the surface normal ns.
fn reflect_dir(d: vec3<f32>, ns: vec3<f32>) -> vec3<f32> {
    return normalize(d - 2.0 * dot(d, ns) * ns);
}

/// Snell's law with eta = n1 / n2 and ns facing the incoming ray; the caller
/// has ruled out total internal reflection (fresnel < 1).
fn refract_dir(d: vec3<f32>, ns: vec3<f32>, eta: f32) -> vec3<f32> {
    let cos_i = -dot(d, ns);
    let cos_t = sqrt(max(0.0, 1.0 - eta * eta * (1.0 - cos_i * cos_i)));
    return normalize(eta * d + (eta * cos_i - cos_t) * ns);
}

/// Local illumination: ambient, plus Lambert and Blinn-Phong for every light
/// that the point sees (a shadow ray to it hits nothing).
fn shade_local(hit: Hit, ns: vec3<f32>, d: vec3<f32>, m: Material, albedo: vec3<f32>) -> vec3<f32> {
    var color = globals().ambient * albedo * m.diffuse;
    if !HAS_LIGHTS {
        return color;
    }
    // Off the surface along the geometric normal, on the lit side.
    let ng = select(-hit.normal, hit.normal, dot(hit.normal, ns) >= 0.0);
    let shadow_origin = offset_ray(hit.point, ng, hit.error_scale);
    for (var i = 0u; i < globals().light_count; i++) {
        let light = load_light(i);
        // A light at p (or nearer than length() can resolve) has no
        // direction and lights nothing: never divide by a zero length.
        let from_p = light.position - hit.point;
        let len = scaled_length(from_p);
        if len <= 0.0 {
            continue;
        }
        let l = from_p / len;
        let n_dot_l = dot(ns, l);
        if n_dot_l <= 0.0 {
            continue;
        }
        let to_light = light.position - shadow_origin;
        let dist = scaled_length(to_light);
        if dist <= 0.0 {
            continue;
        }
        if SHADOWS {
            count_ray(1u);
            count_shadow_ray();
            let blocked = occluded(Ray(shadow_origin, to_light / dist, 0.0), dist);
            tree_shadow(i, shadow_origin, to_light / dist, dist, blocked);
            if blocked {
                continue;
            }
        }
        var highlight = 0.0;
        let n_dot_h = dot(ns, normalize(l - d));
        if m.specular > 0.0 && n_dot_h > 0.0 {
            highlight = m.specular * pow(n_dot_h, m.shininess);
        }
        let term = light.radiance * (m.diffuse * albedo * n_dot_l + highlight);
        tree_light(i, term);
        color += term;
    }
    return color;
}

/// The ray-counting variant (`raysandbox bench --throughput`,
/// docs/performance.md, "Rays per second"): true adds up, per pixel, the
/// rays traced by kind (primary, shadow, reflected, refracted) in
/// `ray_counts`, which fs_trace then writes instead of the radiance. Every
/// other pipeline has it false, and the counting is dead code there.
override COUNT_RAYS: bool = false;
var<private> ray_counts: vec4<f32>;

/// Counts one traced ray of kind `kind` (0 primary, 1 shadow, 2 reflected,
/// 3 refracted) in the counting variant.
fn count_ray(kind: u32) {
    if COUNT_RAYS {
        ray_counts[kind] += 1.0;
    }
}

/// A ray waiting to be traced: the explicit stack replaces the recursion of
/// the lecture's trace(ray, depth, weight), which WGSL does not allow.
struct PendingRay {
    ray: Ray,
    depth: u32,
    weight: f32,             // the rendering model's scalar weight, for the min_weight rule
    throughput: vec3<f32>,   // what this ray's radiance is multiplied by in the pixel
}

// The stack: depth-first, the reflected child traced at once and the
// refracted one waiting, so at most one ray waits per level and max_depth
// entries suffice (the generated STACK_SIZE is max_depth + 1, what an
// earlier version of trace() needed, so that copies of these files made
// before still work). STACK_SIZE is declared by the program in a generated
// part in front of these files (at most 17; src/gpu/shaders.rs): WGSL
// cannot size an array with an `override`, and a stack no larger than
// needed is markedly faster.

/// Whether the rendering model allows a child ray of this depth and weight.
fn worth_tracing(depth: u32, weight: f32) -> bool {
    return depth <= globals().max_depth && weight > 0.0 && weight >= globals().min_weight;
}

/// trace = local + wr * trace(reflected) + wt * albedo * trace(refracted),
/// unrolled: each ray adds throughput * local to the pixel. The ray being
/// traced is held in `job`; a hit's reflected child takes its place at
/// once (the recursion's first call), and only where it also has a
/// refracted child does that one wait on the stack. On llvmpipe each read
/// or write of the stack at an index that differs by pixel costs in
/// proportion to its size (docs/performance.md, "The ray stack"), so a
/// ray that has one child, and every ray of a scene without glass, never
/// touches it.
fn trace(primary: Ray) -> vec3<f32> {
    var stack: array<PendingRay, STACK_SIZE>;
    var top = 0u;
    var job = PendingRay(primary, 0u, 1.0, vec3(1.0));
    // Where `job` came from, for the ray-tree pass: the stack entry it was
    // popped from, or TREE_HELD for a child traced at once.
    var slot = TREE_HELD;
    tree_pending(TREE_HELD, TREE_CAMERA);
    count_ray(0u);
    var radiance = vec3(0.0);
    loop {
        let ray = job.ray;
        count_depth(job.depth);
        tree_begin(slot, ray, job.depth, job.throughput);
        var next = false;
        let hit = hit_scene(ray, T_FAR);
        if hit.kind == KIND_NONE {
            tree_missed(job.throughput * globals().background);
            radiance += job.throughput * globals().background;
        } else {
            var m = load_material(material_of(hit));
            if is_opaque(hit.kind) {
                m.transparency = 0.0;
            }
            let into_surface = dot(ray.dir, hit.normal) < 0.0;
            // Shading (lighting, mirror) by the shading normal facing the ray;
            // secondary rays leave along the geometric one.
            let ns = select(-hit.shading, hit.shading, into_surface);
            let ng = select(-hit.normal, hit.normal, into_surface);
            let albedo = albedo_at(m, hit.point, hit.normal);
            tree_hit(hit, ray, ns);
            let local = shade_local(hit, ns, ray.dir, m, albedo);
            radiance += job.throughput * local;

            // Fresnel only where the material has a dielectric part.
            var f = 0.0;
            var eta = 1.0;
            if HAS_TRANSPARENCY && m.transparency > 0.0 {
                let cos_i = -dot(ray.dir, ns);
                if is_thin(hit.kind) || into_surface {
                    f = fresnel(cos_i, 1.0, m.ior);
                    eta = 1.0 / m.ior;
                } else {
                    f = fresnel(cos_i, m.ior, 1.0);
                    eta = m.ior;
                }
            }
            let wr = m.mirror + m.transparency * f;
            let wt = m.transparency * (1.0 - f);
            tree_split(local, f, wr, wt);
            let child_depth = job.depth + 1u;

            let refracted_weight = job.weight * wt * max(albedo.r, max(albedo.g, albedo.b));
            let refracts = HAS_TRANSPARENCY && REFRACTION && worth_tracing(child_depth, refracted_weight);
            let reflected_weight = job.weight * wr;
            let reflects = (HAS_MIRRORS || HAS_TRANSPARENCY) && REFLECTION
                && worth_tracing(child_depth, reflected_weight);
            if refracts {
                var dir = ray.dir;             // thin planes pass the ray on unbent
                if !is_thin(hit.kind) {
                    dir = refract_dir(ray.dir, ns, eta);
                }
                let origin = offset_ray(hit.point, -ng, hit.error_scale);
                let child = PendingRay(Ray(origin, dir, 0.0), child_depth, refracted_weight, job.throughput * wt * albedo);
                count_ray(3u);
                if !reflects {
                    // The only child: traced next, in this ray's place.
                    job = child;
                    slot = TREE_HELD;
                    tree_pending(TREE_HELD, TREE_REFRACTED);
                    next = true;
                } else if top < STACK_SIZE {
                    stack[top] = child;
                    tree_pending(top, TREE_REFRACTED);
                    top += 1u;
                }
            }
            if reflects {
                count_ray(2u);
                tree_pending(TREE_HELD, tree_reflected_kind(f, !into_surface && !is_thin(hit.kind), m.transparency > 0.0));
                let origin = offset_ray(hit.point, ng, hit.error_scale);
                job = PendingRay(Ray(origin, reflect_dir(ray.dir, ns), 0.0), child_depth, reflected_weight, job.throughput * wr);
                slot = TREE_HELD;
                next = true;
            }
        }
        if !next && top > 0u {
            top -= 1u;
            job = stack[top];
            slot = top;
            next = true;
        }
        if !next {
            break;
        }
    }
    return radiance;
}
