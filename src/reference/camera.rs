//! The lecture's pinhole camera with the film one unit in front of the eye,
//! plus the optional thin lens (docs/rendering-model.md, "Camera").

use glam::{DVec2, DVec3};

use super::ray::Ray;
use crate::scene;

/// The camera as tracing needs it: eye, orthonormal basis and film size.
#[derive(Debug, Clone)]
pub struct Camera {
    /// The eye `e` (`from`).
    pub eye: DVec3,
    /// Right on the film.
    pub u: DVec3,
    /// Up on the film.
    pub v: DVec3,
    /// Backwards, away from what we look at.
    pub w: DVec3,
    /// Film height at unit distance, `2 tan(fov / 2)`.
    pub film_height: f64,
    /// Lens radius; 0 is a pinhole.
    pub aperture: f64,
    /// Distance from the eye to the plane in focus.
    pub focus_distance: f64,
}

impl Camera {
    pub fn new(camera: &scene::Camera) -> Self {
        let (u, v, w) = camera_basis(camera.from, camera.to, camera.up);
        Self {
            eye: camera.from,
            u,
            v,
            w,
            film_height: 2.0 * (camera.fov.to_radians() / 2.0).tan(),
            aperture: camera.aperture,
            focus_distance: camera.focus_distance(),
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
/// As in the shader (`camera_basis` in `shaders/camera.wgsl`), `up` is
/// normalised first, so the rendering model's test `|cross(up, w)| < 1e-6 |up|` reads
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

/// The camera ray through the film point `(px, py)` of a `width x height`
/// image, in pixel units: pixel `(i, j)` with sample offset `(sx, sy)` is
/// `(i + sx, j + sy)`, and `(0, 0)` is the top left corner of the film.
/// `lens` is a point of the unit disk; `(0, 0)` is the lens centre.
///
/// docs/rendering-model.md, "Camera": the film point is `x u + y v - w` from the eye with
/// `x = (h W / H) (px / W - 0.5)` and `y = h (0.5 - py / H)`. The film size
/// depends only on `fov` and the aspect ratio, never on the resolution.
///
/// Thin lens (docs/implementation.md, "Camera"): the ray leaves the lens point
/// `o = e + aperture (a u + b v)` towards the focus point
/// `P = e + fd (x u + y v - w)`. Its direction is computed as
/// `fd (x u + y v - w) - aperture (a u + b v)`, from the basis, rather than as
/// `P - o`: two far-away world points would cancel and lose digits. With
/// `aperture = 0` or the lens centre this is the pinhole ray.
pub fn camera_ray(cam: &Camera, width: u32, height: u32, px: f64, py: f64, lens: DVec2) -> Ray {
    let (w_px, h_px) = (f64::from(width), f64::from(height));
    let h = cam.film_height;
    let x = (h * w_px / h_px) * (px / w_px - 0.5);
    let y = h * (0.5 - py / h_px);
    let film = x * cam.u + y * cam.v - cam.w;
    if cam.aperture <= 0.0 {
        // The pinhole, as the shader's branch: never scaled by the focus
        // distance, which is 0 when eye and target coincide after rounding.
        return Ray::new(cam.eye, film);
    }
    let lens_offset = cam.aperture * (lens.x * cam.u + lens.y * cam.v);
    let dir = cam.focus_distance * film - lens_offset;
    Ray::new(cam.eye + lens_offset, normalize_or(dir, -cam.w))
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

    #[test]
    fn pinhole_ray_does_not_need_a_focus_distance() {
        // Eye and target equal (as after rounding to f32): focus distance 0,
        // the pinhole ray still points along -w = -z.
        let mut cam = camera(45.0);
        cam.focus_distance = 0.0;
        let ray = camera_ray(&cam, 3, 3, 1.5, 1.5, DVec2::ZERO);
        assert!(close(ray.dir, -DVec3::Z), "{}", ray.dir);
    }

    fn camera(fov: f64) -> Camera {
        Camera::new(&scene::Camera {
            from: DVec3::ZERO,
            to: -DVec3::Z,
            up: DVec3::Y,
            fov,
            aperture: 0.0,
            focus_distance: None,
        })
    }

    #[test]
    fn ray_through_the_centre_pixel() {
        // 3 x 3 pixels: the centre of pixel (1, 1) is the film centre.
        let ray = camera_ray(&camera(45.0), 3, 3, 1.5, 1.5, DVec2::ZERO);
        assert_eq!(ray.origin, DVec3::ZERO);
        assert!(close(ray.dir, -DVec3::Z));
    }

    #[test]
    fn ray_through_the_top_left_pixel() {
        // fov 90: h = 2, film 4 x 2 at unit distance for a 4 x 2 image.
        // Pixel (0, 0) centre: x = 4 (0.5/4 - 0.5) = -1.5, y = 2 (0.5 - 0.5/2) = 0.5.
        let ray = camera_ray(&camera(90.0), 4, 2, 0.5, 0.5, DVec2::ZERO);
        assert!(close(ray.dir, DVec3::new(-1.5, 0.5, -1.0).normalize()));
        // Bottom right corner of the film: x = 2, y = -1.
        let ray = camera_ray(&camera(90.0), 4, 2, 4.0, 2.0, DVec2::ZERO);
        assert!(close(ray.dir, DVec3::new(2.0, -1.0, -1.0).normalize()));
    }

    #[test]
    fn film_size_does_not_depend_on_resolution() {
        let cam = camera(60.0);
        let a = camera_ray(&cam, 64, 48, 16.0, 12.0, DVec2::ZERO);
        let b = camera_ray(&cam, 640, 480, 160.0, 120.0, DVec2::ZERO);
        assert!(close(a.dir, b.dir));
    }

    #[test]
    fn thin_lens_rays_meet_at_the_focus_point() {
        let mut cam = camera(45.0);
        cam.aperture = 0.25;
        cam.focus_distance = 3.0;
        let (px, py) = (10.3, 4.7);
        let pinhole = camera_ray(&cam, 32, 16, px, py, DVec2::ZERO);
        // P = e + fd (x u + y v - w); the film point is one unit along -w.
        let focus = pinhole.origin + pinhole.dir * (3.0 / pinhole.dir.dot(-cam.w));
        for lens in [
            DVec2::new(1.0, 0.0),
            DVec2::new(-0.3, 0.6),
            DVec2::new(0.0, -1.0),
        ] {
            let ray = camera_ray(&cam, 32, 16, px, py, lens);
            let expected_origin = cam.eye + 0.25 * (lens.x * cam.u + lens.y * cam.v);
            assert!(close(ray.origin, expected_origin));
            let t = (focus - ray.origin).dot(ray.dir);
            assert!(close(ray.at(t), focus), "lens {lens}");
        }
    }
}
