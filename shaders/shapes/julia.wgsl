// shapes/julia.wgsl: the quaternion Julia set (docs/rendering-model.md,
// "Implicit surfaces"; Crane 2005). The f64 twin is
// src/reference/shapes/julia.rs. Buffer, KIND_JULIA, HAS_JULIAS and the loops
// are generated (src/gpu/shapes/glue.rs).

/// A Julia set placed by world = center + scale * rotation * local.
struct Julia {
    center: vec3<f32>,
    scale: f32,
    rotation: mat3x3<f32>,
    c: vec4<f32>,            // real, i, j, k
    slice: f32,
    iterations: u32,
    epsilon: f32,            // local units
    material: u32,
    footprint: u32,          // 1: epsilon grows with the pixel footprint
}

/// The distance estimate at local point p: z <- z^2 + c from z = (p, slice),
/// dz <- 2 |z| dz, then 0.5 |z| ln|z| / dz. dz is held below 1e30 (8^64 would
/// overflow an f32): past that the estimate is below any epsilon anyway.
fn julia_distance(s: Julia, p: vec3<f32>) -> f32 {
    var z = vec4(p, s.slice);
    var dz = 1.0;
    for (var i = 0u; i < s.iterations; i++) {
        dz = min(dz * 2.0 * length(z), 1e30);
        z = vec4(z.x * z.x - dot(z.yzw, z.yzw), 2.0 * z.x * z.yzw) + s.c;
        if length(z) > 4.0 {
            break;
        }
    }
    let r = length(z);
    return 0.5 * r * log(r) / dz;
}

/// grad DE by central differences with step e (the epsilon of the hit).
fn julia_normal(s: Julia, p: vec3<f32>, e: f32) -> vec3<f32> {
    return vec3(
        julia_distance(s, p + vec3(e, 0.0, 0.0)) - julia_distance(s, p - vec3(e, 0.0, 0.0)),
        julia_distance(s, p + vec3(0.0, e, 0.0)) - julia_distance(s, p - vec3(0.0, e, 0.0)),
        julia_distance(s, p + vec3(0.0, 0.0, e)) - julia_distance(s, p - vec3(0.0, 0.0, e)),
    );
}

/// The surface distance (local units) at local parameter u: epsilon, or
/// with the footprint on at least the width one pixel subtends at the
/// distance travelled along the ray (from the eye for camera rays, whose
/// t_min reaches back to it, from the surface left for the others).
/// `pixel_angle` is the film's height over its pixel rows.
fn julia_epsilon(ray: Ray, s: Julia, l: LocalRay, u: f32, pixel_angle: f32) -> f32 {
    if s.footprint == 0u {
        return s.epsilon;
    }
    let travelled = l.s + l.scale * u - min(ray.t_min, 0.0);
    return max(s.epsilon, pixel_angle * travelled / l.scale);
}

/// Sphere tracing from where the ray enters the sphere |p| < 2 (or from its
/// start inside it) to the first point with DE < epsilon (julia_epsilon);
/// leaving the sphere or 1024 steps is a miss. Rays leaving the surface
/// start 2 epsilon off it: the error_scale for which offset_ray moves them
/// that far.
fn hit_julia(ray: Ray, s: Julia, index: u32, best: Hit) -> Hit {
    let l = local_ray(ray, s.center, s.scale, s.rotation);
    let qq = dot(l.q, l.q);
    if qq >= 4.0 {
        return best;
    }
    let h = sqrt(4.0 - qq);
    let end = min(h, local_u(l, best.t));
    var u = max(-h, local_u(l, ray.t_min));
    // The hit (its normal takes six more estimates) is made after the
    // loop, not inside it: lavapipe runs an `if`'s body for all 8 pixels
    // it shades together, taken or not, so inside the loop it would cost
    // every step (docs/performance.md, "Work moved out of loops").
    var found = false;
    var epsilon = 0.0;
    // The angle one pixel subtends, read once rather than every step.
    let pixel_angle = globals().film_height / f32(globals().resolution.y);
    for (var i = 0u; i < 1024u; i++) {
        if u > end {
            break;
        }
        count_step();
        let de = julia_distance(s, l.q + u * l.d);
        epsilon = julia_epsilon(ray, s, l, u, pixel_angle);
        if de < epsilon {
            found = true;
            break;
        }
        u += de;
    }
    if !found {
        return best;
    }
    let p = l.q + u * l.d;
    let error_scale = max(
        offset_scale_for(2.0 * epsilon * s.scale),
        max3(abs(s.center)) + 2.0 * s.scale,
    );
    return placed_hit(ray, best, l, u, julia_normal(s, p, epsilon), s.center, s.rotation, KIND_JULIA, index, error_scale);
}
