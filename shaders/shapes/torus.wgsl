// shapes/torus.wgsl: the torus (docs/rendering-model.md, "Implicit surfaces").
//
// A shape kind's WGSL: its struct, twin of src/gpu/shapes/torus.rs (the layout
// test checks it), and `hit_torus(ray, shape, index, best) -> Hit`. The
// buffer, KIND_TORUS, HAS_TORI and the loops are generated (src/gpu/shapes/glue.rs).
// The f64 twin is src/reference/shapes/torus.rs; the method is described in
// docs/implementation.md, "Torus".

/// A torus in world units: the ring of radius `major` (the scene's R times
/// its scale) around `axis` through `center`, the tube of radius `minor`.
/// The rest of its placement, a turn about its own axis, changes nothing.
struct Torus {
    center: vec3<f32>,
    major: f32,
    axis: vec3<f32>,         // unit length
    minor: f32,
    material: u32,
}

/// u^4 + b u^2 + c u + e: the torus's quartic along a ray measured from the
/// foot of the perpendicular from its centre (no cubic term: q.d = 0).
struct Quartic {
    b: f32,
    c: f32,
    e: f32,
}

/// The quartic for the points q + u d (q the foot, relative to the centre,
/// d the unit direction): (|p|^2 + R^2 - r^2)^2 = 4 R^2 |p_perp|^2, with
/// p_perp the part of p across the axis (docs/implementation.md, "Torus").
fn torus_quartic(q: vec3<f32>, d: vec3<f32>, s: Torus) -> Quartic {
    let q_perp = q - dot(q, s.axis) * s.axis;
    let d_perp = d - dot(d, s.axis) * s.axis;
    let a = dot(q, q) + s.major * s.major - s.minor * s.minor;
    let four_r2 = 4.0 * s.major * s.major;
    return Quartic(
        2.0 * a - four_r2 * dot(d_perp, d_perp),
        -2.0 * four_r2 * dot(q_perp, d_perp),
        a * a - four_r2 * dot(q_perp, q_perp),
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
        count_step();
        let mid = 0.5 * (a + b);
        if mid <= a || mid >= b {
            break;
        }
        let gm = quartic_at(k, slope, mid);
        if gm == 0.0 {
            return mid;
        }
        narrow_bracket(&a, &b, mid, gm, a_negative);
    }
    return b;
}

