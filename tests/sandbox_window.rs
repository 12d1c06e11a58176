//! `raysandbox shader` as a person uses it: the real binary in a window under
//! Xvfb, the shader file edited on disk, the window's pixels captured with
//! ImageMagick's `import` and compared with headless renders.
//!
//! The hidden `--print-events` flag prints a line per event ("ready",
//! "shader-reloaded", "shader-error FILE:LINE:COL", ...) once the frame it
//! concerns is on screen, so the test waits for events instead of sleeping.

mod common;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::{Duration, Instant};

use image::RgbaImage;
use raysandbox::compare::diff_images;
use raysandbox::sandbox::render_file;

const WIDTH: u32 = 640;
const HEIGHT: u32 = 360;
/// A part of the window the panel (top left) and the error overlay (bottom)
/// leave uncovered.
const FREE: (u32, u32, u32, u32) = (350, 0, 290, 150);
const TIMEOUT: Duration = Duration::from_secs(120);

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
            eprintln!("!!! SKIPPING SANDBOX WINDOW TEST: {missing:?} missing. Run scripts/test.");
            return None;
        }
        common::gpu()?;
        // Display numbers apart from tests/viewer.rs's (40..=439 + n).
        let number = (0..)
            .map(|k| 500 + std::process::id() % 400 + k)
            .find(|n| !Path::new(&format!("/tmp/.X11-unix/X{n}")).exists())
            .unwrap();
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

/// The sandbox window and the events it prints.
struct Window<'d> {
    display: &'d Display,
    child: Child,
    events: Receiver<String>,
    id: String,
}

impl<'d> Window<'d> {
    fn open(display: &'d Display, shader: &Path) -> Window<'d> {
        let mut child = Command::new(env!("CARGO_BIN_EXE_raysandbox"))
            .args(["shader", shader.to_str().unwrap()])
            .args(["--size", &format!("{WIDTH}x{HEIGHT}")])
            .args(["--start-paused", "--print-events"])
            .env("DISPLAY", &display.name)
            .env_remove("WAYLAND_DISPLAY")
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("start raysandbox shader");
        let stdout = child.stdout.take().unwrap();
        let (tx, events) = channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines().map_while(Result::ok) {
                if tx.send(line).is_err() {
                    break;
                }
            }
        });
        let mut window = Window {
            display,
            child,
            events,
            id: String::new(),
        };
        window.wait_for("ready");
        window.id = window
            .xdotool(&["search", "--sync", "--name", "raysandbox"])
            .lines()
            .last()
            .expect("a window")
            .to_string();
        window
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
                Err(RecvTimeoutError::Disconnected) => panic!(
                    "the window closed while waiting for '{prefix}': {:?}",
                    self.child.try_wait()
                ),
            }
        }
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

    /// Without a window manager nobody gives the window the keyboard: the
    /// test does, as a click would.
    fn key(&self, keys: &str) {
        self.xdotool(&["windowfocus", "--sync", &self.id]);
        self.xdotool(&["key", keys]);
    }

    fn capture(&self, dir: &Path) -> RgbaImage {
        let file = dir.join(format!("capture-{}.png", self.id));
        let status = Command::new("import")
            .args(["-window", &self.id, file.to_str().unwrap()])
            .env("DISPLAY", &self.display.name)
            .status()
            .expect("run import");
        assert!(status.success(), "import failed");
        let image = image::open(&file).expect("captured PNG").to_rgba8();
        assert_eq!(image.dimensions(), (WIDTH, HEIGHT), "window size");
        image
    }
}

impl Drop for Window<'_> {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn crop(image: &RgbaImage, (x, y, w, h): (u32, u32, u32, u32)) -> RgbaImage {
    image::imageops::crop_imm(image, x, y, w, h).to_image()
}

const RINGS: &str = "\
uniform float time;
uniform vec2 resolution;

void main() {
    vec2 p = gl_FragCoord.xy / resolution;
    float r = length(p - vec2(0.7, 0.6));
    gl_FragColor = vec4(p.x, p.y, 0.5 + 0.5 * sin(60.0 * r - time), 1.0);
}
";

#[test]
fn the_window_renders_the_file_and_follows_its_edits() {
    let Some(display) = Display::start() else {
        return;
    };
    let gpu = common::gpu().unwrap();
    let dir = std::env::temp_dir().join(format!("raysandbox-window-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let shader = dir.join("live.frag");
    std::fs::write(&shader, RINGS).unwrap();
    let headless = |shader: &PathBuf| {
        let (image, _) = render_file(&gpu, shader, (WIDTH, HEIGHT), 0.0, None).unwrap();
        crop(&image, FREE)
    };

    let mut window = Window::open(&display, &shader);
    let first = crop(&window.capture(&dir), FREE);
    let d = diff_images(&first, &headless(&shader));
    assert!(d.max_abs <= 1, "the window shows the shader: {d:?}");

    // An edit in another program: the window follows.
    let edited = RINGS.replace("vec2(0.7, 0.6)", "vec2(0.9, 0.2)");
    std::fs::write(&shader, &edited).unwrap();
    window.wait_for("shader-reloaded");
    let second = crop(&window.capture(&dir), FREE);
    assert!(diff_images(&first, &second).max_abs > 50, "the edit shows");
    let d = diff_images(&second, &headless(&shader));
    assert!(d.max_abs <= 1, "the window shows the edit: {d:?}");

    // A mistake: reported at its line, the last good image stays.
    let broken = edited.replace("float r = length", "float r = lenght");
    std::fs::write(&shader, &broken).unwrap();
    let location = window.wait_for("shader-error");
    assert_eq!(location, format!("{}:6:15", shader.display()));
    let during = crop(&window.capture(&dir), FREE);
    assert_eq!(
        diff_images(&second, &during).max_abs,
        0,
        "the last good image stays"
    );

    // Fixed again, then a screenshot of the image.
    std::fs::write(&shader, RINGS).unwrap();
    window.wait_for("shader-reloaded");
    let fixed = crop(&window.capture(&dir), FREE);
    assert_eq!(diff_images(&first, &fixed).max_abs, 0);
    window.key("p");
    let path = PathBuf::from(window.wait_for("screenshot"));
    assert_eq!(path, dir.join("live-screenshot-1.png"));
    let shot = image::open(&path).unwrap().to_rgba8();
    assert_eq!(shot.dimensions(), (WIDTH, HEIGHT));
    drop(window);
    std::fs::remove_dir_all(&dir).unwrap();
}
