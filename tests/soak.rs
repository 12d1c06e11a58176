//! Memory under live editing (docs/reliability.md): the real viewer and
//! sandbox window under Xvfb (tests/common/xwindow.rs) go through scene-file
//! saves, shader saves, panel edits, scene switches among bundled scenes
//! (meshes and the Julia set among them) and mesh-file reloads, and the
//! sandbox through shader saves, while their resident memory is sampled;
//! the page in Chromium (tests/common/browser.rs) goes through scene edits,
//! orbits, shader edits and scene switches typed into its editor, while its
//! JS heap and WebAssembly memory are read through the DevTools protocol.
//! After a warm-up round of every action, memory may grow by at most
//! [`MAX_GROWTH_MB`] over the rest of the soak, counted from the most it
//! held during the warm-up.
//!
//! The test runs a short soak; `scripts/soak` runs the full one (the
//! counts of [`Counts::FULL`]) through the same code by setting
//! `RAYSANDBOX_SOAK=full` (or `N`: N times the short soak).

mod common;

use std::path::{Path, PathBuf};

use common::browser::{self, Browser, Button};
use common::xwindow::{Display, Window};
use serde_json::json;

/// The bound on growth after the warm-up, over the whole soak, in MB.
const MAX_GROWTH_MB: f64 = 50.0;

const SIZE: (u32, u32) = (640, 360);

/// Every how many actions a sample is printed.
const SAMPLES_EVERY: usize = 10;

/// How many of each action, after the warm-up round.
#[derive(Debug, Clone, Copy)]
struct Counts {
    scene_saves: usize,
    shader_saves: usize,
    panel_edits: usize,
    scene_switches: usize,
    mesh_reloads: usize,
    sandbox_saves: usize,
    page_scene_edits: usize,
    page_shader_edits: usize,
    page_orbits: usize,
    page_switches: usize,
}

impl Counts {
    /// A minute or two on 2 cores with lavapipe.
    const SHORT: Counts = Counts {
        scene_saves: 40,
        shader_saves: 4,
        panel_edits: 10,
        scene_switches: 5,
        mesh_reloads: 10,
        sandbox_saves: 20,
        page_scene_edits: 10,
        page_shader_edits: 5,
        page_orbits: 5,
        page_switches: 5,
    };
    /// An hour of editing, as docs/reliability.md asks.
    const FULL: Counts = Counts {
        scene_saves: 1000,
        shader_saves: 1000,
        panel_edits: 500,
        scene_switches: 200,
        mesh_reloads: 100,
        sandbox_saves: 1000,
        page_scene_edits: 1000,
        page_shader_edits: 1000,
        page_orbits: 500,
        page_switches: 200,
    };

    /// Only the viewer's scene switches, as many as the full soak's: how
    /// their memory levels off (docs/reliability.md, "The soak").
    const SWITCHES: Counts = Counts {
        scene_saves: 0,
        shader_saves: 0,
        panel_edits: 0,
        scene_switches: Self::FULL.scene_switches,
        mesh_reloads: 0,
        sandbox_saves: 0,
        page_scene_edits: 0,
        page_shader_edits: 0,
        page_orbits: 0,
        page_switches: Self::FULL.page_switches,
    };

    /// `RAYSANDBOX_SOAK`: `full`, `switches`, or a whole number `N` for N
    /// times the short soak; unset, the short soak.
    fn chosen() -> Counts {
        let times = |n: usize| Counts {
            scene_saves: Self::SHORT.scene_saves * n,
            shader_saves: Self::SHORT.shader_saves * n,
            panel_edits: Self::SHORT.panel_edits * n,
            scene_switches: Self::SHORT.scene_switches * n,
            mesh_reloads: Self::SHORT.mesh_reloads * n,
            sandbox_saves: Self::SHORT.sandbox_saves * n,
            page_scene_edits: Self::SHORT.page_scene_edits * n,
            page_shader_edits: Self::SHORT.page_shader_edits * n,
            page_orbits: Self::SHORT.page_orbits * n,
            page_switches: Self::SHORT.page_switches * n,
        };
        match std::env::var("RAYSANDBOX_SOAK").as_deref() {
            Ok("full") => Counts::FULL,
            Ok("switches") => Counts::SWITCHES,
            Ok(n) => times(n.parse().expect("RAYSANDBOX_SOAK: full or a whole number")),
            Err(_) => Counts::SHORT,
        }
    }
}

