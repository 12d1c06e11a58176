//! The browser page (docs/web.md) in a real Chromium: WebGPU on SwiftShader,
//! headed under an Xvfb server of the test's own (only there does a WebGPU
//! canvas present), the page served from `dist/web/` (built by `scripts/web`,
//! which `scripts/test` runs first) by a small HTTP server in the test.
//! The page reports on the console (`raysandbox: EVENT` lines, read from
//! Chromium's stderr); the screen is captured with ImageMagick's `import`.

mod common;

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::{Duration, Instant};

use image::RgbaImage;
use raysandbox::compare::{diff_images, distinct_colors, nan_pixels};
use raysandbox::reference;
use raysandbox::scene::{Scene, bundled};
use raysandbox::web::link;

/// Size of the browser window, and so of the page's canvas, in pixels.
const SIZE: (u32, u32) = (480, 270);
/// Chromium on SwiftShader compiles the tracer on the CPU, on two busy cores.
const TIMEOUT: Duration = Duration::from_secs(180);

/// The flags under which Chromium presents a WebGPU canvas without a GPU:
/// Vulkan, ANGLE and the WebGPU adapter all on SwiftShader.
const WEBGPU_FLAGS: [&str; 7] = [
    "--enable-unsafe-webgpu",
    "--enable-features=Vulkan",
    "--use-vulkan=swiftshader",
    "--use-angle=swiftshader",
    "--use-webgpu-adapter=swiftshader",
    "--disable-vulkan-surface",
    "--ignore-gpu-blocklist",
];

/// The built page, or a failure saying how to build it.
fn page_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("dist/web");
    assert!(
        dir.join("raysandbox_bg.wasm").is_file() && dir.join("index.html").is_file(),
        "the web page is not built in {}: run scripts/web (scripts/test does)",
        dir.display()
    );
    dir
}

/// Serves the files of `dir` on a free port of 127.0.0.1 from a thread;
/// returns the page's address.
fn serve(dir: PathBuf) -> String {
    let listener = TcpListener::bind("127.0.0.1:0").expect("bind a local port");
    let address = format!("http://{}/", listener.local_addr().unwrap());
    std::thread::spawn(move || {
        for stream in listener.incoming().map_while(Result::ok) {
            let dir = dir.clone();
            std::thread::spawn(move || answer(stream, &dir));
        }
    });
    address
}

/// Answers one GET request with the file it names (index.html for `/`).
fn answer(mut stream: std::net::TcpStream, dir: &Path) {
    let mut request = String::new();
    if BufReader::new(&stream).read_line(&mut request).is_err() {
        return;
    }
    let path = request.split_whitespace().nth(1).unwrap_or("/");
    let path = path.split(['?', '#']).next().unwrap_or("/");
    let name = match path.trim_start_matches('/') {
        "" => "index.html",
        name => name,
    };
    let file = dir.join(name);
    let (status, body) = match std::fs::read(&file) {
        Ok(body) if !name.contains("..") => ("200 OK", body),
        _ => ("404 Not Found", Vec::new()),
    };
    let kind = match file.extension().and_then(|e| e.to_str()) {
        Some("html") => "text/html; charset=utf-8",
        Some("js") => "text/javascript",
        Some("css") => "text/css",
        Some("wasm") => "application/wasm",
        _ => "application/octet-stream",
    };
    let header = format!(
        "HTTP/1.1 {status}\r\nContent-Type: {kind}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
        body.len()
    );
    let _ = stream.write_all(header.as_bytes());
    let _ = stream.write_all(&body);
    let _ = stream.flush();
    let _ = stream.read(&mut [0; 1]);
}

/// The Chromium binary, or a failure saying how to install it.
fn chromium() -> &'static str {
    let found = Command::new("chromium")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(
        found,
        "the web tests need Chromium: install it with `sudo apt-get install chromium`, \
         or run scripts/test, which does"
    );
    "chromium"
}

