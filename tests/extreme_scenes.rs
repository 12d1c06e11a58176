//! Scenes with extreme but valid values render on the GPU without a device
//! loss, a panic, a hang or a NaN explosion (docs/reliability.md, "Extreme
//! scenes on the GPU"): radii of 1e-30 and 1e30, a million spheres,
//! max_depth 16 between mirrors and glass, exposure 1e30 and the largest a
//! scene may hold. Every scene goes through the same parser and checks as a
//! file; the picture may not hold a pixel the shader marks as non-finite
//! (magenta), and must show something (the scene is not lost to black).

mod common;

use std::fmt::Write as _;

use image::RgbaImage;
use raysandbox::compare::{NAN_MAGENTA, distinct_colors};
use raysandbox::gpu::render_image;
use raysandbox::scene::Scene;

const WIDTH: u32 = 96;
const HEIGHT: u32 = 64;

/// A glass sphere, a mirror sphere and a diffuse cube on a floor, every
/// length multiplied by `scale` (camera, lights and shapes alike, so the
/// picture is the same at any scale that f32 can hold).
fn scaled_scene(scale: f64) -> String {
    let v = |x: f64, y: f64, z: f64| format!("[{:e}, {:e}, {:e}]", x * scale, y * scale, z * scale);
    format!(
        "[render]\nmax_depth = 6\nbackground = [0.5, 0.6, 0.8]\n\
         [camera]\nfrom = {}\nto = {}\nfov = 40\n\
         [[lights]]\nposition = {}\nintensity = 0.9\n\
         [materials.glass]\ncolor = [1, 1, 1]\ntransparency = 0.9\nior = 1.5\n\
         [materials.mirror]\ncolor = [0.9, 0.9, 0.9]\nmirror = 0.8\n\
         [materials.floor]\ncolor = [0.8, 0.8, 0.8]\n\
         checker = {{ color = [0.2, 0.2, 0.2], size = {:e} }}\n\
         [[spheres]]\ncenter = {}\nradius = {:e}\nmaterial = \"glass\"\n\
         [[spheres]]\ncenter = {}\nradius = {:e}\nmaterial = \"mirror\"\n\
         [[cubes]]\ncenter = {}\nsize = {:e}\n\
         [[planes]]\npoint = {}\nnormal = [0, 1, 0]\nmaterial = \"floor\"\n",
        v(0.0, 1.5, 6.0),
        v(0.0, 0.5, 0.0),
        v(-3.0, 6.0, 4.0),
        0.5 * scale,
        v(-0.8, 0.5, 0.0),
        0.5 * scale,
        v(0.8, 0.5, 0.0),
        0.5 * scale,
        v(0.0, 0.3, -1.2),
        0.6 * scale,
        v(0.0, 0.0, 0.0),
    )
}

/// Parses `text` as a scene file, renders it at 1 sample per pixel, and
/// checks the picture: no non-finite pixel, more than one colour.
fn render_checked(name: &str, text: &str) -> RgbaImage {
    let gpu = common::gpu();
    let scene = Scene::from_toml_str(text, None).unwrap_or_else(|e| panic!("{name}: {e}"));
    let image = render_image(&gpu, &scene, WIDTH, HEIGHT, 1)
        .unwrap_or_else(|e| panic!("{name}: the render failed: {e}"));
    let magenta = image.pixels().filter(|p| p.0[..3] == NAN_MAGENTA).count();
    assert_eq!(magenta, 0, "{name}: {magenta} pixels are not finite");
    assert!(
        distinct_colors(&image, 4) > 1,
        "{name}: the picture is one colour"
    );
    image
}

/// Fraction of channels that differ by more than 8 of 255.
fn fraction_off(a: &RgbaImage, b: &RgbaImage) -> f64 {
    let off = a
        .pixels()
        .zip(b.pixels())
        .flat_map(|(p, q)| (0..3).map(move |c| p.0[c].abs_diff(q.0[c]) > 8))
        .filter(|&off| off)
        .count();
    off as f64 / (3 * a.width() * a.height()) as f64
}

#[test]
fn radii_of_1e_minus_30_and_1e30_render_finite_pictures() {
    let plain = render_checked("scale 1", &scaled_scene(1.0));
    let tiny = render_checked("scale 1e-30", &scaled_scene(1e-30));
    let off = fraction_off(&plain, &tiny);
    println!(
        "scale 1e-30: {:.3}% of the channels differ from scale 1",
        100.0 * off
    );
    assert!(off < 0.1, "scale 1e-30: {:.1}% differ", 100.0 * off);
    // The same picture: the floor lies 1e30 to 1e32 away, within the
    // tracer's T_FAR = 1e38 (shaders/intersect.wgsl).
    let huge = render_checked("scale 1e30", &scaled_scene(1e30));
    let off = fraction_off(&plain, &huge);
    println!(
        "scale 1e30: {:.3}% of the channels differ from scale 1",
        100.0 * off
    );
    assert!(off < 0.001, "scale 1e30: {:.3}% differ", 100.0 * off);
}

