//! The lecture switch `intersections` of `[render]` (docs/rendering-model.md,
//! "Lecture switches") on the GPU and in the reference: both renderers
//! follow it, so the textbook routines' failures that exist in exact
//! arithmetic (a fixed offset larger than the scene's details) show in
//! both pictures alike, while those of f32 arithmetic (the textbook
//! discriminant far from the sphere) show as the difference the error
//! view marks. The budget is tests/gpu_vs_reference.rs's.

mod common;

use image::RgbaImage;
use raysandbox::compare::{ImageDiff, diff_images};
use raysandbox::gpu::{Gpu, render_image};
use raysandbox::reference;
use raysandbox::scene::{Intersections, Scene};
use raysandbox::stress::scenes;

const WIDTH: u32 = 320;
const HEIGHT: u32 = 180;

/// The GPU's picture and the reference's of `scene` with `intersections`
/// (the reference gets the scene rounded to f32, as the GPU's buffers hold
/// it: docs/accuracy.md).
fn pictures(gpu: &Gpu, scene: &Scene, intersections: Intersections) -> (RgbaImage, RgbaImage) {
    let mut scene = scene.clone();
    scene.render.intersections = intersections;
    let on_gpu = render_image(gpu, &scene, WIDTH, HEIGHT, 1).unwrap_or_else(|e| panic!("{e}"));
    let rounded = scenes::round_to_f32(&scene);
    (on_gpu, reference::render_rgba8(&rounded, WIDTH, HEIGHT, 1))
}

/// Within tests/gpu_vs_reference.rs's budget.
fn within_budget(d: &ImageDiff) -> bool {
    d.mean_abs <= 0.5 && d.frac_over_8 <= 0.005
}

fn describe(what: &str, d: &ImageDiff) -> String {
    format!(
        "{what}: mean |d| {:.3}, {:.2} % of pixels off by > 8",
        d.mean_abs,
        d.frac_over_8 * 100.0
    )
}

/// The GPU's and the reference's pictures of the stress scene `name`,
/// robust and textbook, compared (and printed).
struct Differences {
    /// The GPU's robust picture against its textbook one.
    switched: ImageDiff,
    /// The reference's robust picture against its textbook one.
    switched_reference: ImageDiff,
    /// The GPU against the reference, both textbook.
    textbook: ImageDiff,
    /// The GPU against the reference, both robust.
    robust: ImageDiff,
}

fn differences(gpu: &Gpu, name: &str) -> Differences {
    let scene = scenes::load(name);
    let (robust, robust_reference) = pictures(gpu, &scene, Intersections::Robust);
    let (textbook, textbook_reference) = pictures(gpu, &scene, Intersections::Textbook);
    let d = Differences {
        switched: diff_images(&robust, &textbook),
        switched_reference: diff_images(&robust_reference, &textbook_reference),
        textbook: diff_images(&textbook, &textbook_reference),
        robust: diff_images(&robust, &robust_reference),
    };
    println!("{name}:");
    println!("{}", describe("GPU robust against textbook", &d.switched));
    println!(
        "{}",
        describe("reference robust against textbook", &d.switched_reference)
    );
    println!(
        "{}",
        describe("textbook: GPU against reference", &d.textbook)
    );
    println!("{}", describe("robust: GPU against reference", &d.robust));
    assert!(
        within_budget(&d.robust),
        "{}",
        describe("robust", &d.robust)
    );
    d
}

/// `scale_1e-3`: the base scene 1000 times smaller, where the textbook
/// offset of 1e-3 exceeds the glass sphere's radius: refracted rays start
/// beyond it and contact shadows come loose, in f64 as in f32. The GPU's
/// textbook picture differs from its robust one and is the reference's
/// textbook picture.
#[test]
fn textbook_offsets_leak_alike_on_the_gpu_and_in_the_reference() {
    let gpu = common::gpu();
    let d = differences(&gpu, "scale_1e-3");
    assert!(
        d.switched.frac_over_8 > 0.01,
        "{}",
        describe("the switch changed too little", &d.switched)
    );
    assert!(
        within_budget(&d.textbook),
        "{}",
        describe("textbook", &d.textbook)
    );
}

/// `small_sphere_1e3`: a sphere of radius 0.1 seen from 1000 units. The
/// textbook discriminant fails in f32 only: the reference's textbook
/// picture is its robust one, the GPU's is far off, and that difference is
/// what the error view shows.
#[test]
fn the_textbook_discriminant_fails_in_f32_only() {
    let gpu = common::gpu();
    let d = differences(&gpu, "small_sphere_1e3");
    assert!(
        within_budget(&d.switched_reference),
        "{}",
        describe("f64", &d.switched_reference)
    );
    assert!(
        d.textbook.frac_over_8 > 0.01,
        "{}",
        describe("the f32 failure is missing", &d.textbook)
    );
}
