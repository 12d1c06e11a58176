//! A sphere for the f64 tracer (docs/rendering-model.md, "Shapes").

use glam::DVec3;
use num_traits::Float;

use super::{Prepare, traced_by};
use crate::reference::hit::{Hit, foot, major_axis};
use crate::reference::ray::Ray;
use crate::scene::{self, Instance};

/// A sphere; `material` indexes `PreparedScene::materials`.
#[derive(Debug, Clone)]
pub struct Sphere {
    pub center: DVec3,
    pub radius: f64,
}

traced_by!(Sphere: hit_sphere, hit_sphere_naive);

impl Sphere {
    pub fn new(center: DVec3, radius: f64) -> Self {
        Self { center, radius }
    }
}

impl Prepare for scene::Sphere {
    type Traced = Sphere;

    fn prepare(shape: &Instance<Self>) -> Sphere {
        Sphere::new(shape.center, shape.radius)
    }

    /// The sphere's texture coordinates ([`uv`]).
    fn view_coordinates(hit: &Hit) -> [f64; 3] {
        uv(hit.n)
    }
}

/// A sphere's texture coordinates at the outward normal `n`: `u` the
/// longitude about +y from -x (`0.5 + atan2(n.z, n.x) / 2 pi`), `v` the
/// colatitude from +y (`acos(n.y) / pi`); the third is 0.
pub fn uv(n: DVec3) -> [f64; 3] {
    use std::f64::consts::PI;
    [
        0.5 + n.z.atan2(n.x) / (2.0 * PI),
        n.y.clamp(-1.0, 1.0).acos() / PI,
        0.0,
    ]
}

/// The sphere hit nearest to the ray origin with `0 < t < t_max`.
///
/// Numerics (docs/implementation.md, docs/accuracy.md; Haines, Günther and
/// Akenine-Möller, "Precision Improvements for Ray/Sphere Intersection", Ray
/// Tracing Gems ch. 7): with unit `d` and `f = o - c` the quadratic is
/// `t^2 + 2 b t + c = 0`, `b = f.d`. The textbook discriminant `b^2 - c`
/// cancels catastrophically for small spheres far away; the equivalent
/// `r^2 - |g|^2` with `g = f - b d` (Hearn and Baker) measures the squared
/// distance from the centre to the ray directly. The roots come from
/// `q = -(b + sign(b) sqrt(disc))` as `q` and `c / q`, which never subtracts
/// nearly equal numbers (Press et al., Numerical Recipes 5.6).
///
/// Refinements for scenes with large numbers, the same as the shader's:
/// - `g` is perpendicular to `d`, so one Gram-Schmidt step (`g -= (g.d) d`)
///   removes the rounding error of `f - b d` along `d`;
/// - `c = |f|^2 - r^2` is formed as `(f - r u).(f + r u) = |s|^2 + 2 r s.u`
///   with `u` the major axis of `f` and `s = o - (centre + r u)`, the origin
///   relative to the sphere's nearest pole: on a huge ground sphere `f` is
///   rounded at the scale of the radius, `s` is not;
/// - with `c` that accurate, the textbook `b^2 - c` has the rounding error
///   `eps (b^2 + |c|)` against `eps r^2` for `r^2 - |g|^2`; the smaller wins
///   (near a huge sphere, e.g. at its horizon, the first);
/// - the normal is `normalize(g -+ sqrt(disc) d)` (`f + t d` for the near and
///   the far root, `t = -b -+ sqrt(disc)`), and the hit point is `o + t d`
///   when those numbers are smaller than the centre's, else the re-projection
///   `centre + r n`.
///
/// From inside (`c < 0`) the roots have opposite signs and the far one is
/// hit. `error_scale` is the size of the numbers the hit point and a later
/// test against this sphere involve (see [`Hit::error_scale`]).
pub fn hit_sphere(sphere: &Sphere, ray: &Ray, t_max: f64) -> Option<Hit> {
    let (d, r, centre) = (ray.dir, sphere.radius, sphere.center);
    let f = ray.origin - centre;
    let b = f.dot(d);
    let g = foot(ray, centre).0;
    let u = major_axis(f);
    let from_pole = ray.origin - (centre + r * u);
    let c = from_pole.length_squared() + 2.0 * r * from_pole.dot(u);
    // Of the discriminant's two forms, the one with the smaller rounding
    // error: eps r^2 for r^2 - |g|^2, eps (b^2 + |c|) for b^2 - c.
    let disc = if b * b + c.abs() < r * r {
        b * b - c
    } else {
        r * r - g.length_squared()
    };
    if disc < 0.0 || r * r == 0.0 {
        return None;
    }
    let h = disc.sqrt();
    let sign_b = if b >= 0.0 { 1.0 } else { -1.0 }; // sign(0) = +1
    let q = -(b + sign_b * h);
    if q == 0.0 {
        return None;
    }
    let (t0, t1) = (c / q, q);
    let (near, far) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
    // The near root is -b - sqrt(disc), the far one -b + sqrt(disc).
    let (t, along) = if near > 0.0 && near < t_max {
        (near, -h)
    } else if far > 0.0 && far < t_max {
        (far, h)
    } else {
        return None;
    };
    let n = (g + along * d).normalize();
    let ray_scale = ray.origin.abs().max_element() + t;
    let centre_scale = centre.abs().max_element() + r;
    let p = if ray_scale < centre_scale {
        ray.at(t)
    } else {
        centre + r * n
    };
    let pole_scale = (centre + r * major_axis(n)).abs().max_element();
    Some(Hit::new(
        t,
        p,
        n,
        pole_scale.max(ray_scale.min(centre_scale)),
    ))
}

