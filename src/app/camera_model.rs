//! The camera model seen from outside (docs/ray-tree.md, "The camera
//! model"): `C` switches the picture to an observer's camera, and the
//! scene's camera is drawn in 3D as the lecture draws it: the eye (or, for
//! a thin lens, the lens disc and the plane in focus), the film at unit
//! distance in front of the eye with the grid of the image's pixels, and
//! the frustum through the film's corners. The segments are in world
//! coordinates, drawn by the line overlay as the ray tree's are. The
//! camera rays of the selected pixels (Shift+click or `T` adds one) go from
//! the eye through their cell of the film to the first hit.

use glam::{DVec2, DVec3};

use crate::gpu::Segment;
use crate::reference::{self, PreparedScene};
use crate::scene::{Camera, Scene};

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
    /// The camera rays of the selected pixels: lime, which neither the
    /// ray tree's colours nor the bundled scenes' pictures have (a test
    /// finds it, tests/ray_tree_window.rs).
    pub pixel_ray: [u8; 3],
}

pub const COLOURS: Colours = Colours {
    film: [255, 0, 128],
    frustum: [170, 120, 255],
    eye: [255, 255, 255],
    focus: [0, 160, 255],
    pixel_ray: [150, 255, 0],
};

/// At most this many selected pixels: the oldest goes when another is
/// added, so that the drawing stays readable and cheap to trace.
pub const MAX_PIXELS: usize = 8;

/// Points of the lens's rim that a thin lens's pixel rays leave from,
/// besides its centre: they meet again on the plane in focus.
const LENS_POINTS: [DVec2; 4] = [
    DVec2::new(1.0, 0.0),
    DVec2::new(0.0, 1.0),
    DVec2::new(-1.0, 0.0),
    DVec2::new(0.0, -1.0),
];

/// How long a pixel ray that misses everything is drawn, in eye-target
/// distances (the ray tree's misses are as long).
const MISS_LENGTH: f64 = 1.5;

/// Adds `pixel` to the `selected` ones (at most [`MAX_PIXELS`], the oldest
/// dropped; selecting one again makes it the newest).
pub fn select(selected: &mut Vec<(u32, u32)>, pixel: (u32, u32)) {
    selected.retain(|&p| p != pixel);
    selected.push(pixel);
    if selected.len() > MAX_PIXELS {
        selected.remove(0);
    }
}

/// The camera rays of the selected pixels, traced by the reference when the
/// scene, the pixels or the image size changed, and kept while the
/// observer orbits (the BVH of a large mesh takes a while to build).
#[derive(Default)]
pub struct PixelRays {
    traced_for: Option<Traced>,
    segments: Vec<Segment>,
}

/// What the pixel rays were traced for.
struct Traced {
    scene: Scene,
    pixels: Vec<(u32, u32)>,
    size: (u32, u32),
}

impl PixelRays {
    /// The segments of `pixels` of a `size` image of `scene`.
    pub fn segments(
        &mut self,
        scene: &Scene,
        pixels: &[(u32, u32)],
        size: (u32, u32),
    ) -> &[Segment] {
        let traced = self
            .traced_for
            .as_ref()
            .is_some_and(|t| t.scene == *scene && t.pixels == pixels && t.size == size);
        if !traced {
            self.segments = pixel_rays(scene, pixels, size);
            self.traced_for = Some(Traced {
                scene: scene.clone(),
                pixels: pixels.to_vec(),
                size,
            });
        }
        &self.segments
    }
}

/// The camera ray of each of `pixels` (of an image of `size`) through its
/// centre, from the eye through the film to its first hit; for a thin lens
/// also the rays from four points of the lens's rim, which cross on the
/// plane in focus.
pub fn pixel_rays(scene: &Scene, pixels: &[(u32, u32)], size: (u32, u32)) -> Vec<Segment> {
    if pixels.is_empty() || size.0 == 0 || size.1 == 0 {
        return Vec::new();
    }
    let prepared = PreparedScene::new(scene);
    let miss = MISS_LENGTH * scene.view_scale();
    let lens_points: &[DVec2] = if scene.camera.aperture > 0.0 {
        &LENS_POINTS
    } else {
        &[]
    };
    let mut out = Vec::new();
    for &(x, y) in pixels {
        let centre = (f64::from(x) + 0.5, f64::from(y) + 0.5);
        for &lens in std::iter::once(&DVec2::ZERO).chain(lens_points) {
            let (ray, hit) = reference::lens_ray(&prepared, size.0, size.1, centre, lens);
            let end = hit.map_or(ray.origin + miss * ray.dir, |(_, p)| p);
            out.push(Segment {
                a: ray.origin,
                b: end,
                colour: COLOURS.pixel_ray,
            });
        }
    }
    out
}

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

    fn whitted(aperture: f64) -> Scene {
        let text = crate::scene::bundled::text("whitted").unwrap();
        let mut scene = Scene::from_toml_str(text, None).unwrap();
        scene.camera.aperture = aperture;
        scene
    }

    /// A pixel's ray goes from the eye through the film point of the
    /// pixel's centre, where the grid draws its cell, to the first hit.
    #[test]
    fn a_pixel_ray_runs_from_the_eye_through_its_cell_to_the_hit() {
        let scene = whitted(0.0);
        let size = (80, 45);
        let rays = pixel_rays(&scene, &[(50, 20)], size);
        assert_eq!(rays.len(), 1);
        let ray = rays[0];
        assert_eq!(ray.colour, COLOURS.pixel_ray);
        assert!((ray.a - scene.camera.from).length() < 1e-12);
        let prepared = PreparedScene::new(&scene);
        let (_, hit) = reference::pick(&prepared, 80, 45, 50.5, 20.5).unwrap();
        assert!((ray.b - hit).length() < 1e-9, "{} {hit}", ray.b);
        // The film point of the pixel's centre, as `segments` places it.
        let film = scene.camera.film();
        let (film_w, film_h) = (film.height * 80.0 / 45.0, film.height);
        let cell = scene.camera.from
            + film_w * (50.5 / 80.0 - 0.5) * film.u
            + film_h * (0.5 - 20.5 / 45.0) * film.v
            - film.w;
        let along = (ray.b - ray.a).normalize();
        assert!((along - (cell - ray.a).normalize()).length() < 1e-9);
    }

    /// A thin lens adds four rays from its rim; all five cross on the plane
    /// in focus. Selecting keeps at most `MAX_PIXELS`, the newest last.
    #[test]
    fn lens_rays_cross_in_focus_and_the_selection_is_bounded() {
        let scene = whitted(0.3);
        let rays = pixel_rays(&scene, &[(30, 30), (10, 5)], (80, 45));
        assert_eq!(rays.len(), 10);
        let w = scene.camera.film().w;
        let focus = scene.camera.focus_distance();
        let in_focus = |s: &Segment| {
            let along = (s.b - s.a).normalize();
            let t = ((s.a - scene.camera.from).dot(w) + focus) / -along.dot(w);
            s.a + t * along
        };
        for pixel in rays.chunks(5) {
            let meet = in_focus(&pixel[0]);
            for ray in &pixel[1..] {
                assert!(((ray.a - scene.camera.from).length() - 0.3).abs() < 1e-9);
                assert!((in_focus(ray) - meet).length() < 1e-9);
            }
        }
        let mut selected = Vec::new();
        for x in 0..10 {
            select(&mut selected, (x, 0));
        }
        select(&mut selected, (4, 0));
        assert_eq!(selected.len(), MAX_PIXELS);
        assert_eq!(selected.first(), Some(&(2, 0)));
        assert_eq!(selected.last(), Some(&(4, 0)));
    }
}
