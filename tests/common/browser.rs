//! The browser page (docs/web.md) in a real Chromium, driven through the
//! DevTools protocol: what the page's tests need.
//!
//! Chromium runs headed under an Xvfb server of the test's own, WebGPU on
//! SwiftShader ([`WEBGPU_FLAGS`]): only there does a WebGPU canvas present
//! (headless Chromium renders offscreen but shows no canvas). It is started
//! with a fresh profile, on an empty page in an `--app` window (no toolbar,
//! so the page's viewport is the window's top-left [`SIZE`]) and with
//! `--remote-debugging-port=0`; the driver reads the port Chromium chose from
//! the profile's `DevToolsActivePort` file and talks to the page over a
//! WebSocket (`tungstenite`), one request at a time.
//!
//! A test typically does:
//!
//! ```ignore
//! // Xvfb, dist/web served over http, Chromium showing the page:
//! let (_display, mut page) = browser::open_page("?samples=1");
//! page.wait_for("ready");                            // a `raysandbox: ready ...` line
//! page.drag(Button::Left, (240.0, 135.0), (300.0, 135.0));
//! let picture = page.capture_picture();              // the X screen, top-left SIZE
//! let text = page.evaluate("document.title");        // JSON
//! ```
//!
//! The page's console lines `raysandbox: EVENT` arrive as
//! `Runtime.consoleAPICalled` events; [`Browser::wait_for`] waits for one
//! and fails the test on an `error ...` line or an uncaught exception it was
//! not waiting for. Mouse and keyboard go through `Input.dispatch*Event`, as
//! if a person used them: the page sees ordinary DOM events.
//!
//! Two screenshots: [`Browser::capture_picture`] takes the X screen
//! (ImageMagick's `import`), what a person sees; [`Browser::screenshot`] asks
//! Chromium (`Page.captureScreenshot`), which in this headed setup shows the
//! WebGPU canvas too, pixel for pixel the same as the X screen, and the HTML
//! over it. (Headless Chromium presents no WebGPU canvas at all.)

use std::collections::{HashMap, VecDeque};
use std::fs::File;
use std::io::{BufRead, BufReader, ErrorKind, Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicU32, Ordering};
use std::time::{Duration, Instant};

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use image::RgbaImage;
use raysandbox::compare::distinct_colors;
use serde_json::{Value, json};
use tungstenite::{Message, WebSocket};

use super::xwindow::{Display, Rect, crop, parse_layout};

/// Size of the browser window, and so of the page's canvas, in pixels.
pub const SIZE: (u32, u32) = (480, 270);

/// How long the page may take for anything: Chromium on SwiftShader
/// compiles the tracer on the CPU, on two busy cores.
pub const TIMEOUT: Duration = Duration::from_secs(180);

/// The flags under which Chromium presents a WebGPU canvas without a GPU:
/// Vulkan, ANGLE and the WebGPU adapter all on SwiftShader.
pub const WEBGPU_FLAGS: [&str; 7] = [
    "--enable-unsafe-webgpu",
    "--enable-features=Vulkan",
    "--use-vulkan=swiftshader",
    "--use-angle=swiftshader",
    "--use-webgpu-adapter=swiftshader",
    "--disable-vulkan-surface",
    "--ignore-gpu-blocklist",
];

/// How to get Chromium when it is missing or does not start.
const INSTALL_HINT: &str = "the web tests need Chromium and Xvfb: install them with \
     `sudo apt-get install chromium xvfb`, or run scripts/test, which does";

/// The built page, or a failure saying how to build it.
pub fn page_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("dist/web");
    assert!(
        dir.join("raysandbox_bg.wasm").is_file() && dir.join("index.html").is_file(),
        "the web page is not built in {}: run scripts/web (scripts/test does)",
        dir.display()
    );
    dir
}

/// An Xvfb server and Chromium showing the built page at `query` (what
/// follows the page's address: `?samples=1&ui=0#scene=...`). Keep the display alive as long as the browser: the
/// tuple's browser is dropped first when both are bound by one `let`.
pub fn open_page(query: &str) -> (Display, Browser) {
    let display = Display::start();
    let url = serve(page_dir());
    let page = Browser::open(&display, &format!("{url}{query}"));
    (display, page)
}

