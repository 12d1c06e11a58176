//! Every bundled scene, rendered by the WGSL shader on the GPU and by the f64
//! CPU reference at 320x180 and 1 sample per pixel, must agree: mean absolute
//! difference <= 0.5 (8-bit units, all channels), at most 0.5% of pixels with
//! a channel off by more than 8, no non-finite (magenta) pixels, and no blank
//! image where the reference shows a picture.

mod common;

use raysandbox::compare::{diff_images, distinct_colors, nan_pixels};
use raysandbox::gpu::render_image;
use raysandbox::reference;
use raysandbox::scene::Scene;

const WIDTH: u32 = 320;
const HEIGHT: u32 = 180;

#[test]
fn gpu_matches_reference_on_every_bundled_scene() {
    let Some(gpu) = common::gpu() else { return };
    let scenes = common::toml_files(&common::scenes_dir());
    assert!(
        scenes.len() >= 5,
        "expected the bundled scenes, found {scenes:?}"
    );
    let mut failures = Vec::new();
    println!(
        "{:<24} {:>9} {:>9} {:>5} {:>5}",
        "scene", "mean|d|", ">8 (%)", "max", "NaN"
    );
    for path in &scenes {
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        let scene = Scene::load(path).unwrap_or_else(|e| panic!("{e}"));
        let gpu_image =
            render_image(&gpu, &scene, WIDTH, HEIGHT, 1).unwrap_or_else(|e| panic!("{e}"));
        let ref_image = reference::render_rgba8(&scene, WIDTH, HEIGHT, 1);
        let failures_before = failures.len();
        let d = diff_images(&gpu_image, &ref_image);
        let nans = nan_pixels(&gpu_image, &ref_image);
        println!(
            "{name:<24} {:>9.4} {:>9.4} {:>5} {:>5}",
            d.mean_abs,
            d.frac_over_8 * 100.0,
            d.max_abs,
            nans
        );
        if d.mean_abs > 0.5 {
            failures.push(format!("{name}: mean |difference| {:.4} > 0.5", d.mean_abs));
        }
        if d.frac_over_8 > 0.005 {
            failures.push(format!(
                "{name}: {:.3}% of pixels differ by > 8",
                d.frac_over_8 * 100.0
            ));
        }
        if nans > 0 {
            failures.push(format!("{name}: {nans} non-finite (magenta) pixels"));
        }
        if distinct_colors(&ref_image, 16) >= 16 && distinct_colors(&gpu_image, 16) < 16 {
            failures.push(format!(
                "{name}: the GPU image is blank where the reference is not"
            ));
        }
        if failures.len() > failures_before {
            let dir = std::env::temp_dir();
            gpu_image.save(dir.join(format!("{name}-gpu.png"))).unwrap();
            ref_image
                .save(dir.join(format!("{name}-reference.png")))
                .unwrap();
        }
    }
    assert!(
        failures.is_empty(),
        "GPU and reference disagree:\n{}",
        failures.join("\n")
    );
}
