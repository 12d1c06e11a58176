//! The viewer as a person uses it: the real binary in a window under Xvfb,
//! driven with xdotool, its pixels captured with ImageMagick's `import`.
//!
//! The binary's hidden `--print-events` flag prints a line per event
//! ("ready samples=N" when refinement is done, "saved PATH", "shader-error",
//! ...), so the tests wait for what they need instead of sleeping blindly.

mod common;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, Instant};

use image::RgbaImage;
use raysandbox::compare::diff_images;
use raysandbox::gpu::render_image;
use raysandbox::scene::Scene;

const WIDTH: u32 = 800;
const HEIGHT: u32 = 450;
/// The part of the window that shows the image: right of the side panel
/// (about 300 px wide) and above the status line.
const VIEW: (u32, u32, u32, u32) = (360, 0, WIDTH - 360, HEIGHT - 40);
/// Lavapipe on two cores is slow: refinement can take a while.
const TIMEOUT: Duration = Duration::from_secs(120);

/// One viewer at a time: each drives its own X server, but lavapipe's
/// rendering shares the machine's two cores.
static SERIAL: Mutex<()> = Mutex::new(());

fn serial() -> MutexGuard<'static, ()> {
    SERIAL.lock().unwrap_or_else(|e| e.into_inner())
}

fn have(tool: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {tool}")])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// An Xvfb server of our own, stopped on drop.
struct Display {
    server: Child,
    name: String,
}

impl Display {
    /// `None` (with a loud message) off CI when Xvfb, xdotool or ImageMagick
    /// is missing; in CI their absence fails the test (scripts/test installs them).
    fn start() -> Option<Display> {
        let missing: Vec<&str> = ["Xvfb", "xdotool", "import"]
            .into_iter()
            .filter(|t| !have(t))
            .collect();
        if !missing.is_empty() {
            if std::env::var("CI").is_ok_and(|v| v == "true") {
                panic!("CI=true and {missing:?} missing: scripts/test installs them");
            }
            eprintln!("!!! SKIPPING VIEWER TEST: {missing:?} missing. Run scripts/test.");
            return None;
        }
        common::gpu()?;
        static NEXT: AtomicU32 = AtomicU32::new(0);
        let number = loop {
            let n = 40 + std::process::id() % 400 + NEXT.fetch_add(1, Ordering::SeqCst);
            if !Path::new(&format!("/tmp/.X11-unix/X{n}")).exists() {
                break n;
            }
        };
        let name = format!(":{number}");
        let server = Command::new("Xvfb")
            .args([
                name.as_str(),
                "-screen",
                "0",
                "1024x768x24",
                "-nolisten",
                "tcp",
            ])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("start Xvfb");
        let socket = format!("/tmp/.X11-unix/X{number}");
        let start = Instant::now();
        while !Path::new(&socket).exists() {
            assert!(
                start.elapsed() < Duration::from_secs(20),
                "Xvfb did not start"
            );
            std::thread::sleep(Duration::from_millis(50));
        }
        Some(Display { server, name })
    }
}

impl Drop for Display {
    fn drop(&mut self) {
        let _ = self.server.kill();
        let _ = self.server.wait();
    }
}

/// The viewer process and the events it prints.
struct Viewer<'d> {
    display: &'d Display,
    child: Child,
    events: Receiver<String>,
    window: String,
}

