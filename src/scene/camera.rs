//! The camera's basis and film size (docs/rendering-model.md, "Camera";
//! docs/implementation.md, "Camera"), computed once from the scene's
//! camera in f64: the reference traces with it, the GPU reads it rounded to
//! f32 (`Globals` in `src/gpu/layout.rs`), the viewer pans and places new
//! shapes with it.

use glam::DVec3;

use super::Camera;

/// Where the film is: the camera's orthonormal basis and the film's height
/// at unit distance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Film {
    /// Right on the film.
    pub u: DVec3,
    /// Up on the film.
    pub v: DVec3,
    /// Backwards, away from what we look at.
    pub w: DVec3,
    /// Film height at unit distance, `2 tan(fov / 2)`.
    pub height: f64,
}

impl Camera {
    /// The basis of `from`, `to` and `up` ([`camera_basis`]) and the film
    /// height of `fov`.
    pub fn film(&self) -> Film {
        let (u, v, w) = camera_basis(self.from, self.to, self.up);
        Film {
            u,
            v,
            w,
            height: 2.0 * (self.fov.to_radians() / 2.0).tan(),
        }
    }
}

/// The camera's orthonormal basis `(u, v, w)` (docs/rendering-model.md,
/// "Camera"): `w = normalize(from - to)`, `u = normalize(cross(up, w))`,
/// `v = cross(w, u)`.
///
/// When `up` is (nearly) parallel to the view, `cross(up, w)` is (nearly)
/// zero and `u` would be NaN or noise. The rendering model's rule then replaces `up` by
/// the coordinate axis along which `w` is smallest (x before y before z on a
/// tie), the axis most perpendicular to `w`. Looking straight down or up, `w`
/// is ±y and the replacement is x.
///
/// `up` is normalised first, so the rendering model's test `|cross(up, w)| < 1e-6 |up|` reads
/// `|cross(up, w)| < 1e-6`, and both normalisations divide by the largest
/// component first ([`normalize_or`]), so that no length over- or underflows.
/// Validation rejects `from == to` and `up == 0`; they still give a basis
/// here (`w = +z`, resp. the replaced `up`) so that no NaN can ever arise.
pub fn camera_basis(from: DVec3, to: DVec3, up: DVec3) -> (DVec3, DVec3, DVec3) {
    let w = normalize_or(from - to, DVec3::Z);
    let up = normalize_or(up, DVec3::ZERO);
    let up = if up.cross(w).length() < 1e-6 {
        smallest_axis(w)
    } else {
        up
    };
    let u = up.cross(w).normalize();
    let v = w.cross(u);
    (u, v, w)
}

/// `v / |v|`, computed as `(v / m) / |v / m|` with `m` the largest `|v_i|`,
/// so that the squares inside the length neither overflow (`|v| ~ 1e200`)
/// nor underflow (`|v| ~ 1e-200`); `fallback` for the zero vector (the
/// shader's `normalize_or`).
pub fn normalize_or(v: DVec3, fallback: DVec3) -> DVec3 {
    let m = v.abs().max_element();
    if m > 0.0 && m.is_finite() {
        (v / m).normalize()
    } else {
        fallback
    }
}

