//! The program's window as a person meets it: the real binary under an Xvfb
//! server of the test's own, driven with xdotool, its pixels captured with
//! ImageMagick's `import`.
//!
//! The binary's hidden `--print-events` flag prints a line per event
//! ("ready", "saved PATH", "shader-error FILE:LINE:COL", ...) once the frame
//! it concerns is on screen, so tests wait for events instead of sleeping.
//! Its `layout` events say where the panel and its parts are
//! (`src/app/layout.rs`): tests find what to click there, not at fixed
//! pixels, which move with the fonts and the length of a file's path.

use std::collections::HashMap;
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use image::RgbaImage;

/// One viewer at a time in a test binary: each test drives its own X
/// server, but lavapipe's rendering shares the machine's two cores, and a
/// viewer starved by two others answered too late for the tests' waits.
static SERIAL: Mutex<()> = Mutex::new(());

/// Held for the whole of a window test ([`SERIAL`]).
pub fn serial() -> MutexGuard<'static, ()> {
    SERIAL.lock().unwrap_or_else(|e| e.into_inner())
}

/// Lavapipe on two cores is slow: refinement can take a while.
const TIMEOUT: Duration = Duration::from_secs(120);

fn have(tool: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {tool}")])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// An Xvfb server of our own, stopped on drop.
pub struct Display {
    server: Child,
    name: String,
}

impl Display {
    /// The server, once Xvfb, xdotool, ImageMagick and a GPU adapter are
    /// found. Without one of them the test fails with a message saying how to
    /// install it.
    pub fn start() -> Display {
        let missing: Vec<&str> = ["Xvfb", "xdotool", "import"]
            .into_iter()
            .filter(|t| !have(t))
            .collect();
        assert!(
            missing.is_empty(),
            "this window test needs {missing:?}: install them with \
             `sudo apt-get install xvfb xdotool imagemagick`, or run scripts/test, which does."
        );
        super::require_gpu();
        super::record("window");
        // A free display number; test binaries run in parallel, so each
        // process starts from its own offset.
        static NEXT: AtomicU32 = AtomicU32::new(0);
        let number = loop {
            let n = 40 + std::process::id() % 4000 + NEXT.fetch_add(1, Ordering::SeqCst);
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
        Display { server, name }
    }
}

impl Display {
    /// The X display name (`:N`), for programs other than raysandbox.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Runs `raysandbox ARGS` on this display until it exits, e.g. to see it
    /// refuse to open a window.
    pub fn run(&self, args: &[&str]) -> std::process::Output {
        Command::new(env!("CARGO_BIN_EXE_raysandbox"))
            .args(args)
            .env("DISPLAY", &self.name)
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .expect("run raysandbox")
    }
}

impl Drop for Display {
    fn drop(&mut self) {
        let _ = self.server.kill();
        let _ = self.server.wait();
    }
}

/// A raysandbox window and the events it prints.
pub struct Window<'d> {
    display: &'d Display,
    child: Child,
    events: Receiver<String>,
    /// The parts of the last `layout` event, by name.
    layout: Arc<Mutex<HashMap<String, Rect>>>,
    /// The X window id.
    pub id: String,
    /// The first `ready` event, without its name (`samples=1 jobs=...`).
    pub ready: String,
    size: (u32, u32),
}

impl<'d> Window<'d> {
    /// Runs `raysandbox ARGS --size WxH --print-events` on `display` and
    /// waits until its first frame is ready.
    pub fn open(display: &'d Display, args: &[&str], size: (u32, u32)) -> Window<'d> {
        let mut child = Command::new(env!("CARGO_BIN_EXE_raysandbox"))
            .args(args)
            .args([
                "--size",
                &format!("{}x{}", size.0, size.1),
                "--print-events",
            ])
            .env("DISPLAY", &display.name)
            .env_remove("WAYLAND_DISPLAY")
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("start raysandbox");
        let stdout = child.stdout.take().unwrap();
        let (tx, events) = channel();
        let layout = Arc::new(Mutex::new(HashMap::new()));
        let parts = Arc::clone(&layout);
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines().map_while(Result::ok) {
                if let Some(described) = line.strip_prefix("event: layout ") {
                    *parts.lock().unwrap() = parse_layout(described);
                } else if tx.send(line).is_err() {
                    break;
                }
            }
        });
        let mut window = Window {
            display,
            child,
            events,
            layout,
            id: String::new(),
            ready: String::new(),
            size,
        };
        window.ready = window.wait_for("ready");
        window.id = window
            .xdotool(&["search", "--sync", "--name", "raysandbox"])
            .lines()
            .last()
            .expect("a window")
            .to_string();
        window
    }

    /// Waits for an event line starting with `prefix`; returns the rest.
    pub fn wait_for(&mut self, prefix: &str) -> String {
        let deadline = Instant::now() + TIMEOUT;
        // The last lines passed over, for the failure's message.
        let mut passed: Vec<String> = Vec::new();
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.events.recv_timeout(left) {
                Ok(line) => {
                    if let Some(rest) = line.strip_prefix(&format!("event: {prefix}")) {
                        return rest.trim().to_string();
                    }
                    passed.push(line);
                    if passed.len() > 20 {
                        passed.remove(0);
                    }
                }
                Err(RecvTimeoutError::Timeout) => panic!(
                    "no '{prefix}' event within {TIMEOUT:?}; the last lines before: {passed:#?}"
                ),
                Err(RecvTimeoutError::Disconnected) => panic!(
                    "the window closed while waiting for '{prefix}': {:?}",
                    self.child.try_wait()
                ),
            }
        }
    }

    /// Events that arrive within `wait`, without waiting for a given one.
    pub fn events_within(&self, wait: Duration) -> Vec<String> {
        std::thread::sleep(wait);
        self.events.try_iter().collect()
    }

    /// Where the window drew its part `name` in the last frame told
    /// (`panel`, `status`, `view`, `title`, `camera-fov`, ... in
    /// src/app/layout.rs). Waits for it to appear, up to a few seconds.
    pub fn part(&self, name: &str) -> Rect {
        let deadline = Instant::now() + Duration::from_secs(10);
        loop {
            let parts = self.layout.lock().unwrap().clone();
            if let Some(&rect) = parts.get(name) {
                return rect;
            }
            assert!(
                Instant::now() < deadline,
                "the window told no part {name:?}; it told {:?}",
                parts.keys().collect::<Vec<_>>()
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    pub fn xdotool(&self, args: &[&str]) -> String {
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
    pub fn drag(&self, button: &str, a: (u32, u32), b: (u32, u32)) {
        let at = |p: (u32, u32)| {
            self.xdotool(&[
                "mousemove",
                "--window",
                &self.id,
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

    pub fn click(&self, at: (u32, u32)) {
        let (x, y) = (at.0.to_string(), at.1.to_string());
        self.xdotool(&["mousemove", "--window", &self.id, &x, &y, "click", "1"]);
    }

    /// Presses keys in the window. Without a window manager nobody gives the
    /// window the keyboard focus, so the test does, as a click would.
    pub fn key(&self, keys: &str) {
        self.xdotool(&["windowfocus", "--sync", &self.id]);
        self.xdotool(&["key", keys]);
    }

    /// The window's pixels as shown on the X server.
    pub fn capture(&self) -> RgbaImage {
        // Window ids repeat across X servers: the display is in the name.
        let file = std::env::temp_dir().join(format!(
            "raysandbox-capture-{}-{}-{}.png",
            std::process::id(),
            self.display.name.trim_start_matches(':'),
            self.id
        ));
        let status = Command::new("import")
            .args(["-window", &self.id, file.to_str().unwrap()])
            .env("DISPLAY", &self.display.name)
            .status()
            .expect("run import");
        assert!(status.success(), "import failed");
        let image = image::open(&file).expect("captured PNG").to_rgba8();
        let _ = std::fs::remove_file(&file);
        assert_eq!(image.dimensions(), self.size, "window size");
        image
    }

    /// The process id, e.g. to read its resident memory.
    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// Sends SIGUSR1, on which the program destroys its own GPU device as
    /// a driver reset would lose it, and waits until it has made a new one
    /// (`device-lost`, `device-recovered`) and shown a frame drawn with it
    /// (the next `ready`). Prints how long that took, for
    /// docs/reliability.md ("The GPU's limits and a lost device").
    pub fn lose_device(&mut self, program: &str) -> Recovery {
        let pid = i32::try_from(self.pid()).unwrap();
        let (start, cpu) = (Instant::now(), self.cpu_time());
        // SAFETY: kill(2) with a valid signal number only sends the signal.
        assert_eq!(unsafe { libc::kill(pid, libc::SIGUSR1) }, 0);
        let reason = self.wait_for("device-lost");
        self.wait_for("device-recovered");
        let recovered = start.elapsed();
        self.wait_for("ready");
        let recovery = Recovery {
            reason,
            recovered,
            ready: start.elapsed(),
            cpu: self.cpu_time() - cpu,
        };
        eprintln!(
            "{program}: SIGUSR1 to device-recovered {:.2} s, to the next ready {:.2} s \
             ({:.2} s of CPU time; load average {})",
            recovery.recovered.as_secs_f64(),
            recovery.ready.as_secs_f64(),
            recovery.cpu.as_secs_f64(),
            super::load_average()
        );
        recovery
    }

    /// The CPU time the program used so far, all its threads (from
    /// `/proc/PID/stat`).
    pub fn cpu_time(&self) -> Duration {
        let stat = std::fs::read_to_string(format!("/proc/{}/stat", self.pid()))
            .expect("the window's /proc/PID/stat");
        // The fields after the command's name, which ends with ')':
        // state is field 3, utime and stime 14 and 15.
        let fields: Vec<&str> = stat[stat.rfind(')').unwrap() + 2..]
            .split_whitespace()
            .collect();
        let ticks: u64 = fields[11].parse::<u64>().unwrap() + fields[12].parse::<u64>().unwrap();
        // SAFETY: sysconf only reads a system constant.
        let per_second = u64::try_from(unsafe { libc::sysconf(libc::_SC_CLK_TCK) }).unwrap();
        Duration::from_millis(ticks * 1000 / per_second)
    }

    pub fn is_running(&mut self) -> bool {
        self.child
            .try_wait()
            .expect("query the window's process")
            .is_none()
    }
}

impl Drop for Window<'_> {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// What [`Window::lose_device`] measured.
pub struct Recovery {
    /// The `device-lost` event's reason.
    pub reason: String,
    /// From SIGUSR1 to `device-recovered`.
    pub recovered: Duration,
    /// From SIGUSR1 to the first `ready` after it.
    pub ready: Duration,
    /// The CPU time the program used meanwhile.
    pub cpu: Duration,
}

/// A part of the window in pixels, as a `layout` event tells it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    pub x: i32,
    pub y: i32,
    pub w: i32,
    pub h: i32,
}

impl Rect {
    pub fn right(self) -> i32 {
        self.x + self.w
    }

    pub fn bottom(self) -> i32 {
        self.y + self.h
    }

    /// The point at fractions `(fx, fy)` of the width and height.
    pub fn at(self, fx: f64, fy: f64) -> (u32, u32) {
        let x = f64::from(self.x) + fx * f64::from(self.w);
        let y = f64::from(self.y) + fy * f64::from(self.h);
        (x.round().max(0.0) as u32, y.round().max(0.0) as u32)
    }

    /// As `(x, y, width, height)` for [`crop`]; panics when empty or off
    /// the window's top left.
    pub fn crop(self) -> (u32, u32, u32, u32) {
        assert!(
            self.x >= 0 && self.y >= 0 && self.w > 0 && self.h > 0,
            "not a part of the window: {self:?}"
        );
        (self.x as u32, self.y as u32, self.w as u32, self.h as u32)
    }
}

/// `panel=0,0,330,410 status=0,410,800,40`: the parts by name.
pub fn parse_layout(described: &str) -> HashMap<String, Rect> {
    described
        .split_whitespace()
        .filter_map(|part| {
            let (name, place) = part.split_once('=')?;
            let n: Vec<i32> = place.split(',').filter_map(|v| v.parse().ok()).collect();
            let &[x, y, w, h] = n.as_slice() else {
                return None;
            };
            Some((name.to_string(), Rect { x, y, w, h }))
        })
        .collect()
}

/// The part `(x, y, width, height)` of an image.
pub fn crop(image: &RgbaImage, (x, y, w, h): (u32, u32, u32, u32)) -> RgbaImage {
    image::imageops::crop_imm(image, x, y, w, h).to_image()
}