/// A Chromium window showing the page, with a fresh profile, and the page's
/// `raysandbox:` console lines.
struct Browser {
    child: Child,
    lines: Receiver<String>,
    _profile: TempDir,
}

impl Browser {
    fn open(display: &common::xwindow::Display, url: &str) -> Browser {
        let profile = TempDir::new("raysandbox-chromium");
        let mut child = Command::new(chromium())
            .args(WEBGPU_FLAGS)
            .args([
                "--no-sandbox",
                "--test-type",
                "--no-first-run",
                "--no-default-browser-check",
                "--disable-extensions",
                "--enable-logging=stderr",
                "--v=0",
                "--window-position=0,0",
                &format!("--window-size={},{}", SIZE.0, SIZE.1),
                &format!("--user-data-dir={}", profile.0.display()),
                &format!("--app={url}"),
            ])
            .env("DISPLAY", display.name())
            .env_remove("WAYLAND_DISPLAY")
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| panic!("cannot start Chromium: {e}"));
        let stderr = child.stderr.take().unwrap();
        let (tx, lines) = channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stderr).lines().map_while(Result::ok) {
                if let Some(event) = page_event(&line)
                    && tx.send(event).is_err()
                {
                    break;
                }
            }
        });
        Browser {
            child,
            lines,
            _profile: profile,
        }
    }

    /// Waits for the page's event starting with `prefix`; returns the rest.
    /// An error the page reports fails the test with its message.
    fn wait_for(&mut self, prefix: &str) -> String {
        let deadline = Instant::now() + TIMEOUT;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.lines.recv_timeout(left) {
                Ok(line) => {
                    if let Some(rest) = line.strip_prefix(prefix) {
                        return rest.trim().to_string();
                    }
                    assert!(
                        !line.starts_with("error"),
                        "the page reported: {line} (waiting for '{prefix}')"
                    );
                }
                Err(RecvTimeoutError::Timeout) => {
                    panic!("no '{prefix}' from the page within {TIMEOUT:?}")
                }
                Err(RecvTimeoutError::Disconnected) => panic!(
                    "Chromium stopped while waiting for '{prefix}': {:?}",
                    self.child.try_wait()
                ),
            }
        }
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The page's own console line in a line of Chromium's log, e.g.
/// `[...:INFO:CONSOLE(1)] "raysandbox: ready samples=1", source: ...`.
fn page_event(log_line: &str) -> Option<String> {
    let start = log_line.find("\"raysandbox: ")? + "\"raysandbox: ".len();
    let rest = &log_line[start..];
    let end = rest.rfind("\", source:").unwrap_or(rest.len());
    Some(rest[..end].to_string())
}

