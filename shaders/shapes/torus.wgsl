// shapes/torus.wgsl: the torus (docs/rendering-model.md, "Implicit surfaces").
//
// A shape kind's WGSL: its struct, twin of src/gpu/shapes/torus.rs (the layout
// test checks it), and `hit_torus(ray, shape, index, best) -> Hit`. The
// buffer, KIND_TORUS, HAS_TORI and the loops are generated (src/gpu/shaders.rs).
// The f64 twin is src/reference/shapes/torus.rs; the method is described in
// docs/implementation.md, "Torus".

/// A torus around the local y axis, placed by world = center + scale * rotation * local.
struct Torus {
    center: vec3<f32>,
    scale: f32,
    rotation: mat3x3<f32>,
    major: f32,              // R, the radius of the ring
    minor: f32,              // r, the radius of the tube
    material: u32,
    _pad: u32,
}

/// u^4 + b u^2 + c u + e: the torus's quartic along a ray measured from the
/// foot of the perpendicular from its centre (no cubic term: q.d = 0).
struct Quartic {
    b: f32,
    c: f32,
    e: f32,
}

fn torus_quartic(q: vec3<f32>, d: vec3<f32>, major: f32, minor: f32) -> Quartic {
    let a = dot(q, q) + major * major - minor * minor;
    let four_r2 = 4.0 * major * major;
    return Quartic(
        2.0 * a - four_r2 * (d.x * d.x + d.z * d.z),
        -2.0 * four_r2 * (q.x * d.x + q.z * d.z),
        a * a - four_r2 * (q.x * q.x + q.z * q.z),
    );
}

/// The quartic (slope = false) or its derivative (slope = true) at u.
fn quartic_at(k: Quartic, slope: bool, u: f32) -> f32 {
    let u2 = u * u;
    if slope {
        return (4.0 * u2 + 2.0 * k.b) * u + k.c;
    }
    return (u2 + k.b) * u2 + k.c * u + k.e;
}

/// The root in (a, b] when the ends differ in sign (or the far one is 0),
/// by bisection until the bracket cannot shrink or 32 halvings (the bracket
/// is then 2^-32 of its start, below f32's precision of the answer); T_FAR
/// when there is none.
fn quartic_bracketed(k: Quartic, slope: bool, a_in: f32, b_in: f32) -> f32 {
    var a = a_in;
    var b = b_in;
    let ga = quartic_at(k, slope, a);
    let gb = quartic_at(k, slope, b);
    if ga == 0.0 || !(gb == 0.0 || (ga < 0.0) != (gb < 0.0)) {
        return T_FAR;
    }
    let a_negative = ga < 0.0;
    for (var i = 0; i < 32; i++) {
        let mid = 0.5 * (a + b);
        if mid <= a || mid >= b {
            break;
        }
        let gm = quartic_at(k, slope, mid);
        if gm == 0.0 {
            return mid;
        }
        if (gm < 0.0) == a_negative {
            a = mid;
        } else {
            b = mid;
        }
    }
    return b;
}

/// How the torus's quartic is solved (`TorusMethod` in
/// src/scene/shapes/torus.rs, docs/implementation.md "Torus"):
/// 0 = bisection on monotone pieces, 1 = the slope's roots in closed form
/// and safeguarded Newton steps on the monotone pieces.
override TORUS_METHOD: u32 = 1u;

/// The first root in (lo, hi], T_FAR when there is none: the zeros of the
/// second derivative 12 u^2 + 2 b split [lo, hi] into pieces where the
/// slope is monotone, each holding at most one zero of the slope; those
/// split it into pieces where the quartic is monotone, each holding at most
/// one root. The first piece with a sign change holds the nearest root.
fn quartic_first_root(k: Quartic, lo: f32, hi: f32) -> f32 {
    if TORUS_METHOD == 1u {
        return quartic_first_root_newton(k, lo, hi);
    }
    var splits = array<f32, 4>(lo, hi, hi, hi);
    var n = 1u;
    if k.b < 0.0 {
        let m = sqrt(-k.b / 6.0);
        if lo < -m && -m < hi {
            splits[n] = -m;
            n += 1u;
        }
        if lo < m && m < hi {
            splits[n] = m;
            n += 1u;
        }
    }
    splits[n] = hi;
    var ends = array<f32, 5>(lo, hi, hi, hi, hi);
    var m = 1u;
    for (var i = 0u; i < n; i++) {
        let x = quartic_bracketed(k, true, splits[i], splits[i + 1u]);
        if x < hi {
            ends[m] = x;
            m += 1u;
        }
    }
    ends[m] = hi;
    for (var i = 0u; i < m; i++) {
        let x = quartic_bracketed(k, false, ends[i], ends[i + 1u]);
        if x <= hi {
            return x;
        }
    }
    return T_FAR;
}

