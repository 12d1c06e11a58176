//! An infinite, two-sided, thin plane for the f64 tracer (docs/rendering-model.md, "Shapes").

use glam::DVec3;

use super::{Prepare, traced_by};
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

traced_by!(Plane: hit_plane, hit_plane_naive);

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::shapes::test_rays::ray;

    fn floor_plane() -> Plane {
        Plane::new(DVec3::new(0.0, -1.0, 0.0), DVec3::Y)
    }

    #[test]
    fn plane_hit_from_either_side() {
        let p = floor_plane();
        let hit = hit_plane(&p, &ray([0.0; 3], [0.0, -1.0, 0.0]), f64::INFINITY).unwrap();
        assert_eq!((hit.t, hit.p, hit.n), (1.0, -DVec3::Y, DVec3::Y));
        // From behind: the normal is still the declared (outward) one.
        let hit = hit_plane(&p, &ray([2.0, -3.0, 0.0], [0.0, 1.0, 0.0]), f64::INFINITY).unwrap();
        assert_eq!(
            (hit.t, hit.p, hit.n),
            (2.0, DVec3::new(2.0, -1.0, 0.0), DVec3::Y)
        );
        // Oblique: 45 degrees down, t = sqrt(2).
        let hit = hit_plane(&p, &ray([0.0; 3], [1.0, -1.0, 0.0]), f64::INFINITY).unwrap();
        assert!((hit.t - 2f64.sqrt()).abs() < 1e-15);
        assert_eq!(hit.p.y, -1.0, "re-projected exactly onto the plane");
    }

    #[test]
    fn plane_misses() {
        let p = floor_plane();
        // Parallel, above and inside the plane.
        assert!(hit_plane(&p, &ray([0.0; 3], [1.0, 0.0, 0.0]), f64::INFINITY).is_none());
        assert!(hit_plane(&p, &ray([0.0, -1.0, 0.0], [1.0, 0.0, 1.0]), f64::INFINITY).is_none());
        // Nearly parallel: t would exceed 1e38.
        assert!(hit_plane(&p, &ray([0.0; 3], [1.0, -1e-39, 0.0]), f64::INFINITY).is_none());
        // Going away.
        assert!(hit_plane(&p, &ray([0.0; 3], [0.0, 1.0, 0.0]), f64::INFINITY).is_none());
        // Beyond t_max.
        assert!(hit_plane(&p, &ray([0.0; 3], [0.0, -1.0, 0.0]), 1.0).is_none());
    }
}