/// Serves the files of `dir` on a free port of 127.0.0.1 from a thread;
/// returns the page's address (ending in `/`).
pub fn serve(dir: PathBuf) -> String {
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
fn answer(mut stream: TcpStream, dir: &Path) {
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

/// A mouse button, as `Input.dispatchMouseEvent` names it.
#[derive(Clone, Copy, Debug)]
pub enum Button {
    Left,
    Middle,
    Right,
}

impl Button {
    fn name(self) -> &'static str {
        match self {
            Button::Left => "left",
            Button::Middle => "middle",
            Button::Right => "right",
        }
    }

    /// The button's bit in a DOM `MouseEvent.buttons` mask.
    fn bit(self) -> u32 {
        match self {
            Button::Left => 1,
            Button::Right => 2,
            Button::Middle => 4,
        }
    }
}

/// How Chromium is started.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// WebGPU on SwiftShader ([`WEBGPU_FLAGS`]); without them Chromium on
    /// Linux has no WebGPU, as a browser where it is missing.
    pub webgpu: bool,
    /// The window's size; the X screen is 1024 x 768.
    pub size: (u32, u32),
}

impl Default for Options {
    fn default() -> Options {
        Options {
            webgpu: true,
            size: SIZE,
        }
    }
}

/// A Chromium window with a fresh profile, driven through DevTools.
pub struct Browser {
    child: Child,
    socket: WebSocket<TcpStream>,
    next_id: u64,
    /// The page's `raysandbox:` console lines not yet waited for, without
    /// the prefix.
    lines: VecDeque<String>,
    /// The parts of the page's last `layout` line, by name (in the page's
    /// pixels).
    layout: HashMap<String, Rect>,
    /// Uncaught exceptions of the page, in order.
    exceptions: Vec<String>,
    /// How many of `exceptions` the test has seen ([`Browser::exceptions`]).
    exceptions_seen: usize,
    /// Mouse buttons held down, as a DOM `buttons` mask.
    buttons: u32,
    display: String,
    profile: TempDir,
}

impl Browser {
    /// Chromium with WebGPU showing `url`.
    pub fn open(display: &Display, url: &str) -> Browser {
        let mut browser = Browser::start(display, Options::default());
        browser.navigate(url);
        browser
    }

    /// Chromium on an empty page, connected; fails the test with how to
    /// install Chromium when it does not start.
    pub fn start(display: &Display, options: Options) -> Browser {
        let profile = TempDir::new("raysandbox-chromium");
        let log_path = profile.0.join("chromium.log");
        let log = File::create(&log_path).expect("create Chromium's log file");
        let flags: &[&str] = if options.webgpu { &WEBGPU_FLAGS } else { &[] };
        let mut child = Command::new("chromium")
            .args(flags)
            .args([
                "--no-sandbox",
                "--test-type",
                "--no-first-run",
                "--no-default-browser-check",
                "--disable-extensions",
                "--enable-logging=stderr",
                "--v=0",
                "--remote-debugging-port=0",
                "--window-position=0,0",
                // A CSS pixel is a screen pixel: the page's layout lines
                // (in device pixels) are where the tests click.
                "--force-device-scale-factor=1",
                &format!("--window-size={},{}", options.size.0, options.size.1),
                &format!("--user-data-dir={}", profile.0.display()),
                // `--app=about:blank` opens a normal window with a toolbar.
                "--app=data:text/html,",
            ])
            .env("DISPLAY", display.name())
            .env_remove("WAYLAND_DISPLAY")
            // Chromium's singleton socket goes to a folder of its own in the
            // temporary directory, which a killed Chromium leaves behind:
            // inside the profile it goes when the profile does.
            .env("TMPDIR", &profile.0)
            .stdout(Stdio::null())
            .stderr(log)
            .spawn()
            .unwrap_or_else(|e| panic!("cannot start `chromium`: {e}; {INSTALL_HINT}"));
        let port = match devtools_port(&mut child, &profile.0) {
            Ok(port) => port,
            Err(why) => {
                let _ = child.kill();
                let _ = child.wait();
                let log = std::fs::read_to_string(&log_path).unwrap_or_default();
                let tail: Vec<&str> = log.lines().rev().take(20).collect();
                panic!(
                    "Chromium did not start: {why}; {INSTALL_HINT}.\nIts last log lines:\n{}",
                    tail.into_iter().rev().collect::<Vec<_>>().join("\n")
                );
            }
        };
        let socket = connect_to_page(port);
        let mut browser = Browser {
            child,
            socket,
            next_id: 1,
            lines: VecDeque::new(),
            layout: HashMap::new(),
            exceptions: Vec::new(),
            exceptions_seen: 0,
            buttons: 0,
            display: display.name().to_string(),
            profile,
        };
        browser.call("Runtime.enable", json!({}));
        browser.call("Page.enable", json!({}));
        browser
    }

