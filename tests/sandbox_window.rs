//! `raysandbox shader` as a person uses it: the real binary in a window under
//! Xvfb, the shader file edited on disk, the window's pixels captured with
//! ImageMagick's `import` and compared with headless renders.
//!
//! The harness is tests/common/xwindow.rs.

mod common;

use std::path::PathBuf;

use common::xwindow::{Display, Rect, Window, crop};
use raysandbox::compare::diff_images;
use raysandbox::sandbox::render_file;

const WIDTH: u32 = 640;
const HEIGHT: u32 = 360;

/// A part of the window that the panel (top left) and its shadow leave
/// uncovered, from the window's own layout; the error overlay (bottom) must
/// stay below it (checked where one shows, by [`below_free`]).
fn free(window: &Window) -> (u32, u32, u32, u32) {
    let x = window.part("panel").right() + 48;
    let free = Rect {
        x,
        y: 0,
        w: WIDTH as i32 - x,
        h: 150,
    };
    assert!(free.w >= 150, "the panel leaves too little: {free:?}");
    free.crop()
}

/// Asserts that the error overlay leaves the free part uncovered.
fn below_free(window: &Window) {
    let error = window.part("shader-error");
    assert!(
        error.y >= 150,
        "the error overlay {error:?} covers the free part"
    );
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
    let display = Display::start();
    let gpu = common::gpu();
    let dir = std::env::temp_dir().join(format!("raysandbox-window-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let shader = dir.join("live.frag");
    std::fs::write(&shader, RINGS).unwrap();
    let mut window = Window::open(
        &display,
        &["shader", shader.to_str().unwrap(), "--start-paused"],
        (WIDTH, HEIGHT),
    );
    let area = free(&window);
    let headless = |shader: &PathBuf| {
        let (image, _) = render_file(&gpu, shader, (WIDTH, HEIGHT), 0.0, None).unwrap();
        crop(&image, area)
    };
    let first = crop(&window.capture(), area);
    let d = diff_images(&first, &headless(&shader));
    assert!(d.max_abs <= 1, "the window shows the shader: {d:?}");

    // An edit in another program: the window follows.
    let edited = RINGS.replace("vec2(0.7, 0.6)", "vec2(0.9, 0.2)");
    std::fs::write(&shader, &edited).unwrap();
    window.wait_for("shader-reloaded");
    let second = crop(&window.capture(), area);
    assert!(diff_images(&first, &second).max_abs > 50, "the edit shows");
    let d = diff_images(&second, &headless(&shader));
    assert!(d.max_abs <= 1, "the window shows the edit: {d:?}");

    // A mistake: reported at its line, the last good image stays.
    let broken = edited.replace("float r = length", "float r = lenght");
    std::fs::write(&shader, &broken).unwrap();
    let location = window.wait_for("shader-error");
    below_free(&window);
    assert_eq!(location, format!("{}:6:15", shader.display()));
    let during = crop(&window.capture(), area);
    assert_eq!(
        diff_images(&second, &during).max_abs,
        0,
        "the last good image stays"
    );

    // A loop that never ends: the watchdog's trial frame refuses it, the
    // window keeps running the last good shader.
    let endless = edited.replace(
        "float r = length",
        "float x = p.x;\n    while (x < 2.0) { x = fract(x + sin(x * 7.0 + p.y)); }\n    float r = x + length",
    );
    std::fs::write(&shader, &endless).unwrap();
    let location = window.wait_for("shader-error");
    below_free(&window);
    assert!(
        location.contains("live.frag: a frame would take about"),
        "{location}"
    );
    let during = crop(&window.capture(), area);
    assert_eq!(
        diff_images(&second, &during).max_abs,
        0,
        "the last good image stays"
    );

    // Fixed again, then a screenshot of the image.
    std::fs::write(&shader, RINGS).unwrap();
    window.wait_for("shader-reloaded");
    let fixed = crop(&window.capture(), area);
    assert_eq!(diff_images(&first, &fixed).max_abs, 0);
    window.key("p");
    let path = PathBuf::from(window.wait_for("screenshot"));
    assert_eq!(path, dir.join("live-screenshot-1.png"));
    let shot = image::open(&path).unwrap().to_rgba8();
    assert_eq!(shot.dimensions(), (WIDTH, HEIGHT));
    drop(window);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A glslViewer-style shader that includes its colour from a library and
/// declares a uniform nothing sets.
const INCLUDING: &str = "\
uniform vec2 u_resolution;
uniform float u_gain;
#include \"lib/tint.glsl\"
void main() {
    vec2 st = gl_FragCoord.xy / u_resolution;
    gl_FragColor = vec4(tint() * st.x + u_gain, 1.0);
}
";

/// Includes (docs/sandbox.md, "Includes"): an edit of the included file
/// reloads the shader in the window; and the uniform nothing sets is
/// announced once ("Uniforms nobody sets").
#[test]
fn the_window_follows_included_files_and_warns_of_uniforms_nothing_sets() {
    let display = Display::start();
    let gpu = common::gpu();
    let dir =
        std::env::temp_dir().join(format!("raysandbox-window-include-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("lib")).unwrap();
    let shader = dir.join("book.frag");
    let library = dir.join("lib/tint.glsl");
    std::fs::write(&library, "vec3 tint() { return vec3(1.0, 0.5, 0.0); }\n").unwrap();
    std::fs::write(&shader, INCLUDING).unwrap();
    let mut window = Window::open(
        &display,
        &["shader", shader.to_str().unwrap(), "--start-paused"],
        (WIDTH, HEIGHT),
    );
    assert_eq!(window.wait_for("shader-warning").trim(), "1");
    // Below the warning shown at the top of the image.
    let x = window.part("panel").right() + 48;
    let area = Rect {
        x,
        y: 220,
        w: WIDTH as i32 - x,
        h: 120,
    }
    .crop();
    let headless = || {
        let (image, _) = render_file(&gpu, &shader, (WIDTH, HEIGHT), 0.0, None).unwrap();
        crop(&image, area)
    };
    let first = crop(&window.capture(), area);
    let d = diff_images(&first, &headless());
    assert!(d.max_abs <= 1, "the window shows the shader: {d:?}");

    std::fs::write(&library, "vec3 tint() { return vec3(0.0, 0.5, 1.0); }\n").unwrap();
    window.wait_for("shader-reloaded");
    let second = crop(&window.capture(), area);
    assert!(diff_images(&first, &second).max_abs > 50, "the edit shows");
    let d = diff_images(&second, &headless());
    assert!(d.max_abs <= 1, "the window shows the edit: {d:?}");

    // A mistake in the included file: reported at its own line.
    std::fs::write(&library, "\nvec3 tint() { return vec3(0.0, 0.5, 1.0) }\n").unwrap();
    let location = window.wait_for("shader-error");
    assert!(location.ends_with("lib/tint.glsl:2:42"), "{location}");
    drop(window);
    std::fs::remove_dir_all(&dir).unwrap();
}

const SHOW_CHANNEL0: &str = "\
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    fragColor = texture(iChannel0, fragCoord / iResolution.xy);
}
";

/// Opens the window, paused, on the GLSL `shader` in a fresh folder
/// (`raysandbox-window-NAME-PID`), with `input` as `--channel0`; returns
/// it and the folder.
fn open_with_channel0<'d>(
    display: &'d Display,
    name: &str,
    shader: &str,
    input: &image::RgbaImage,
) -> (Window<'d>, PathBuf) {
    let dir = std::env::temp_dir().join(format!("raysandbox-window-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("shader.glsl");
    std::fs::write(&path, shader).unwrap();
    let input_path = dir.join("input.png");
    input.save(&input_path).unwrap();
    let window = Window::open(
        display,
        &[
            "shader",
            path.to_str().unwrap(),
            "--start-paused",
            "--channel0",
            input_path.to_str().unwrap(),
        ],
        (WIDTH, HEIGHT),
    );
    (window, dir)
}

#[test]
fn the_window_shows_the_channel_image_given_on_the_command_line() {
    let display = Display::start();
    let input = image::RgbaImage::from_fn(WIDTH, HEIGHT, |x, y| {
        image::Rgba([
            (x % 256) as u8,
            (y % 256) as u8,
            ((x / 3) ^ (y / 5)) as u8,
            255,
        ])
    });
    let (window, dir) = open_with_channel0(&display, "ch", SHOW_CHANNEL0, &input);
    let area = free(&window);
    let shown = crop(&window.capture(), area);
    let d = diff_images(&shown, &crop(&input, area));
    assert!(d.max_abs <= 1, "the window shows the image: {d:?}");
    drop(window);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Rings over the channel image: both must come back after a lost device.
const RINGS_OVER_CHANNEL0: &str = "\
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 p = fragCoord / iResolution.xy;
    float r = length(p - vec2(0.7, 0.6));
    vec3 image = texture(iChannel0, p).rgb;
    fragColor = vec4(image.rg, 0.5 + 0.5 * sin(60.0 * r - iTime), 1.0);
}
";

/// A lost GPU device (SIGUSR1 destroys it, as a driver reset would lose it)
/// is replaced by a new one in the same window (docs/reliability.md, "The
/// GPU's limits and a lost device"): the shader, built again, draws the
/// same picture with its channel image, the clock paused where it was.
#[test]
fn a_lost_device_is_recovered_keeping_the_shader_and_its_channel() {
    let display = Display::start();
    let input = image::RgbaImage::from_fn(WIDTH, HEIGHT, |x, y| {
        image::Rgba([(x % 256) as u8, ((x ^ y) % 256) as u8, 0, 255])
    });
    let (mut window, dir) = open_with_channel0(&display, "lost", RINGS_OVER_CHANNEL0, &input);
    let area = free(&window);
    let before = crop(&window.capture(), area);

    let recovery = window.lose_device("sandbox window");
    assert!(recovery.reason.contains("destroyed"), "{}", recovery.reason);
    let after = crop(&window.capture(), area);
    let d = diff_images(&before, &after);
    assert!(d.max_abs <= 1, "the same picture after the loss: {d:?}");
    assert!(window.is_running());
    drop(window);
    std::fs::remove_dir_all(&dir).unwrap();
}
