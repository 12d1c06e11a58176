//! Orbit camera control, as in Blender or three.js OrbitControls: the eye moves
//! on a sphere around the target `to`, with the camera's `up` as the pole.
//!
//! Every operation keeps the camera valid for the rendering model (from != to, finite)
//! and never produces NaN, whatever the input: elevation is clamped short of
//! the poles and the distance never reaches zero.

use glam::DVec3;

use crate::scene::Camera;

/// Elevation limit: 89.5 degrees, so the view never flips over the pole.
const MAX_ELEVATION: f64 = 89.5 * std::f64::consts::PI / 180.0;

/// Closest the eye may come to the target, relative to the distance at which
/// the interaction started (a zoom can only shrink it by this factor).
const MIN_DISTANCE_FRACTION: f64 = 1e-4;

/// Radians of orbit per pixel of mouse motion.
const ORBIT_SPEED: f64 = 0.008;

/// Orthonormal frame whose third axis is the pole (the camera's up).
fn pole_frame(up: DVec3) -> (DVec3, DVec3, DVec3) {
    let pole = up.try_normalize().unwrap_or(DVec3::Y);
    let e1 = pole.any_orthonormal_vector();
    let e2 = pole.cross(e1);
    (e1, e2, pole)
}

/// (distance, azimuth, elevation) of `from` around `to`.
fn spherical(camera: &Camera) -> (f64, f64, f64) {
    let (e1, e2, pole) = pole_frame(camera.up);
    let offset = camera.from - camera.to;
    let distance = offset.length();
    let azimuth = offset.dot(e2).atan2(offset.dot(e1));
    let elevation = (offset.dot(pole) / distance).clamp(-1.0, 1.0).asin();
    (distance, azimuth, elevation)
}

fn from_spherical(camera: &mut Camera, distance: f64, azimuth: f64, elevation: f64) {
    let (e1, e2, pole) = pole_frame(camera.up);
    let el = elevation.clamp(-MAX_ELEVATION, MAX_ELEVATION);
    let dir = el.cos() * (azimuth.cos() * e1 + azimuth.sin() * e2) + el.sin() * pole;
    camera.from = camera.to + distance * dir;
}

/// Left-drag: turns the eye around `to` by a mouse motion of (dx, dy) pixels.
/// Dragging right turns the scene right (the eye goes left), dragging down
/// looks from higher up, as in Blender.
pub fn orbit(camera: &mut Camera, dx: f64, dy: f64) {
    if !(dx.is_finite() && dy.is_finite()) {
        return;
    }
    let (distance, azimuth, elevation) = spherical(camera);
    from_spherical(
        camera,
        distance,
        azimuth - dx * ORBIT_SPEED,
        (elevation + dy * ORBIT_SPEED).clamp(-MAX_ELEVATION, MAX_ELEVATION),
    );
}

/// Right/middle-drag: moves eye and target together across the view, so the
/// point at the target's depth follows the mouse. `viewport_height` is in the
/// same pixels as (dx, dy).
pub fn pan(camera: &mut Camera, dx: f64, dy: f64, viewport_height: f64) {
    if !(dx.is_finite() && dy.is_finite()) || viewport_height <= 0.0 {
        return;
    }
    let film = camera.film();
    let distance = (camera.from - camera.to).length();
    let world_per_pixel = film.height * distance / viewport_height;
    let shift = (-dx * film.u + dy * film.v) * world_per_pixel;
    camera.from += shift;
    camera.to += shift;
}

/// Mouse wheel: dollies towards `to` by a factor per notch, never through it
/// and never closer than a small fraction of `start_distance`.
pub fn zoom(camera: &mut Camera, notches: f64, start_distance: f64) {
    if !notches.is_finite() {
        return;
    }
    let offset = camera.from - camera.to;
    let distance = offset.length();
    let min = (start_distance * MIN_DISTANCE_FRACTION).max(f64::MIN_POSITIVE.sqrt());
    let new_distance = (distance * 0.85f64.powf(notches)).max(min);
    camera.from = camera.to + offset * (new_distance / distance);
}

