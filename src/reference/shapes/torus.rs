//! A torus for the f64 tracer (docs/rendering-model.md, "Implicit surfaces";
//! the method in docs/implementation.md, "Torus").

use glam::DVec3;

use super::placement::{LocalRay, Placed};
use super::{Prepare, traced_by};
use crate::reference::hit::Hit;
use crate::reference::ray::Ray;
use crate::scene::{self, Instance};

/// A torus around the local y axis: the tube of radius `minor` around the
/// circle of radius `major`.
#[derive(Debug, Clone)]
pub struct Torus {
    pub placed: Placed,
    pub major: f64,
    pub minor: f64,
}

// One method for both variants: the textbook has no torus to compare with.
traced_by!(Torus: hit_torus);

impl Prepare for scene::Torus {
    type Traced = Torus;

    fn prepare(shape: &Instance<Self>) -> Torus {
        Torus {
            placed: Placed::new(&shape.placement),
            major: shape.major_radius,
            minor: shape.minor_radius,
        }
    }
}

/// `u^4 + b u^2 + c u + e`: the torus's quartic along a ray measured from the
/// foot of the perpendicular from its centre. (From the foot, `q.d = 0` and
/// `|q + u d|^2 = |q|^2 + u^2`, so the cubic term vanishes.)
#[derive(Debug, Clone, Copy)]
pub struct Quartic {
    pub b: f64,
    pub c: f64,
    pub e: f64,
}

impl Quartic {
    /// `f(q + u d)` for `f = (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + z^2)`.
    pub fn along(q: DVec3, d: DVec3, major: f64, minor: f64) -> Quartic {
        let a = q.length_squared() + major * major - minor * minor;
        let four_r2 = 4.0 * major * major;
        Quartic {
            b: 2.0 * a - four_r2 * (d.x * d.x + d.z * d.z),
            c: -2.0 * four_r2 * (q.x * d.x + q.z * d.z),
            e: a * a - four_r2 * (q.x * q.x + q.z * q.z),
        }
    }

    pub fn value(&self, u: f64) -> f64 {
        let u2 = u * u;
        (u2 + self.b) * u2 + self.c * u + self.e
    }

    pub fn slope(&self, u: f64) -> f64 {
        (4.0 * u * u + 2.0 * self.b) * u + self.c
    }

    /// The first root in `(lo, hi]`, by bracketing: the slope's own slope
    /// `12 u^2 + 2 b` vanishes at most at `±sqrt(-b / 6)`, which splits
    /// `[lo, hi]` into pieces where the slope is monotone; each holds at most
    /// one root of the slope, found by bisection; those split `[lo, hi]` into
    /// pieces where the quartic is monotone, each holding at most one root.
    /// The first piece whose ends differ in sign holds the nearest root, and
    /// bisection finds it. No root is ever skipped, however close two are.
    pub fn first_root(&self, lo: f64, hi: f64) -> Option<f64> {
        let mut splits = [lo, hi, hi, hi, hi, hi];
        let mut n = 1;
        if self.b < 0.0 {
            let k = (-self.b / 6.0).sqrt();
            for x in [-k, k] {
                if lo < x && x < hi {
                    splits[n] = x;
                    n += 1;
                }
            }
        }
        splits[n] = hi;
        // The slope's roots, at most one per piece.
        let mut ends = [lo, hi, hi, hi, hi];
        let mut m = 1;
        for i in 0..n {
            if let Some(x) = bracketed(|u| self.slope(u), splits[i], splits[i + 1])
                && x < hi
            {
                ends[m] = x;
                m += 1;
            }
        }
        ends[m] = hi;
        (0..m).find_map(|i| bracketed(|u| self.value(u), ends[i], ends[i + 1]))
    }
}

/// The root of `g` in `(a, b]` when `g(a)` and `g(b)` differ in sign or
/// `g(b) = 0` (and `g(a) != 0`): bisection until the bracket cannot shrink.
pub fn bracketed(g: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> Option<f64> {
    let (ga, gb) = (g(a), g(b));
    if ga == 0.0 || !(gb == 0.0 || (ga < 0.0) != (gb < 0.0)) {
        return None;
    }
    let a_negative = ga < 0.0;
    loop {
        let mid = 0.5 * (a + b);
        if mid <= a || mid >= b {
            return Some(b);
        }
        let gm = g(mid);
        if gm == 0.0 {
            return Some(mid);
        }
        if (gm < 0.0) == a_negative {
            a = mid;
        } else {
            b = mid;
        }
    }
}

/// The torus hit nearest to the ray origin with `0 < t < t_max`.
pub fn hit_torus(torus: &Torus, ray: &Ray, t_max: f64) -> Option<Hit> {
    let local = torus.placed.local(ray);
    let u = first_root(torus, &local, local.u(0.0), local.u(t_max))?;
    let hit = torus_hit(torus, &local, u);
    (hit.t > 0.0 && hit.t < t_max).then_some(hit)
}

/// The first root with `lo < u <= hi` (local parameters), inside the
/// bounding sphere of radius `R + r`.
pub fn first_root(torus: &Torus, ray: &LocalRay, lo: f64, hi: f64) -> Option<f64> {
    let outer = torus.major + torus.minor;
    let qq = ray.q.length_squared();
    if qq >= outer * outer {
        return None;
    }
    let h = (outer * outer - qq).sqrt();
    let (lo, hi) = (lo.max(-h), hi.min(h));
    if lo >= hi {
        return None;
    }
    Quartic::along(ray.q, ray.d, torus.major, torus.minor).first_root(lo, hi)
}

/// The hit at local parameter `u`. The normal is the gradient's direction,
/// written as `p - R (x, 0, z) / |(x, 0, z)|` (on the surface the gradient
/// `4 (|p|^2 + R^2 - r^2) p - 8 R^2 (x, 0, z)` is `8 R rho` times it, `rho =
/// |(x, 0, z)|`), which loses no digits to the quartic's large terms.
pub fn torus_hit(torus: &Torus, ray: &LocalRay, u: f64) -> Hit {
    let p = ray.at(u);
    let ring = DVec3::new(p.x, 0.0, p.z).normalize_or_zero() * torus.major;
    torus.placed.hit(
        ray,
        u,
        p - ring,
        torus.placed.error_scale(torus.major + torus.minor),
    )
}
