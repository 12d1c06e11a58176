//! The accuracy targets of docs/accuracy.md, at 321 x 181 (odd, so that the
//! centre row and column of rays have exactly zero direction components), GPU
//! (robust and naive) against the f64 reference fed the same f32-rounded
//! scenes:
//! - every bundled and stress scene: FLIP mean <= 0.01, first-hit mismatch
//!   <= 0.1 % outside silhouette bands, no NaN pixel, every series member
//!   included (the small sphere from 1e6 units, obliquely too; the scene
//!   1e6 from the origin; scaled from 1e-4 to 1e4), but the two members
//!   that show where the limits are;
//! - position independence: the base scene translated by 1e6 along five
//!   directions (and by up to 1e12 along one), scaled from 1e-6 to 1e16
//!   (1e-4 and 1e4 are the targets), and the oblique small sphere
//!   moved 1e6 away, each against the f64 image of the scene before it was
//!   moved (the exact answer, sharing no rounding with the render), with
//!   the same targets; the naive variant (world coordinates, rays from the
//!   eye) fails every one of them;
//! - no acne on the plane lit at 0.01 degrees, and the same image when the
//!   scene is scaled by 1000 or 1/1000;
//! - the naive switch shows the failures the robust code fixes.

mod common;

use std::collections::HashMap;

use raysandbox::gpu::ShaderSource;
use raysandbox::stress::metrics::Comparison;
use raysandbox::stress::{self, Harness, scenes};

const WIDTH: u32 = 321;
const HEIGHT: u32 = 181;

/// Scenes the naive variant must fail (the evidence that the robust code
/// matters), with what gives way.
const NAIVE_FAILS: &[(&str, &str)] = &[
    ("small_sphere_1e2", "b^2 - 4ac cancels"),
    ("small_sphere_1e3", "b^2 - 4ac cancels"),
    ("small_sphere_1e4", "b^2 - 4ac cancels"),
    ("small_sphere_oblique_1e3", "b^2 - 4ac cancels"),
    (
        "ground_sphere_1e5",
        "hit point and offset at the scale of R",
    ),
    ("far_box_1e4", "hit points o + t d 1e4 away, fixed offset"),
    ("box_axis_rays", "0 * inf in the slab test"),
    (
        "camera_straight_up",
        "the fixed offset leaks light and shadow",
    ),
    (
        "scale_1e-3",
        "the fixed offset 1e-3 is as large as the scene",
    ),
    ("scale_1e3", "the fixed offset is lost in the rounding"),
    (
        "scale_1e-4",
        "the fixed offset 1e-3 is larger than the spheres",
    ),
    ("scale_1e4", "the fixed offset is lost in the rounding"),
    ("translate_1e5", "world coordinates 0.008 apart"),
    ("translate_1e6", "world coordinates 0.06 apart"),
    (
        "small_sphere_oblique_1e6",
        "b^2 - 4ac cancels, directions rounded 6e-8 D off",
    ),
];

/// The naive variant must fail every moved copy (scenes::moved) but the
/// unmoved one: world coordinates rounded at 1e6, rays from a far eye, a
/// fixed offset.
const MOVED_NAIVE_FAILS: &str = "world coordinates, rays from the eye, fixed offset";

/// The members beyond the limits measured in docs/accuracy.md: at 1e14 from
/// the origin f64 itself spaces the scene's numbers 0.016 apart (the moved
/// scene is no longer the same scene), and at a scale of 1e-7 the offset's
/// floor (8 ulps of 1/32, 3e-8) is larger than the smallest sphere.
const BEYOND_LIMITS: &[&str] = &["moved_1e14", "scaled_1e-7"];

fn measure_all() -> HashMap<String, (Comparison, Comparison)> {
    let gpu = common::gpu();
    let harness = Harness::new(&gpu, &ShaderSource::embedded()).unwrap_or_else(|e| panic!("{e}"));
    let mut out = HashMap::new();
    for entry in stress::entries(None, true).unwrap_or_else(|e| panic!("{e}")) {
        let m = harness
            .measure_entry(&gpu, &entry, WIDTH, HEIGHT)
            .unwrap_or_else(|e| panic!("{}: {e}", entry.name));
        println!(
            "{:<26} robust FLIP {:.4} id {:.3}% acne {:.3}% NaN {} | naive FLIP {:.4} id {:.3}% NaN {}",
            entry.name,
            m.robust_cmp.flip_mean,
            m.robust_cmp.id_mismatch * 100.0,
            m.robust_cmp.false_shadow * 100.0,
            m.robust_cmp.nan_pixels,
            m.naive_cmp.flip_mean,
            m.naive_cmp.id_mismatch * 100.0,
            m.naive_cmp.nan_pixels
        );
        if !m.robust_cmp.passes() && !BEYOND_LIMITS.contains(&entry.name.as_str()) {
            let dir = std::env::temp_dir();
            m.robust
                .image
                .save(dir.join(format!("{}-robust.png", entry.name)))
                .unwrap();
            m.reference
                .image
                .save(dir.join(format!("{}-reference.png", entry.name)))
                .unwrap();
        }
        out.insert(entry.name, (m.robust_cmp, m.naive_cmp));
    }
    out
}

