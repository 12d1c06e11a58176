//! An infinite, two-sided, thin plane for the f64 tracer (docs/rendering-model.md, "Shapes").

use glam::DVec3;

use super::{Prepare, Trace, robust_or_naive};
use crate::reference::ReferenceOptions;
use crate::reference::hit::{Hit, foot};
use crate::reference::ray::Ray;
use crate::scene::{self, Instance};

/// An infinite, two-sided, thin plane with unit `normal`.
#[derive(Debug, Clone)]
pub struct Plane {
    pub point: DVec3,
    pub normal: DVec3,
    /// `|point|_max`, see [`Hit::error_scale`].
    pub error_scale: f64,
}

impl Plane {
    /// `normal` is normalised here; a zero normal (which validation rejects)
    /// gives a plane that every ray misses.
    pub fn new(point: DVec3, normal: DVec3) -> Self {
        Self {
            point,
            normal: normal.normalize_or_zero(),
            error_scale: point.abs().max_element(),
        }
    }
}

impl Prepare for scene::Plane {
    type Traced = Plane;

    /// Loading normalises plane normals already; `Plane::new` does it again
    /// for scenes built by hand.
    fn prepare(shape: &Instance<Self>) -> Plane {
        Plane::new(shape.point, shape.normal)
    }
}

impl Trace for Plane {
    fn hit(&self, ray: &Ray, t_max: f64, options: &ReferenceOptions) -> Option<Hit> {
        robust_or_naive(options, hit_plane, hit_plane_naive)(self, ray, t_max)
    }
}

/// The plane hit with `0 < t < t_max`.
///
/// `t = ((point - o).n) / (n.d)`. A ray parallel to the plane (`n.d = 0`, or
/// so small that `t` would be astronomically large) misses: the test
/// `|num| < |denom| 1e38` rejects it without ever forming inf or NaN. The hit
/// point is `o + t d` or, when that involves larger numbers (a plane seen from
/// far away), `point + q` from the foot of the perpendicular from `point`
/// ([`foot`]), then re-projected onto the plane. `t` stays the plain
/// quotient, so that a box face lying in the plane ties with it exactly.
pub fn hit_plane(plane: &Plane, ray: &Ray, t_max: f64) -> Option<Hit> {
    let n = plane.normal;
    let denom = n.dot(ray.dir);
    let num = (plane.point - ray.origin).dot(n);
    // A hit needs |num| < |denom| 1e38; with denom = 0 nothing is below 0.
    if num.abs() >= denom.abs() * 1e38 {
        return None;
    }
    let t = num / denom;
    if t <= 0.0 || t >= t_max {
        return None;
    }
    let (g, _) = foot(ray, plane.point);
    let t_foot = -g.dot(n) / denom;
    let mut p =
        if ray.origin.abs().max_element() + t > plane.point.abs().max_element() + t_foot.abs() {
            plane.point + (g + t_foot * ray.dir)
        } else {
            ray.at(t)
        };
    p -= (p - plane.point).dot(n) * n;
    Some(Hit::new(t, p, n, plane.error_scale))
}

/// The lecture's plane (the naive variant, the shader's `hit_plane_naive`):
/// parallel when `|n.d| < 1e-6`, else `t = ((point - o).n) / (n.d)` and the
/// hit point `o + t d`, not re-projected.
pub fn hit_plane_naive(plane: &Plane, ray: &Ray, t_max: f64) -> Option<Hit> {
    let n = plane.normal;
    let denom = n.dot(ray.dir);
    if denom.abs() < 1e-6 {
        return None;
    }
    let t = (plane.point - ray.origin).dot(n) / denom;
    if t <= 0.0 || t >= t_max {
        return None;
    }
    Some(Hit::new(t, ray.at(t), n, 0.0))
}
