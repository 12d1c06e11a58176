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
/// by bisection until the bracket cannot shrink; T_FAR when there is none.
fn quartic_bracketed(k: Quartic, slope: bool, a_in: f32, b_in: f32) -> f32 {
    var a = a_in;
    var b = b_in;
    let ga = quartic_at(k, slope, a);
    let gb = quartic_at(k, slope, b);
    if ga == 0.0 || !(gb == 0.0 || (ga < 0.0) != (gb < 0.0)) {
        return T_FAR;
    }
    let a_negative = ga < 0.0;
    for (var i = 0; i < 64; i++) {
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

/// The first root in (lo, hi], T_FAR when there is none: the zeros of the
/// second derivative 12 u^2 + 2 b split [lo, hi] into pieces where the
/// slope is monotone, each holding at most one zero of the slope; those
/// split it into pieces where the quartic is monotone, each holding at most
/// one root. The first piece with a sign change holds the nearest root.
fn quartic_first_root(k: Quartic, lo: f32, hi: f32) -> f32 {
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