    /// The process id of Chromium's browser process (its GPU and renderer
    /// processes are its children).
    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// Opens `url` in the window; forgets the previous page's lines and
    /// layout.
    pub fn navigate(&mut self, url: &str) {
        self.lines.clear();
        self.layout.clear();
        let result = self.call("Page.navigate", json!({ "url": url }));
        if let Some(error) = result.get("errorText") {
            panic!("cannot open {url}: {error}");
        }
    }

    /// Sends one DevTools command and returns its result, keeping the events
    /// that arrive meanwhile. A protocol error fails the test.
    pub fn call(&mut self, method: &str, params: Value) -> Value {
        let id = self.next_id;
        self.next_id += 1;
        let request = json!({ "id": id, "method": method, "params": params });
        let mut sent = self.socket.send(Message::text(request.to_string()));
        // Interrupted by a signal, the frame stays queued: flushing writes
        // the rest.
        while matches!(&sent, Err(tungstenite::Error::Io(e)) if e.kind() == ErrorKind::Interrupted)
        {
            sent = self.socket.flush();
        }
        sent.unwrap_or_else(|e| panic!("DevTools {method}: {e}"));
        let deadline = Instant::now() + TIMEOUT;
        loop {
            let Some(message) = self.receive(deadline) else {
                panic!("no answer to DevTools {method} within {TIMEOUT:?}");
            };
            if message["id"] == id {
                if let Some(error) = message.get("error") {
                    panic!("DevTools {method}: {error}");
                }
                return message["result"].clone();
            }
            self.keep_event(&message);
        }
    }

    /// The value of the JavaScript expression `js` in the page, as JSON;
    /// a promise is awaited. A thrown exception fails the test.
    pub fn evaluate(&mut self, js: &str) -> Value {
        let result = self.call(
            "Runtime.evaluate",
            json!({ "expression": js, "returnByValue": true, "awaitPromise": true }),
        );
        if let Some(details) = result.get("exceptionDetails") {
            panic!("{js}\nthrew: {}", exception_text(details));
        }
        result["result"]["value"].clone()
    }

    /// Where the page's panel drew its part `name` (`menu:Scenes`,
    /// `item:Scenes/cornell`, `camera-fov`, ... in src/app/layout.rs) in its
    /// last frame, in page pixels. Waits for it, up to a few seconds.
    pub fn part(&mut self, name: &str) -> Rect {
        // The lines already sent first: the last layout may be among them.
        let pending = Instant::now() + Duration::from_millis(100);
        while let Some(message) = self.receive(pending) {
            self.keep_event(&message);
        }
        let deadline = Instant::now() + Duration::from_secs(10);
        loop {
            if let Some(&rect) = self.layout.get(name) {
                return rect;
            }
            match self.receive(deadline) {
                Some(message) => self.keep_event(&message),
                None => panic!(
                    "the page told no part {name:?}; it told {:?}",
                    self.layout.keys().collect::<Vec<_>>()
                ),
            }
        }
    }

