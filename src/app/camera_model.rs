//! The camera model seen from outside (docs/ray-tree.md, "The camera
//! model"): `C` switches the picture to an observer's camera, and the
//! scene's camera is drawn in 3D as the lecture draws it: the eye (or, for
//! a thin lens, the lens disc and the plane in focus), the film at unit
//! distance in front of the eye with the grid of the image's pixels, and
//! the frustum through the film's corners. The segments are in world
//! coordinates, drawn by the line overlay as the ray tree's are.

use glam::DVec3;

use crate::gpu::Segment;
use crate::scene::Camera;

/// The colours (sRGB) of the parts drawn, apart from the picture's.
pub struct Colours {
    /// The film and its pixel grid.
    pub film: [u8; 3],
    /// The frustum's edges, from the eye through the film's corners.
    pub frustum: [u8; 3],
    /// The eye, or the lens disc.
    pub eye: [u8; 3],
    /// The plane in focus of a thin lens.
    pub focus: [u8; 3],
}

pub const COLOURS: Colours = Colours {
    film: [255, 0, 128],
    frustum: [170, 120, 255],
    eye: [255, 255, 255],
    focus: [0, 160, 255],
};

/// At most this many grid cells along a side of the film: a grid line
/// every `grid_step` pixels (every pixel of a small image).
const MAX_CELLS: u32 = 16;

/// Segments of the lens disc's circle.
const CIRCLE_SEGMENTS: u32 = 32;

/// The grid's spacing in pixels for an image of `width` x `height`.
pub fn grid_step((width, height): (u32, u32)) -> u32 {
    width.max(height).div_ceil(MAX_CELLS).max(1)
}

/// Where the observer starts: to the right of the scene's camera, a little
/// above and behind it, 0.8 eye-target distances away, looking at a point
/// near the eye, so that the eye, the film and the frustum show from the
/// side; moved sideways so that they show right of the window's middle
/// (the panel covers its left).
pub fn observer_for(camera: &Camera) -> Camera {
    let film = camera.film();
    let distance = (camera.from - camera.to).length().max(1e-3);
    let target = camera.from + 0.2 * (camera.to - camera.from);
    let side = (film.u + 0.5 * film.v + 0.3 * film.w).normalize();
    let mut observer = Camera {
        from: target + 0.8 * distance * side,
        to: target,
        up: camera.up,
        fov: 40.0,
        aperture: 0.0,
        focus_distance: None,
    };
    let shift = 0.3 * distance * observer.film().u;
    observer.from -= shift;
    observer.to -= shift;
    observer
}

/// The scene's `camera` making an image of `size` pixels, as segments.
pub fn segments(camera: &Camera, size: (u32, u32)) -> Vec<Segment> {
    let film = camera.film();
    let (width, height) = (f64::from(size.0.max(1)), f64::from(size.1.max(1)));
    let (film_w, film_h) = (film.height * width / height, film.height);
    // The film point of image coordinates (px, py), `camera_ray`'s.
    let at = |px: f64, py: f64| {
        camera.from + film_w * (px / width - 0.5) * film.u + film_h * (0.5 - py / height) * film.v
            - film.w
    };
    let line = |a, b, colour| Segment { a, b, colour };
    let mut out = Vec::new();
    let step = grid_step(size) as usize;
    let columns = (0..size.0).step_by(step).chain([size.0]);
    for px in columns.map(f64::from) {
        out.push(line(at(px, 0.0), at(px, height), COLOURS.film));
    }
    let rows = (0..size.1).step_by(step).chain([size.1]);
    for py in rows.map(f64::from) {
        out.push(line(at(0.0, py), at(width, py), COLOURS.film));
    }
    let corners = [(0.0, 0.0), (width, 0.0), (width, height), (0.0, height)].map(|(x, y)| at(x, y));
    let focus = camera.focus_distance().max(1e-9);
    let far = |p: DVec3| camera.from + focus * (p - camera.from);
    for corner in corners {
        out.push(line(camera.from, far(corner), COLOURS.frustum));
    }
    if camera.aperture > 0.0 {
        // The plane in focus, where the lens's rays of a pixel meet again.
        for i in 0..4 {
            let (a, b) = (corners[i], corners[(i + 1) % 4]);
            out.push(line(far(a), far(b), COLOURS.focus));
        }
        let point = |k: u32| {
            let angle = std::f64::consts::TAU * f64::from(k) / f64::from(CIRCLE_SEGMENTS);
            camera.from + camera.aperture * (angle.cos() * film.u + angle.sin() * film.v)
        };
        for k in 0..CIRCLE_SEGMENTS {
            out.push(line(point(k), point(k + 1), COLOURS.eye));
        }
    } else {
        let half = 0.03 * (camera.from - camera.to).length();
        for axis in [film.u, film.v, film.w] {
            out.push(line(
                camera.from - half * axis,
                camera.from + half * axis,
                COLOURS.eye,
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    fn camera(aperture: f64) -> Camera {
        Camera {
            from: DVec3::new(0.2, 1.4, 5.8),
            to: DVec3::new(0.1, 0.8, 0.0),
            up: DVec3::Y,
            fov: 40.0,
            aperture,
            focus_distance: None,
        }
    }

    /// The film's corners and grid lie on the rays through the image's
    /// corners and pixel edges: the drawing is the tracer's camera model.
    #[test]
    fn the_film_lies_on_the_camera_rays() {
        let scene_camera = camera(0.0);
        let size = (32, 18);
        assert_eq!(grid_step(size), 2);
        let drawn = segments(&scene_camera, size);
        // 17 columns, 10 rows, 4 frustum edges and the eye's 3 axes.
        assert_eq!(drawn.len(), 17 + 10 + 4 + 3);
        let reference = crate::reference::Camera::new(&scene_camera);
        let ray = crate::reference::camera_ray(&reference, 32, 18, 32.0, 18.0, DVec2::ZERO);
        let corner = drawn[16].b;
        let along = (corner - ray.origin).normalize();
        assert!((along - ray.dir).length() < 1e-12, "{along} {}", ray.dir);
        let distance_to_film = (corner - scene_camera.from).dot(-scene_camera.film().w);
        assert!((distance_to_film - 1.0).abs() < 1e-12);
    }

    /// A thin lens draws its disc and the plane in focus instead of the
    /// eye; the observer looks at the camera from outside it.
    #[test]
    fn a_thin_lens_draws_its_disc_and_focus_plane() {
        let lens = camera(0.2);
        let drawn = segments(&lens, (1280, 720));
        assert_eq!(grid_step((1280, 720)), 80);
        assert_eq!(drawn.len(), 17 + 10 + 4 + 4 + CIRCLE_SEGMENTS as usize);
        let mut disc = drawn.iter().filter(|s| s.colour == COLOURS.eye);
        assert!(disc.all(|s| ((s.a - lens.from).length() - 0.2).abs() < 1e-12));
        // The observer sees the lens, right of the middle of its picture.
        let observer = observer_for(&lens);
        let c = crate::gpu::project(&observer, 16.0 / 9.0, lens.from);
        let (x, y) = (c[0] / c[3], c[1] / c[3]);
        assert!(
            c[3] > 0.0 && (0.0..1.0).contains(&x) && y.abs() < 1.0,
            "{c:?}"
        );
    }
}
