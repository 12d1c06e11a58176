//! The lecture's pinhole camera with the film one unit in front of the eye,
//! plus the optional thin lens (docs/rendering-model.md, "Camera").

use glam::{DVec2, DVec3};

use super::ray::Ray;
use crate::scene::{self, normalize_or};

/// The camera as tracing needs it: eye, orthonormal basis and film size.
#[derive(Debug, Clone)]
pub struct Camera {
    /// The eye `e`, the camera's `from`.
    pub from: DVec3,
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
        let film = camera.film();
        Self {
            from: camera.from,
            u: film.u,
            v: film.v,
            w: film.w,
            film_height: film.height,
            aperture: camera.aperture,
            focus_distance: camera.focus_distance(),
        }
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
        return Ray::new(cam.from, film);
    }
    let lens_offset = cam.aperture * (lens.x * cam.u + lens.y * cam.v);
    let dir = cam.focus_distance * film - lens_offset;
    Ray::new(cam.from + lens_offset, normalize_or(dir, -cam.w))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
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
            let expected_origin = cam.from + 0.25 * (lens.x * cam.u + lens.y * cam.v);
            assert!(close(ray.origin, expected_origin));
            let t = (focus - ray.origin).dot(ray.dir);
            assert!(close(ray.at(t), focus), "lens {lens}");
        }
    }
}