    /// Waits for the page's event starting with `prefix`; returns the rest.
    /// An `error` line or an uncaught exception before it fails the test with
    /// its message (wait for `"error"` to expect one).
    pub fn wait_for(&mut self, prefix: &str) -> String {
        let deadline = Instant::now() + TIMEOUT;
        loop {
            while let Some(line) = self.lines.pop_front() {
                if let Some(rest) = line.strip_prefix(prefix) {
                    return rest.trim().to_string();
                }
                assert!(
                    !line.starts_with("error"),
                    "the page reported: {line} (waiting for '{prefix}')"
                );
            }
            let new = self.exceptions();
            assert!(
                new.is_empty(),
                "the page threw {new:?} (waiting for '{prefix}')"
            );
            match self.receive(deadline) {
                Some(message) => self.keep_event(&message),
                None => panic!("no '{prefix}' from the page within {TIMEOUT:?}"),
            }
        }
    }

    /// The page's lines that arrive within `wait`, without waiting for a
    /// given one (e.g. to see that nothing more happens).
    pub fn events_within(&mut self, wait: Duration) -> Vec<String> {
        let deadline = Instant::now() + wait;
        while let Some(message) = self.receive(deadline) {
            self.keep_event(&message);
        }
        self.lines.drain(..).collect()
    }

    /// The page's uncaught exceptions since the last call.
    pub fn exceptions(&mut self) -> Vec<String> {
        let new = self.exceptions[self.exceptions_seen..].to_vec();
        self.exceptions_seen = self.exceptions.len();
        new
    }

    /// The text of the page's message box (`#message` over the canvas)
    /// when it is shown.
    pub fn message(&mut self) -> Option<String> {
        let value = self.evaluate(
            "(() => { const m = document.getElementById('message'); \
             return m && m.classList.contains('shown') ? \
             document.getElementById('message-text').textContent : null; })()",
        );
        value.as_str().map(str::to_string)
    }

    /// Where the page's element `id` is, in page pixels (`None` when it
    /// is not displayed).
    pub fn element(&mut self, id: &str) -> Option<Rect> {
        let value = self.evaluate(&format!(
            "(() => {{ const e = document.getElementById('{id}'); \
             if (!e) return null; const r = e.getBoundingClientRect(); \
             return r.width > 0 && r.height > 0 ? \
             [r.x, r.y, r.width, r.height].map(Math.round) : null; }})()"
        ));
        let v = value.as_array()?;
        let at = |k: usize| v[k].as_i64().unwrap_or_default() as i32;
        Some(Rect {
            x: at(0),
            y: at(1),
            w: at(2),
            h: at(3),
        })
    }

    /// The parts of the page's panel in its last layout (see
    /// [`Browser::part`]), after the lines already sent.
    pub fn parts(&mut self) -> HashMap<String, Rect> {
        let pending = Instant::now() + Duration::from_millis(100);
        while let Some(message) = self.receive(pending) {
            self.keep_event(&message);
        }
        self.layout.clone()
    }

    /// Runs `js` in every page this browser opens from now on, before the
    /// page's own scripts (tests reach the page's WebGPU device this way).
    pub fn before_each_page(&mut self, js: &str) {
        self.call(
            "Page.addScriptToEvaluateOnNewDocument",
            json!({ "source": js }),
        );
    }

    /// The top-left [`SIZE`] of the X screen, where the page is.
    pub fn capture_screen(&self) -> RgbaImage {
        let file = std::env::temp_dir().join(format!(
            "raysandbox-web-{}-{}.png",
            std::process::id(),
            self.display.trim_start_matches(':')
        ));
        let status = Command::new("import")
            .args(["-window", "root", file.to_str().unwrap()])
            .env("DISPLAY", &self.display)
            .status()
            .expect("run import");
        assert!(status.success(), "import failed");
        let screen = image::open(&file).expect("captured PNG").to_rgba8();
        let _ = std::fs::remove_file(&file);
        crop(&screen, (0, 0, SIZE.0, SIZE.1))
    }

    /// The page's picture once it is on the X screen: the browser composites
    /// the canvas some time after the page presented it, and the page
    /// presents the rows of a sample as its short GPU jobs finish them, so
    /// the screen is captured until it shows more than a blank window and
    /// two captures half a second apart agree (or [`TIMEOUT`]).
    pub fn capture_picture(&self) -> RgbaImage {
        let deadline = Instant::now() + TIMEOUT;
        let mut last: Option<RgbaImage> = None;
        loop {
            let screen = self.capture_screen();
            let settled = last.as_ref() == Some(&screen);
            if (settled && distinct_colors(&screen, 16) >= 16) || Instant::now() > deadline {
                return screen;
            }
            last = Some(screen);
            std::thread::sleep(Duration::from_millis(500));
        }
    }