impl<'d> Viewer<'d> {
    fn start(display: &'d Display, args: &[&str]) -> Viewer<'d> {
        let size = format!("{WIDTH}x{HEIGHT}");
        let mut child = Command::new(env!("CARGO_BIN_EXE_raysandbox"))
            .arg("view")
            .args(args)
            .args(["--size", &size, "--max-samples", "1", "--print-events"])
            .env("DISPLAY", &display.name)
            .env_remove("WAYLAND_DISPLAY")
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("start the viewer");
        let stdout = child.stdout.take().unwrap();
        let (tx, events) = channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines().map_while(Result::ok) {
                if tx.send(line).is_err() {
                    break;
                }
            }
        });
        let mut viewer = Viewer {
            display,
            child,
            events,
            window: String::new(),
        };
        viewer.wait_for("ready");
        viewer.window = viewer
            .xdotool(&["search", "--sync", "--name", "raysandbox"])
            .lines()
            .last()
            .expect("a window")
            .to_string();
        viewer
    }

    /// Waits for an event line starting with `prefix`; returns the rest.
    fn wait_for(&mut self, prefix: &str) -> String {
        let deadline = Instant::now() + TIMEOUT;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.events.recv_timeout(left) {
                Ok(line) => {
                    if let Some(rest) = line.strip_prefix(&format!("event: {prefix}")) {
                        return rest.trim().to_string();
                    }
                }
                Err(RecvTimeoutError::Timeout) => panic!("no '{prefix}' event within {TIMEOUT:?}"),
                Err(RecvTimeoutError::Disconnected) => {
                    panic!(
                        "the viewer exited while waiting for '{prefix}': {:?}",
                        self.child.try_wait()
                    )
                }
            }
        }
    }

    /// Events that arrive within `wait`, without waiting for a given one.
    fn events_within(&self, wait: Duration) -> Vec<String> {
        std::thread::sleep(wait);
        self.events.try_iter().collect()
    }

    fn xdotool(&self, args: &[&str]) -> String {
        let out = Command::new("xdotool")
            .args(args)
            .env("DISPLAY", &self.display.name)
            .output()
            .expect("run xdotool");
        assert!(
            out.status.success(),
            "xdotool {args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stdout).into_owned()
    }

    /// Drags with `button` from `a` to `b` (window pixels) in small steps.
    fn drag(&self, button: &str, a: (u32, u32), b: (u32, u32)) {
        let window = self.window.clone();
        let at = |p: (u32, u32)| {
            self.xdotool(&[
                "mousemove",
                "--window",
                &window,
                &p.0.to_string(),
                &p.1.to_string(),
            ]);
        };
        at(a);
        self.xdotool(&["mousedown", button]);
        for step in 1..=10 {
            let lerp = |s: u32, e: u32| (s as i64 + (e as i64 - s as i64) * step / 10) as u32;
            at((lerp(a.0, b.0), lerp(a.1, b.1)));
            std::thread::sleep(Duration::from_millis(30));
        }
        self.xdotool(&["mouseup", button]);
    }

    fn click(&self, at: (u32, u32)) {
        let (x, y) = (at.0.to_string(), at.1.to_string());
        self.xdotool(&["mousemove", "--window", &self.window, &x, &y, "click", "1"]);
    }

    /// Presses keys in the window. Without a window manager nobody gives the
    /// window the keyboard focus, so the test does, as a click would.
    fn key(&self, keys: &str) {
        self.xdotool(&["windowfocus", "--sync", &self.window]);
        self.xdotool(&["key", keys]);
    }

    /// The window's pixels as shown on the X server.
    fn capture(&self) -> RgbaImage {
        let file = temp_dir("capture").join(format!("{}.png", self.window));
        let status = Command::new("import")
            .args(["-window", &self.window, file.to_str().unwrap()])
            .env("DISPLAY", &self.display.name)
            .status()
            .expect("run import");
        assert!(status.success(), "import failed");
        let image = image::open(&file).expect("captured PNG").to_rgba8();
        assert_eq!(image.dimensions(), (WIDTH, HEIGHT), "window size");
        image
    }

    fn is_running(&mut self) -> bool {
        self.child.try_wait().expect("query the viewer").is_none()
    }
}

impl Drop for Viewer<'_> {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("raysandbox-viewer-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn crop(image: &RgbaImage, (x, y, w, h): (u32, u32, u32, u32)) -> RgbaImage {
    image::imageops::crop_imm(image, x, y, w, h).to_image()
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
    let viewer = Viewer::start(&display, &[path.to_str().unwrap()]);
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
    let mut viewer = Viewer::start(&display, &[path.to_str().unwrap()]);
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
    let mut viewer = Viewer::start(&display, &[path.to_str().unwrap()]);
    // The glass sphere fills the middle of the right half; the sky is above.
    viewer.click((560, 200));
    assert_eq!(viewer.wait_for("selected"), "Some(Sphere(0))");
    viewer.click((560, 20));
    assert_eq!(viewer.wait_for("selected"), "None");
}

#[test]
fn a_broken_shader_keeps_the_last_good_image_and_the_fix_renders_again() {
    let _serial = serial();
    let Some(display) = Display::start() else {
        return;
    };
    let dir = temp_dir("shaders");
    let shaders = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
    for entry in std::fs::read_dir(&shaders).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), dir.join(entry.file_name())).unwrap();
    }
    let path = scene_path("whitted");
    let mut viewer = Viewer::start(
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
    let mut viewer = Viewer::start(&display, &[path.to_str().unwrap()]);

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
