//! Rays, and the offset that keeps a secondary ray from hitting the surface it
//! starts on.

use glam::DVec3;

/// The ray `origin + t * dir`.
///
/// `dir` is always unit length (docs/implementation.md, "Rays"): [`Ray::new`]
/// normalises it. The intersection routines rely on this, e.g. the sphere's
/// quadratic then has `a = 1`, and `t` is a distance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    pub origin: DVec3,
    pub dir: DVec3,
}

impl Ray {
    /// A ray from `origin` along `dir`, which must not be zero (every caller
    /// makes directions that have length 1 up to rounding, or checks first).
    pub fn new(origin: DVec3, dir: DVec3) -> Self {
        Self {
            origin,
            dir: dir.normalize(),
        }
    }

    /// The point at parameter `t`.
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.dir
    }
}

/// The offset is 256 units in the last place of the scale: `256 * 2^-52`.
const OFFSET_ULPS: f64 = 256.0 * f64::EPSILON;
/// Below this scale the offset stops shrinking (Wächter and Binder's
/// "origin"), so that tiny scenes at the origin still get a usable offset.
const MIN_SCALE: f64 = 1.0 / 32.0;

/// Moves the surface point `p` off the surface, to the side that the unit
/// vector `n` points to, by `256 * eps * max(|p|_max, error_scale, 1/32)`
/// (`eps = 2^-52`).
///
/// Why: a computed hit point is off the true surface by rounding error, and
/// so is the test of a new ray against that surface; unless the new ray
/// starts farther away than both errors, it can hit its own surface at
/// `t ~ 0` ("shadow acne"). A fixed epsilon is too large in small scenes and
/// too small in large ones. The rounding errors are a few `eps` times the
/// magnitude of the numbers involved: the coordinates of `p` and the size and
/// position of the shape (`error_scale`, see `Hit`). 256 times that is far
/// above the error and still only ~6e-14 of the scale.
///
/// This follows the idea of Wächter and Binder, "A Fast and Robust Method for
/// Avoiding Self-Intersection" (Ray Tracing Gems ch. 6: 256 ulps, an absolute
/// floor near the origin), but measures the ulps at the scale of the shape
/// instead of at each coordinate of `p`. Their per-coordinate rule assumes the
/// error of `p` scales with `|p|`, which fails for our shapes: on the classic
/// ground sphere (centre y = -1000, radius 1000) a point near y = 0 has an
/// error of ~1e-13 from the centre's magnitude, while an offset scaled by
/// `|p_y|` is ~1e-14, and half the lit ground came out shadowed. See
/// docs/implementation.md, "Offsets", for the shader's side.
pub fn offset_ray(p: DVec3, n: DVec3, error_scale: f64) -> DVec3 {
    let scale = p.abs().max_element().max(error_scale).max(MIN_SCALE);
    p + (OFFSET_ULPS * scale) * n
}

/// The `error_scale` for which [`offset_ray`] moves a point (at least)
/// `distance` off its surface: for a shape whose rule names the distance,
/// the Julia set's `2 epsilon` (docs/rendering-model.md, "Implicit surfaces").
pub fn offset_ray_scale(distance: f64) -> f64 {
    distance / OFFSET_ULPS
}

/// The textbook offset (the naive variant, `ReferenceOptions::robust =
/// false`, the shader's `NAIVE_OFFSET`): a fixed `1e-3` along `n`, whatever
/// the size of the scene.
pub fn offset_ray_naive(p: DVec3, n: DVec3) -> DVec3 {
    p + 1e-3 * n
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_direction_is_normalised() {
        let r = Ray::new(DVec3::ZERO, DVec3::new(3.0, 0.0, 4.0));
        assert!((r.dir - DVec3::new(0.6, 0.0, 0.8)).length() < 1e-15);
        assert!((r.at(5.0) - DVec3::new(3.0, 0.0, 4.0)).length() < 1e-14);
    }

    #[test]
    fn offset_moves_away_along_the_normal() {
        let n = DVec3::new(1.0, 1.0, 1.0).normalize();
        for p in [
            DVec3::new(1.0, 2.0, -3.0),
            DVec3::new(-100.0, 0.01, 7.5),
            DVec3::ZERO,
        ] {
            let o = offset_ray(p, n, 0.0);
            assert!((o - p).dot(n) > 0.0, "{p} -> {o}");
            assert!(o.x > p.x && o.y > p.y && o.z > p.z, "{p} -> {o}");
            let back = offset_ray(p, -n, 0.0);
            assert!(
                back.x < p.x && back.y < p.y && back.z < p.z,
                "{p} -> {back}"
            );
        }
    }

    #[test]
    fn offset_scales_with_p_and_with_the_shape() {
        // 256 ulps of 1 = 2^-44 at |p| = 1, along n only.
        let o = offset_ray(DVec3::new(1.0, -1.0, 0.0), DVec3::X, 0.0);
        assert_eq!(o, DVec3::new(1.0 + 2f64.powi(-44), -1.0, 0.0));
        // The largest coordinate sets the scale.
        let far = offset_ray(DVec3::new(1.0, -1024.0, 0.0), DVec3::X, 0.0);
        assert_eq!(far.x - 1.0, 1024.0 * 2f64.powi(-44));
        // A large shape raises it: a point near y = 0 on the ground sphere.
        let ground = offset_ray(DVec3::new(0.0, 1e-3, 0.0), DVec3::Y, 2000.0);
        assert!((ground.y - 1e-3 - 2000.0 * 2f64.powi(-44)).abs() < 1e-18);
        // Near the origin the floor 1/32 applies.
        let small = offset_ray(DVec3::new(0.001, 0.0, 0.0), -DVec3::X, 0.01);
        assert_eq!(small.x, 0.001 - 2f64.powi(-49));
        // Well within the rendering model's "at most 1e-4 of max(1, |p|)" for small shapes.
        assert!(far.x - 1.0 < 1e-4 * 1024.0);
    }
}
