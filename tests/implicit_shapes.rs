//! Tori, implicit surfaces and Julia sets (docs/rendering-model.md,
//! "Implicit surfaces"): the WGSL shader on the GPU against the f64 reference,
//! FLIP within the budgets of docs/accuracy.md (torus and implicit surfaces
//! 0.01, Julia sets 0.02 for their fractal edges), on the bundled scenes and
//! the stress cases: a torus edge-on, from 1e4 units, rays grazing its inner
//! equator, an implicit sphere whose silhouette rays are near double roots,
//! and a Julia set at high zoom; and the Julia set with its epsilon grown to
//! the pixel footprint. Scenes with tori are drawn with every GPU torus
//! method (`TorusMethod`), each held to the budget.

mod common;

use raysandbox::gpu::{OffscreenRenderer, ShaderOptions, ShaderSource};
use raysandbox::reference;
use raysandbox::scene::{NamedOption, Scene, TorusMethod, bundled};
use raysandbox::stress::{metrics, scenes};

const WIDTH: u32 = 320;
const HEIGHT: u32 = 180;

/// The implicit sphere's stress scene: its silhouette, zoomed.
fn tangent_sphere_text() -> &'static str {
    scenes::text("implicit_tangent_sphere").expect("a stress scene")
}

/// `scene` with every Julia set's epsilon grown to the pixel footprint.
fn with_footprint(mut scene: Scene) -> Scene {
    scene.julias.iter_mut().for_each(|j| j.footprint = true);
    scene
}

fn cases() -> Vec<(String, Scene, f64)> {
    let bundled = |name: &str| Scene::from_toml_str(bundled::text(name).unwrap(), None).unwrap();
    vec![
        ("torus".into(), bundled("torus"), 0.01),
        ("implicits".into(), bundled("implicits"), 0.01),
        ("julia".into(), bundled("julia"), 0.02),
        ("torus_edge_on".into(), scenes::load("torus_edge_on"), 0.01),
        (
            "torus_from_far".into(),
            scenes::load("torus_from_far"),
            0.01,
        ),
        (
            "torus_inner_equator".into(),
            scenes::load("torus_inner_equator"),
            0.01,
        ),
        ("julia_zoom".into(), scenes::load("julia_zoom"), 0.02),
        (
            "julia_footprint".into(),
            with_footprint(bundled("julia")),
            0.02,
        ),
        (
            "implicit_tangent_sphere".into(),
            scenes::load("implicit_tangent_sphere"),
            0.01,
        ),
    ]
}

/// The generic pipeline's image of `scene` with the tori solved by `torus`.
fn render_with(gpu: &raysandbox::gpu::Gpu, scene: &Scene, torus: TorusMethod) -> image::RgbaImage {
    let mut options = ShaderOptions::generic(scene);
    options.kinds.tori = torus;
    let source = ShaderSource::embedded();
    let mut renderer = OffscreenRenderer::new(gpu, &source, &options, scene, WIDTH, HEIGHT)
        .unwrap_or_else(|e| panic!("{e}"));
    renderer.render(gpu, 1).unwrap_or_else(|e| panic!("{e}"));
    renderer.read_image(gpu).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn gpu_matches_the_reference_within_the_flip_budgets() {
    let gpu = common::gpu();
    let mut failures = Vec::new();
    println!("{:<40} {:>8} {:>8}", "scene", "FLIP", "budget");
    for (name, scene, budget) in cases() {
        let ref_image = reference::render_rgba8(&scene, WIDTH, HEIGHT, 1);
        let methods = if scene.tori.is_empty() {
            &[TorusMethod::default()][..]
        } else {
            TorusMethod::all()
        };
        for &method in methods {
            let gpu_image = render_with(&gpu, &scene, method);
            let (flip, _) = metrics::flip(&ref_image, &gpu_image);
            let label = if scene.tori.is_empty() {
                name.clone()
            } else {
                format!("{name} ({})", method.name())
            };
            println!("{label:<40} {flip:>8.5} {budget:>8}");
            if flip > budget {
                let dir = std::env::temp_dir();
                let stem = format!("{name}-{}", method.name());
                gpu_image.save(dir.join(format!("{stem}-gpu.png"))).unwrap();
                ref_image
                    .save(dir.join(format!("{name}-reference.png")))
                    .unwrap();
                failures.push(format!("{label}: FLIP {flip:.5} > {budget}"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The implicit sphere is the sphere: the reference's root finding (256
/// samples, bisection to 1e-6 of the segment) against the closed-form
/// sphere, an independent answer, on the near-tangent view.
#[test]
fn the_implicit_sphere_matches_the_closed_form_sphere() {
    let implicit = scenes::load("implicit_tangent_sphere");
    let closed_form = Scene::from_toml_str(
        &tangent_sphere_text().replace(
            "[[implicits]]\nf = \"x^2 + y^2 + z^2 - 1\"\nbounds = [[-1.2, -1.2, -1.2], [1.2, 1.2, 1.2]]",
            "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1",
        ),
        None,
    )
    .unwrap();
    assert!(closed_form.implicits.is_empty() && closed_form.spheres.len() == 1);
    let a = reference::render_rgba8(&implicit, WIDTH, HEIGHT, 1);
    let b = reference::render_rgba8(&closed_form, WIDTH, HEIGHT, 1);
    let (flip, _) = metrics::flip(&b, &a);
    println!("implicit sphere against the sphere: FLIP {flip:.5}");
    assert!(flip <= 0.01, "FLIP {flip}");
}
