//! The viewer as a person uses it: the real binary in a window under Xvfb,
//! driven with xdotool, its pixels captured with ImageMagick's `import`
//! (tests/common/xwindow.rs).

mod common;

use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};
use std::time::Duration;

use common::xwindow::{Display, Window, crop};
use raysandbox::compare::diff_images;
use raysandbox::gpu::{OUTLINE_COLOR, render_image};
use raysandbox::reference;
use raysandbox::scene::{Scene, ShapeId};

const WIDTH: u32 = 800;
const HEIGHT: u32 = 450;
/// The part of the window that shows the image: right of the side panel
/// (about 300 px wide) and above the status line.
const VIEW: (u32, u32, u32, u32) = (360, 0, WIDTH - 360, HEIGHT - 40);

/// One viewer at a time: each drives its own X server, but lavapipe's
/// rendering shares the machine's two cores.
static SERIAL: Mutex<()> = Mutex::new(());

fn serial() -> MutexGuard<'static, ()> {
    SERIAL.lock().unwrap_or_else(|e| e.into_inner())
}

/// `raysandbox view ARGS`, refined to 1 sample per pixel (what a headless
/// render at 1 spp shows).
fn open<'d>(display: &'d Display, args: &[&str]) -> Window<'d> {
    let mut all = vec!["view"];
    all.extend_from_slice(args);
    all.extend(["--max-samples", "1"]);
    Window::open(display, &all, (WIDTH, HEIGHT))
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("raysandbox-viewer-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn scene_path(name: &str) -> PathBuf {
    common::scenes_dir().join(format!("{name}.toml"))
}

/// A copy of a bundled scene in a fresh folder (the viewer may write to it).
fn scene_copy(name: &str, dir: &Path) -> PathBuf {
    let path = dir.join(format!("{name}.toml"));
    std::fs::copy(scene_path(name), &path).unwrap();
    path
}

#[test]
fn window_shows_the_same_pixels_as_a_headless_render() {
    let _serial = serial();
    let Some(display) = Display::start() else {
        return;
    };
    let path = scene_path("whitted");
    let viewer = open(&display, &[path.to_str().unwrap()]);
    let window = viewer.capture();
    let gpu = common::gpu().unwrap();
    let scene = Scene::load(&path).unwrap();
    let headless = render_image(&gpu, &scene, WIDTH, HEIGHT, 1).unwrap();
    let d = diff_images(&crop(&window, VIEW), &crop(&headless, VIEW));
    println!(
        "window vs headless: mean {:.4}, max {}",
        d.mean_abs, d.max_abs
    );
    assert!(d.mean_abs <= 0.5 && d.frac_over_8 <= 0.001, "{d:?}");
}

#[test]
fn dragging_in_the_view_orbits_but_dragging_on_the_panel_does_not() {
    let _serial = serial();
    let Some(display) = Display::start() else {
        return;
    };
    let path = scene_path("mirror_cube");
    let mut viewer = open(&display, &[path.to_str().unwrap()]);
    let before = crop(&viewer.capture(), VIEW);

    // A drag over the panel's empty lower part: egui takes it.
    viewer.drag("1", (150, 380), (260, 300));
    let events = viewer.events_within(Duration::from_secs(2));
    assert!(events.is_empty(), "the camera moved: {events:?}");
    let after_panel = crop(&viewer.capture(), VIEW);
    assert_eq!(
        diff_images(&before, &after_panel).max_abs,
        0,
        "a panel drag changed the image"
    );

    viewer.drag("1", (550, 200), (650, 240));
    viewer.wait_for("ready");
    let after_view = crop(&viewer.capture(), VIEW);
    let d = diff_images(&before, &after_view);
    assert!(
        d.frac_over_8 > 0.05,
        "a view drag should change the image: {d:?}"
    );
    assert!(viewer.is_running());
}