/// Double-click: orbit around `point` from now on, keeping the eye in place.
/// Ignored when `point` is (nearly) the eye itself.
pub fn recenter(camera: &mut Camera, point: DVec3) {
    let distance = (camera.from - point).length();
    if point.is_finite() && distance > 1e-9 * camera.from.length().max(1.0) {
        camera.to = point;
        camera.focus_distance = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera(from: [f64; 3], to: [f64; 3]) -> Camera {
        Camera {
            from: DVec3::from(from),
            to: DVec3::from(to),
            up: DVec3::Y,
            fov: 45.0,
            aperture: 0.0,
            focus_distance: None,
        }
    }

    fn assert_finite(c: &Camera) {
        assert!(c.from.is_finite() && c.to.is_finite(), "{c:?}");
        assert!((c.from - c.to).length() > 0.0, "{c:?}");
    }

    #[test]
    fn orbit_keeps_distance_and_target() {
        let mut c = camera([0.0, 1.0, 5.0], [0.0, 1.0, 0.0]);
        orbit(&mut c, 100.0, 30.0);
        assert!(((c.from - c.to).length() - 5.0).abs() < 1e-9);
        assert_eq!(c.to, DVec3::new(0.0, 1.0, 0.0));
        assert!(c.from.y > 1.0, "dragging down looks from above: {c:?}");
    }

    #[test]
    fn orbit_never_flips_over_the_pole_nor_gives_nan() {
        let mut c = camera([0.0, 0.0, 5.0], [0.0, 0.0, 0.0]);
        for _ in 0..100 {
            orbit(&mut c, 3.0, 500.0);
            assert_finite(&c);
        }
        let (_, _, elevation) = spherical(&c);
        assert!(elevation <= MAX_ELEVATION + 1e-12 && elevation > 1.5);
        // Still in front of the pole: the view direction is not parallel to up.
        assert!(c.from.x.hypot(c.from.z) > 0.0);
        for _ in 0..200 {
            orbit(&mut c, -7.0, -500.0);
            assert_finite(&c);
        }
        assert!(spherical(&c).2 >= -MAX_ELEVATION - 1e-12);
    }

    #[test]
    fn orbit_from_exactly_the_pole_is_finite() {
        // Looking straight down: from - to parallel to up.
        let mut c = camera([0.0, 10.0, 0.0], [0.0, 0.0, 0.0]);
        orbit(&mut c, 10.0, 10.0);
        assert_finite(&c);
        orbit(&mut c, f64::NAN, 1.0);
        assert_finite(&c);
    }

    #[test]
    fn zoom_never_passes_the_target() {
        let mut c = camera([0.0, 0.0, 5.0], [0.0, 0.0, 0.0]);
        for _ in 0..10_000 {
            zoom(&mut c, 5.0, 5.0);
        }
        assert_finite(&c);
        assert!(c.from.z > 0.0, "the eye stays on its side: {c:?}");
        assert!((c.from - c.to).length() >= 5.0 * MIN_DISTANCE_FRACTION * 0.999);
        zoom(&mut c, -3.0, 5.0);
        assert!(c.from.z > 5.0 * MIN_DISTANCE_FRACTION);
    }

    #[test]
    fn zoom_out_and_in_returns() {
        let mut c = camera([1.0, 2.0, 3.0], [0.0, 0.0, 0.0]);
        zoom(&mut c, 2.0, 3.7);
        zoom(&mut c, -2.0, 3.7);
        assert!((c.from - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-12);
    }

    #[test]
    fn pan_keeps_the_view_direction() {
        let mut c = camera([1.0, 2.0, 6.0], [0.0, 1.0, 0.0]);
        let before = (c.to - c.from).normalize();
        pan(&mut c, 40.0, -25.0, 720.0);
        let after = (c.to - c.from).normalize();
        assert!((before - after).length() < 1e-12);
        assert!(c.to != DVec3::new(0.0, 1.0, 0.0), "the target moved");
    }

    #[test]
    fn recenter_moves_the_target_but_not_the_eye() {
        let mut c = camera([0.0, 0.0, 5.0], [0.0, 0.0, 0.0]);
        recenter(&mut c, DVec3::new(1.0, 0.0, 0.0));
        assert_eq!(c.to, DVec3::X);
        assert_eq!(c.from, DVec3::new(0.0, 0.0, 5.0));
        let eye = c.from;
        recenter(&mut c, eye);
        assert_eq!(c.to, DVec3::X, "a point at the eye is ignored");
    }
}