/// The unit axis of the smallest `|w_i|`, the first in x, y, z order on a tie.
fn smallest_axis(w: DVec3) -> DVec3 {
    let a = w.abs();
    if a.x <= a.y && a.x <= a.z {
        DVec3::X
    } else if a.y <= a.z {
        DVec3::Y
    } else {
        DVec3::Z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn basis_normal_case_by_hand() {
        // Looking from +z towards the origin: w = +z, u = +x, v = +y.
        let (u, v, w) = camera_basis(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, DVec3::Y);
        assert!(close(u, DVec3::X) && close(v, DVec3::Y) && close(w, DVec3::Z));
        // Looking from +x: w = +x, u = cross(y, x) = -z, v = cross(x, -z) = +y.
        // A non-unit `up` that is not perpendicular to w gives the same basis.
        let (u, v, w) = camera_basis(
            DVec3::new(3.0, 0.0, 0.0),
            DVec3::ZERO,
            DVec3::new(1.0, 2.0, 0.0),
        );
        assert!(close(u, -DVec3::Z) && close(v, DVec3::Y) && close(w, DVec3::X));
    }

    #[test]
    fn basis_is_orthonormal_and_right_handed() {
        let (u, v, w) = camera_basis(
            DVec3::new(0.0, 1.5, 6.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::Y,
        );
        for (a, b) in [(u, v), (v, w), (w, u)] {
            assert!(a.dot(b).abs() < 1e-15);
        }
        for a in [u, v, w] {
            assert!((a.length() - 1.0).abs() < 1e-15);
        }
        assert!(close(u.cross(v), w));
    }

    #[test]
    fn basis_looking_straight_down() {
        // w = +y, up = +y is degenerate. |w| = (0, 1, 0): x and z tie at 0,
        // x wins. u = cross(x, y) = +z, v = cross(y, z) = +x.
        let (u, v, w) = camera_basis(DVec3::new(0.0, 5.0, 0.0), DVec3::ZERO, DVec3::Y);
        assert_eq!((u, v, w), (DVec3::Z, DVec3::X, DVec3::Y));
    }

    #[test]
    fn basis_looking_straight_up() {
        // w = -y; up = x: u = cross(x, -y) = -z, v = cross(-y, -z) = +x.
        let (u, v, w) = camera_basis(DVec3::ZERO, DVec3::new(0.0, 5.0, 0.0), DVec3::Y);
        assert_eq!((u, v, w), (-DVec3::Z, DVec3::X, -DVec3::Y));
    }

    #[test]
    fn basis_nearly_parallel_up_is_degenerate() {
        // |cross(up, w)| = 1e-7 < 1e-6 |up|: replaced, as if exactly parallel
        // (kept, it would give u = -z).
        let up = DVec3::new(-1e-7, 1.0, 0.0);
        let (u, v, _) = camera_basis(DVec3::new(0.0, 5.0, 0.0), DVec3::ZERO, up);
        assert_eq!((u, v), (DVec3::Z, DVec3::X));
        // 1e-5 is well above the threshold: kept, u = normalize(cross(up, y)) = -z.
        let up = DVec3::new(-1e-5, 1.0, 0.0);
        let (u, _, _) = camera_basis(DVec3::new(0.0, 5.0, 0.0), DVec3::ZERO, up);
        assert!(close(u, -DVec3::Z));
    }

    #[test]
    fn basis_tie_rule() {
        // w = (1, 1, 1)/sqrt(3): all |w_i| tie, x wins.
        assert_eq!(smallest_axis(DVec3::splat(1.0).normalize()), DVec3::X);
        // y and z tie below x: y wins.
        assert_eq!(smallest_axis(DVec3::new(0.8, 0.6, -0.6)), DVec3::Y);
        assert_eq!(smallest_axis(DVec3::new(0.8, 0.6, 0.0)), DVec3::Z);
        let (u, v, w) = camera_basis(DVec3::ONE, DVec3::ZERO, DVec3::ONE);
        let s = 1.0 / 3.0_f64.sqrt();
        assert!(close(w, DVec3::splat(s)));
        // up = x: u = normalize(cross(x, w)) = (0, -1, 1)/sqrt(2).
        assert!(close(u, DVec3::new(0.0, -1.0, 1.0).normalize()));
        assert!(close(v, w.cross(u)));
    }

    #[test]
    fn basis_never_nan() {
        for (from, to, up) in [
            (DVec3::ONE, DVec3::ONE, DVec3::Y),
            (DVec3::ZERO, DVec3::Z, DVec3::ZERO),
            (DVec3::ZERO, -DVec3::Z, DVec3::new(0.0, 0.0, 1e-300)),
        ] {
            let (u, v, w) = camera_basis(from, to, up);
            assert!(
                !(u.is_nan() || v.is_nan() || w.is_nan()),
                "{from} {to} {up}"
            );
        }
    }

    #[test]
    fn basis_survives_tiny_and_huge_distances() {
        // Eye and target 1e-200 or 1e200 apart: |from - to|^2 under- or
        // overflows, the scaled normalisation does not.
        for scale in [1e-200, 1e-30, 1.0, 1e30, 1e200] {
            let from = DVec3::new(0.3, -0.4, 1.2) * scale;
            let (u, v, w) = camera_basis(from, DVec3::ZERO, DVec3::Y);
            assert!(
                close(w, DVec3::new(0.3, -0.4, 1.2).normalize()),
                "{scale}: {w}"
            );
            assert!((u.length() - 1.0).abs() < 1e-15 && (v.length() - 1.0).abs() < 1e-15);
            assert!(u.dot(w).abs() < 1e-15);
        }
        // A tiny up is as good as a unit one.
        let (u, _, _) = camera_basis(DVec3::Z, DVec3::ZERO, DVec3::Y * 1e-300);
        assert!(close(u, DVec3::X));
        assert_eq!(normalize_or(DVec3::ZERO, DVec3::X), DVec3::X);
        assert_eq!(
            normalize_or(DVec3::new(0.0, 5e-324, 0.0), DVec3::X),
            DVec3::Y
        );
    }
}
