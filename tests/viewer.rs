//! The viewer as a person uses it: the real binary in a window under Xvfb,
//! driven with xdotool, its pixels captured with ImageMagick's `import`
//! (tests/common/xwindow.rs).

mod common;

use std::path::{Path, PathBuf};
use std::time::Duration;

use common::xwindow::{Display, Rect, Window, crop, serial};
use raysandbox::compare::diff_images;
use raysandbox::gpu::{OUTLINE_COLOR, render_image};
use raysandbox::reference;
use raysandbox::scene::{Scene, ShapeId};

const WIDTH: u32 = 800;
const HEIGHT: u32 = 450;

/// The part of the window that shows the image uncovered, from the
/// window's own layout: right of the side panel (and its resize handle)
/// and above the status line.
fn view(viewer: &Window) -> Rect {
    let panel = viewer.part("panel");
    let status = viewer.part("status");
    let x = panel.right() + 16;
    let view = Rect {
        x,
        y: 0,
        w: WIDTH as i32 - x,
        h: status.y,
    };
    assert!(
        view.w >= 200 && view.h >= 200,
        "the panel leaves too little of the image: {view:?}"
    );
    view
}

/// How far an egui window's shadow reaches beyond the window, in pixels
/// (egui's default shadow: 20 px down, blurred over 15).
const SHADOW: i32 = 40;

/// Asserts that a point the test clicks on in the image is in its
/// uncovered part.
fn in_view(viewer: &Window, (x, y): (u32, u32)) -> (u32, u32) {
    let view = view(viewer);
    let (x, y) = (x as i32, y as i32);
    assert!(
        (view.x..view.right()).contains(&x) && (view.y..view.bottom()).contains(&y),
        "({x}, {y}) is not in the uncovered image {view:?}"
    );
    (x as u32, y as u32)
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
    let display = Display::start();
    let path = scene_path("whitted");
    let viewer = open(&display, &[path.to_str().unwrap()]);
    let window = viewer.capture();
    let gpu = common::gpu();
    let scene = Scene::load(&path).unwrap();
    let headless = render_image(&gpu, &scene, WIDTH, HEIGHT, 1).unwrap();
    let area = view(&viewer).crop();
    assert_same_picture(
        &crop(&window, area),
        &crop(&headless, area),
        "window vs headless",
    );
}

#[test]
fn dragging_in_the_view_orbits_but_dragging_on_the_panel_does_not() {
    let _serial = serial();
    let display = Display::start();
    let path = scene_path("mirror_cube");
    let mut viewer = open(&display, &[path.to_str().unwrap()]);
    let area = view(&viewer).crop();
    let before = crop(&viewer.capture(), area);

    // A drag over the panel's empty lower part, below its last row: egui
    // takes it.
    let panel = viewer.part("panel");
    let content = viewer.part("panel-content");
    let empty = Rect {
        y: content.bottom(),
        h: panel.bottom() - content.bottom(),
        ..panel
    };
    assert!(
        empty.h >= 40,
        "the panel {panel:?} has no empty part below its rows {content:?}"
    );
    viewer.drag("1", empty.at(0.3, 0.8), empty.at(0.7, 0.2));
    let events = viewer.events_within(Duration::from_secs(2));
    assert!(events.is_empty(), "the camera moved: {events:?}");
    let after_panel = crop(&viewer.capture(), area);
    assert_eq!(
        diff_images(&before, &after_panel).max_abs,
        0,
        "a panel drag changed the image"
    );

    orbit(&mut viewer, area, &before);
    assert!(viewer.is_running());
}

/// Drags in the view (an orbit), waits until the image is refined and
/// returns it, cropped to `area`; it must differ from `before`.
fn orbit(
    viewer: &mut Window,
    area: (u32, u32, u32, u32),
    before: &image::RgbaImage,
) -> image::RgbaImage {
    viewer.drag("1", in_view(viewer, (550, 200)), (650, 240));
    viewer.wait_for("ready");
    let after = crop(&viewer.capture(), area);
    let d = diff_images(before, &after);
    assert!(
        d.frac_over_8 > 0.05,
        "a view drag should change the image: {d:?}"
    );
    after
}

/// The number after `NAME=` in an event line (`ready samples=4 jobs=9`).
fn event_field(line: &str, name: &str) -> f64 {
    line.split_whitespace()
        .find_map(|field| field.strip_prefix(name)?.strip_prefix('='))
        .and_then(|value| value.parse().ok())
        .unwrap_or_else(|| panic!("no {name} in {line:?}"))
}

