//! A pixel's ray tree in the viewer (docs/ray-tree.md) as a person uses it,
//! under Xvfb (tests/common/xwindow.rs): Shift+click on the glass sphere of
//! the Whitted scene shows the tree in the panel, both trees alike, and
//! draws its rays over the picture where they project; they stay in the
//! scene while the camera orbits, and Esc clears them. `C` shows the
//! scene's camera from an observer's view, which follows the panel's
//! camera fields and orbits without moving the scene's camera, and draws
//! the camera rays of the pixels Shift+clicked.

mod common;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use common::xwindow::{Display, Rect, Window, serial};
use glam::DVec3;
use image::{Rgba, RgbaImage};
use raysandbox::app::camera_model;
use raysandbox::gpu::{DEFAULT_MIN_WEIGHT, project};
use raysandbox::reference::{self, PreparedScene, RayKind};
use raysandbox::scene::{Camera, Scene};

const SIZE: (u32, u32) = (800, 450);

/// The colour of refracted rays over the picture
/// (`REFRACTED_COLOUR` in src/app/ray_tree.rs): pure green, which the
/// Whitted scene's picture has nowhere.
fn refracted_colour(p: &Rgba<u8>) -> bool {
    p[0] < 40 && p[1] > 215 && p[2] < 40
}

/// The part of the window right of the panel and above the status line.
fn view(viewer: &Window) -> Rect {
    let panel = viewer.part("panel");
    let status = viewer.part("status");
    let x = panel.right() + 16;
    Rect {
        x,
        y: 0,
        w: SIZE.0 as i32 - x,
        h: status.y,
    }
}

/// The pixels of `area` whose colour passes `colour`.
fn pixels(image: &RgbaImage, area: Rect, colour: fn(&Rgba<u8>) -> bool) -> Vec<(i32, i32)> {
    let (x0, y0, w, h) = area.crop();
    (y0..y0 + h)
        .flat_map(|y| (x0..x0 + w).map(move |x| (x, y)))
        .filter(|&(x, y)| colour(image.get_pixel(x, y)))
        .map(|(x, y)| (x as i32, y as i32))
        .collect()
}

/// The pixels of `area` in the refracted rays' colour.
fn green_pixels(image: &RgbaImage, area: Rect) -> Vec<(i32, i32)> {
    pixels(image, area, refracted_colour)
}

/// A copy of the Whitted scene in a fresh folder (the test saves it),
/// open in a window refined to one sample per pixel.
fn open_whitted<'d>(display: &'d Display, test: &str) -> (Window<'d>, PathBuf) {
    let dir = common::temp_dir("ray-tree-window", test);
    let path = dir.join("whitted.toml");
    std::fs::copy(common::scenes_dir().join("whitted.toml"), &path).unwrap();
    let args = ["view", path.to_str().unwrap(), "--max-samples", "1"];
    (Window::open(display, &args, SIZE), path)
}

/// The window's pixels, kept as `name` beside the scene file, to be
/// looked at.
fn capture_kept(viewer: &Window, path: &Path, name: &str) -> RgbaImage {
    let image = viewer.capture();
    image.save(path.with_file_name(name)).unwrap();
    image
}

/// Captures the window until `done` holds of its pixels, at most a minute:
/// what a person waits for. After a drag of the fov slider the viewer may
/// have told `ready` several times, so the events cannot say which frame
/// shows the next step.
fn capture_until(
    viewer: &Window,
    path: &Path,
    name: &str,
    done: impl Fn(&RgbaImage) -> bool,
) -> RgbaImage {
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        let image = capture_kept(viewer, path, name);
        if done(&image) || Instant::now() > deadline {
            return image;
        }
        std::thread::sleep(Duration::from_millis(250));
    }
}

/// Ctrl+S, then the scene as saved.
fn saved(viewer: &mut Window, path: &Path) -> Scene {
    viewer.key("ctrl+s");
    viewer.wait_for("saved");
    Scene::load(path).unwrap()
}