#[test]
fn clicking_an_object_selects_it_in_the_panel() {
    let _serial = serial();
    let Some(display) = Display::start() else {
        return;
    };
    let path = scene_path("whitted");
    let mut viewer = open(&display, &[path.to_str().unwrap()]);
    // The glass sphere fills the middle of the right half; the sky is above.
    viewer.click((560, 200));
    assert_eq!(viewer.wait_for("selected"), "Some(Sphere(0))");
    viewer.click((560, 20));
    assert_eq!(viewer.wait_for("selected"), "None");
}

/// Squared distance (in pixels, up to `reach`) from each pixel to the
/// nearest pixel where `inside` holds; `reach + 1` when none is that close.
fn squared_distances(inside: &[bool], (w, h): (u32, u32), reach: i64) -> Vec<i64> {
    let r = (reach as f64).sqrt().ceil() as i64;
    let (w, h) = (i64::from(w), i64::from(h));
    let mut out = vec![reach + 1; inside.len()];
    for y in 0..h {
        for x in 0..w {
            for dy in -r..=r {
                for dx in -r..=r {
                    let (u, v) = (x + dx, y + dy);
                    let d = dx * dx + dy * dy;
                    let i = (y * w + x) as usize;
                    if (0..w).contains(&u)
                        && (0..h).contains(&v)
                        && d < out[i]
                        && inside[(v * w + u) as usize]
                    {
                        out[i] = d;
                    }
                }
            }
        }
    }
    out
}

#[test]
fn the_picked_object_is_outlined_around_its_silhouette() {
    let _serial = serial();
    let Some(display) = Display::start() else {
        return;
    };
    let path = scene_path("whitted");
    let mut viewer = open(&display, &[path.to_str().unwrap()]);
    let before = viewer.capture();
    viewer.click((560, 200));
    assert_eq!(viewer.wait_for("selected"), "Some(Sphere(0))");
    let after = viewer.capture();

    // Where the glass sphere is, from the reference's first hits.
    let scene = Scene::load(&path).unwrap();
    let hits = reference::first_hits(&reference::PreparedScene::new(&scene), WIDTH, HEIGHT);
    let sphere: Vec<bool> = hits
        .iter()
        .map(|h| matches!(h, Some((ShapeId::Sphere(0), _))))
        .collect();
    // The band is 2 px wide, then a dark ring; the GPU's silhouette may
    // differ from the reference's by a pixel.
    let distance = squared_distances(&sphere, (WIDTH, HEIGHT), 16);
    let (x0, y0, w, h) = VIEW;
    let (mut changed, mut changed_away, mut next_to, mut next_to_outlined) = (0, 0, 0, 0);
    for y in y0..y0 + h {
        for x in x0..x0 + w {
            let d = distance[(y * WIDTH + x) as usize];
            let now = after.get_pixel(x, y);
            if now != before.get_pixel(x, y) {
                changed += 1;
                if d == 0 || d > 16 {
                    changed_away += 1;
                }
            }
            if d == 1 {
                next_to += 1;
                if now.0[..3] == OUTLINE_COLOR {
                    next_to_outlined += 1;
                }
            }
        }
    }
    println!(
        "changed {changed} pixels, {changed_away} away from the silhouette; \
         {next_to_outlined} of {next_to} pixels next to it outlined"
    );
    assert!(changed > 500, "no outline drawn: {changed} pixels changed");
    assert!(
        changed_away * 100 <= changed,
        "{changed_away} of {changed} changed pixels are not around the sphere"
    );
    assert!(
        next_to > 300 && next_to_outlined * 100 >= next_to * 95,
        "{next_to_outlined} of {next_to} pixels next to the sphere are outlined"
    );

    viewer.click((560, 20));
    assert_eq!(viewer.wait_for("selected"), "None");
    assert_eq!(
        diff_images(&crop(&before, VIEW), &crop(&viewer.capture(), VIEW)).max_abs,
        0,
        "the outline is gone with the selection"
    );
}