/// Asserts that two pictures of the window are the same but for the
/// rounding of a few pixels; prints how far apart they are.
fn assert_same_picture(a: &image::RgbaImage, b: &image::RgbaImage, what: &str) {
    let d = diff_images(a, b);
    println!("{what}: mean {:.4}, max {}", d.mean_abs, d.max_abs);
    assert!(d.mean_abs <= 0.5 && d.frac_over_8 <= 0.001, "{what}: {d:?}");
}

/// Dragging a slider of the panel (the camera's fov, in the Camera section
/// open at the start) traces at a moving scale below 1, and the image
/// refines once the slider is let go (docs/performance.md, "Julia sets:
/// dragging c").
#[test]
fn dragging_a_slider_traces_at_the_moving_scale_then_refines() {
    let _serial = serial();
    let display = Display::start();
    let path = scene_path("mirror_cube");
    let mut viewer = open(&display, &[path.to_str().unwrap()]);
    // On the slider's rail, left of its number.
    let (x, y) = viewer.part("camera-fov").at(0.1, 0.5);
    viewer.drag("1", (x, y), (x + 50, y));
    let moving = viewer.wait_for("moving-frame");
    let scale = event_field(&moving, "scale");
    assert!((0.125..1.0).contains(&scale), "{moving}");
    viewer.wait_for("ready");
    assert!(viewer.is_running());
}

#[test]
fn clicking_an_object_selects_it_in_the_panel() {
    let _serial = serial();
    let display = Display::start();
    let path = scene_path("whitted");
    let mut viewer = open(&display, &[path.to_str().unwrap()]);
    // The glass sphere fills the middle of the right half; the sky is above.
    viewer.click(in_view(&viewer, (560, 200)));
    assert_eq!(viewer.wait_for("selected"), "Some(Sphere(0))");
    viewer.click(in_view(&viewer, (560, 20)));
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
    let display = Display::start();
    let path = scene_path("whitted");
    let mut viewer = open(&display, &[path.to_str().unwrap()]);
    let before = viewer.capture();
    viewer.click(in_view(&viewer, (560, 200)));
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
    let area = view(&viewer).crop();
    let (x0, y0, w, h) = area;
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

    viewer.click(in_view(&viewer, (560, 20)));
    assert_eq!(viewer.wait_for("selected"), "None");
    assert_eq!(
        diff_images(&crop(&before, area), &crop(&viewer.capture(), area)).max_abs,
        0,
        "the outline is gone with the selection"
    );
}

#[test]
fn a_broken_shader_keeps_the_last_good_image_and_the_fix_renders_again() {
    let _serial = serial();
    let display = Display::start();
    let dir = temp_dir("shaders");
    let shaders = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
    common::copy_dir(&shaders, &dir);
    let path = scene_path("whitted");
    let mut viewer = open(
        &display,
        &[path.to_str().unwrap(), "--shaders", dir.to_str().unwrap()],
    );
    let good = viewer.capture();
    let area = view(&viewer);

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
    let overlay = viewer.part("shader-error");
    let below_overlay = Rect {
        y: overlay.bottom() + SHADOW,
        h: area.bottom() - overlay.bottom() - SHADOW,
        ..area
    }
    .crop();
    assert_eq!(
        diff_images(&crop(&good, below_overlay), &crop(&during, below_overlay)).max_abs,
        0,
        "the last good image must stay"
    );
    let top = Rect {
        h: overlay.bottom(),
        ..area
    }
    .crop();
    assert!(
        diff_images(&crop(&good, top), &crop(&during, top)).frac_over_8 > 0.05,
        "the error overlay should be visible"
    );

    std::fs::write(&shade, &original).unwrap();
    viewer.wait_for("shaders-reloaded");
    viewer.wait_for("ready");
    let fixed = viewer.capture();
    let area = area.crop();
    assert_eq!(
        diff_images(&crop(&good, area), &crop(&fixed, area)).max_abs,
        0
    );
}