/// The refracted rays of the tree of `pixel` of `scene`, projected with
/// `camera` into the window.
fn projected_refracted(scene: &Scene, pixel: (u32, u32), camera: &Camera) -> Vec<[(f64, f64); 2]> {
    let mut scene = scene.clone();
    scene.render.min_weight = scene.render.min_weight.max(DEFAULT_MIN_WEIGHT);
    let tree = reference::ray_tree(
        &PreparedScene::new(&scene),
        SIZE.0,
        SIZE.1,
        pixel.0,
        pixel.1,
    );
    let rays: Vec<[DVec3; 2]> = tree
        .rays
        .iter()
        .filter(|r| r.kind == RayKind::Refracted)
        .map(|r| {
            // A ray that misses is drawn some way on: all of it lies on
            // this far longer segment.
            let far = r.origin + 1e3 * scene.view_scale() * r.dir;
            [r.origin, r.end().unwrap_or(far)]
        })
        .collect();
    projected(&rays, camera)
}

/// World segments projected with `camera` into the window: segments in
/// window pixels, cut where they pass behind the eye (as the GPU clips
/// them).
fn projected(segments: &[[DVec3; 2]], camera: &Camera) -> Vec<[(f64, f64); 2]> {
    let aspect = f64::from(SIZE.0) / f64::from(SIZE.1);
    let clip = |p: DVec3| project(camera, aspect, p).map(f64::from);
    let to_window = |c: [f64; 4]| {
        (
            (c[0] / c[3] + 1.0) / 2.0 * f64::from(SIZE.0),
            (1.0 - c[1] / c[3]) / 2.0 * f64::from(SIZE.1),
        )
    };
    let near = 0.01 * (camera.from - camera.to).length();
    segments
        .iter()
        .filter_map(|&[mut a, mut b]| {
            let (wa, wb) = (clip(a)[3], clip(b)[3]);
            if wa < near && wb < near {
                return None;
            }
            if wa < near {
                a = a + (near - wa) / (wb - wa) * (b - a);
            } else if wb < near {
                b = a + (near - wa) / (wb - wa) * (b - a);
            }
            Some([to_window(clip(a)), to_window(clip(b))])
        })
        .collect()
}