/// Resident memory of process `pid` in MB (`VmRSS`).
fn resident_mb(pid: u32) -> f64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap();
    let kb: f64 = status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.split_whitespace().next()?.parse().ok())
        .expect("VmRSS in /proc/PID/status");
    kb / 1024.0
}

/// A memory figure (resident memory, a heap) during the warm-up and after
/// each action, in MB.
struct Samples {
    what: &'static str,
    /// The most resident during the warm-up round: its working set (which
    /// of the scenes' pipelines and meshes happen to be held moves it by
    /// tens of MB from one action to the next, leak or not).
    after_warm_up: f64,
    peak: f64,
    last: f64,
    actions: usize,
}

impl Samples {
    fn start(what: &'static str, now: f64) -> Samples {
        Samples {
            what,
            after_warm_up: now,
            peak: now,
            last: now,
            actions: 0,
        }
    }

    /// A sample during the warm-up: it raises the level growth is counted
    /// from.
    fn warm_up(&mut self, now: f64) {
        self.after_warm_up = self.after_warm_up.max(now);
        self.peak = self.after_warm_up;
        self.last = self.after_warm_up;
    }

    fn sample(&mut self, now: f64) {
        self.last = now;
        self.peak = self.peak.max(self.last);
        self.actions += 1;
        if self.actions.is_multiple_of(SAMPLES_EVERY) {
            println!(
                "{}: {} actions, {:.1} MB",
                self.what, self.actions, self.last
            );
        }
    }

    /// Prints the growth and checks it against the bound.
    fn check(&self) {
        let growth = self.last - self.after_warm_up;
        let peak = self.peak - self.after_warm_up;
        println!(
            "{}: {} actions; after warm-up {:.1} MB, at the end {:.1} MB \
             (growth {growth:+.1} MB), peak {:.1} MB ({peak:+.1} MB)",
            self.what, self.actions, self.after_warm_up, self.last, self.peak
        );
        assert!(
            growth < MAX_GROWTH_MB && peak < MAX_GROWTH_MB,
            "{}: memory grew by {growth:.1} MB (peak {peak:.1} MB) after the warm-up, \
             more than {MAX_GROWTH_MB} MB",
            self.what
        );
    }
}

/// Writes a file as editors do: a new file renamed over the old one.
fn save(path: &Path, text: &str) {
    let tmp = path.with_extension("soak-tmp");
    std::fs::write(&tmp, text).unwrap();
    std::fs::rename(&tmp, path).unwrap();
}

/// A small mesh whose apex height changes with `n`: each save is new geometry.
fn pyramid(n: usize) -> String {
    let h = 1.0 + 0.01 * (n % 50) as f64;
    format!(
        "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 {h} 0\n\
         f 1 2 3\nf 1 3 4\nf 1 5 2\nf 2 5 3\nf 3 5 4\nf 4 5 1\n"
    )
}

/// The files the viewer edits: a copy of the shader folder, the scene file
/// (whitted with the pyramid mesh) and the bundled scenes it switches to.
struct Workspace {
    shaders: PathBuf,
    scene: PathBuf,
    mesh: PathBuf,
    base_scene: String,
    shade: String,
    /// Scenes to switch to: the Julia set, meshes, implicit surfaces, boxes.
    switches: Vec<String>,
}

impl Workspace {
    fn new() -> Workspace {
        let dir = common::temp_dir("soak", "viewer");
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let shaders = dir.join("shaders");
        common::copy_dir(&root.join("shaders"), &shaders);
        let mesh = common::write_file(&dir, "pyramid.obj", &pyramid(0));
        let whitted = std::fs::read_to_string(common::scenes_dir().join("whitted.toml")).unwrap();
        let base_scene = format!(
            "{whitted}\n[[meshes]]\nfile = \"pyramid.obj\"\nscale = 0.3\n\
             translate = [2.0, 0.0, 0.0]\nmaterial = \"mirror\"\n"
        );
        let scene = common::write_file(&dir, "scene.toml", &base_scene);
        let meshes = root.join("assets/meshes");
        let bundled = |name: &str| -> String {
            let path = [format!("{name}.toml"), format!("meshes/{name}.toml")]
                .into_iter()
                .map(|f| common::scenes_dir().join(f))
                .find(|p| p.is_file())
                .unwrap();
            let text = std::fs::read_to_string(path).unwrap();
            text.replace("../../meshes/", &format!("{}/", meshes.display()))
        };
        let switches = [
            "julia",
            "glass_bunny",
            "implicits",
            "mirror_teapot",
            "rotated_cubes",
        ]
        .map(bundled)
        .into_iter()
        .chain([base_scene.clone()])
        .collect();
        let shade = std::fs::read_to_string(shaders.join("shade.wgsl")).unwrap();
        Workspace {
            shaders,
            scene,
            mesh,
            base_scene,
            shade,
            switches,
        }
    }
}

