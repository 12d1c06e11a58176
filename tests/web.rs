//! The browser page (docs/web.md) in a real Chromium, WebGPU on SwiftShader,
//! driven through the DevTools protocol (tests/common/browser.rs): the page
//! served from `dist/web/` (built by `scripts/web`, which `scripts/test` runs
//! first) by a small HTTP server in the test, its console's
//! `raysandbox: EVENT` lines awaited, the screen captured with `import`.

mod common;

use common::browser::{self, Browser, SIZE};
use image::RgbaImage;
use raysandbox::compare::{diff_images, distinct_colors, nan_pixels};
use raysandbox::reference;
use raysandbox::scene::{Scene, bundled};
use raysandbox::web::link;

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
/// (`ui=0`, here and below: the picture alone, without the page's controls
/// over it).
#[test]
fn the_page_renders_the_whitted_scene_like_the_reference() {
    let Some(display) = common::xwindow::Display::start() else {
        return;
    };
    let url = browser::serve(browser::page_dir());
    let mut page = Browser::open(&display, &format!("{url}?samples=1&ui=0"));
    assert_eq!(page.wait_for("scene"), "whitted");
    let adapter = page.wait_for("adapter");
    eprintln!("page adapter: {adapter}");
    let size = page.wait_for("first-frame");
    assert_eq!(size, format!("{}x{}", SIZE.0, SIZE.1), "canvas size");
    page.wait_for("ready");
    assert_like_reference("whitted", &page.capture_picture(), &whitted().1);
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
    let url = browser::serve(browser::page_dir());
    let address = format!("{url}?samples=1&ui=0#{}", link::scene_hash(&edited));
    let mut page = Browser::open(&display, &address);
    assert_eq!(page.wait_for("scene"), "from-link");
    page.wait_for("ready");
    assert_like_reference("link", &page.capture_picture(), &scene);
}

/// The error the page reports once it met one, which it must show over the
/// canvas, where the user looks, as well as log. The message box is hidden
/// afterwards so that the picture under it can be compared.
fn error_shown(page: &mut Browser) -> String {
    let logged = page.wait_for("error");
    let shown = page.message();
    assert_eq!(
        shown.as_deref(),
        Some(logged.as_str()),
        "the error is shown over the canvas"
    );
    assert!(!logged.contains("panicked"), "the page panicked: {logged}");
    page.evaluate("document.getElementById('message').className = ''");
    logged
}

/// A link damaged on its way (cut short when copied) is reported over the
/// canvas, and the page shows the bundled Whitted scene instead.
#[test]
fn a_damaged_link_is_reported_and_the_whitted_scene_shown() {
    let Some(display) = common::xwindow::Display::start() else {
        return;
    };
    let hash = link::scene_hash(&whitted().0);
    let cut = &hash[..hash.len() / 2];
    let url = browser::serve(browser::page_dir());
    let mut page = Browser::open(&display, &format!("{url}?samples=1&ui=0#{cut}"));
    let error = error_shown(&mut page);
    assert!(error.contains("the link is damaged"), "{error}");
    assert_eq!(page.wait_for("scene"), "whitted");
    page.wait_for("ready");
    assert_like_reference("damaged-link", &page.capture_picture(), &whitted().1);
    assert_eq!(page.exceptions(), Vec::<String>::new());
}

/// A link that decodes to a scene with a mistake (here a colour with two
/// components) names the scene's line, and the Whitted scene is shown.
#[test]
fn a_link_to_a_bad_scene_names_the_line_and_the_whitted_scene_is_shown() {
    let Some(display) = common::xwindow::Display::start() else {
        return;
    };
    let text = whitted().0;
    let bad = text.replace("ambient = [0.12, 0.12, 0.12]", "ambient = [0.12, 0.12]");
    assert_ne!(bad, text, "the mistake was made");
    let line = 1 + bad
        .lines()
        .position(|l| l.starts_with("ambient ="))
        .unwrap();
    let url = browser::serve(browser::page_dir());
    let address = format!("{url}?samples=1&ui=0#{}", link::scene_hash(&bad));
    let mut page = Browser::open(&display, &address);
    let error = error_shown(&mut page);
    assert!(error.contains(&format!("<scene>:{line}:")), "{error}");
    assert!(error.contains("ambient"), "{error}");
    assert_eq!(page.wait_for("scene"), "whitted");
    page.wait_for("ready");
    assert_like_reference("bad-scene-link", &page.capture_picture(), &whitted().1);
    assert_eq!(page.exceptions(), Vec::<String>::new());
}

/// In a browser without WebGPU (Chromium on Linux without its WebGPU
/// flags) the page says so over the canvas, naming the browsers and the flag
/// that have it, and nothing panics.
#[test]
fn without_webgpu_the_page_says_which_browsers_have_it() {
    let Some(display) = common::xwindow::Display::start() else {
        return;
    };
    let url = browser::serve(browser::page_dir());
    let mut page = Browser::start(&display, browser::Options { webgpu: false });
    page.navigate(&format!("{url}?samples=1&ui=0"));
    let gpu = page.evaluate(
        "navigator.gpu ? navigator.gpu.requestAdapter().then(a => a ? 'adapter' : 'no adapter') \
         : 'no navigator.gpu'",
    );
    eprintln!("without the WebGPU flags: {gpu}");
    assert_ne!(gpu, "adapter", "this Chromium has WebGPU without its flags");
    let error = error_shown(&mut page);
    eprintln!("the page says: {error}");
    for hint in [
        "WebGPU is not available",
        "Chrome",
        "Firefox",
        "Safari",
        "--enable-unsafe-webgpu",
    ] {
        assert!(error.contains(hint), "{hint:?} is not in: {error}");
    }
    let later = page.events_within(std::time::Duration::from_secs(1));
    assert!(later.is_empty(), "after the error the page said {later:?}");
    assert_eq!(page.exceptions(), Vec::<String>::new());
}