    /// The page's viewport as Chromium composites it, canvas included.
    pub fn screenshot(&mut self) -> RgbaImage {
        let shot = self.call("Page.captureScreenshot", json!({ "format": "png" }));
        let png = STANDARD
            .decode(shot["data"].as_str().expect("a screenshot"))
            .expect("a screenshot in base64");
        image::load_from_memory(&png)
            .expect("a PNG screenshot")
            .to_rgba8()
    }

    /// Moves the mouse to `at` (CSS pixels from the page's top-left).
    pub fn mouse_move(&mut self, at: (f64, f64)) {
        self.mouse("mouseMoved", at, None, json!({}));
    }

    pub fn mouse_press(&mut self, button: Button, at: (f64, f64)) {
        self.buttons |= button.bit();
        self.mouse("mousePressed", at, Some(button), json!({ "clickCount": 1 }));
    }

    pub fn mouse_release(&mut self, button: Button, at: (f64, f64)) {
        self.buttons &= !button.bit();
        self.mouse(
            "mouseReleased",
            at,
            Some(button),
            json!({ "clickCount": 1 }),
        );
    }

    pub fn click(&mut self, at: (f64, f64)) {
        self.mouse_move(at);
        self.mouse_press(Button::Left, at);
        self.mouse_release(Button::Left, at);
    }

    /// Drags with `button` from `a` to `b` in ten steps, as a hand would.
    pub fn drag(&mut self, button: Button, a: (f64, f64), b: (f64, f64)) {
        self.mouse_move(a);
        self.mouse_press(button, a);
        for step in 1..=10 {
            let t = f64::from(step) / 10.0;
            self.mouse_move((a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t));
            std::thread::sleep(Duration::from_millis(20));
        }
        self.mouse_release(button, b);
    }

    /// Turns the mouse wheel at `at` by `delta` CSS pixels (positive `y`
    /// scrolls down, i.e. towards the user).
    pub fn wheel(&mut self, at: (f64, f64), delta: (f64, f64)) {
        self.mouse(
            "mouseWheel",
            at,
            None,
            json!({ "deltaX": delta.0, "deltaY": delta.1 }),
        );
    }

    fn mouse(&mut self, kind: &str, at: (f64, f64), button: Option<Button>, extra: Value) {
        let mut params = json!({
            "type": kind,
            "x": at.0,
            "y": at.1,
            "button": button.map_or("none", Button::name),
            "buttons": self.buttons,
        });
        params
            .as_object_mut()
            .unwrap()
            .extend(extra.as_object().unwrap().clone());
        self.call("Input.dispatchMouseEvent", params);
    }

    /// Drops the file at `path` at `at` as a person dragging it from a file
    /// manager would: `dragenter`, `dragover` and `drop` events whose
    /// `DataTransfer` holds the file (`Input.dispatchDragEvent`).
    pub fn drop_file(&mut self, path: &Path, at: (f64, f64)) {
        let path = path.canonicalize().expect("the file to drop exists");
        let data = json!({
            "items": [],
            "files": [path.to_str().expect("a UTF-8 path")],
            "dragOperationsMask": 1,
        });
        for kind in ["dragEnter", "dragOver", "drop"] {
            self.call(
                "Input.dispatchDragEvent",
                json!({ "type": kind, "x": at.0, "y": at.1, "data": data }),
            );
        }
    }

    /// Types `text` into the focused element as an input method would (one
    /// `input` event; what an HTML text field or textarea takes). A canvas
    /// drawn by egui reads key events instead: use [`Browser::key`].
    pub fn insert_text(&mut self, text: &str) {
        self.call("Input.insertText", json!({ "text": text }));
    }