/// One action on the viewer, waited for until its frame is ready.
fn scene_save(viewer: &mut Window, ws: &Workspace, n: usize) {
    let radius = 0.8 + 0.001 * (n % 50 + 1) as f64;
    let text = ws
        .base_scene
        .replacen("radius = 0.8", &format!("radius = {radius:.3}"), 1);
    save(&ws.scene, &text);
    viewer.wait_for("scene-reloaded");
    viewer.wait_for("ready");
}

fn shader_save(viewer: &mut Window, ws: &Workspace, n: usize) {
    save(
        &ws.shaders.join("shade.wgsl"),
        &format!("{}// soak edit {n}\n", ws.shade),
    );
    viewer.wait_for("shaders-reloaded");
    viewer.wait_for("ready");
}

fn mesh_reload(viewer: &mut Window, ws: &Workspace, n: usize) {
    save(&ws.mesh, &pyramid(n + 1));
    viewer.wait_for("file-reloaded");
    viewer.wait_for("ready");
}

/// Drags the camera's fov slider (the Camera section is open at the start),
/// then saves with Ctrl+S so that the file can be reloaded afterwards.
fn panel_edit(viewer: &mut Window, n: usize) {
    let (from, to) = if n.is_multiple_of(2) {
        (100, 130)
    } else {
        (130, 100)
    };
    viewer.drag("1", (from, 145), (to, 145));
    viewer.wait_for("ready");
    viewer.key("ctrl+s");
    viewer.wait_for("saved");
}

/// Opens another scene by replacing the watched file's contents (the last
/// switch goes back to the starting scene, with its mesh).
fn scene_switch(viewer: &mut Window, ws: &Workspace, n: usize) {
    save(&ws.scene, &ws.switches[n % ws.switches.len()]);
    viewer.wait_for("scene-reloaded");
    viewer.wait_for("ready");
}

fn soak_viewer(display: &Display, counts: Counts) {
    let ws = Workspace::new();
    let mut viewer = Window::open(
        display,
        &[
            "view",
            ws.scene.to_str().unwrap(),
            "--shaders",
            ws.shaders.to_str().unwrap(),
            "--max-samples",
            "1",
        ],
        SIZE,
    );
    // Warm-up: every action once (every scene of the switches too).
    let pid = viewer.pid();
    let mut samples = Samples::start("viewer", resident_mb(pid));
    scene_save(&mut viewer, &ws, 0);
    samples.warm_up(resident_mb(pid));
    shader_save(&mut viewer, &ws, 0);
    samples.warm_up(resident_mb(pid));
    mesh_reload(&mut viewer, &ws, 0);
    samples.warm_up(resident_mb(pid));
    panel_edit(&mut viewer, 0);
    samples.warm_up(resident_mb(pid));
    for n in 0..ws.switches.len() {
        scene_switch(&mut viewer, &ws, n);
        samples.warm_up(resident_mb(pid));
    }
    for n in 1..=counts.scene_saves {
        scene_save(&mut viewer, &ws, n);
        samples.sample(resident_mb(pid));
    }
    for n in 1..=counts.shader_saves {
        shader_save(&mut viewer, &ws, n);
        samples.sample(resident_mb(pid));
    }
    for n in 1..=counts.mesh_reloads {
        mesh_reload(&mut viewer, &ws, n);
        samples.sample(resident_mb(pid));
    }
    for n in 1..=counts.panel_edits {
        panel_edit(&mut viewer, n);
        samples.sample(resident_mb(pid));
    }
    for n in 0..counts.scene_switches {
        scene_switch(&mut viewer, &ws, n);
        samples.sample(resident_mb(pid));
    }
    assert!(viewer.is_running());
    samples.check();
}

/// A GLSL Sandbox shader whose picture moves with the clock.
const WAVES: &str = "uniform float time;\nuniform vec2 resolution;\n\
void main() { vec2 p = gl_FragCoord.xy / resolution; \
gl_FragColor = vec4(0.5 + 0.5 * sin(10.0 * p.x + time), p.y, 0.3, 1.0); }\n";