/// The lecture's sphere (the naive variant, `ReferenceOptions::robust =
/// false`, the shader's `hit_sphere_naive`): `a t^2 + b t + c = 0` with
/// `a = d.d`, `b = 2 f.d`, `c = f.f - r^2`, `disc = b^2 - 4ac` and
/// `t = (-b -+ sqrt(disc)) / 2a`; the hit point `o + t d` and the normal
/// `(p - c) / r` (docs/rendering-model.md, "Shapes").
pub fn hit_sphere_naive(sphere: &Sphere, ray: &Ray, t_max: f64) -> Option<Hit> {
    let d = ray.dir;
    let f = ray.origin - sphere.center;
    let a = d.dot(d);
    let b = 2.0 * f.dot(d);
    let c = f.dot(f) - sphere.radius * sphere.radius;
    let t = naive_root(a, b, c, t_max)?;
    let p = ray.at(t);
    Some(Hit::new(t, p, (p - sphere.center) / sphere.radius, 0.0))
}

/// The naive sphere's root of `a t^2 + b t + c` in any float type (f64
/// here, f32 in the port of the shader, `src/stress/f32_intersect.rs`):
/// `(-b - sqrt(disc)) / 2a`, else `(-b + sqrt(disc)) / 2a`, if in
/// `(0, t_max)`.
pub fn naive_root<T: Float>(a: T, b: T, c: T, t_max: T) -> Option<T> {
    let (zero, two) = (T::zero(), T::one() + T::one());
    let disc = b * b - (two + two) * a * c;
    if disc < zero {
        return None;
    }
    let mut t = (-b - disc.sqrt()) / (two * a);
    if t <= zero {
        t = (-b + disc.sqrt()) / (two * a);
    }
    if t <= zero || t >= t_max {
        return None;
    }
    Some(t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::shapes::test_rays::{close, ray};
    use proptest::prelude::*;

    fn unit_sphere_at(c: [f64; 3]) -> Sphere {
        Sphere::new(DVec3::from(c), 1.0)
    }

    #[test]
    fn sphere_from_outside() {
        let s = unit_sphere_at([0.0, 0.0, -5.0]);
        let hit = hit_sphere(&s, &ray([0.0; 3], [0.0, 0.0, -1.0]), f64::INFINITY).unwrap();
        assert_eq!(hit.t, 4.0);
        assert_eq!(hit.p, DVec3::new(0.0, 0.0, -4.0));
        assert_eq!(hit.n, DVec3::Z);
        // Off centre: x = 0.6 meets the sphere where z = -5 + 0.8.
        let hit = hit_sphere(&s, &ray([0.6, 0.0, 0.0], [0.0, 0.0, -1.0]), 10.0).unwrap();
        assert!((hit.t - 4.2).abs() < 1e-14);
        assert!(close(hit.n, DVec3::new(0.6, 0.0, 0.8)));
        // Nearer than t_max only.
        assert!(hit_sphere(&s, &ray([0.0; 3], [0.0, 0.0, -1.0]), 4.0).is_none());
    }

    #[test]
    fn sphere_from_inside_hits_the_far_side() {
        let s = unit_sphere_at([1.0, 2.0, 3.0]);
        let hit = hit_sphere(&s, &ray([1.0, 2.0, 3.0], [1.0, 0.0, 0.0]), f64::INFINITY).unwrap();
        assert_eq!(hit.t, 1.0);
        assert_eq!(hit.n, DVec3::X, "outward, along the ray");
        let hit = hit_sphere(&s, &ray([1.0, 2.0, 2.5], [0.0, 0.0, 1.0]), f64::INFINITY).unwrap();
        assert!((hit.t - 1.5).abs() < 1e-15);
        assert!(close(hit.p, DVec3::new(1.0, 2.0, 4.0)));
    }

    #[test]
    fn sphere_tangent_ish() {
        let s = unit_sphere_at([0.0, 0.0, -5.0]);
        let y: f64 = 1.0 - 1e-9;
        let hit = hit_sphere(&s, &ray([0.0, y, 0.0], [0.0, 0.0, -1.0]), f64::INFINITY).unwrap();
        // z^2 = 1 - y^2 = (1 - y)(1 + y), the near root at t = 5 - |z|.
        let z = ((1.0 - y) * (1.0 + y)).sqrt();
        // Near tangency t is ill-conditioned: 1 - y^2 has a relative error
        // of ~1e-16 / 2e-9, and z of half that.
        assert!(
            (hit.t - (5.0 - z)).abs() < 1e-10,
            "{} vs {}",
            hit.t,
            5.0 - z
        );
        assert!(hit.n.y > 0.999_999 && (hit.n.length() - 1.0).abs() < 1e-15);
        assert!(
            hit_sphere(
                &s,
                &ray([0.0, 1.0 + 1e-9, 0.0], [0.0, 0.0, -1.0]),
                f64::INFINITY
            )
            .is_none()
        );
    }

    #[test]
    fn sphere_behind_the_ray_is_missed() {
        let s = unit_sphere_at([0.0, 0.0, 5.0]);
        assert!(hit_sphere(&s, &ray([0.0; 3], [0.0, 0.0, -1.0]), f64::INFINITY).is_none());
        // Starting on the surface and leaving: the root at t = 0 is rejected.
        let s = unit_sphere_at([0.0, 0.0, -1.0]);
        assert!(hit_sphere(&s, &ray([0.0; 3], [0.0, 0.0, 1.0]), f64::INFINITY).is_none());
    }

    #[test]
    fn small_sphere_far_away() {
        // The textbook b^2 - c loses every digit here; r^2 - |f - b d|^2 does not.
        let s = Sphere::new(DVec3::new(0.0, 0.0, -1e6), 1e-3);
        let hit = hit_sphere(&s, &ray([0.0, 5e-4, 0.0], [0.0, 0.0, -1.0]), f64::INFINITY).unwrap();
        let z = (1e-6_f64 - 25e-8).sqrt();
        // Points near z = -1e6 are only known to ~1e-10 (an ulp), which
        // limits t and, over a radius of 1e-3, the normal.
        assert!((hit.t - (1e6 - z)).abs() < 1e-9);
        let n = DVec3::new(0.0, 0.5, 0.75f64.sqrt());
        assert!((hit.n - n).length() < 1e-6);
    }

    proptest! {
        /// Rays from anywhere that hit a sphere, from outside or from inside,
        /// hit its surface, with a unit normal facing the ray from outside.
        #[test]
        fn sphere_hits_lie_on_the_surface(
            origin in prop::array::uniform3(-10.0..10.0f64),
            dir in prop::array::uniform3(-1.0..1.0f64),
            radius in 0.01..5.0f64,
        ) {
            let dir = DVec3::from(dir);
            prop_assume!(dir.length() > 0.1);
            let s = Sphere::new(DVec3::new(1.0, 2.0, 3.0), radius);
            let r = Ray::new(DVec3::from(origin), dir);
            if let Some(hit) = hit_sphere(&s, &r, f64::INFINITY) {
                prop_assert!(hit.t > 0.0);
                prop_assert!(((hit.p - s.center).length() - radius).abs() < 1e-12 * 10.0);
                prop_assert!((r.at(hit.t) - hit.p).length() < 1e-9);
                let inside = (r.origin - s.center).length() < radius;
                prop_assert_eq!(hit.n.dot(r.dir) > 0.0, inside);
            }
        }
    }
}
