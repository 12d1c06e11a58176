// shapes/implicit.wgsl: a user's implicit surface f(x, y, z) = 0
// (docs/rendering-model.md, "Implicit surfaces"). The f64 twin is
// src/reference/shapes/implicit.rs. implicit_value(function, p) and
// implicit_gradient(function, p) are generated from the scene's functions
// (src/expr, src/gpu/shaders.rs), as are the buffer, KIND_IMPLICIT,
// HAS_IMPLICITS and the loops.

/// An implicit surface placed by world = center + scale * rotation * local,
/// looked for inside the local box [bounds_min, bounds_max].
struct Implicit {
    center: vec3<f32>,
    scale: f32,
    rotation: mat3x3<f32>,
    bounds_min: vec3<f32>,
    function: u32,           // which generated function
    bounds_max: vec3<f32>,
    steps: u32,
    material: u32,
}

/// The root is known to 1e-6 of the segment (the rendering model).
const IMPLICIT_ROOT_TOLERANCE: f32 = 1e-6;

/// Bisection of the sign change of f in [a, b] (f(a) < 0 when a_negative)
/// until the bracket is `tolerance` wide: its midpoint.
fn implicit_bisect(s: Implicit, l: LocalRay, a_in: f32, b_in: f32, a_negative: bool, tolerance: f32) -> f32 {
    var a = a_in;
    var b = b_in;
    for (var i = 0; i < 64; i++) {
        count_step();
        let mid = 0.5 * (a + b);
        if b - a <= tolerance || mid <= a || mid >= b {
            break;
        }
        let gm = implicit_value(s.function, l.q + mid * l.d);
        if gm == 0.0 {
            return mid;
        }
        narrow_bracket(&a, &b, mid, gm, a_negative);
    }
    return 0.5 * (a + b);
}

/// Samples f at `steps` equal steps over the part of the ray inside the box
/// (the slab test), and refines the first sign change by bisection. The
/// normal is the exact gradient (dual numbers), -d where it is zero.
fn hit_implicit(ray: Ray, s: Implicit, index: u32, best: Hit) -> Hit {
    let l = local_ray(ray, s.center, s.scale, s.rotation);
    var near = local_u(l, ray.t_min);
    var far = local_u(l, best.t);
    for (var i = 0u; i < 3u; i++) {
        if abs(l.d[i]) < 1e-20 {
            if l.q[i] < s.bounds_min[i] || l.q[i] > s.bounds_max[i] {
                return best;
            }
            continue;
        }
        let ta = (s.bounds_min[i] - l.q[i]) / l.d[i];
        let tb = (s.bounds_max[i] - l.q[i]) / l.d[i];
        near = max(near, min(ta, tb));
        far = min(far, max(ta, tb));
    }
    if !(near < far) {
        return best;
    }
    let step = (far - near) / f32(s.steps);
    var a = near;
    var ga = implicit_value(s.function, l.q + a * l.d);
    var u = T_FAR;
    for (var i = 1u; i <= s.steps; i++) {
        count_step();
        let b = select(near + f32(i) * step, far, i == s.steps);
        let gb = implicit_value(s.function, l.q + b * l.d);
        if gb == 0.0 && ga != 0.0 {
            u = b;
            break;
        }
        if (ga < 0.0 && gb > 0.0) || (ga > 0.0 && gb < 0.0) {
            u = implicit_bisect(s, l, a, b, ga < 0.0, IMPLICIT_ROOT_TOLERANCE * (far - near));
            break;
        }
        a = b;
        ga = gb;
    }
    if u == T_FAR {
        return best;
    }
    let p = l.q + u * l.d;
    let diagonal = length(s.bounds_max - s.bounds_min) * s.scale;
    let extent = length(max(abs(s.bounds_min), abs(s.bounds_max)));
    let error_scale = max(
        offset_scale_for(2.0 * IMPLICIT_ROOT_TOLERANCE * diagonal),
        max3(abs(s.center)) + s.scale * extent,
    );
    return placed_hit(ray, best, l, u, implicit_gradient(s.function, p), s.center, s.rotation, KIND_IMPLICIT, index, error_scale);
}