    /// Presses and releases a key, with modifiers joined by `+`, as
    /// xdotool names them: `"a"`, `"Enter"`, `"Backspace"`, `"ArrowLeft"`,
    /// `"Control+a"`, `"Shift+Tab"`. A printable key without Control, Alt or
    /// Meta also types its character.
    pub fn key(&mut self, keys: &str) {
        let mut parts: Vec<&str> = keys.split('+').collect();
        let key = parts.pop().filter(|k| !k.is_empty()).unwrap_or("+");
        let modifiers = parts.iter().fold(0, |m, part| {
            m | match *part {
                "Alt" => 1,
                "Control" | "Ctrl" => 2,
                "Meta" => 4,
                "Shift" => 8,
                other => panic!("unknown modifier {other} in {keys}"),
            }
        });
        let (code, virtual_key, text) = key_codes(key, modifiers & 8 != 0);
        let text = if modifiers & 7 == 0 { text } else { None };
        let mut down = json!({
            "type": if text.is_some() { "keyDown" } else { "rawKeyDown" },
            "key": key,
            "code": code,
            "windowsVirtualKeyCode": virtual_key,
            "modifiers": modifiers,
        });
        if let Some(text) = text {
            down["text"] = json!(text);
            down["unmodifiedText"] = json!(text);
        }
        self.call("Input.dispatchKeyEvent", down);
        self.call(
            "Input.dispatchKeyEvent",
            json!({
                "type": "keyUp",
                "key": key,
                "code": code,
                "windowsVirtualKeyCode": virtual_key,
                "modifiers": modifiers,
            }),
        );
    }

    /// Reads DevTools messages until one arrives or `deadline`; `None` at
    /// the deadline. Chromium exiting fails the test.
    fn receive(&mut self, deadline: Instant) -> Option<Value> {
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return None;
            }
            let wait = left.min(Duration::from_millis(200));
            self.socket
                .get_mut()
                .set_read_timeout(Some(wait))
                .expect("set the DevTools socket's timeout");
            match self.socket.read() {
                Ok(Message::Text(text)) => {
                    return Some(serde_json::from_str(&text).expect("DevTools sends JSON"));
                }
                Ok(_) => {}
                // A signal landing during the read (EINTR) leaves the socket
                // as a timeout does: nothing consumed, so read again.
                Err(tungstenite::Error::Io(e))
                    if matches!(
                        e.kind(),
                        ErrorKind::WouldBlock | ErrorKind::TimedOut | ErrorKind::Interrupted
                    ) => {}
                Err(e) => panic!(
                    "the connection to Chromium broke: {e} (Chromium: {:?})",
                    self.child.try_wait()
                ),
            }
        }
    }

    /// Keeps what the tests read of a DevTools event: the page's console
    /// lines and its uncaught exceptions.
    fn keep_event(&mut self, message: &Value) {
        let params = &message["params"];
        match message["method"].as_str() {
            Some("Runtime.consoleAPICalled") => {
                let text = params["args"][0]["value"].as_str().unwrap_or_default();
                if let Some(described) = text.strip_prefix("raysandbox: layout ") {
                    self.layout = parse_layout(described);
                } else if let Some(line) = text.strip_prefix("raysandbox: ") {
                    self.lines.push_back(line.to_string());
                }
            }
            Some("Runtime.exceptionThrown") => {
                let text = exception_text(&params["exceptionDetails"]);
                self.exceptions.push(text);
            }
            _ => {}
        }
    }
}

