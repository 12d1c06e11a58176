//! A multipass shader in the window (docs/sandbox.md, "Multipass"), as a
//! person uses it: the real binary under Xvfb (tests/common/xwindow.rs),
//! the folder's files edited on disk, `R` pressed.

mod common;

use std::path::Path;

use common::xwindow::{Display, Rect, Window, crop};
use raysandbox::compare::diff_images;

const WIDTH: u32 = 480;
const HEIGHT: u32 = 270;

/// The part of the image right of the panel.
fn free(window: &Window) -> (u32, u32, u32, u32) {
    let x = window.part("panel").right() + 48;
    let free = Rect {
        x,
        y: 0,
        w: WIDTH as i32 - x,
        h: 120,
    };
    assert!(free.w >= 100, "the panel leaves too little: {free:?}");
    free.crop()
}

/// The share of pixels whose red is neither 0 nor 255: the progressive
/// average's first frame is one sample per pixel (0 or 1), later frames
/// average several.
fn averaged(window: &Window, area: (u32, u32, u32, u32)) -> f64 {
    let image = crop(&window.capture(), area);
    let grey = image.pixels().filter(|p| p[0] != 0 && p[0] != 255).count();
    grey as f64 / f64::from(image.width() * image.height())
}

/// Opens the window on a copy of tests/shaders/multipass/progressive in a
/// fresh folder (named with `prefix`), with the options `more`; returns it
/// and the folder.
fn open_progressive<'d>(
    display: &'d Display,
    prefix: &str,
    more: &[&str],
) -> (Window<'d>, std::path::PathBuf) {
    let dir = common::temp_dir(prefix, "progressive");
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/shaders/multipass/progressive");
    common::copy_dir(&source, &dir);
    let mut args = vec!["shader", dir.to_str().unwrap()];
    args.extend_from_slice(more);
    (Window::open(display, &args, (WIDTH, HEIGHT)), dir)
}

/// Lets the running clock run for 2 s, then pauses it: the frames have
/// accumulated.
fn run_then_pause(window: &Window, area: (u32, u32, u32, u32)) {
    std::thread::sleep(std::time::Duration::from_secs(2));
    window.key("space");
    std::thread::sleep(std::time::Duration::from_millis(500));
    let accumulated = averaged(window, area);
    assert!(
        accumulated > 0.5,
        "the frames accumulate: {accumulated} of the pixels grey"
    );
}

/// tests/shaders/multipass/progressive accumulates while the clock runs;
/// `R` clears its buffer (the next frame is frame 0 again); a saved pass
/// reloads; a mistake in a pass or in channels.toml is reported at its
/// file, and the last good passes keep running.
#[test]
fn a_multipass_folder_accumulates_resets_on_r_and_reloads_each_pass() {
    let display = Display::start();
    let (mut window, dir) = open_progressive(&display, "multipass-window", &[]);
    let area = free(&window);
    run_then_pause(&window, area);

    window.key("r");
    window.wait_for("buffers-cleared");
    let after = averaged(&window, area);
    assert_eq!(after, 0.0, "after R the buffer holds one sample per pixel");

    // The Image pass edited: only it reloads.
    let image = dir.join("image.glsl");
    let text = std::fs::read_to_string(&image).unwrap();
    std::fs::write(
        &image,
        text.replace("fragColor = texture", "fragColor = 0.5 * texture"),
    )
    .unwrap();
    window.wait_for("shader-reloaded");
    let halved = crop(&window.capture(), area);
    assert!(
        halved
            .pixels()
            .all(|p| p[0] == 0 || (127..=128).contains(&p[0])),
        "the edited Image pass shows the same buffer at half"
    );

    // A mistake in Buffer A: at its file and line.
    let buffer_a = dir.join("buffer_a.glsl");
    let text = std::fs::read_to_string(&buffer_a).unwrap();
    std::fs::write(
        &buffer_a,
        text.replace("float x = random", "float x = randm"),
    )
    .unwrap();
    let location = window.wait_for("shader-error");
    assert!(
        location.starts_with(&format!("{}:7:", buffer_a.display())),
        "{location}"
    );
    // A mistake in the bindings: the file and the key.
    std::fs::write(&buffer_a, &text).unwrap();
    let bindings = dir.join("channels.toml");
    let toml = std::fs::read_to_string(&bindings).unwrap();
    std::fs::write(
        &bindings,
        toml.replace(
            "[image]\niChannel0 = \"buffer_a\"",
            "[image]\niChannel0 = \"buffer_x\"",
        ),
    )
    .unwrap();
    let location = window.wait_for("shader-error");
    assert!(
        location.starts_with(&format!("{}: [image] iChannel0", bindings.display())),
        "{location}"
    );
    std::fs::write(&bindings, &toml).unwrap();
    window.wait_for("shader-reloaded");
    assert!(window.is_running());
}

/// A lost GPU device (SIGUSR1, docs/reliability.md, "The GPU's limits and
/// a lost device"): the passes are built again on a new device and the
/// buffers start again with the clock, as after `R`: the progressive
/// average's frame 0, the same picture as when the window opened paused.
#[test]
fn a_lost_device_restarts_the_buffers_with_the_clock() {
    let display = Display::start();
    let (mut window, _) = open_progressive(&display, "multipass-window-lost", &["--start-paused"]);
    let area = free(&window);
    let first = crop(&window.capture(), area);
    window.key("space");
    run_then_pause(&window, area);

    let recovery = window.lose_device("sandbox window, multipass");
    assert!(recovery.reason.contains("destroyed"), "{}", recovery.reason);
    let after = crop(&window.capture(), area);
    let d = diff_images(&first, &after);
    assert!(
        d.max_abs <= 1,
        "after the loss the buffers start again at frame 0, as when the window opened: {d:?}"
    );
    assert!(window.is_running());
}