/// Distance from `p` to the segment `[a, b]`.
fn distance((px, py): (f64, f64), [a, b]: [(f64, f64); 2]) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let length2 = dx * dx + dy * dy;
    let s = if length2 > 0.0 {
        (((px - a.0) * dx + (py - a.1) * dy) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (px - a.0 - s * dx).hypot(py - a.1 - s * dy)
}

/// The green pixels of `image`'s view `area`, all on the projected
/// refracted rays (within the lines' width).
fn on_the_rays(image: &RgbaImage, area: Rect, rays: &[[(f64, f64); 2]]) -> Vec<(i32, i32)> {
    on_the_lines(image, area, rays, refracted_colour, "refracted ray")
}

/// The pixels of `image`'s view `area` in `colour`: at least 20, all on
/// the projected `lines` (within the lines' width).
fn on_the_lines(
    image: &RgbaImage,
    area: Rect,
    lines: &[[(f64, f64); 2]],
    colour: fn(&Rgba<u8>) -> bool,
    what: &str,
) -> Vec<(i32, i32)> {
    let found = pixels(image, area, colour);
    let off: Vec<_> = found
        .iter()
        .filter(|&&(x, y)| {
            let centre = (f64::from(x) + 0.5, f64::from(y) + 0.5);
            lines.iter().all(|&s| distance(centre, s) > 3.0)
        })
        .collect();
    println!(
        "{} {what} pixels, {} off the projected lines {lines:?}",
        found.len(),
        off.len()
    );
    assert!(found.len() >= 20, "too few {what} pixels: {}", found.len());
    assert!(
        off.len() * 50 <= found.len(),
        "{what} pixels off the lines: {:?}",
        &off[..off.len().min(20)]
    );
    found
}

#[test]
fn shift_click_shows_a_pixels_ray_tree_which_stays_in_the_scene_while_orbiting() {
    let _serial = serial();
    let display = Display::start();
    let (mut viewer, path) = open_whitted(&display, "orbit");
    let area = view(&viewer);
    let before = viewer.capture();
    assert!(
        green_pixels(&before, area).is_empty(),
        "green before any tree"
    );

    // Shift+click on the glass sphere (the middle of the right half). The
    // window needs the keyboard focus to see Shift held.
    viewer.xdotool(&["windowfocus", "--sync", &viewer.id]);
    let at = area.at(0.45, 0.45);
    let pixel = shift_click(&mut viewer, at);
    assert_eq!(pixel, at);
    // The GPU's tree, traced on the worker thread, has as many rays.
    let answered = viewer.wait_for("ray-tree ");
    println!("{answered}");
    let rays = |name: &str| -> usize {
        let field = answered
            .split_whitespace()
            .find_map(|f| f.strip_prefix(&format!("{name}=")))
            .unwrap_or_else(|| panic!("{name} in {answered:?}"));
        field
            .parse()
            .unwrap_or_else(|_| panic!("{name} in {answered:?}"))
    };
    assert!(rays("rays") > 4, "{answered}");
    assert_eq!(rays("rays"), rays("gpu"), "{answered}");
    // The panel shows the section, and it was not a selection.
    viewer.part("ray-tree");
    assert!(
        viewer
            .events_within(std::time::Duration::from_millis(500))
            .iter()
            .all(|e| !e.contains("selected")),
        "Shift+click selected"
    );

    let scene = Scene::load(&path).unwrap();
    let rays = projected_refracted(&scene, pixel, &scene.camera);
    let first = on_the_rays(&capture_kept(&viewer, &path, "drawn.png"), area, &rays);

    // Orbit: the rays stay where they are in the scene, so they move on
    // the screen, onto the projection with the new camera.
    viewer.drag("1", area.at(0.5, 0.8), area.at(0.8, 0.8));
    viewer.wait_for("ready");
    let orbited = saved(&mut viewer, &path);
    assert_ne!(orbited.camera.from, scene.camera.from, "the drag orbited");
    let rays = projected_refracted(&scene, pixel, &orbited.camera);
    let second = on_the_rays(&capture_kept(&viewer, &path, "orbited.png"), area, &rays);
    assert_ne!(first, second, "the rays moved on the screen");

    // Esc clears them.
    viewer.key("Escape");
    viewer.wait_for("ray-tree-cleared");
    let cleared = viewer.capture();
    assert!(
        green_pixels(&cleared, area).is_empty(),
        "rays left after Esc"
    );
}

/// The film's colour (`COLOURS.film` in src/app/camera_model.rs), which the
/// Whitted scene's picture has nowhere (its red floor is far less blue).
fn film_pixels(image: &RgbaImage, area: Rect) -> Vec<(i32, i32)> {
    pixels(image, area, |p| {
        p[0] > 215 && p[1] < 40 && (90..170).contains(&p[2])
    })
}

#[test]
fn the_observer_sees_the_scene_camera_follow_the_panel_and_orbits_alone() {
    let _serial = serial();
    let display = Display::start();
    let (mut viewer, path) = open_whitted(&display, "observer");
    let original = Scene::load(&path).unwrap();
    let area = view(&viewer);
    assert!(film_pixels(&viewer.capture(), area).is_empty());

    viewer.key("c");
    viewer.wait_for("observer on");
    viewer.wait_for("ready");
    let image = capture_kept(&viewer, &path, "observer.png");
    let film = film_pixels(&image, area);
    println!("film: {} pixels", film.len());
    assert!(
        film.len() >= 100,
        "the film is drawn: {} pixels",
        film.len()
    );

    // The scene's camera edited in the panel: a wider field of view, a
    // larger film; the drawing follows.
    let (x, y) = viewer.part("camera-fov").at(0.1, 0.5);
    viewer.drag("1", (x, y), (x + 60, y));
    viewer.wait_for("ready");
    let image = capture_kept(&viewer, &path, "wider.png");
    let wider = film_pixels(&image, area);
    println!("wider film: {} pixels", wider.len());
    assert!(
        wider.len() >= 100 && wider != film,
        "the film follows the fov"
    );

    // Orbiting moves the observer: the drawing moves, the scene's camera
    // stays where the panel put it.
    viewer.drag("1", area.at(0.5, 0.85), area.at(0.8, 0.85));
    let image = capture_until(&viewer, &path, "orbited.png", |image| {
        film_pixels(image, area) != wider
    });
    let orbited = film_pixels(&image, area);
    assert!(
        orbited.len() >= 100 && orbited != wider,
        "the observer orbited"
    );
    let saved = saved(&mut viewer, &path);
    assert_eq!(
        saved.camera.from, original.camera.from,
        "the scene's eye stayed"
    );
    assert_eq!(saved.camera.to, original.camera.to);
    assert!(saved.camera.fov > original.camera.fov, "the fov was edited");

    viewer.key("c");
    viewer.wait_for("observer off");
    let image = capture_until(&viewer, &path, "off.png", |image| {
        film_pixels(image, area).is_empty()
    });
    assert!(film_pixels(&image, area).is_empty(), "film left");
}

/// The selected pixels' camera rays (`COLOURS.pixel_ray` in
/// src/app/camera_model.rs): lime, which neither the Whitted scene's
/// picture nor the other lines have.
fn pixel_ray_colour(p: &Rgba<u8>) -> bool {
    (110..190).contains(&p[0]) && p[1] > 215 && p[2] < 40
}

/// Shift+click on the window point `at`; returns the pixel asked for.
fn shift_click(viewer: &mut Window, at: (u32, u32)) -> (u32, u32) {
    let (x, y) = (at.0.to_string(), at.1.to_string());
    viewer.xdotool(&["mousemove", "--window", &viewer.id, &x, &y]);
    viewer.xdotool(&["keydown", "shift", "click", "1", "keyup", "shift"]);
    let asked = viewer.wait_for("ray-tree-asked");
    let (px, py) = asked.split_once(',').expect("X,Y");
    (px.parse().unwrap(), py.parse().unwrap())
}

#[test]
fn the_camera_model_draws_the_selected_pixels_rays_and_they_follow_the_observer() {
    let _serial = serial();
    let display = Display::start();
    let (mut viewer, path) = open_whitted(&display, "pixel-rays");
    let scene = Scene::load(&path).unwrap();
    // Two pixels: on the glass sphere and on the floor, each once the
    // panel shows the previous tree (which widens it).
    viewer.xdotool(&["windowfocus", "--sync", &viewer.id]);
    let at = view(&viewer).at(0.45, 0.45);
    let first = shift_click(&mut viewer, at);
    viewer.wait_for("ray-tree ");
    // Later than egui's double-click delay (0.3 s): a second click sooner
    // is a double click, which orbits around the point instead.
    std::thread::sleep(std::time::Duration::from_millis(600));
    let at = view(&viewer).at(0.8, 0.85);
    let second = shift_click(&mut viewer, at);
    let selected = [first, second];
    viewer.wait_for("ray-tree ");
    let area = view(&viewer);
    assert!(
        pixels(&viewer.capture(), area, pixel_ray_colour).is_empty(),
        "pixel rays drawn outside the camera model"
    );

    viewer.key("c");
    viewer.wait_for("observer on");
    viewer.wait_for("ready");
    let image = capture_kept(&viewer, &path, "pixel-rays.png");
    let rays = camera_model::pixel_rays(&scene, &selected, SIZE);
    assert_eq!(rays.len(), 2, "a pinhole: one ray per pixel");
    let world: Vec<[DVec3; 2]> = rays.iter().map(|s| [s.a, s.b]).collect();
    let observer = camera_model::observer_for(&scene.camera);
    let lines = projected(&world, &observer);
    let first = on_the_lines(&image, area, &lines, pixel_ray_colour, "pixel ray");

    // The observer orbits: the rays stay in the scene, so they move on the
    // screen.
    viewer.drag("1", area.at(0.5, 0.85), area.at(0.8, 0.85));
    viewer.wait_for("ready");
    let image = capture_kept(&viewer, &path, "pixel-rays-orbited.png");
    let orbited = pixels(&image, area, pixel_ray_colour);
    println!("{} pixel ray pixels after the orbit", orbited.len());
    assert!(
        orbited.len() >= 20 && orbited != first,
        "the rays moved with the observer"
    );

    // Esc forgets the pixels with the tree.
    viewer.key("Escape");
    viewer.wait_for("ray-tree-cleared");
    assert!(
        pixels(&viewer.capture(), area, pixel_ray_colour).is_empty(),
        "pixel rays left after Esc"
    );
}