/// The centre of a part the page told ([`Browser::part`]), as page
/// coordinates to click at.
pub fn page_point(part: Rect) -> (f64, f64) {
    (
        f64::from(part.x) + f64::from(part.w) / 2.0,
        f64::from(part.y) + f64::from(part.h) / 2.0,
    )
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The port Chromium listens on for DevTools, from the `DevToolsActivePort`
/// file it writes into its profile once it is up.
fn devtools_port(child: &mut Child, profile: &Path) -> Result<u16, String> {
    let file = profile.join("DevToolsActivePort");
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        if let Some(port) = std::fs::read_to_string(&file)
            .ok()
            .and_then(|text| text.lines().next()?.trim().parse().ok())
        {
            return Ok(port);
        }
        if let Ok(Some(status)) = child.try_wait() {
            return Err(format!("it exited ({status})"));
        }
        if Instant::now() > deadline {
            return Err(format!("no {} within 60 s", file.display()));
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// A WebSocket to the window's page, found in Chromium's `/json/list`.
fn connect_to_page(port: u16) -> WebSocket<TcpStream> {
    let deadline = Instant::now() + Duration::from_secs(30);
    let url = loop {
        let list = http_get(port, "/json/list");
        let targets: Vec<Value> = serde_json::from_str(&list).unwrap_or_default();
        let page = targets.iter().find(|t| {
            t["type"] == "page" && t["url"].as_str().is_some_and(|u| u.starts_with("data:"))
        });
        if let Some(url) = page.and_then(|t| t["webSocketDebuggerUrl"].as_str()) {
            break url.to_string();
        }
        assert!(
            Instant::now() < deadline,
            "Chromium lists no page to drive: {list}"
        );
        std::thread::sleep(Duration::from_millis(100));
    };
    let stream = TcpStream::connect(("127.0.0.1", port)).expect("connect to Chromium's DevTools");
    let (socket, _) = tungstenite::client(url.as_str(), stream)
        .unwrap_or_else(|e| panic!("DevTools WebSocket {url}: {e}"));
    socket
}

/// The body of `GET path` from Chromium's DevTools HTTP server, which keeps
/// the connection open: the body is read up to its `Content-Length`.
fn http_get(port: u16, path: &str) -> String {
    let stream = TcpStream::connect(("127.0.0.1", port)).expect("connect to Chromium");
    write!(
        &stream,
        "GET {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n"
    )
    .expect("ask Chromium");
    let mut reader = BufReader::new(stream);
    let mut length = 0;
    loop {
        let mut line = String::new();
        reader.read_line(&mut line).expect("Chromium's answer");
        let line = line.trim();
        if line.is_empty() {
            break;
        }
        if let Some((name, value)) = line.split_once(':')
            && name.eq_ignore_ascii_case("content-length")
        {
            length = value.trim().parse().expect("a Content-Length");
        }
    }
    let mut body = vec![0; length];
    reader.read_exact(&mut body).expect("Chromium's answer");
    String::from_utf8_lossy(&body).into_owned()
}

/// What an exception's DevTools details say: the error's description
/// (message and stack) when there is one.
fn exception_text(details: &Value) -> String {
    details["exception"]["description"]
        .as_str()
        .or_else(|| details["text"].as_str())
        .unwrap_or("an exception")
        .to_string()
}

/// The DOM `code`, Windows virtual key code and typed text of a key.
fn key_codes(key: &str, shift: bool) -> (String, u32, Option<String>) {
    let named = match key {
        "Enter" => Some(("Enter", 13, Some("\r"))),
        "Tab" => Some(("Tab", 9, None)),
        "Backspace" => Some(("Backspace", 8, None)),
        "Escape" => Some(("Escape", 27, None)),
        "F1" => Some(("F1", 112, None)),
        "=" => Some(("Equal", 187, Some("="))),
        "-" => Some(("Minus", 189, Some("-"))),
        "Delete" => Some(("Delete", 46, None)),
        "Home" => Some(("Home", 36, None)),
        "End" => Some(("End", 35, None)),
        "ArrowLeft" => Some(("ArrowLeft", 37, None)),
        "ArrowUp" => Some(("ArrowUp", 38, None)),
        "ArrowRight" => Some(("ArrowRight", 39, None)),
        "ArrowDown" => Some(("ArrowDown", 40, None)),
        " " | "Space" => Some(("Space", 32, Some(" "))),
        _ => None,
    };
    if let Some((code, virtual_key, text)) = named {
        return (code.to_string(), virtual_key, text.map(str::to_string));
    }
    let mut chars = key.chars();
    let (Some(c), None) = (chars.next(), chars.next()) else {
        panic!("key {key:?}: not a single character nor a key the driver knows");
    };
    let upper = c.to_ascii_uppercase();
    let code = if c.is_ascii_alphabetic() {
        format!("Key{upper}")
    } else if c.is_ascii_digit() {
        format!("Digit{c}")
    } else {
        String::new()
    };
    let text = if shift { upper } else { c };
    (code, u32::from(upper), Some(text.to_string()))
}

/// A folder removed on drop.
pub struct TempDir(pub PathBuf);

impl TempDir {
    pub fn new(prefix: &str) -> TempDir {
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