#[test]
fn a_tiny_and_a_huge_sphere_beside_ordinary_shapes_render_finite_pictures() {
    let mut text = scaled_scene(1.0);
    text.push_str(
        "[[spheres]]\ncenter = [0.3, 1.0, 1.0]\nradius = 1e-30\n\
         [[spheres]]\ncenter = [0, -1e30, -20]\nradius = 1e30\nmaterial = \"mirror\"\n",
    );
    render_checked("radius 1e-30 and 1e30 at scale 1", &text);
}

/// A million spheres: the scene file is written and parsed as a user's
/// would be.
#[test]
fn a_million_spheres_render() {
    const SIDE: usize = 100;
    let mut text = scaled_scene(1.0);
    for i in 0..SIDE * SIDE * SIDE {
        let (x, y, z) = (i % SIDE, i / SIDE % SIDE, i / (SIDE * SIDE));
        let _ = write!(
            text,
            "[[spheres]]\ncenter = [{}, {}, {}]\nradius = 0.004\n",
            -2.0 + 0.04 * x as f64,
            1.5 + 0.04 * y as f64,
            -4.0 - 0.04 * z as f64
        );
    }
    let start = std::time::Instant::now();
    render_checked("a million spheres", &text);
    println!(
        "a million spheres: parsed and rendered in {:?}",
        start.elapsed()
    );
}

/// A closed box of mirrors round three glass spheres, every ray followed to
/// depth 16. The mirrors have a diffuse part: with none, no surface in the
/// box gives off light and the right picture is black everywhere, so "more
/// than one colour" held only where a ray leaked out of the closed box to
/// the background (one pixel of the generic pipeline, which any change in
/// how the compiler rounds could close).
#[test]
fn max_depth_16_between_mirrors_and_glass_renders() {
    let mut text = String::from(
        "[render]\nmax_depth = 16\nmin_weight = 0\nbackground = [0.3, 0.4, 0.6]\n\
         [camera]\nfrom = [0, 0, 3.5]\nto = [0, 0, 0]\nfov = 60\n\
         [[lights]]\nposition = [0, 1.5, 0]\nintensity = 1.0\n\
         [materials.mirror]\ncolor = [1, 1, 1]\nmirror = 1.0\ndiffuse = 0.2\n\
         [materials.glass]\ncolor = [1, 1, 1]\ntransparency = 1.0\nior = 1.5\ndiffuse = 0\n",
    );
    for (point, normal) in [
        ("[0, -2, 0]", "[0, 1, 0]"),
        ("[0, 2, 0]", "[0, -1, 0]"),
        ("[-2, 0, 0]", "[1, 0, 0]"),
        ("[2, 0, 0]", "[-1, 0, 0]"),
        ("[0, 0, -2]", "[0, 0, 1]"),
        ("[0, 0, 4]", "[0, 0, -1]"),
    ] {
        let _ = write!(
            text,
            "[[planes]]\npoint = {point}\nnormal = {normal}\nmaterial = \"mirror\"\n"
        );
    }
    for x in [-1.0, 0.0, 1.0] {
        let _ = write!(
            text,
            "[[spheres]]\ncenter = [{x}, 0, 0]\nradius = 0.45\nmaterial = \"glass\"\n"
        );
    }
    render_checked("max_depth 16", &text);
}

#[test]
fn exposures_up_to_the_largest_a_scene_may_hold_render() {
    let text = scaled_scene(1.0);
    for exposure in ["1e30", "1e38", "1e300", "1.7976931348623157e308", "1e-30"] {
        let text = text.replace("[render]\n", &format!("[render]\nexposure = {exposure}\n"));
        let name = format!("exposure {exposure}");
        let scene = Scene::from_toml_str(&text, None).unwrap_or_else(|e| panic!("{name}: {e}"));
        let gpu = common::gpu();
        let image = render_image(&gpu, &scene, WIDTH, HEIGHT, 1).unwrap();
        let magenta = image.pixels().filter(|p| p.0[..3] == NAN_MAGENTA).count();
        assert_eq!(magenta, 0, "{name}: {magenta} pixels are not finite");
        // Every pixel has some light (the ambient term, the background):
        // white at a huge exposure, black at a tiny one.
        let expected = if exposure == "1e-30" {
            [0, 0, 0]
        } else {
            [255, 255, 255]
        };
        let other = image.pixels().filter(|p| p.0[..3] != expected).count();
        assert_eq!(other, 0, "{name}: {other} pixels are not {expected:?}");
    }
}