/// The real roots of the slope 4 u^3 + 2 b u + c, a depressed cubic
/// u^3 + p u + q (p = b / 2, q = c / 4), in increasing order; a single real
/// root is repeated three times. Cardano's formula in its cancellation-free
/// form for one real root, the trigonometric one for three.
fn slope_roots(k: Quartic) -> vec3<f32> {
    let p = 0.5 * k.b;
    let q = 0.25 * k.c;
    let d = 0.25 * q * q + p * p * p / 27.0;
    if d >= 0.0 {
        let s = 0.5 * abs(q) + sqrt(d);
        let a = -sign(q) * pow(s, 1.0 / 3.0);
        let u = select(0.0, a - p / (3.0 * a), a != 0.0);
        return vec3(u);
    }
    // d < 0 needs p < 0: three real roots 2 sqrt(-p/3) cos(phi + 2 pi j / 3),
    // phi in [0, pi/3]: j = 1 gives the smallest (its angle is in
    // [2pi/3, pi]), j = 2 the middle one, j = 0 the largest.
    let r = sqrt(-p / 3.0);
    let phi = acos(clamp(-0.5 * q / (r * r * r), -1.0, 1.0)) / 3.0;
    let third = 2.0943951;
    return 2.0 * r * vec3(cos(phi + third), cos(phi + 2.0 * third), cos(phi));
}

/// The root in (a, b] of the quartic, monotone there, when its ends differ
/// in sign (or the far one is 0): Newton steps from the middle, each kept
/// inside the shrinking bracket (a step that would leave it halves the
/// bracket instead), until a step is below 1e-6 of the piece or 24 steps;
/// T_FAR when there is no root.
fn quartic_newton(k: Quartic, a_in: f32, b_in: f32) -> f32 {
    var a = a_in;
    var b = b_in;
    let ga = quartic_at(k, false, a);
    let gb = quartic_at(k, false, b);
    if gb == 0.0 && ga != 0.0 {
        return b;
    }
    if ga == 0.0 || (ga < 0.0) == (gb < 0.0) {
        return T_FAR;
    }
    let a_negative = ga < 0.0;
    let tolerance = 1e-6 * (b - a);
    var x = 0.5 * (a + b);
    for (var i = 0; i < 24; i++) {
        let g = quartic_at(k, false, x);
        if g == 0.0 {
            return x;
        }
        if (g < 0.0) == a_negative {
            a = x;
        } else {
            b = x;
        }
        var next = x - g / quartic_at(k, true, x);
        if !(next > a && next < b) {
            next = 0.5 * (a + b);
        }
        let step = abs(next - x);
        x = next;
        if step <= tolerance {
            break;
        }
    }
    return x;
}

/// The first root in (lo, hi] as in quartic_first_root, with the slope's
/// zeros from the closed-form cubic and Newton steps instead of halvings.
fn quartic_first_root_newton(k: Quartic, lo: f32, hi: f32) -> f32 {
    let roots = slope_roots(k);
    var a = lo;
    for (var i = 0u; i < 3u; i++) {
        let x = roots[i];
        if x > a && x < hi {
            let u = quartic_newton(k, a, x);
            if u <= hi {
                return u;
            }
            a = x;
        }
    }
    return quartic_newton(k, a, hi);
}

/// Torus: the first root of its quartic inside the bounding sphere of
/// radius R + r, from the foot of the perpendicular from its centre. The
/// normal is the gradient's direction written as p - R (x, 0, z) / |(x, 0, z)|.
fn hit_torus(ray: Ray, s: Torus, index: u32, best: Hit) -> Hit {
    let l = local_ray(ray, s.center, s.scale, s.rotation);
    let outer = s.major + s.minor;
    let qq = dot(l.q, l.q);
    if qq >= outer * outer {
        return best;
    }
    let h = sqrt(outer * outer - qq);
    let lo = max(-h, local_u(l, ray.t_min));
    let hi = min(h, local_u(l, best.t));
    if lo >= hi {
        return best;
    }
    let u = quartic_first_root(torus_quartic(l.q, l.d, s.major, s.minor), lo, hi);
    if u > hi {
        return best;
    }
    let p = l.q + u * l.d;
    let rho = length(p.xz);
    let ring = select(vec3(0.0), vec3(p.x, 0.0, p.z) * (s.major / rho), rho > 0.0);
    let error_scale = max3(abs(s.center)) + s.scale * outer;
    return placed_hit(ray, best, l, u, p - ring, s.center, s.rotation, KIND_TORUS, index, error_scale);
}
