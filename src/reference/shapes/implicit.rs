//! A user's implicit surface `f(x, y, z) = 0` for the f64 tracer
//! (docs/rendering-model.md, "Implicit surfaces"): sampling over the part of
//! the ray inside `bounds`, then bisection; the normal is the exact gradient
//! by dual numbers.

use std::sync::Arc;

use glam::DVec3;

use super::placement::{LocalRay, Placed};
use super::{Prepare, traced_by};
use crate::expr::Function;
use crate::reference::hit::Hit;
use crate::reference::ray::{Ray, offset_ray_scale};
use crate::scene::{self, Instance};

#[derive(Debug, Clone)]
pub struct Implicit {
    pub placed: Placed,
    pub f: Arc<Function>,
    /// The local box `[min, max]` the surface is looked for in.
    pub bounds: [DVec3; 2],
    pub steps: u32,
}

traced_by!(Implicit: hit_implicit);

/// The refined root is within this fraction of the segment's length of the
/// true one (the rendering model's 1e-6).
pub const ROOT_TOLERANCE: f64 = 1e-6;

impl Prepare for scene::Implicit {
    type Traced = Implicit;

    fn prepare(shape: &Instance<Self>) -> Implicit {
        // A validated scene's function parses; the fallback is never used.
        let f = Function::parse(&shape.f).unwrap_or_else(|_| Function::parse("1").unwrap());
        Implicit {
            placed: Placed::new(&shape.placement),
            f: Arc::new(f),
            bounds: shape.bounds,
            steps: shape.steps,
        }
    }
}

/// The part `[u0, u1]` of the local ray inside the box, clipped to
/// `[lo, hi]`: the slab test.
pub fn clip_to_box(ray: &LocalRay, bounds: [DVec3; 2], lo: f64, hi: f64) -> Option<(f64, f64)> {
    let (mut near, mut far) = (lo, hi);
    let [lo_corner, hi_corner] = bounds;
    for i in 0..3 {
        let (o, d) = (ray.q[i], ray.d[i]);
        if d == 0.0 {
            if o < lo_corner[i] || o > hi_corner[i] {
                return None;
            }
            continue;
        }
        let ta = (lo_corner[i] - o) / d;
        let tb = (hi_corner[i] - o) / d;
        near = near.max(ta.min(tb));
        far = far.min(ta.max(tb));
    }
    (near < far).then_some((near, far))
}

/// The first sign change of `g(u) = f(q + u d)` over `steps` equal steps of
/// `[u0, u1]`, refined by bisection to `ROOT_TOLERANCE` of the segment. A
/// sample that is NaN has no sign and brackets nothing.
pub fn first_root(f: &Function, ray: &LocalRay, u0: f64, u1: f64, steps: u32) -> Option<f64> {
    let g = |u: f64| f.value(ray.at(u));
    let step = (u1 - u0) / f64::from(steps);
    let mut a = u0;
    let mut ga = g(a);
    for i in 1..=steps {
        let b = if i == steps {
            u1
        } else {
            u0 + f64::from(i) * step
        };
        let gb = g(b);
        if gb == 0.0 && ga != 0.0 {
            return Some(b);
        }
        if (ga < 0.0 && gb > 0.0) || (ga > 0.0 && gb < 0.0) {
            return Some(bisect(&g, a, b, ga < 0.0, ROOT_TOLERANCE * (u1 - u0)));
        }
        (a, ga) = (b, gb);
    }
    None
}

/// Bisection of a sign change in `[a, b]` (`g(a) < 0` when `a_negative`)
/// until the bracket is `tolerance` wide; its midpoint.
fn bisect(
    g: &impl Fn(f64) -> f64,
    mut a: f64,
    mut b: f64,
    a_negative: bool,
    tolerance: f64,
) -> f64 {
    while b - a > tolerance {
        let mid = 0.5 * (a + b);
        if mid <= a || mid >= b {
            break;
        }
        let gm = g(mid);
        if gm == 0.0 {
            return mid;
        }
        if (gm < 0.0) == a_negative {
            a = mid;
        } else {
            b = mid;
        }
    }
    0.5 * (a + b)
}

/// The root is only known to `ROOT_TOLERANCE` of the segment, at most the
/// box's diagonal: rays leaving the surface start twice that off it (and no
/// less than the shape's size asks for), so that they never find the
/// surface they leave.
pub fn error_scale(implicit: &Implicit) -> f64 {
    let [lo, hi] = implicit.bounds;
    let diagonal = (hi - lo).length() * implicit.placed.scale;
    let extent = lo.abs().max(hi.abs()).length();
    offset_ray_scale(2.0 * ROOT_TOLERANCE * diagonal).max(implicit.placed.error_scale(extent))
}

/// The hit nearest to the ray origin with `0 < t < t_max`.
pub fn hit_implicit(implicit: &Implicit, ray: &Ray, t_max: f64) -> Option<Hit> {
    let local = implicit.placed.local(ray);
    let (u0, u1) = clip_to_box(&local, implicit.bounds, local.u(0.0), local.u(t_max))?;
    let u = first_root(&implicit.f, &local, u0, u1, implicit.steps)?;
    let (_, gradient) = implicit.f.value_and_gradient(local.at(u));
    let hit = implicit
        .placed
        .hit(&local, u, gradient, error_scale(implicit));
    (hit.t > 0.0 && hit.t < t_max).then_some(hit)
}