/// How the torus's quartic is solved (`TorusMethod` in
/// src/scene/shapes/torus.rs, docs/implementation.md "Torus"):
/// 0 = bisection on monotone pieces, 1 = the slope's roots in closed form
/// and safeguarded Newton steps on the monotone pieces, 2 = the quartic's
/// roots in closed form (Descartes' factorisation) polished by Newton steps.
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
    if TORUS_METHOD == 2u {
        return quartic_first_root_closed(k, lo, hi);
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
/// root is repeated three times.
fn slope_roots(k: Quartic) -> vec3<f32> {
    return depressed_cubic_roots(0.5 * k.b, 0.25 * k.c);
}

/// The real roots of u^3 + p u + q in increasing order; a single real root
/// is repeated three times. Cardano's formula in its cancellation-free form
/// for one real root (d >= 0), the trigonometric one for three. Both are
/// computed and one selected: llvmpipe runs both sides of a branch anyway,
/// and the branch with its early return cost more (docs/performance.md,
/// "The torus against its sphere").
fn depressed_cubic_roots(p: f32, q: f32) -> vec3<f32> {
    let d = 0.25 * q * q + p * p * p / 27.0;
    let s1 = 0.5 * abs(q) + sqrt(max(d, 0.0));
    let a = -sign(q) * pow(s1, 1.0 / 3.0);
    let one = select(0.0, a - p / (3.0 * a), a != 0.0);
    // d < 0 needs p < 0: three real roots 2 sqrt(-p/3) cos(phi + 2 pi j / 3),
    // phi in [0, pi/3]: j = 1 gives the smallest (its angle is in
    // [2pi/3, pi]), j = 2 the middle one, j = 0 the largest.
    // cos(phi -+ 2pi/3) = -cos(phi) / 2 -+ sin(phi) sqrt(3) / 2, sin(phi) >= 0:
    // one cosine instead of three.
    let r = sqrt(max(-p / 3.0, 0.0));
    let phi = acos(clamp(-0.5 * q / (r * r * r), -1.0, 1.0)) / 3.0;
    let c = cos(phi);
    let s = 0.8660254 * sqrt(max(0.0, 1.0 - c * c));
    return select(2.0 * r * vec3(-0.5 * c - s, -0.5 * c + s, c), vec3(one), d >= 0.0);
}

/// The quartic's real roots in closed form (docs/implementation.md,
/// "Torus", the closed form): u^4 + b u^2 + c u + e = (u^2 + s u + t)(u^2 - s u + v)
/// where y = s^2 is the largest root of the resolvent cubic
/// y^3 + 2b y^2 + (b^2 - 4e) y - c^2 (never negative: the cubic is -c^2 <= 0
/// at 0), t + v = b + y and v - t = c / s. The two quadratics' roots, in
/// increasing order within each (`.xy` from the first, `.zw` from the
/// second); T_FAR where a quadratic has none.
fn quartic_roots_closed(k: Quartic) -> vec4<f32> {
    // The resolvent y^3 + A y^2 + B y + C, depressed by y = x - A/3.
    let a2 = 2.0 * k.b;
    let b1 = k.b * k.b - 4.0 * k.e;
    let p = b1 - a2 * a2 / 3.0;
    let q = a2 * (2.0 * a2 * a2 - 9.0 * b1) / 27.0 - k.c * k.c;
    let y = max(0.0, depressed_cubic_roots(p, q).z - a2 / 3.0);
    let s = sqrt(y);
    // v - t two ways: c / s, or |v - t| from (v - t)^2 = (t + v)^2 - 4 t v
    // = (b + y)^2 - 4e with the sign of c. y carries an error of about
    // f32's epsilon times |b| (the shift a2 / 3), so c / s is good when
    // |b| / y is small, the square root when (b + y)^2 / (v - t)^2 is:
    // take the one with the smaller relative error.
    let sum = k.b + y;
    let w2 = max(0.0, sum * sum - 4.0 * k.e);
    let w = select(sign(k.c) * sqrt(w2), k.c / s, abs(k.b) * w2 < y * sum * sum);
    let t = 0.5 * (sum - w);
    let v = 0.5 * (sum + w);
    // u^2 + s u + t = 0 and u^2 - s u + v = 0.
    let d1 = y - 4.0 * t;
    let d2 = y - 4.0 * v;
    let h1 = sqrt(max(d1, 0.0));
    let h2 = sqrt(max(d2, 0.0));
    return vec4(
        select(T_FAR, 0.5 * (-s - h1), d1 >= 0.0),
        select(T_FAR, 0.5 * (-s + h1), d1 >= 0.0),
        select(T_FAR, 0.5 * (s - h2), d2 >= 0.0),
        select(T_FAR, 0.5 * (s + h2), d2 >= 0.0),
    );
}

/// One Newton step on the quartic from u, to win back the digits the
/// closed form loses; kept only when it moves u by less than `limit` (near
/// a double root the slope vanishes and the step means nothing).
fn quartic_polish(k: Quartic, u: f32, limit: f32) -> f32 {
    let step = quartic_at(k, false, u) / quartic_at(k, true, u);
    return select(u, u - step, abs(step) < limit);
}

/// The first root in (lo, hi] from the closed form, polished by one Newton
/// step (a second changed neither the error nor the time measurably,
/// docs/performance.md "The torus against its sphere"); T_FAR when there is
/// none. No loop at all. The polish also decides a root that the closed
/// form puts just after lo while it lies at or before it (a secondary ray
/// leaving the surface it starts on): without it shadow rays shadow their
/// own surface. Then the next root is the answer (the far side of the tube
/// for a refracted ray, of the ring for a shadow ray); that case is rare,
/// so it is a branch rather than a second polish for every ray.
fn quartic_first_root_closed(k: Quartic, lo: f32, hi: f32) -> f32 {
    let roots = quartic_roots_closed(k);
    let after = select(vec4(T_FAR), roots, roots > vec4(lo));
    // The two smallest of the four.
    let near = min(after.xy, after.zw);
    let far = max(after.xy, after.zw);
    var root = min(near.x, near.y);
    let second = min(max(near.x, near.y), min(far.x, far.y));
    let limit = 1e-2 * (hi - lo);
    var u = quartic_polish(k, root, limit);
    if u <= lo {
        root = second;
        u = quartic_polish(k, root, limit);
    }
    return select(T_FAR, u, root < T_FAR && u > lo && u <= hi);
}

/// A piece (a, b] of the search interval on which the quartic is
/// monotone, and its value `ga` at a.
struct Piece {
    a: f32,
    ga: f32,
    b: f32,
}

/// The first of the pieces that the slope's zeros (in closed form) cut
/// (lo, hi] into whose ends differ in sign, or the last piece when none
/// does (it then holds no root). The nearest root is in this piece or
/// nowhere.
///
/// The zeros are clamped to [lo, hi], so a zero outside gives an empty
/// piece, which never counts; the quartic is evaluated at all three at once
/// and the piece chosen by selects. Straight-line code on purpose: llvmpipe
/// runs a fragment shader on a group of pixels at once and runs every
/// branch that any of them takes, and every loop until all of them are
/// done, so one refinement loop on the right piece costs far less than a
/// loop per piece; and this form made the opaque torus scene faster than
/// a loop over the zeros did (docs/performance.md, "The torus against its
/// sphere").
fn first_sign_change(k: Quartic, lo: f32, hi: f32) -> Piece {
    let x = clamp(slope_roots(k), vec3(lo), vec3(hi));
    let x2 = x * x;
    let g = (x2 + k.b) * x2 + k.c * x + k.e;
    let g_lo = quartic_at(k, false, lo);
    // The pieces (lo, x.x], (x.x, x.y], (x.y, x.z]: non-empty, and their
    // ends differ in sign or the far end is a root.
    let in0 = x.x > lo && g_lo != 0.0 && (g.x == 0.0 || (g_lo < 0.0) != (g.x < 0.0));
    let in1 = x.y > x.x && g.x != 0.0 && (g.y == 0.0 || (g.x < 0.0) != (g.y < 0.0));
    let in2 = x.z > x.y && g.y != 0.0 && (g.z == 0.0 || (g.y < 0.0) != (g.z < 0.0));
    // The first of them, else the last piece (x.z, hi].
    let a = select(select(select(x.z, x.y, in2), x.x, in1), lo, in0);
    let ga = select(select(select(g.z, g.y, in2), g.x, in1), g_lo, in0);
    let b = select(select(select(hi, x.z, in2), x.y, in1), x.x, in0);
    return Piece(a, ga, b);
}

/// Whether the piece holds a root: its ends differ in sign, or its far end
/// (`gb` the value there) is one and its near end is not.
fn holds_root(p: Piece, gb: f32) -> bool {
    return p.ga != 0.0 && (gb == 0.0 || (p.ga < 0.0) != (gb < 0.0));
}

/// The first root in (lo, hi] as in quartic_first_root, with the slope's
/// zeros from the closed-form cubic and Newton steps instead of halvings,
/// on the first piece with a sign change only; T_FAR when there is none.
fn quartic_first_root_newton(k: Quartic, lo: f32, hi: f32) -> f32 {
    let piece = first_sign_change(k, lo, hi);
    let gb = quartic_at(k, false, piece.b);
    if !holds_root(piece, gb) {
        return T_FAR;
    }
    if gb == 0.0 {
        return piece.b;
    }
    return quartic_newton(k, piece);
}

/// The root in (a, b] of the quartic, monotone there, whose ends differ in
/// sign: Newton steps from the middle, each kept inside the shrinking
/// bracket (a step that would leave it halves the bracket instead), until
/// a step is below 1e-6 of the piece or 24 steps.
fn quartic_newton(k: Quartic, piece: Piece) -> f32 {
    var a = piece.a;
    var b = piece.b;
    let a_negative = piece.ga < 0.0;
    let tolerance = 1e-6 * (b - a);
    var x = 0.5 * (a + b);
    for (var i = 0; i < 24; i++) {
        count_step();
        let g = quartic_at(k, false, x);
        if g == 0.0 {
            return x;
        }
        narrow_bracket(&a, &b, x, g, a_negative);
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

/// The part (lo, hi] of the ray to search, in u = t - f.s (from the foot
/// f): inside the bounding sphere of radius R + r (|u| <= h) and inside
/// t_min < t < t_max; empty (lo >= hi) when the ray misses the sphere. The
/// callers search even an empty span and discard the answer, with no early
/// return: straight-line code is cheaper on llvmpipe (docs/performance.md,
/// "The torus against its sphere").
fn torus_span(f: Foot, s: Torus, t_min: f32, t_max: f32) -> vec2<f32> {
    let outer = s.major + s.minor;
    let qq = dot(f.g, f.g);
    let h = sqrt(max(outer * outer - qq, 0.0));
    return select(vec2(0.0), vec2(max(-h, t_min - f.s), min(h, t_max - f.s)), qq < outer * outer);
}

/// The outward normal at p (relative to the centre): the gradient's
/// direction, p minus its nearest point on the ring, R p_perp / |p_perp|.
/// A zero or non-finite vector (p on the axis) falls back to -d.
fn torus_normal(p: vec3<f32>, s: Torus, d: vec3<f32>) -> vec3<f32> {
    let p_perp = p - dot(p, s.axis) * s.axis;
    let rho = length(p_perp);
    let ring = select(vec3(0.0), p_perp * (s.major / rho), rho > 0.0);
    let n = p - ring;
    let len = length(n);
    return select(-d, n / len, len > 1e-30 && len < 1e30);
}

/// Torus: the first root of its quartic inside the bounding sphere of
/// radius R + r, from the foot of the perpendicular from its centre.
fn hit_torus(ray: Ray, s: Torus, index: u32, best: Hit) -> Hit {
    let f = foot(ray, s.center);
    let span = torus_span(f, s, ray.t_min, best.t);
    let u = quartic_first_root(torus_quartic(f.g, ray.dir, s), span.x, span.y);
    let t = f.s + u;
    if !(span.x < span.y && u <= span.y && t > ray.t_min && t < best.t) {
        return best;
    }
    let p = f.g + u * ray.dir;
    let error_scale = max3(abs(s.center)) + s.major + s.minor;
    return surface_hit(t, s.center + p, torus_normal(p, s, ray.dir), KIND_TORUS, index, error_scale);
}

/// Whether the torus blocks the ray somewhere in t_min < t < t_max (shadow
/// rays): whether its quartic has a root there. With Newton's method that
/// is whether the first piece with a sign change exists, so no root is
/// refined at all; bisection and the closed form find the root as for a hit.
fn occludes_torus(ray: Ray, s: Torus, t_max: f32) -> bool {
    let f = foot(ray, s.center);
    let span = torus_span(f, s, ray.t_min, t_max);
    let k = torus_quartic(f.g, ray.dir, s);
    var blocked = false;
    if TORUS_METHOD != 1u {
        blocked = quartic_first_root(k, span.x, span.y) <= span.y;
    } else {
        let piece = first_sign_change(k, span.x, span.y);
        blocked = holds_root(piece, quartic_at(k, false, piece.b));
    }
    return span.x < span.y && blocked;
}