/// A folder removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(prefix: &str) -> TempDir {
        // Tests run in parallel: each folder gets its own number.
        static NEXT: AtomicU32 = AtomicU32::new(0);
        let n = NEXT.fetch_add(1, Ordering::SeqCst);
        let dir = std::env::temp_dir().join(format!("{prefix}-{}-{n}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create a temporary folder");
        TempDir(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The top-left `SIZE` of the X screen, where the page's window is.
fn capture_screen(display: &common::xwindow::Display) -> RgbaImage {
    let file = std::env::temp_dir().join(format!(
        "raysandbox-web-{}-{}.png",
        std::process::id(),
        display.name().trim_start_matches(':')
    ));
    let status = Command::new("import")
        .args(["-window", "root", file.to_str().unwrap()])
        .env("DISPLAY", display.name())
        .status()
        .expect("run import");
    assert!(status.success(), "import failed");
    let screen = image::open(&file).expect("captured PNG").to_rgba8();
    let _ = std::fs::remove_file(&file);
    common::xwindow::crop(&screen, (0, 0, SIZE.0, SIZE.1))
}

/// The page's picture once it is on the X screen: the browser composites
/// the canvas some time after the page presented it, so the screen is
/// captured until it shows more than a blank window (or [`TIMEOUT`]).
fn capture_picture(display: &common::xwindow::Display) -> RgbaImage {
    let deadline = Instant::now() + TIMEOUT;
    loop {
        let screen = capture_screen(display);
        if distinct_colors(&screen, 16) >= 16 || Instant::now() > deadline {
            return screen;
        }
        std::thread::sleep(Duration::from_millis(500));
    }
}

/// Compares the page's picture with the reference image of `scene` at 1
/// sample per pixel, within the budget of tests/gpu_vs_reference.rs (mean
/// |difference| <= 0.5, at most 0.5% of pixels off by more than 8, no
/// non-finite pixels, not blank); saves both images when they differ.
fn assert_like_reference(name: &str, page: &RgbaImage, scene: &Scene) {
    let expected = reference::render_rgba8(scene, SIZE.0, SIZE.1, 1);
    let d = diff_images(page, &expected);
    let nans = nan_pixels(page, &expected);
    eprintln!(
        "{name}: page vs reference: mean |d| {:.4}, {:.3}% > 8, max {}, {nans} NaN",
        d.mean_abs,
        d.frac_over_8 * 100.0,
        d.max_abs
    );
    let within =
        d.mean_abs <= 0.5 && d.frac_over_8 <= 0.005 && nans == 0 && distinct_colors(page, 16) >= 16;
    if !within {
        let out = std::env::temp_dir();
        page.save(out.join(format!("web-{name}-page.png"))).unwrap();
        expected
            .save(out.join(format!("web-{name}-reference.png")))
            .unwrap();
    }
    assert!(
        within,
        "{name}: the page's picture differs from the reference (both saved in {})",
        std::env::temp_dir().display()
    );
}

fn whitted() -> (String, Scene) {
    let name = bundled::names()[0];
    assert_eq!(name, "whitted");
    let text = bundled::text(name).unwrap().to_string();
    let scene = Scene::from_toml_str(&text, None).unwrap();
    (text, scene)
}

/// Opened without link data, the page shows the bundled Whitted scene, and
/// its first frame (1 sample per pixel) is the native renderer's picture
/// (`ui=0`: the picture alone, without the page's controls over it).
#[test]
fn the_page_renders_the_whitted_scene_like_the_reference() {
    let Some(display) = common::xwindow::Display::start() else {
        return;
    };
    let url = serve(page_dir());
    let mut browser = Browser::open(&display, &format!("{url}?samples=1&ui=0"));
    assert_eq!(browser.wait_for("scene"), "whitted");
    let adapter = browser.wait_for("adapter");
    eprintln!("page adapter: {adapter}");
    let size = browser.wait_for("first-frame");
    assert_eq!(size, format!("{}x{}", SIZE.0, SIZE.1), "canvas size");
    browser.wait_for("ready");
    assert_like_reference("whitted", &capture_picture(&display), &whitted().1);
}

/// A link made from an edited scene (another sky and camera) reproduces
/// that scene, not the default one, in a fresh browser.
#[test]
fn a_shared_link_reproduces_the_scene_in_a_fresh_browser() {
    let Some(display) = common::xwindow::Display::start() else {
        return;
    };
    let (text, original) = whitted();
    let edited = text
        .replace(
            "background = [0.25, 0.55, 0.95]",
            "background = [0.9, 0.5, 0.2]",
        )
        .replace("from = [0.2, 1.4, 5.8]", "from = [-2.0, 2.5, 5.0]");
    let scene = Scene::from_toml_str(&edited, None).unwrap();
    assert_ne!(scene, original, "the edit changed the scene");
    let url = serve(page_dir());
    let address = format!("{url}?samples=1&ui=0#{}", link::scene_hash(&edited));
    let mut browser = Browser::open(&display, &address);
    assert_eq!(browser.wait_for("scene"), "from-link");
    browser.wait_for("ready");
    assert_like_reference("link", &capture_picture(&display), &scene);
}