fn soak_sandbox(display: &Display, counts: Counts) {
    let dir = common::temp_dir("soak", "sandbox");
    let file = common::write_file(&dir, "waves.frag", WAVES);
    let mut window = Window::open(display, &["shader", file.to_str().unwrap()], SIZE);
    let edit = |window: &mut Window, n: usize| {
        save(&file, &format!("{WAVES}// soak edit {n}\n"));
        window.wait_for("shader-reloaded");
    };
    let pid = window.pid();
    let mut samples = Samples::start("sandbox", resident_mb(pid));
    edit(&mut window, 0);
    samples.warm_up(resident_mb(pid));
    for n in 1..=counts.sandbox_saves {
        edit(&mut window, n);
        samples.sample(resident_mb(pid));
    }
    assert!(window.is_running());
    samples.check();
}

/// The page's memory in MB, read through the DevTools protocol without
/// collecting garbage first, as a user's browser would leave it: the JS heap
/// in use, and the linear memory of every `WebAssembly.Memory` (the Rust
/// side's heap; it only ever grows, so it holds the most the page ever
/// needed). A forced collection would also free GPU buffers and textures
/// whose wrappers the page dropped without destroying them, which a small JS
/// heap otherwise keeps for a long time (docs/web.md, "GPU memory").
fn page_memory_mb(page: &mut Browser) -> (f64, f64) {
    let heap = page.call("Runtime.getHeapUsage", json!({}));
    let js = heap["usedSize"].as_f64().expect("usedSize");
    let group = json!("soak");
    let prototype = page.call(
        "Runtime.evaluate",
        json!({ "expression": "WebAssembly.Memory.prototype", "objectGroup": group }),
    );
    let found = page.call(
        "Runtime.queryObjects",
        json!({ "prototypeObjectId": prototype["result"]["objectId"], "objectGroup": group }),
    );
    let bytes = page.call(
        "Runtime.callFunctionOn",
        json!({
            "objectId": found["objects"]["objectId"],
            "functionDeclaration":
                "function () { return this.reduce((sum, m) => sum + m.buffer.byteLength, 0); }",
            "returnByValue": true,
        }),
    );
    page.call(
        "Runtime.releaseObjectGroup",
        json!({ "objectGroup": group }),
    );
    let wasm = bytes["result"]["value"]
        .as_f64()
        .expect("wasm memory bytes");
    assert!(wasm > 0.0, "the page holds no WebAssembly memory");
    (js / 1e6, wasm / 1e6)
}

/// Resident memory of Chromium's GPU process in MB: where SwiftShader
/// holds the page's buffers, textures and pipelines (what the JS heap and
/// the WebAssembly memory do not show). It is a grandchild of the browser
/// process (through the zygote).
fn gpu_process_mb(page: &Browser) -> f64 {
    let parent_of = |pid: u32| -> Option<u32> {
        let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
        // After the command name in parentheses: the state, then the parent.
        let (_, rest) = stat.rsplit_once(')')?;
        rest.split_whitespace().nth(1)?.parse().ok()
    };
    let descends_from_browser = |mut pid: u32| {
        while let Some(parent) = parent_of(pid).filter(|&p| p > 1) {
            if parent == page.pid() {
                return true;
            }
            pid = parent;
        }
        false
    };
    let is_gpu_process = |pid: &u32| {
        let cmdline = std::fs::read(format!("/proc/{pid}/cmdline")).unwrap_or_default();
        String::from_utf8_lossy(&cmdline).contains("--type=gpu-process")
    };
    let gpu = std::fs::read_dir("/proc")
        .unwrap()
        .filter_map(|entry| entry.ok()?.file_name().to_str()?.parse::<u32>().ok())
        .find(|pid| is_gpu_process(pid) && descends_from_browser(*pid))
        .expect("Chromium's GPU process");
    resident_mb(gpu)
}

/// Shows the editor's tab `doc` and puts `text` in place of its document,
/// as a user selecting all and typing.
fn page_edit(page: &mut Browser, doc: &str, text: &str) {
    page.evaluate(&format!(
        "(() => {{ document.getElementById('{doc}-tab').click(); \
         const t = document.getElementById('{doc}-text'); t.focus(); t.select(); }})()"
    ));
    page.insert_text(text);
}

