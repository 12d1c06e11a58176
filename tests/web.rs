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
/// its first frame (1 sample per pixel) is the native renderer's picture.
#[test]
fn the_page_renders_the_whitted_scene_like_the_reference() {
    let Some(display) = common::xwindow::Display::start() else {
        return;
    };
    let url = browser::serve(browser::page_dir());
    let mut page = Browser::open(&display, &format!("{url}?samples=1"));
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
    let address = format!("{url}?samples=1#{}", link::scene_hash(&edited));
    let mut page = Browser::open(&display, &address);
    assert_eq!(page.wait_for("scene"), "from-link");
    page.wait_for("ready");
    assert_like_reference("link", &page.capture_picture(), &scene);
}