#[test]
fn a_scene_saved_from_the_viewer_loads_back_equal() {
    let _serial = serial();
    let display = Display::start();
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

    viewer.drag("1", in_view(&viewer, (550, 200)), (640, 260));
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
    let display = Display::start();
    let max = common::gpu().device.limits().max_texture_dimension_2d;
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

/// A floor, a light and one mesh read from `shape.obj` beside the scene.
const MESH_SCENE: &str = r#"
[render]
ambient = [0.2, 0.2, 0.2]
[camera]
from = [0, 1.5, 4]
to = [0, 0.5, 0]
fov = 45
[[lights]]
position = [3, 6, 4]
[materials.red]
color = [0.9, 0.2, 0.1]
[[planes]]
point = [0, 0, 0]
normal = [0, 1, 0]
[[meshes]]
file = "shape.obj"
material = "red"
"#;

/// A tetrahedron standing on the floor, and a wide flat quad.
const TETRAHEDRON: &str =
    "v -1 0 1\nv 1 0 1\nv 0 0 -1\nv 0 1.5 0\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
const QUAD: &str = "v -2 0.01 -1\nv 2 0.01 -1\nv 2 1.2 -1\nv -2 1.2 -1\nf 1 2 3 4\n";

/// Types `text` into the panel's field at `at` and presses Enter.
fn type_into(viewer: &Window, at: (u32, u32), text: &str) {
    viewer.click(at);
    viewer.key("ctrl+a");
    viewer.xdotool(&["type", "--delay", "10", text]);
    viewer.key("Return");
}

/// A model typed into "Add file" is read and added in front of the camera,
/// named relative to the scene file; a file no shape is made from is
/// reported and the scene left as it was.
#[test]
fn a_model_typed_into_add_file_is_added_in_view_and_another_file_is_refused() {
    let _serial = serial();
    let display = Display::start();
    let dir = temp_dir("add-file");
    std::fs::create_dir_all(dir.join("models")).unwrap();
    std::fs::write(dir.join("models/tet.obj"), TETRAHEDRON).unwrap();
    std::fs::write(dir.join("notes.stl"), "solid").unwrap();
    let path = dir.join("scene.toml");
    let scene_text =
        MESH_SCENE.replace("[[meshes]]\nfile = \"shape.obj\"\nmaterial = \"red\"\n", "");
    std::fs::write(&path, &scene_text).unwrap();
    let mut viewer = open(&display, &[path.to_str().unwrap()]);
    viewer.click(viewer.part("section:Shapes").at(0.3, 0.5));
    // The refused file first: adding a shape selects it, and the panel
    // scrolls to the selection, away from the field.
    let field = viewer.part("add-file").at(0.8, 0.5);
    type_into(&viewer, field, dir.join("notes.stl").to_str().unwrap());
    let error = viewer.wait_for("file-error");
    assert!(
        error.contains("notes.stl: no shape is made from this file"),
        "{error}"
    );
    viewer.key("ctrl+s");
    viewer.wait_for("saved");
    let before = Scene::from_toml_str(&scene_text, None).unwrap();
    assert_eq!(
        Scene::load(&path).unwrap(),
        before,
        "the scene is as it was"
    );

    let field = viewer.part("add-file").at(0.8, 0.5);
    type_into(&viewer, field, dir.join("models/tet.obj").to_str().unwrap());
    assert!(viewer.wait_for("shape-added").ends_with("tet.obj"));
    viewer.wait_for("ready");
    viewer.key("ctrl+s");
    viewer.wait_for("saved");
    let saved = Scene::load(&path).unwrap();
    assert_eq!(saved.meshes.len(), 1);
    assert_eq!(
        saved.meshes[0].file.as_deref(),
        Some(Path::new("models/tet.obj"))
    );
    let [lo, hi] = saved.meshes[0].bounds();
    let centre = 0.5 * (lo + hi);
    assert!((centre - saved.camera.to).length() < 1e-9, "{centre}");
    assert!(viewer.is_running());
}

#[test]
fn a_mesh_file_edited_on_disk_reloads_and_a_bad_edit_keeps_the_last_good_mesh() {
    let _serial = serial();
    let display = Display::start();
    let dir = temp_dir("mesh-reload");
    let obj = dir.join("shape.obj");
    std::fs::write(&obj, TETRAHEDRON).unwrap();
    let path = dir.join("scene.toml");
    std::fs::write(&path, MESH_SCENE).unwrap();
    let mut viewer = open(&display, &[path.to_str().unwrap()]);
    let tetrahedron = viewer.capture();
    let (area, panel) = (view(&viewer).crop(), viewer.part("panel").crop());

    // Another good mesh: it is drawn.
    std::fs::write(&obj, QUAD).unwrap();
    assert!(viewer.wait_for("file-reloaded").ends_with("shape.obj"));
    viewer.wait_for("ready");
    let quad = viewer.capture();
    let d = diff_images(&crop(&tetrahedron, area), &crop(&quad, area));
    assert!(d.frac_over_8 > 0.02, "the new mesh is not drawn: {d:?}");

    // A bad file (line 5 names a vertex that does not exist): the error
    // names the file and the line, the last good mesh keeps rendering and
    // the panel shows the error.
    let bad = QUAD.replace("f 1 2 3 4", "f 1 2 3 9");
    std::fs::write(&obj, bad).unwrap();
    let error = viewer.wait_for("file-error");
    assert!(
        error.contains("shape.obj:5: face vertex index 9"),
        "{error}"
    );
    std::thread::sleep(Duration::from_millis(500));
    assert!(
        viewer.is_running(),
        "a bad mesh file must not stop the viewer"
    );
    let during = viewer.capture();
    // The status line may have wrapped its figures to another height since.
    let area = (area.0, area.1, area.2, area.3.min(view(&viewer).crop().3));
    assert_eq!(
        diff_images(&crop(&quad, area), &crop(&during, area)).max_abs,
        0,
        "the last good mesh must stay"
    );
    let shown = diff_images(&crop(&quad, panel), &crop(&during, panel));
    assert!(
        shown.frac_over_8 > 0.002,
        "no error in the panel: {shown:?}"
    );

    // Fixed again: drawn again, the error is gone from the panel.
    std::fs::write(&obj, TETRAHEDRON).unwrap();
    viewer.wait_for("file-reloaded");
    viewer.wait_for("ready");
    let fixed = viewer.capture();
    assert_eq!(
        diff_images(&crop(&tetrahedron, area), &crop(&fixed, area)).max_abs,
        0
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An implicit surface and a Julia set on a floor.
const IMPLICIT_SCENE: &str = r#"
[render]
ambient = [0.2, 0.2, 0.2]
[camera]
from = [0, 1.5, 5]
to = [0, 0.7, 0]
fov = 45
[[lights]]
position = [3, 6, 4]
[materials.blue]
color = [0.2, 0.35, 0.85]
[[planes]]
point = [0, 0, 0]
normal = [0, 1, 0]
[[implicits]]
f = "x^2 + y^2 + z^2 - 1"
bounds = [[-1.1, -1.1, -1.1], [1.1, 1.1, 1.1]]
steps = 64
translate = [-1, 0.8, 0]
scale = 0.7
material = "blue"
[[julias]]
c = [-0.2, 0.6, 0.2, 0.2]
translate = [1, 0.8, 0]
scale = 0.5
"#;

/// The viewer is given the scene file rewritten with bad implicit input
/// (docs/scene-format.md, "Errors"): each time it reports the key (and the
/// column of a bad function) and keeps drawing the last good scene under the
/// error window, then takes the file again once it is fixed.
#[test]
fn bad_implicit_input_keeps_the_last_good_scene_and_shows_the_error() {
    let _serial = serial();
    let display = Display::start();
    let dir = temp_dir("bad-implicit");
    let path = dir.join("implicit.toml");
    std::fs::write(&path, IMPLICIT_SCENE).unwrap();
    let mut viewer = open(&display, &[path.to_str().unwrap()]);
    let good = viewer.capture();
    let area = view(&viewer);
    let cases = [
        (
            r#"f = "x^2 + y^2 + z^2 - 1""#,
            r#"f = "x^2 + (y^2 + z^2 - 1""#,
            "implicits[0].f: column",
        ),
        (
            r#"f = "x^2 + y^2 + z^2 - 1""#,
            r#"f = "x^2 + foo(y) - 1""#,
            "implicits[0].f: column",
        ),
        (
            "c = [-0.2, 0.6, 0.2, 0.2]",
            "c = [2.5, 0, 0, 0]",
            "julias[0].c",
        ),
        ("steps = 64", "steps = 0", "implicits[0].steps"),
        (
            "c = [-0.2, 0.6, 0.2, 0.2]",
            "c = [-0.2, 0.6, 0.2, 0.2]\niterations = 0",
            "julias[0].iterations",
        ),
        (
            "bounds = [[-1.1, -1.1, -1.1], [1.1, 1.1, 1.1]]",
            "bounds = [[1.1, -1.1, -1.1], [-1.1, 1.1, 1.1]]",
            "implicits[0].bounds",
        ),
        ("scale = 0.5", "scale = nan", "julias[0].scale"),
    ];
    for (good_text, bad_text, key) in cases {
        let bad = IMPLICIT_SCENE.replacen(good_text, bad_text, 1);
        assert_ne!(bad, IMPLICIT_SCENE);
        // One write may reach the watcher as several changes: forget the
        // reports of the last one.
        viewer.events_within(Duration::from_millis(300));
        std::fs::write(&path, &bad).unwrap();
        let error = viewer.wait_for("scene-error");
        assert!(error.contains("implicit.toml:"), "{bad_text}: {error}");
        assert!(error.contains(key), "{bad_text}: {error}");
        std::thread::sleep(Duration::from_millis(500));
        assert!(viewer.is_running(), "{bad_text} stopped the viewer");
        let during = viewer.capture();
        // The error window sits at the bottom of the window; above it the
        // view must not change.
        let error = viewer.part("scene-error");
        let above_error = Rect {
            h: error.y - SHADOW,
            ..area
        }
        .crop();
        let error_area = Rect {
            y: error.y,
            h: area.bottom() - error.y,
            ..area
        }
        .crop();
        assert_eq!(
            diff_images(&crop(&good, above_error), &crop(&during, above_error)).max_abs,
            0,
            "{bad_text}: the last good scene must keep rendering"
        );
        let shown = diff_images(&crop(&good, error_area), &crop(&during, error_area));
        assert!(
            shown.frac_over_8 > 0.02,
            "{bad_text}: no error shown: {shown:?}"
        );
    }
    std::fs::write(&path, IMPLICIT_SCENE).unwrap();
    viewer.wait_for("scene-error-cleared");
    std::thread::sleep(Duration::from_millis(500));
    assert_eq!(
        diff_images(
            &crop(&good, area.crop()),
            &crop(&viewer.capture(), area.crop())
        )
        .max_abs,
        0,
        "the error window is gone once the file is fixed"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A lost GPU device (SIGUSR1 destroys it, as a driver reset would lose it)
/// is replaced by a new one in the same window: the picture comes back, the
/// edit made before the loss (an orbit) included.
#[test]
fn a_lost_device_is_recovered_keeping_the_scene_and_its_edits() {
    let _serial = serial();
    let display = Display::start();
    let path = scene_path("mirror_cube");
    let mut viewer = open(&display, &[path.to_str().unwrap()]);
    let area = view(&viewer).crop();
    let before = crop(&viewer.capture(), area);
    let orbited = orbit(&mut viewer, area, &before);

    let recovery = viewer.lose_device("viewer");
    assert!(recovery.reason.contains("destroyed"), "{}", recovery.reason);
    // The status line says what happened on a row of its own: the
    // uncovered image is shorter now.
    let shorter = view(&viewer).crop();
    let (w, h) = (area.2.min(shorter.2), area.3.min(shorter.3));
    let recovered = crop(&viewer.capture(), (area.0, area.1, w, h));
    assert_same_picture(
        &crop(&orbited, (0, 0, w, h)),
        &recovered,
        "the orbited view before the loss and after",
    );
    assert!(viewer.is_running());
}

/// While the view rests, each sample is traced in short GPU jobs of a few
/// rows (docs/performance.md, "Short GPU jobs"): four samples take at least
/// four jobs, the longest the planner sized is logged against its budget
/// (never below [`JOB_BUDGET`](raysandbox::gpu::JOB_BUDGET)), and the image the
/// jobs add up to is the headless render's at the same sample count.
#[test]
fn refinement_in_short_jobs_adds_up_to_the_headless_image() {
    let _serial = serial();
    let display = Display::start();
    let path = scene_path("whitted");
    let viewer = Window::open(
        &display,
        &["view", path.to_str().unwrap(), "--max-samples", "4"],
        (WIDTH, HEIGHT),
    );
    let ready = &viewer.ready;
    let field = |name: &str| event_field(ready, name);
    let (samples, jobs, longest) = (field("samples"), field("jobs"), field("longest_job_ms"));
    let (sized, budget) = (
        field("longest_sized_job_ms"),
        field("longest_sized_job_budget_ms"),
    );
    println!(
        "{samples} samples in {jobs} jobs, the longest {longest} ms, predicted {} ms for its {} \
         pixels; the longest the planner sized (not the first draw) {sized} ms against its \
         budget of {budget} ms",
        field("longest_job_predicted_ms"),
        field("longest_job_pixels"),
    );
    assert_eq!(samples, 4.0);
    assert!(jobs >= samples, "{ready}");
    assert!(sized > 0.0 && sized <= longest, "{ready}");
    let least = raysandbox::gpu::JOB_BUDGET.as_secs_f64() * 1e3;
    assert!(budget >= least, "a budget below {least} ms: {ready}");

    let window = viewer.capture();
    let gpu = common::gpu();
    let scene = Scene::load(&path).unwrap();
    let headless = render_image(&gpu, &scene, WIDTH, HEIGHT, 4).unwrap();
    let area = view(&viewer).crop();
    assert_same_picture(
        &crop(&window, area),
        &crop(&headless, area),
        "window vs headless at 4 spp",
    );
}
