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

/// One axis of the slab test of implicit_bracket: the span (near, far)
/// narrowed to lo <= q + u d <= hi, or an empty one where the ray runs
/// parallel to the slab outside it. Called once per axis rather than in a
/// loop over them: lavapipe does not unroll shader loops
/// (docs/performance.md, "Work moved out of loops").
fn implicit_slab(span: vec2<f32>, q: f32, d: f32, lo: f32, hi: f32) -> vec2<f32> {
    if abs(d) < 1e-20 {
        return select(span, vec2(1.0, 0.0), q < lo || q > hi);
    }
    let ta = (lo - q) / d;
    let tb = (hi - q) / d;
    return vec2(max(span.x, min(ta, tb)), min(span.y, max(ta, tb)));
}

/// The first sign change of f along a ray: the bracket [a, b] that holds
/// its root, or b itself where f is 0 there (`exact`); none unless `found`.
struct ImplicitBracket {
    found: bool,
    exact: bool,
    a: f32,
    b: f32,
    a_negative: bool,        // f(a) < 0
    span: f32,               // the length searched, the scale of the root's tolerance
}

/// Samples f at `steps` equal steps over the part of the ray inside the box
/// (the slab test) and t_min < t < t_max: the first sign change.
fn implicit_bracket(ray: Ray, s: Implicit, l: LocalRay, t_max: f32) -> ImplicitBracket {
    var bracket = ImplicitBracket(false, false, 0.0, 0.0, false, 0.0);
    var span = vec2(local_u(l, ray.t_min), local_u(l, t_max));
    span = implicit_slab(span, l.q.x, l.d.x, s.bounds_min.x, s.bounds_max.x);
    span = implicit_slab(span, l.q.y, l.d.y, s.bounds_min.y, s.bounds_max.y);
    span = implicit_slab(span, l.q.z, l.d.z, s.bounds_min.z, s.bounds_max.z);
    let near = span.x;
    let far = span.y;
    if !(near < far) {
        return bracket;
    }
    let step = (far - near) / f32(s.steps);
    var a = near;
    var ga = implicit_value(s.function, l.q + a * l.d);
    // The callers refine the bracket after this loop, not inside it:
    // lavapipe runs an `if`'s body for all 8 pixels it shades together,
    // taken or not, so inside the loop the bisection would cost every step
    // (docs/performance.md, "Work moved out of loops").
    for (var i = 1u; i <= s.steps; i++) {
        count_step();
        let b = select(near + f32(i) * step, far, i == s.steps);
        let gb = implicit_value(s.function, l.q + b * l.d);
        let exact = gb == 0.0 && ga != 0.0;
        if exact || (ga < 0.0 && gb > 0.0) || (ga > 0.0 && gb < 0.0) {
            bracket = ImplicitBracket(true, exact, a, b, ga < 0.0, far - near);
            break;
        }
        a = b;
        ga = gb;
    }
    return bracket;
}

/// The first sign change (implicit_bracket), refined by bisection. The
/// normal is the exact gradient (dual numbers), -d where it is zero.
fn hit_implicit(ray: Ray, s: Implicit, index: u32, best: Hit) -> Hit {
    let l = local_ray(ray, s.center, s.scale, s.rotation);
    let bracket = implicit_bracket(ray, s, l, best.t);
    if !bracket.found {
        return best;
    }
    var u = bracket.b;
    if !bracket.exact {
        u = implicit_bisect(s, l, bracket.a, bracket.b, bracket.a_negative, IMPLICIT_ROOT_TOLERANCE * bracket.span);
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

/// Whether the surface blocks the ray in t_min < t < t_max (shadow rays):
/// whether f changes sign there. The bracket holds the root, so none is
/// refined and no gradient taken, as for the torus (docs/implementation.md,
/// "Torus"); only a root within rounding of t_min or t_max could be judged
/// otherwise than hit_implicit's test of t would.
fn occludes_implicit(ray: Ray, s: Implicit, t_max: f32) -> bool {
    let l = local_ray(ray, s.center, s.scale, s.rotation);
    return implicit_bracket(ray, s, l, t_max).found;
}