#[test]
fn every_scene_meets_the_targets_and_naive_shows_the_failures() {
    let results = measure_all();
    let moved = scenes::moved();
    // The targets: translated by 1e6 in five directions, scaled by 1e-4 and
    // 1e4, the oblique small sphere framed from 1e6 units, 1e6 from the
    // origin; all measured against the unmoved scene's f64 image.
    for target in [
        "moved_1e6",
        "base_at_+1e6x",
        "base_at_-1e6y",
        "base_at_+1e6z",
        "base_at_+1e6xyz",
        "scaled_1e-4",
        "scaled_1e4",
        "oblique_1e6_at_-1e6x+1e6y-1e6z",
    ] {
        assert!(
            moved
                .iter()
                .any(|m| m.name == target && m.exact.shape_count() > 0),
            "{target} is measured against the unmoved scene"
        );
    }
    assert!(
        results.len() >= scenes::SCENES.len() + moved.len() + 5,
        "stress, moved and bundled scenes"
    );
    let mut failures = Vec::new();
    for (name, (robust, _)) in &results {
        if robust.nan_pixels > 0 {
            failures.push(format!("{name}: {} NaN pixels", robust.nan_pixels));
        }
        if !BEYOND_LIMITS.contains(&name.as_str()) && !robust.passes() {
            failures.push(format!(
                "{name}: FLIP {:.4} (max 0.01), first hit {:.3}% (max 0.1%)",
                robust.flip_mean,
                robust.id_mismatch * 100.0
            ));
        }
    }
    // The small sphere from 1e2 to 1e6 on an axis and obliquely (covered
    // above); the naive quadratic fails from 1e2 on.
    let naive_fails = NAIVE_FAILS.iter().copied().chain(
        moved
            .iter()
            .filter(|m| m.name != "scaled_1e0")
            .map(|m| (m.name.as_str(), MOVED_NAIVE_FAILS)),
    );
    for (name, why) in naive_fails {
        let (_, naive) = &results[name];
        if naive.passes() {
            failures.push(format!("naive {name} passes, but should fail: {why}"));
        }
    }
    // No acne on the plane lit at 0.01 degrees.
    let (grazing, _) = &results["grazing_light_0.01deg"];
    assert!(
        grazing.lit_pixels > 10_000,
        "{} lit pixels",
        grazing.lit_pixels
    );
    if grazing.false_shadow >= 1e-4 {
        failures.push(format!(
            "grazing_light_0.01deg: {:.4}% of lit pixels in false shadow",
            grazing.false_shadow * 100.0
        ));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn scaled_scenes_render_the_same_images() {
    let gpu = common::gpu();
    let harness = Harness::new(&gpu, &ShaderSource::embedded()).unwrap_or_else(|e| panic!("{e}"));
    let mut failures = Vec::new();
    for name in stress::SCALE_INVARIANCE {
        let scene = scenes::load(name);
        for power in [3, -3] {
            let r = harness
                .invariance(&gpu, name, &scene, power, WIDTH, HEIGHT)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            println!(
                "{name} x 1e{power}: FLIP robust {:.4} naive {:.4}, acne robust {:.4}% naive {:.4}%",
                r.robust_flip,
                r.naive_flip,
                r.robust_false_shadow * 100.0,
                r.naive_false_shadow * 100.0
            );
            if r.robust_flip > 0.005 {
                failures.push(format!(
                    "{name} x 1e{power}: FLIP {:.4} > 0.005",
                    r.robust_flip
                ));
            }
            if r.robust_false_shadow >= 1e-4 {
                failures.push(format!(
                    "{name} x 1e{power}: acne {}",
                    r.robust_false_shadow
                ));
            }
            // The textbook offset of 1e-3 is visibly wrong at 1/1000.
            if power == -3 && r.naive_flip <= 0.005 {
                failures.push(format!(
                    "naive {name} x 1e-3 looks the same (FLIP {:.4})",
                    r.naive_flip
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn stress_command_writes_the_report() {
    common::require_gpu();
    let dir = std::env::temp_dir().join(format!("raysandbox-stress-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_raysandbox"))
        .args(["stress", "--filter", "small_sphere_1e", "--no-bundled"])
        .args(["--width", "41", "--height", "23", "--out"])
        .arg(&dir)
        .output()
        .expect("run raysandbox stress");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("small_sphere_1e4") && stdout.contains("up to 1e6"),
        "{stdout}"
    );
    let csv = std::fs::read_to_string(dir.join("stress.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 2 * 5, "{csv}");
    assert!(csv.starts_with("scene,group,variant,rmse,psnr_db,flip_mean,"));
    let md = std::fs::read_to_string(dir.join("stress.md")).unwrap();
    assert!(
        md.contains("| small_sphere_1e6 |") && md.contains("## Series"),
        "{md}"
    );
    for suffix in [
        "reference",
        "robust",
        "naive",
        "robust-flip",
        "naive-flip",
        "robust-diff",
        "naive-diff",
    ] {
        let path = dir
            .join("images")
            .join(format!("small_sphere_1e3-{suffix}.png"));
        assert_eq!(
            image::image_dimensions(&path).unwrap(),
            (41, 23),
            "{}",
            path.display()
        );
    }
    let panel = dir.join("images/small_sphere_1e3-panel.png");
    assert_eq!(
        image::image_dimensions(&panel).unwrap(),
        (3 * 41 + 8, 2 * 23 + 4)
    );
    std::fs::remove_dir_all(&dir).unwrap();
    // Bad input: an unknown filter is exit status 2.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_raysandbox"))
        .args(["stress", "--filter", "no such scene"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}