#[test]
fn a_broken_shader_keeps_the_last_good_image_and_the_fix_renders_again() {
    let _serial = serial();
    let Some(display) = Display::start() else {
        return;
    };
    let dir = temp_dir("shaders");
    let shaders = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
    common::copy_dir(&shaders, &dir);
    let path = scene_path("whitted");
    let mut viewer = open(
        &display,
        &[path.to_str().unwrap(), "--shaders", dir.to_str().unwrap()],
    );
    let good = viewer.capture();

    let shade = dir.join("shade.wgsl");
    let original = std::fs::read_to_string(&shade).unwrap();
    let broken = original.replacen("return color;", "return color", 1);
    let line = original[..original.find("return color;").unwrap()]
        .lines()
        .count()
        + 1;
    std::fs::write(&shade, &broken).unwrap();
    let location = viewer.wait_for("shader-error");
    assert!(
        location.contains("shade.wgsl:"),
        "the error names the file: {location}"
    );
    let reported_line: usize = location.split(':').nth(1).unwrap().parse().unwrap();
    assert!(
        reported_line == line || reported_line == line + 1,
        "error at line {reported_line}, the broken line is {line}"
    );
    std::thread::sleep(Duration::from_millis(500));
    assert!(
        viewer.is_running(),
        "a broken shader must not stop the viewer"
    );
    let during = viewer.capture();
    // The overlay covers the top of the view; below it the image is unchanged.
    let below_overlay = (VIEW.0, 250, VIEW.2, VIEW.3 - 250);
    assert_eq!(
        diff_images(&crop(&good, below_overlay), &crop(&during, below_overlay)).max_abs,
        0,
        "the last good image must stay"
    );
    let top = (VIEW.0, 0, VIEW.2, 120);
    assert!(
        diff_images(&crop(&good, top), &crop(&during, top)).frac_over_8 > 0.05,
        "the error overlay should be visible"
    );

    std::fs::write(&shade, &original).unwrap();
    viewer.wait_for("shaders-reloaded");
    viewer.wait_for("ready");
    let fixed = viewer.capture();
    assert_eq!(
        diff_images(&crop(&good, VIEW), &crop(&fixed, VIEW)).max_abs,
        0
    );
}

#[test]
fn a_scene_saved_from_the_viewer_loads_back_equal() {
    let _serial = serial();
    let Some(display) = Display::start() else {
        return;
    };
    let dir = temp_dir("save");
    let path = scene_copy("cornell", &dir);
    let original = Scene::load(&path).unwrap();
    let mut viewer = open(&display, &[path.to_str().unwrap()]);

    viewer.key("ctrl+s");
    let saved = viewer.wait_for("saved");
    assert_eq!(Path::new(&saved), path);
    assert_eq!(
        Scene::load(&path).unwrap(),
        original,
        "an unedited save changes nothing"
    );

    viewer.drag("1", (550, 200), (640, 260));
    viewer.wait_for("ready");
    viewer.key("ctrl+s");
    viewer.wait_for("saved");
    let edited = Scene::load(&path).unwrap();
    assert_ne!(
        edited.camera.from, original.camera.from,
        "the orbit was saved"
    );
    assert_eq!(edited.camera.to, original.camera.to);
    assert_eq!(edited.spheres, original.spheres);
    assert_eq!(edited.materials, original.materials);
    let leftovers = std::fs::read_dir(&dir).unwrap().count();
    assert_eq!(leftovers, 1, "no temporary files are left");
}

/// A window larger than the GPU can draw into is refused before it shows:
/// exit status 2 and a message naming the limit, for the viewer and the
/// shader sandbox alike.
#[test]
fn window_larger_than_the_gpu_allows_exits_2_naming_the_limit() {
    let _serial = serial();
    let Some(display) = Display::start() else {
        return;
    };
    let max = common::gpu()
        .unwrap()
        .device
        .limits()
        .max_texture_dimension_2d;
    let size = format!("{}x64", max + 1);
    let shader = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/shaders/whitted.wgsl");
    for args in [
        vec!["view", "--size", &size],
        vec!["shader", shader.to_str().unwrap(), "--size", &size],
    ] {
        let out = display.run(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains(&format!("1 to {max} pixels")),
            "{args:?}: {stderr}"
        );
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    }
}