/// The page through scene edits (a sphere's radius typed in the editor),
/// orbits (a drag on the canvas, which rewrites the scene text and the
/// address), shader edits (the sandbox's shader with a comment appended)
/// and scene switches (bundled scenes typed in: the Julia set, the mirror
/// teapot's model fetched, implicit surfaces, boxes, back to Whitted).
fn soak_page(display: &Display, counts: Counts) {
    let url = browser::serve(browser::page_dir());
    let mut page = Browser::open(display, &format!("{url}?samples=1&editor"));
    page.wait_for("ready");
    let whitted = std::fs::read_to_string(common::scenes_dir().join("whitted.toml")).unwrap();
    let bundled = |file: &str| std::fs::read_to_string(common::scenes_dir().join(file)).unwrap();
    let switches = [
        bundled("julia.toml"),
        bundled("meshes/mirror_teapot.toml"),
        bundled("implicits.toml"),
        bundled("rotated_cubes.toml"),
        whitted.clone(),
    ];
    let scene_edit = |page: &mut Browser, n: usize| {
        let radius = 0.8 + 0.001 * (n % 50 + 1) as f64;
        page_edit(
            page,
            "scene",
            &whitted.replacen("radius = 0.8", &format!("radius = {radius:.3}"), 1),
        );
        page.wait_for("scene ok");
        page.wait_for("ready");
    };
    let shader_edit = |page: &mut Browser, n: usize| {
        page_edit(page, "shader", &format!("{WAVES}// soak edit {n}\n"));
        page.wait_for("shader ok");
    };
    // After a scene edit: the canvas shows the scene.
    let orbit = |page: &mut Browser, n: usize| {
        let (x, y) = (
            f64::from(browser::SIZE.0) / 4.0,
            f64::from(browser::SIZE.1) / 2.0,
        );
        let dx = if n.is_multiple_of(2) { 40.0 } else { -40.0 };
        page.drag(Button::Left, (x, y), (x + dx, y));
        page.wait_for("ready");
    };
    let switch = |page: &mut Browser, n: usize| {
        page_edit(page, "scene", &switches[n % switches.len()]);
        page.wait_for("scene ok");
        page.wait_for("ready");
    };

    let (js, wasm) = page_memory_mb(&mut page);
    let mut heap = Samples::start("page JS heap", js);
    let mut linear = Samples::start("page wasm memory", wasm);
    let mut gpu = Samples::start("page GPU process", gpu_process_mb(&page));
    let start = std::time::Instant::now();
    let mut sample = |page: &mut Browser, warm_up: bool| {
        let (js, wasm) = page_memory_mb(page);
        let resident = gpu_process_mb(page);
        println!(
            "page at {:.0} s: JS heap {js:.1} MB, wasm memory {wasm:.1} MB, GPU process {resident:.1} MB",
            start.elapsed().as_secs_f64()
        );
        if warm_up {
            heap.warm_up(js);
            linear.warm_up(wasm);
            gpu.warm_up(resident);
        } else {
            heap.sample(js);
            linear.sample(wasm);
            gpu.sample(resident);
        }
    };
    scene_edit(&mut page, 0);
    sample(&mut page, true);
    orbit(&mut page, 0);
    sample(&mut page, true);
    shader_edit(&mut page, 0);
    sample(&mut page, true);
    for n in 0..switches.len() {
        switch(&mut page, n);
        sample(&mut page, true);
    }
    for n in 1..=counts.page_scene_edits {
        scene_edit(&mut page, n);
        sample(&mut page, false);
    }
    for n in 1..=counts.page_orbits {
        orbit(&mut page, n);
        sample(&mut page, false);
    }
    for n in 1..=counts.page_shader_edits {
        shader_edit(&mut page, n);
        sample(&mut page, false);
    }
    for n in 0..counts.page_switches {
        switch(&mut page, n);
        sample(&mut page, false);
    }
    assert_eq!(page.exceptions(), Vec::<String>::new());
    heap.check();
    linear.check();
    gpu.check();
}

#[test]
fn page_memory_stays_flat_under_live_editing() {
    let display = Display::start();
    let counts = Counts::chosen();
    println!("page soak: {counts:?}, bound {MAX_GROWTH_MB} MB after the warm-up");
    soak_page(&display, counts);
}

#[test]
fn memory_stays_flat_under_live_editing() {
    let display = Display::start();
    let counts = Counts::chosen();
    println!("soak: {counts:?}, bound {MAX_GROWTH_MB} MB after the warm-up");
    soak_viewer(&display, counts);
    soak_sandbox(&display, counts);
}
