//! Tests of loading, validation and saving scenes: one or more per rule of
//! the rendering model, the defaults, the error format, and round trips.

use std::path::{Path, PathBuf};

use glam::DVec3;

use super::test_scenes::FULL;
use super::{AxisScale, Intersections, Material, Placement, Render, Scale, Scene, SceneError};

/// A valid camera, for tests about other sections. Three lines long.
const CAMERA: &str = "[camera]\nfrom = [0, 1, 5]\nto = [0, 0, 0]\n";

/// Loads `text` as `test.toml`, with [`CAMERA`] after it unless `text` has
/// its own camera. (After, so that lines keep their numbers and top-level
/// keys stay at the top level.)
fn load(text: &str) -> Result<Scene, SceneError> {
    let text = if text.contains("[camera]") {
        text.to_owned()
    } else {
        format!("{text}{CAMERA}")
    };
    Scene::from_toml_str(&text, Some(Path::new("test.toml")))
}

#[track_caller]
fn loads(text: &str) -> Scene {
    load(text).unwrap_or_else(|e| panic!("should load, but: {e}\n{text}"))
}

/// Asserts that `text` fails with exactly `message` about `key`, at a line.
#[track_caller]
fn rejects(text: &str, key: &str, message: &str) -> SceneError {
    let e = rejects_with(text, key, message);
    assert_eq!(e.message, message, "{e}");
    e
}

/// Asserts that `text` fails with a message containing `part` about `key`,
/// at a line.
#[track_caller]
fn rejects_with(text: &str, key: &str, part: &str) -> SceneError {
    let e = load(text).expect_err(&format!("should fail:\n{text}"));
    assert_eq!(e.key.as_deref(), Some(key), "{e}");
    assert!(e.message.contains(part), "{e:?} lacks {part:?}");
    assert!(e.line.is_some(), "no line in {e}");
    assert_eq!(e.file.as_deref(), Some(Path::new("test.toml")));
    e
}

/// Numbers that are a single value, as (table text without the key, key,
/// key path): every such field of the format.
const SCALARS: &[(&str, &str, &str)] = &[
    ("[render]\n", "min_weight", "render.min_weight"),
    ("[render]\n", "exposure", "render.exposure"),
    (
        "[camera]\nfrom = [0, 1, 5]\nto = [0, 0, 0]\n",
        "fov",
        "camera.fov",
    ),
    (
        "[camera]\nfrom = [0, 1, 5]\nto = [0, 0, 0]\n",
        "aperture",
        "camera.aperture",
    ),
    (
        "[camera]\nfrom = [0, 1, 5]\nto = [0, 0, 0]\n",
        "focus_distance",
        "camera.focus_distance",
    ),
    (
        "[[lights]]\nposition = [0, 5, 0]\n",
        "intensity",
        "lights[0].intensity",
    ),
    ("[materials.m]\n", "diffuse", "materials.m.diffuse"),
    ("[materials.m]\n", "specular", "materials.m.specular"),
    ("[materials.m]\n", "shininess", "materials.m.shininess"),
    ("[materials.m]\n", "mirror", "materials.m.mirror"),
    (
        "[materials.m]\n",
        "transparency",
        "materials.m.transparency",
    ),
    ("[materials.m]\n", "ior", "materials.m.ior"),
    (
        "[materials.m.checker]\ncolor = [0, 0, 0]\n",
        "size",
        "materials.m.checker.size",
    ),
    (
        "[[spheres]]\ncenter = [0, 0, 0]\n",
        "radius",
        "spheres[0].radius",
    ),
    ("[[cubes]]\ncenter = [0, 0, 0]\n", "size", "cubes[0].size"),
];

/// Numbers that are vectors, like [`SCALARS`].
const VECTORS: &[(&str, &str, &str)] = &[
    ("[render]\n", "background", "render.background"),
    ("[render]\n", "ambient", "render.ambient"),
    ("[camera]\nto = [0, 0, 0]\n", "from", "camera.from"),
    ("[camera]\nfrom = [0, 1, 5]\n", "to", "camera.to"),
    (
        "[camera]\nfrom = [0, 1, 5]\nto = [0, 0, 0]\n",
        "up",
        "camera.up",
    ),
    ("[[lights]]\n", "position", "lights[0].position"),
    (
        "[[lights]]\nposition = [0, 5, 0]\n",
        "color",
        "lights[0].color",
    ),
    ("[materials.m]\n", "color", "materials.m.color"),
    (
        "[materials.m.checker]\nsize = 1\n",
        "color",
        "materials.m.checker.color",
    ),
    ("[[spheres]]\nradius = 1\n", "center", "spheres[0].center"),
    (
        "[[planes]]\nnormal = [0, 1, 0]\n",
        "point",
        "planes[0].point",
    ),
    (
        "[[planes]]\npoint = [0, 0, 0]\n",
        "normal",
        "planes[0].normal",
    ),
    ("[[cubes]]\nsize = 1\n", "center", "cubes[0].center"),
    ("[[cubes]]\ncenter = [0, 0, 0]\n", "size", "cubes[0].size"),
    (
        "[[cubes]]\ncenter = [0, 0, 0]\nsize = 1\n",
        "rotation",
        "cubes[0].rotation",
    ),
];

/// The entry of `table` for `key`.
fn case<'a>(table: &'a [(&'a str, &'a str, &'a str)], key: &str) -> (&'a str, &'a str) {
    let (text, field, _) = table
        .iter()
        .find(|(_, _, path)| *path == key)
        .unwrap_or_else(|| panic!("no case for {key}"));
    (text, field)
}

/// `key = value` written into the table of the case for `key`.
fn scalar(key: &str, value: &str) -> String {
    let (text, field) = case(SCALARS, key);
    format!("{text}{field} = {value}\n")
}

fn vector(key: &str, value: &str) -> String {
    let (text, field) = case(VECTORS, key);
    format!("{text}{field} = {value}\n")
}

// ---------------------------------------------------------------- numbers

#[test]
fn every_scalar_must_be_finite() {
    for (_, _, key) in SCALARS {
        for value in ["nan", "inf", "-inf", "+nan"] {
            let got = value.trim_start_matches('+');
            rejects(
                &scalar(key, value),
                key,
                &format!("must be finite, got {got}"),
            );
        }
    }
}

#[test]
fn every_vector_component_must_be_finite() {
    for (_, _, key) in VECTORS {
        rejects(
            &vector(key, "[1, nan, 1]"),
            &format!("{key}[1]"),
            "must be finite, got nan",
        );
        rejects(
            &vector(key, "[1, 1, inf]"),
            &format!("{key}[2]"),
            "must be finite, got inf",
        );
        rejects(
            &vector(key, "[-inf, 1, 1]"),
            &format!("{key}[0]"),
            "must be finite, got -inf",
        );
    }
}

#[test]
fn numbers_may_be_written_as_integers() {
    let scene = loads(
        "[render]\nmin_weight = 0\nexposure = 2\nbackground = [0, 1, 0]\n\
         [[spheres]]\ncenter = [1, 2, 3]\nradius = 1\n\
         [[cubes]]\ncenter = [0, 0, 0]\nsize = 2\nrotation = [0, 90, 0]\n\
         [materials.m]\nshininess = 10\nior = 2\nchecker = { color = [0, 0, 0], size = 3 }\n",
    );
    assert_eq!(scene.spheres[0].radius, 1.0);
    assert_eq!(scene.spheres[0].center, DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(scene.cubes[0].placement.scale, AxisScale::Uniform(2.0));
    assert_eq!(scene.render.exposure, 2.0);
    assert_eq!(
        scene.materials["m"].checker.as_ref().map(|c| c.size),
        Some(3.0)
    );
    assert_eq!(scene.camera.from, DVec3::new(0.0, 1.0, 5.0));
}

#[test]
fn numbers_must_be_numbers() {
    rejects_with(
        &scalar("camera.fov", "\"45\""),
        "camera.fov",
        "expected a number",
    );
    rejects_with(
        &vector("camera.up", "[0, \"1\", 0]"),
        "camera.up[1]",
        "expected a number",
    );
    rejects_with(
        &vector("camera.up", "true"),
        "camera.up",
        "expected an array of 3 numbers",
    );
}

#[test]
fn vectors_must_have_three_numbers() {
    rejects(
        &vector("camera.up", "[0, 1, 0, 0]"),
        "camera.up",
        "must be an array of 3 numbers, got [0, 1, 0, 0]",
    );
    rejects_with(
        &vector("lights[0].color", "[1, 1]"),
        "lights[0].color",
        "invalid length 2",
    );
    rejects(
        &vector("render.ambient", "[0.1, 0.1, 0.1, 0.1]"),
        "render.ambient",
        "must be an array of 3 numbers, got [0.1, 0.1, 0.1, 0.1]",
    );
}

/// A Julia set's `c` is a quaternion of four numbers (its kind says so,
/// `Shape::NOT_VECTORS`); its other arrays, and a `c` of 3, are not.
#[test]
fn only_the_keys_a_kind_names_may_hold_other_than_three_numbers() {
    let julia = "[[julias]]\nc = [0.1, 0.2, 0.3, 0.4]\n";
    assert_eq!(loads(julia).julias[0].c, [0.1, 0.2, 0.3, 0.4]);
    rejects(
        &format!("{julia}translate = [0, 0, 0, 0]\n"),
        "julias[0].translate",
        "must be an array of 3 numbers, got [0, 0, 0, 0]",
    );
    rejects(
        "[[spheres]]\ncenter = [0, 0, 0, 1]\nradius = 1\n",
        "spheres[0].center",
        "must be an array of 3 numbers, got [0, 0, 0, 1]",
    );
    rejects_with(
        "[[julias]]\nc = [0.1, 0.2, 0.3]\n",
        "julias[0].c",
        "invalid length 3",
    );
}

#[test]
fn integers_beyond_64_bits_are_rejected() {
    rejects_with(
        &scalar("spheres[0].radius", "99999999999999999999"),
        "spheres[0].radius",
        "beyond the 64-bit range",
    );
}

#[test]
fn floats_beyond_f64_are_rejected() {
    rejects_with(&scalar("camera.fov", "1e999"), "camera.fov", "overflow");
}

// ---------------------------------------------------------------- ranges

#[test]
fn colours_must_not_be_negative() {
    for key in [
        "render.background",
        "render.ambient",
        "lights[0].color",
        "materials.m.color",
        "materials.m.checker.color",
    ] {
        let text = vector(key, "[0.5, 0.5, -0.5]");
        rejects(&text, &format!("{key}[2]"), "must be >= 0, got -0.5");
        loads(&vector(key, "[0, 0, 0]"));
    }
}

#[test]
fn weights_must_not_be_negative() {
    for key in [
        "render.min_weight",
        "camera.aperture",
        "lights[0].intensity",
        "materials.m.diffuse",
        "materials.m.specular",
        "materials.m.mirror",
        "materials.m.transparency",
    ] {
        rejects(&scalar(key, "-1"), key, "must be >= 0, got -1");
        rejects(&scalar(key, "-0.25"), key, "must be >= 0, got -0.25");
        loads(&scalar(key, "0"));
    }
}

#[test]
fn sizes_and_radii_must_be_positive() {
    for key in [
        "render.exposure",
        "camera.focus_distance",
        "materials.m.shininess",
        "materials.m.ior",
        "materials.m.checker.size",
        "spheres[0].radius",
        "cubes[0].size",
    ] {
        rejects(&scalar(key, "0"), key, "must be > 0, got 0");
        rejects(&scalar(key, "-1"), key, "must be > 0, got -1");
        rejects(&scalar(key, "-0.0"), key, "must be > 0, got -0");
        loads(&scalar(key, "1e-9"));
    }
}

#[test]
fn each_edge_of_a_box_must_be_positive() {
    let text = vector("cubes[0].size", "[1, 2, 0]");
    rejects(&text, "cubes[0].size[2]", "must be > 0, got 0");
    let text = vector("cubes[0].size", "[-1, 2, 3]");
    rejects(&text, "cubes[0].size[0]", "must be > 0, got -1");
}

#[test]
fn cube_size_must_be_a_number_or_three() {
    let want = "must be a number or an array of 3 numbers, got ";
    rejects(
        &scalar("cubes[0].size", "[1, 2]"),
        "cubes[0].size",
        &format!("{want}[1, 2]"),
    );
    rejects(
        &scalar("cubes[0].size", "\"big\""),
        "cubes[0].size",
        &format!("{want}\"big\""),
    );
    rejects(
        &scalar("cubes[0].size", "[1, 2, 3, 4]"),
        "cubes[0].size",
        &format!("{want}[1, 2, 3, 4]"),
    );
}

#[test]
fn max_depth_must_be_0_to_16() {
    let max_depth = |value: &str| format!("[render]\nmax_depth = {value}\n");
    assert_eq!(loads(&max_depth("0")).render.max_depth, 0);
    assert_eq!(loads(&max_depth("16")).render.max_depth, 16);
    let key = "render.max_depth";
    rejects(
        &max_depth("17"),
        key,
        "must be an integer in 0..=16, got 17",
    );
    rejects(
        &max_depth("-1"),
        key,
        "must be an integer in 0..=16, got -1",
    );
    rejects(
        &max_depth("4294967296"),
        key,
        "must be an integer in 0..=16, got 4294967296",
    );
    rejects(
        &max_depth("true"),
        key,
        "must be an integer in 0..=16, got true",
    );
}

#[test]
fn max_depth_must_not_be_a_float() {
    let e = rejects(
        "[render]\nmax_depth = 5.0\n",
        "render.max_depth",
        "must be an integer in 0..=16 (no decimal point), got 5.0",
    );
    assert_eq!(e.line, Some(2));
}

// ---------------------------------------------------------------- camera

#[test]
fn camera_from_and_to_must_differ() {
    rejects(
        "[camera]\nfrom = [0, 1, 0]\nto = [0, 1.0, 0]\n",
        "camera.to",
        "must differ from camera.from, both are [0, 1, 0]",
    );
}

#[test]
fn camera_from_and_to_must_give_a_direction_f64_can_compute() {
    rejects_with(
        "[camera]\nfrom = [0, 0, 1e-300]\nto = [0, 0, 0]\n",
        "camera.to",
        "too close to or too far from camera.from",
    );
    rejects_with(
        "[camera]\nfrom = [0, 0, 1e300]\nto = [0, 0, -1e300]\n",
        "camera.to",
        "|from - to| = inf",
    );
}

#[test]
fn camera_up_must_be_non_zero() {
    rejects(
        &vector("camera.up", "[0, 0, 0]"),
        "camera.up",
        "must be non-zero, got [0, 0, 0]",
    );
    rejects_with(
        &vector("camera.up", "[0, 1e-200, 0]"),
        "camera.up",
        "too short",
    );
}

#[test]
fn camera_up_may_be_parallel_to_the_view() {
    let scene = loads("[camera]\nfrom = [0, 5, 0]\nto = [0, 0, 0]\nup = [0, 1, 0]\n");
    assert_eq!(scene.camera.up, DVec3::Y);
}

#[test]
fn camera_fov_must_be_between_0_and_180() {
    for bad in ["0", "180", "-5", "360"] {
        let got = bad.to_owned();
        rejects(
            &scalar("camera.fov", bad),
            "camera.fov",
            &format!("must be > 0 and < 180, got {got}"),
        );
    }
    for good in ["0.1", "179.9", "90"] {
        loads(&scalar("camera.fov", good));
    }
}

// ---------------------------------------------------------------- shapes

#[test]
fn plane_normal_must_be_non_zero() {
    rejects(
        &vector("planes[0].normal", "[0, 0, 0]"),
        "planes[0].normal",
        "must be non-zero, got [0, 0, 0]",
    );
}

#[test]
fn plane_normal_is_normalised_on_load() {
    let scene = loads(&vector("planes[0].normal", "[3, 0, -4]"));
    let error = scene.planes[0].normal - DVec3::new(0.6, 0.0, -0.8);
    assert!(
        error.abs().max_element() < 1e-15,
        "{}",
        scene.planes[0].normal
    );
    let scene = loads(&vector("planes[0].normal", "[0, 1e-100, 0]"));
    assert_eq!(scene.planes[0].normal, DVec3::Y);
}

#[test]
fn normalising_a_unit_normal_keeps_it_bit_for_bit() {
    let text = vector("planes[0].normal", "[1, 1, 1]");
    let once = loads(&text);
    let twice = loads(&once.to_toml_string());
    assert_eq!(once.planes[0].normal, twice.planes[0].normal);
    assert!((once.planes[0].normal.length() - 1.0).abs() < 1e-15);
}

#[test]
fn shape_materials_must_exist() {
    let materials = "[materials.glass]\n[materials.floor]\n";
    let shapes = [
        (
            "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n",
            "spheres[0].material",
        ),
        (
            "[[planes]]\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\n",
            "planes[0].material",
        ),
        (
            "[[cubes]]\ncenter = [0, 0, 0]\nsize = 1\n",
            "cubes[0].material",
        ),
    ];
    for (shape, key) in shapes {
        let text = format!("{materials}{shape}material = \"glas\"\n");
        rejects(
            &text,
            key,
            r#"no material named "glas" (defined: glass, floor)"#,
        );
        let text = format!("{shape}material = \"glass\"\n");
        rejects(
            &text,
            key,
            r#"no material named "glass" (no materials defined)"#,
        );
        loads(&format!("{materials}{shape}material = \"floor\"\n"));
    }
}

#[test]
fn errors_name_the_right_array_element() {
    let text = "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n\
                [[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n\
                [[spheres]]\ncenter = [0, 0, 0]\nradius = -1\n";
    let e = rejects(text, "spheres[2].radius", "must be > 0, got -1");
    assert_eq!(e.line, Some(9));
    assert_eq!(
        e.to_string(),
        "test.toml:9: spheres[2].radius: must be > 0, got -1"
    );
}

#[test]
fn quoted_material_names_are_quoted_in_key_paths() {
    rejects(
        "[materials.\"my glass\"]\nior = 0\n",
        "materials.\"my glass\".ior",
        "must be > 0, got 0",
    );
}

#[test]
fn inline_tables_and_arrays_of_tables_are_located() {
    let text =
        "spheres = [{ center = [0, 0, 0], radius = 1 },\n{ center = [0, 0, 0], radius = 0 }]\n";
    let e = rejects(text, "spheres[1].radius", "must be > 0, got 0");
    assert_eq!(e.line, Some(2));
    let text = "[materials]\nm = { checker = { color = [0, 0, 0], size = -2 } }\n";
    let e = rejects(text, "materials.m.checker.size", "must be > 0, got -2");
    assert_eq!(e.line, Some(2));
}

// ---------------------------------------------------------------- keys

#[test]
fn unknown_top_level_key_is_named_with_its_line() {
    let e = rejects_with(
        "\nbackground = [1, 1, 1]\n",
        "background",
        "unknown key `background`",
    );
    assert_eq!(e.line, Some(2));
    assert!(
        e.message.contains("expected one of `render`, `camera`"),
        "{e}"
    );
}

#[test]
fn unknown_nested_keys_are_named_with_their_line() {
    let e = rejects_with(
        "[camera]\nfrom = [0, 1, 5]\nto = [0, 0, 0]\nfocus = 3\n",
        "camera.focus",
        "unknown key `focus`",
    );
    assert_eq!(e.line, Some(4));
    let text = "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n\
                [[spheres]]\ncenter = [0, 0, 0]\nradus = 1\n";
    let e = rejects_with(text, "spheres[1].radus", "unknown key `radus`");
    assert_eq!(e.line, Some(6));
    let text = "[materials.m]\nchecker = { color = [0, 0, 0], size = 1, offset = 2 }\n";
    let e = rejects_with(text, "materials.m.checker.offset", "unknown key `offset`");
    assert_eq!((e.line, e.column), (Some(2), Some(42)));
    // `[render]` is read flattened too (the shared keys beside each
    // kind's): the key, its line, and the keys it has, a kind's among them.
    let e = rejects_with(
        "[render]\nmax_depth = 2\ngamma = 2.2\n",
        "render.gamma",
        "unknown key `gamma`, expected one of `max_depth`",
    );
    assert_eq!(e.line, Some(3));
    assert!(e.message.contains("`intersections`, `triangles`"), "{e}");
    rejects_with("[camera.lens]\n", "camera.lens", "unknown key `lens`");
}

/// A placement is read flattened into its shape, where serde no longer
/// knows where its keys are: the error still names the key and its line.
#[test]
fn wrong_and_unknown_placement_keys_are_named_with_their_line() {
    let torus = "[[tori]]\nmajor_radius = 1\nminor_radius = 0.5\n";
    let e = rejects_with(
        &format!("{torus}scale = \"big\"\n"),
        "tori[0].scale",
        "invalid type: string \"big\", expected a number",
    );
    assert_eq!(e.line, Some(4));
    let e = rejects_with(
        &format!("{torus}rotation = [1, 2]\n"),
        "tori[0].rotation",
        "invalid length 2, expected an array of 3 numbers",
    );
    assert_eq!(e.line, Some(4));
    let text = "[[meshes]]\npositions = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n\
                triangles = [[0, 1, 2]]\nscale = true\n";
    let e = rejects(
        text,
        "meshes[0].scale",
        "must be a number or an array of 3 numbers, got true",
    );
    assert_eq!(e.line, Some(4));
    let e = rejects(
        "[[julias]]\nc = [0, 0, 0, 0]\nscael = 2\n",
        "julias[0].scael",
        "unknown key `scael`, expected one of `c`, `slice`, `iterations`, `epsilon`, \
         `footprint`, `translate`, `scale`, `rotation`, `material`",
    );
    assert_eq!(e.line, Some(3));
    for (text, key) in [
        ("tori = [1]\n", "tori[0]"),
        ("meshes = [[]]\n", "meshes[0]"),
    ] {
        rejects_with(text, key, "expected a table");
    }
}

#[test]
fn missing_camera_is_named() {
    for text in ["", "# only a comment\n", "[render]\nmax_depth = 3\n"] {
        let e = Scene::from_toml_str(text, None).expect_err(text);
        assert_eq!(e.key.as_deref(), Some("camera"), "{e}");
        assert!(e.message.contains("[camera] is missing"), "{e}");
        assert_eq!(e.line, None);
    }
    let e = Scene::from_toml_str("", None).expect_err("empty");
    assert_eq!(
        e.to_string(),
        "camera: required table [camera] is missing (the scene is empty)"
    );
}

#[test]
fn missing_required_keys_are_named() {
    rejects(
        "[camera]\nfrom = [0, 1, 5]\n",
        "camera.to",
        "required key is missing",
    );
    let text = "[[spheres]]\ncenter = [0, 0, 0]\n";
    let e = rejects(text, "spheres[0].radius", "required key is missing");
    assert_eq!(e.line, Some(1));
    rejects(
        "[[planes]]\npoint = [0, 0, 0]\n",
        "planes[0].normal",
        "required key is missing",
    );
    rejects(
        "[[cubes]]\ncenter = [0, 0, 0]\n",
        "cubes[0].size",
        "required key is missing",
    );
    rejects(
        "[[lights]]\ncolor = [1, 1, 1]\n",
        "lights[0].position",
        "required key is missing",
    );
    rejects(
        "[materials.m]\nchecker = { color = [0, 0, 0] }\n",
        "materials.m.checker.size",
        "required key is missing",
    );
}

#[test]
fn wrong_table_types_are_reported_in_toml_words() {
    rejects_with("lights = 3\n", "lights", "expected an array");
    rejects_with("[materials]\nm = 3\n", "materials.m", "expected a table");
}

// ---------------------------------------------------------------- syntax

#[test]
fn syntax_errors_have_line_and_column() {
    let e = Scene::from_toml_str("[camera]\nfrom = [0, 1, 5]\nto = [0, 0 0]\n", None)
        .expect_err("syntax");
    assert_eq!(
        (e.line, e.column, e.key.as_deref()),
        (Some(3), Some(10), None),
        "{e}"
    );
    assert!(e.to_string().starts_with("<scene>:3:10: "), "{e}");
}

#[test]
fn duplicate_keys_are_named() {
    let e = load("[camera]\nfrom = [0, 1, 5]\nto = [0, 0, 0]\nfov = 40\nfov = 50\n")
        .expect_err("duplicate");
    assert_eq!(e.line, Some(5));
    assert_eq!(e.message, "duplicate key `fov`");
}

#[test]
fn columns_count_characters_not_bytes() {
    let e = load("[materials.\"grün\"]\nior = \"é\" 1\n").expect_err("syntax");
    assert_eq!((e.line, e.column), (Some(2), Some(11)), "{e}");
}

#[test]
fn no_input_makes_the_loader_panic() {
    // Every prefix of a valid scene: unfinished tables, arrays and strings.
    for end in 0..=FULL.len() {
        let _ = Scene::from_toml_str(&FULL[..end], None);
    }
    for text in [
        "\u{feff}",
        "\0",
        "[",
        "[[",
        "a.b.c.d = 1",
        "cubes = [[]]",
        "[camera]\nfrom = {}",
    ] {
        let _ = Scene::from_toml_str(text, None);
    }
}

// ---------------------------------------------------------------- defaults

#[test]
fn render_defaults_follow_the_spec() {
    // docs/scene-format.md's defaults, written out in the file's own words.
    let spec = loads(
        "[render]\nmax_depth = 5\nmin_weight = 0\nbackground = [0, 0, 0]\n\
         ambient = [0.1, 0.1, 0.1]\nexposure = 1\n\
         shadows = true\nreflection = true\nrefraction = true\n\
         intersections = \"robust\"\n",
    );
    assert_eq!(loads("").render, spec.render);
    assert_eq!(Render::default(), spec.render);
    assert_eq!(loads("[render]\nexposure = 2\n").render.max_depth, 5);
}

#[test]
fn lecture_switches_load_and_only_an_off_one_is_written() {
    let scene = loads("[render]\nshadows = false\nrefraction = false\n");
    let r = &scene.render;
    assert_eq!(
        (r.shadows, r.reflection, r.refraction),
        (false, true, false)
    );
    let written = scene.to_toml_string();
    assert!(written.contains("shadows = false") && written.contains("refraction = false"));
    assert!(!written.contains("reflection"), "{written}");
    assert_eq!(loads(&written).render, scene.render);
}

/// A named lecture switch of `[render]` (docs/scene-format.md): `key =
/// value` is written and read back the same, `key = default` is not
/// written, a name it lacks is refused at its key with the names it has.
fn named_switch_round_trips(key: &str, value: &str, default: &str, a_name: &str) -> Scene {
    let scene = loads(&format!("[render]\n{key} = \"{value}\"\n"));
    let written = scene.to_toml_string();
    assert!(
        written.contains(&format!("{key} = \"{value}\"")),
        "{written}"
    );
    assert_eq!(loads(&written).render, scene.render);
    let unwritten = loads(&format!("[render]\n{key} = \"{default}\"\n")).to_toml_string();
    assert!(!unwritten.contains(&format!("{key} =")), "{unwritten}");
    rejects_with(
        &format!("[render]\n{key} = \"naive\"\n"),
        &format!("render.{key}"),
        &format!("`{a_name}`"),
    );
    scene
}

#[test]
fn a_triangle_test_round_trips_and_a_bad_name_is_refused() {
    let scene = named_switch_round_trips("triangles", "moller-trumbore", "watertight", "cramer");
    assert_eq!(
        scene.render.meshes.triangles,
        super::TriangleTest::MollerTrumbore
    );
}

#[test]
fn textbook_intersections_round_trip_and_a_bad_name_is_refused() {
    let scene = named_switch_round_trips("intersections", "textbook", "robust", "textbook");
    assert_eq!(scene.render.intersections, Intersections::Textbook);
}

#[test]
fn camera_defaults_follow_the_spec() {
    let camera = loads("[camera]\nfrom = [0, 3, 4]\nto = [0, 0, 0]\n").camera;
    assert_eq!(camera.up, DVec3::Y);
    assert_eq!(camera.fov, 45.0);
    assert_eq!(camera.aperture, 0.0);
    assert_eq!(camera.focus_distance, None);
    assert_eq!(camera.focus_distance(), 5.0);
    let camera = loads(&scalar("camera.focus_distance", "2")).camera;
    assert_eq!(camera.focus_distance(), 2.0);
}

#[test]
fn light_defaults_follow_the_spec() {
    let light = &loads("[[lights]]\nposition = [1, 2, 3]\n").lights[0];
    assert_eq!(light.color, DVec3::ONE);
    assert_eq!(light.intensity, 1.0);
}

#[test]
fn material_defaults_follow_the_spec() {
    let scene = loads("[materials.m]\n");
    // docs/scene-format.md's defaults, written out in the file's own words.
    let spec = loads(
        "[materials.m]\ncolor = [0.8, 0.8, 0.8]\ndiffuse = 1\nspecular = 0\n\
         shininess = 32\nmirror = 0\ntransparency = 0\nior = 1.5\n",
    );
    let want = spec.materials["m"].clone();
    assert_eq!(want.checker, None);
    assert_eq!(scene.materials["m"], want);
    assert_eq!(Material::default(), want);
    let scene = loads("[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n");
    assert_eq!(scene.spheres[0].material, None);
    assert_eq!(scene.material(None), &want);
}

#[test]
fn cube_rotation_defaults_to_none() {
    let cube = &loads("[[cubes]]\ncenter = [0, 0, 0]\nsize = [1, 2, 3]\n").cubes[0];
    assert_eq!(cube.placement.rotation, DVec3::ZERO);
    assert_eq!(
        cube.placement.scale,
        AxisScale::PerAxis(DVec3::new(1.0, 2.0, 3.0))
    );
}

#[test]
fn optional_sections_may_be_missing() {
    let scene = loads("");
    assert_eq!(scene.shape_count(), 0);
    assert!(scene.lights.is_empty() && scene.materials.is_empty());
}

// ---------------------------------------------------------------- order

#[test]
fn materials_keep_file_order() {
    let scene = loads(FULL);
    let names: Vec<&str> = scene.materials.keys().map(String::as_str).collect();
    assert_eq!(names, ["glass", "floor", "brushed steel"]);
    assert_eq!(scene.material_slot(Some("floor")), 2);
    let scene = loads("[materials]\nz = {}\na = {}\nm.ior = 2\n");
    let names: Vec<&str> = scene.materials.keys().map(String::as_str).collect();
    assert_eq!(names, ["z", "a", "m"]);
}

// ---------------------------------------------------------------- messages

#[test]
fn display_leaves_out_what_is_unknown() {
    let e = rejects(
        "[render]\nexposure = 0\n",
        "render.exposure",
        "must be > 0, got 0",
    );
    assert_eq!(
        e.to_string(),
        "test.toml:2: render.exposure: must be > 0, got 0"
    );
    let e = Scene::from_toml_str("[render]\nexposure = 0\n", None).expect_err("camera");
    assert_eq!(e.to_string(), "camera: required table [camera] is missing");
    let text = format!("{CAMERA}[render]\nexposure = -0.5\n");
    let e = Scene::from_toml_str(&text, None).expect_err("exposure");
    assert_eq!(
        e.to_string(),
        "<scene>:5: render.exposure: must be > 0, got -0.5"
    );
}

#[test]
fn values_are_printed_plainly() {
    rejects(
        &scalar("spheres[0].radius", "-1e300"),
        "spheres[0].radius",
        "must be > 0, got -1e300",
    );
    rejects(
        &scalar("spheres[0].radius", "-1e-9"),
        "spheres[0].radius",
        "must be > 0, got -1e-9",
    );
    rejects(
        &scalar("spheres[0].radius", "-12.5"),
        "spheres[0].radius",
        "must be > 0, got -12.5",
    );
}

#[test]
fn io_errors_name_the_file() {
    let path = Path::new("no/such/scene.toml");
    let e = Scene::load(path).expect_err("missing file");
    assert_eq!(e.file.as_deref(), Some(path));
    assert!(
        e.to_string()
            .starts_with("no/such/scene.toml: cannot read the file: "),
        "{e}"
    );
}

// ---------------------------------------------------------------- round trip

#[track_caller]
fn assert_round_trip(scene: &Scene) {
    assert_round_trip_at(scene, None);
}

/// The round trip of a scene saved where it was loaded from (mesh files
/// are relative to it).
#[track_caller]
fn assert_round_trip_at(scene: &Scene, origin: Option<&Path>) {
    let text = scene.to_toml_string();
    let back = Scene::from_toml_str(&text, origin).unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert_eq!(&back, scene, "{text}");
}

#[test]
fn every_feature_round_trips() {
    let scene = loads(FULL);
    assert_eq!(scene.cubes[0].placement.scale, AxisScale::Uniform(1.0));
    assert_eq!(
        scene.cubes[1].placement.scale,
        AxisScale::PerAxis(DVec3::new(1.0, 2.0, 3.0))
    );
    assert!(scene.materials["floor"].checker.is_some());
    assert_eq!(scene.camera.focus_distance, Some(6.0));
    assert_round_trip(&scene);
}

/// Every `*.toml` under `dir`, at any depth; none if `dir` does not exist.
fn toml_files(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut files = Vec::new();
    for path in entries.map(|entry| entry.expect("readable directory").path()) {
        if path.is_dir() {
            files.extend(toml_files(&path));
        } else if path.extension().is_some_and(|ext| ext == "toml") {
            files.push(path);
        }
    }
    files
}

#[test]
fn every_asset_scene_loads_and_round_trips() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    for path in toml_files(&dir) {
        let scene = Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_round_trip_at(&scene, Some(&path));
    }
}

/// The placement a placed shape's table writes, read key by key from the
/// TOML with the defaults of docs/scene-format.md: what the scene must hold
/// however [`Placement`] is read (flattened into the shape).
fn written_placement<S: Scale + serde::de::DeserializeOwned>(table: &toml::Table) -> Placement<S> {
    fn key_or<T: serde::de::DeserializeOwned>(table: &toml::Table, key: &str, default: T) -> T {
        table.get(key).map_or(default, |value| {
            value.clone().try_into().expect("the scene loaded")
        })
    }
    Placement {
        translate: key_or(table, "translate", DVec3::ZERO),
        scale: key_or(table, "scale", S::ONE),
        rotation: key_or(table, "rotation", DVec3::ZERO),
    }
}

/// The tables of the array `key` of a scene file.
fn tables<'a>(file: &'a toml::Table, key: &str) -> Vec<&'a toml::Table> {
    let tables = file.get(key).and_then(toml::Value::as_array);
    let tables = tables.map(|array| array.iter().filter_map(toml::Value::as_table));
    tables.into_iter().flatten().collect()
}

#[test]
fn every_asset_scene_places_its_shapes_as_written() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    let mut placed = 0;
    for path in toml_files(&dir) {
        let scene = Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let text = std::fs::read_to_string(&path).unwrap();
        let file: toml::Table = text.parse().unwrap();
        let got: Vec<Placement> = (scene.tori.iter().map(|s| s.placement))
            .chain(scene.implicits.iter().map(|s| s.placement))
            .chain(scene.julias.iter().map(|s| s.placement))
            .collect();
        let want: Vec<Placement> = ["tori", "implicits", "julias"]
            .into_iter()
            .flat_map(|key| tables(&file, key))
            .map(written_placement)
            .collect();
        assert_eq!(got, want, "{}", path.display());
        let meshes: Vec<Placement<AxisScale>> = scene.meshes.iter().map(|m| m.placement).collect();
        let want: Vec<Placement<AxisScale>> = tables(&file, "meshes")
            .into_iter()
            .map(written_placement)
            .collect();
        assert_eq!(meshes, want, "{}", path.display());
        placed += got.len() + meshes.len();
    }
    assert!(
        placed >= 10,
        "only {placed} placed shapes in {}",
        dir.display()
    );
}

mod properties {
    //! Round trips and robustness over generated scenes and texts.

    use glam::DVec3;
    use indexmap::IndexMap;
    use proptest::num::f64::{NEGATIVE, NORMAL, POSITIVE, SUBNORMAL, ZERO};
    use proptest::prelude::*;
    use proptest::sample::Index;

    use super::super::{
        AxisScale, Camera, Centered, Checker, Cube, Implicit, Instance, Intersections, Julia,
        Light, Material, Placement, Plane, Render, RenderSettings, Scene, Sphere, Torus, Unplaced,
    };
    use super::FULL;

    fn finite() -> impl Strategy<Value = f64> + Clone {
        POSITIVE | NEGATIVE | NORMAL | SUBNORMAL | ZERO
    }

    fn non_negative() -> impl Strategy<Value = f64> + Clone {
        POSITIVE | NORMAL | SUBNORMAL | ZERO
    }

    fn positive() -> impl Strategy<Value = f64> + Clone {
        POSITIVE | NORMAL | SUBNORMAL
    }

    fn vec3(s: impl Strategy<Value = f64> + Clone) -> impl Strategy<Value = DVec3> {
        (s.clone(), s.clone(), s).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    /// Directions of moderate length, which the loader accepts.
    fn direction() -> impl Strategy<Value = DVec3> {
        vec3(-1e3..1e3).prop_filter("normalisable", |v| v.try_normalize().is_some())
    }

    prop_compose! {
        fn render()(
            max_depth in 0..=16u32,
            min_weight in non_negative(),
            background in vec3(non_negative()),
            ambient in vec3(non_negative()),
            exposure in positive(),
            switches in 0..16u32,
            triangles in 0..3usize,
        ) -> Render {
            let settings = RenderSettings {
                max_depth,
                min_weight,
                background,
                ambient,
                exposure,
                shadows: switches & 1 != 0,
                reflection: switches & 2 != 0,
                refraction: switches & 4 != 0,
                intersections: if switches & 8 != 0 {
                    Intersections::Textbook
                } else {
                    Intersections::Robust
                },
            };
            let mut render = Render { settings, ..Render::default() };
            render.meshes.triangles = super::super::TriangleTest::ALL[triangles];
            render
        }
    }

    prop_compose! {
        fn camera()(
            (from, to) in (vec3(-1e6..1e6), vec3(-1e6..1e6))
                .prop_filter("distinct", |(from, to)| (*from - *to).try_normalize().is_some()),
            up in direction(),
            fov in 1e-6..180.0,
            aperture in non_negative(),
            focus_distance in proptest::option::of(positive()),
        ) -> Camera {
            Camera { from, to, up, fov, aperture, focus_distance }
        }
    }

    prop_compose! {
        fn light()(
            position in vec3(finite()),
            color in vec3(non_negative()),
            intensity in non_negative(),
        ) -> Light {
            Light { position, color, intensity }
        }
    }

    prop_compose! {
        fn material()(
            color in vec3(non_negative()),
            (diffuse, specular, mirror, transparency) in
                (non_negative(), non_negative(), non_negative(), non_negative()),
            (shininess, ior) in (positive(), positive()),
            checker in proptest::option::of((vec3(non_negative()), positive())),
        ) -> Material {
            let checker = checker.map(|(color, size)| Checker { color, size });
            Material { color, diffuse, specular, shininess, mirror, transparency, ior, checker }
        }
    }

    fn cube_size() -> impl Strategy<Value = AxisScale> {
        prop_oneof![
            positive().prop_map(AxisScale::Uniform),
            vec3(positive()).prop_map(AxisScale::PerAxis),
        ]
    }

    /// The name of material `index`, or none.
    fn pick(names: &[String], index: Option<Index>) -> Option<String> {
        let index = index.filter(|_| !names.is_empty())?;
        Some(index.get(names).clone())
    }

    prop_compose! {
        fn scene()(
            render in render(),
            camera in camera(),
            lights in proptest::collection::vec(light(), 0..3),
            materials in proptest::collection::vec(("\\PC{0,8}", material()), 0..4),
            spheres in proptest::collection::vec(
                (vec3(finite()), positive(), any::<Option<Index>>()), 0..3),
            planes in proptest::collection::vec(
                (vec3(finite()), direction(), any::<Option<Index>>()), 0..3),
            cubes in proptest::collection::vec(
                (vec3(finite()), cube_size(), vec3(finite()), any::<Option<Index>>()), 0..3),
            tori in proptest::collection::vec(
                (positive(), vec3(finite()), positive(), any::<Option<Index>>()), 0..2),
            implicits in proptest::collection::vec(
                (0..3usize, vec3(finite()), 1..1000u32, any::<Option<Index>>()), 0..2),
            julias in proptest::collection::vec(
                (-0.5..0.5f64, 1..=64u32, positive(), any::<Option<Index>>()), 0..2),
        ) -> Scene {
            let materials: IndexMap<String, Material> = materials.into_iter().collect();
            let names: Vec<String> = materials.keys().cloned().collect();
            let spheres = spheres.into_iter().map(|(center, radius, m)| {
                Instance { shape: Sphere { center, radius }, placement: Unplaced, material: pick(&names, m) }
            }).collect();
            let planes = planes.into_iter().map(|(point, normal, m)| {
                Instance { shape: Plane { point, normal }, placement: Unplaced, material: pick(&names, m) }
            }).collect();
            let cubes = cubes.into_iter().map(|(translate, scale, rotation, m)| {
                let placement = Centered(Placement { translate, scale, rotation });
                Instance { shape: Cube {}, placement, material: pick(&names, m) }
            }).collect();
            let tori = tori.into_iter().map(|(major, translate, scale, m)| Instance {
                shape: Torus { major_radius: major, minor_radius: 0.5 * major },
                placement: Placement { translate, scale, rotation: DVec3::new(10.0, 20.0, 30.0) },
                material: pick(&names, m),
            }).collect();
            let implicits = implicits.into_iter().map(|(which, translate, steps, m)| Instance {
                shape: Implicit {
                    f: ["x^2 + y^2 + z^2 - 1", "sin(x) * cos(y) - z", "max(abs(x), y) - 0.5"][which]
                        .to_string(),
                    bounds: [DVec3::splat(-1.0), DVec3::new(1.0, 2.0, 3.0)],
                    steps,
                },
                placement: Placement { translate, scale: 2.0, rotation: DVec3::ZERO },
                material: pick(&names, m),
            }).collect();
            let julias = julias.into_iter().map(|(c, iterations, epsilon, m)| Instance {
                shape: Julia {
                    c: [c, -c, 0.5 * c, 0.25],
                    slice: c,
                    iterations,
                    epsilon,
                    footprint: iterations % 2 == 0,
                },
                placement: Placement::default(),
                material: pick(&names, m),
            }).collect();
            Scene { render, camera, lights, materials, spheres, planes, cubes, tori, implicits, julias, meshes: Vec::new() }
        }
    }

    proptest! {
        #[test]
        fn saved_scenes_load_back_equal(scene in scene()) {
            let text = scene.to_toml_string();
            let loaded = Scene::from_toml_str(&text, None)
                .map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
            // Loading only normalises plane normals.
            let mut want = scene.clone();
            for (plane, got) in want.planes.iter_mut().zip(&loaded.planes) {
                prop_assert!((got.normal.length() - 1.0).abs() < 1e-15);
                prop_assert!(got.normal.dot(plane.normal) > 0.0);
                plane.normal = got.normal;
            }
            prop_assert_eq!(&loaded, &want);
            let again = Scene::from_toml_str(&loaded.to_toml_string(), None);
            prop_assert_eq!(again.as_ref(), Ok(&loaded));
        }

        #[test]
        fn any_text_loads_or_fails_without_panic(text in "\\PC*") {
            let _ = Scene::from_toml_str(&text, None);
        }

        #[test]
        fn edited_scenes_load_or_fail_without_panic(
            start in 0..FULL.len(),
            len in 0..20usize,
            insert in "[\\[\\]{}=,.\"'#a-z0-9 \n-]{0,6}",
        ) {
            let end = (start + len).min(FULL.len());
            let text = format!("{}{insert}{}", &FULL[..start], &FULL[end..]);
            let _ = Scene::from_toml_str(&text, None);
        }
    }
}

// ------------------------------------------------- meshes from a file's bytes

/// A unit square in the z = 0 plane, as two triangles of an OBJ file.
const SQUARE_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

#[test]
fn a_mesh_from_bytes_is_inline_and_its_scene_text_carries_it() {
    let mesh =
        <super::Mesh as super::Shape>::from_bytes("square.obj", SQUARE_OBJ.as_bytes()).unwrap();
    assert_eq!(mesh.file, None);
    assert_eq!(mesh.positions.len(), 4);
    assert_eq!(mesh.triangles.len(), 2);
    let mut scene = loads(CAMERA);
    scene
        .meshes
        .push(super::Instance::new(mesh, Placement::default()));
    assert_round_trip(&scene);
}

#[test]
fn a_malformed_mesh_from_bytes_names_the_file_and_line() {
    let bad = "v 0 0 0\nv 1 0 0\nf 1 2 7\n";
    let e = <super::Mesh as super::Shape>::from_bytes("bad.obj", bad.as_bytes()).unwrap_err();
    assert!(e.starts_with("bad.obj:3:"), "{e}");
    let e = <super::Mesh as super::Shape>::from_bytes("model.stl", b"solid").unwrap_err();
    assert!(e.starts_with("model.stl:"), "{e}");
}

// ------------------------------------ mesh files given as bytes (the web page)

/// A scene naming a mesh file that exists nowhere on disk, at line 5.
const NAMED_SQUARE: &str =
    "[camera]\nfrom = [0, 1, 5]\nto = [0, 0, 0]\n[[meshes]]\nfile = \"models/square.obj\"\n";

#[test]
fn files_named_lists_the_files_as_written_without_reading_them() {
    assert_eq!(
        Scene::files_named(NAMED_SQUARE),
        [PathBuf::from("models/square.obj")]
    );
    assert!(
        Scene::files_named(FULL).is_empty(),
        "inline meshes name no file"
    );
    assert!(
        Scene::files_named("[camera\n").is_empty(),
        "a broken text names none"
    );
}

#[test]
fn given_mesh_bytes_replace_the_file_system() {
    let mut given = super::GivenFiles::new("not given");
    given.insert(PathBuf::from("models/square.obj"), SQUARE_OBJ.into());
    let scene = Scene::from_toml_with_files(NAMED_SQUARE, None, &given).unwrap();
    let geometry = &scene.meshes[0].geometry.0;
    assert_eq!(geometry.positions.len(), 4);
    assert_eq!(geometry.triangles.len(), 2);
    assert_eq!(
        scene.meshes[0].file.as_deref(),
        Some(Path::new("models/square.obj")),
        "the file is kept as written, so the saved scene names it"
    );
    assert_round_trip_text(&scene, NAMED_SQUARE, &given);
}

/// Saving `scene` and loading its text back with the same `given` files
/// gives the same scene.
fn assert_round_trip_text(scene: &Scene, original: &str, given: &super::GivenFiles) {
    let text = scene.to_toml_string();
    assert_eq!(Scene::files_named(&text), Scene::files_named(original));
    let again = Scene::from_toml_with_files(&text, None, given).unwrap();
    assert_eq!(&again, scene);
}

#[test]
fn a_mesh_file_not_given_is_reported_at_its_line_and_never_read_from_disk() {
    let given = super::GivenFiles::new("the page cannot read it");
    let e =
        Scene::from_toml_with_files(NAMED_SQUARE, Some(Path::new("a.toml")), &given).unwrap_err();
    assert_eq!(e.line, Some(5), "{e}");
    assert_eq!(e.key.as_deref(), Some("meshes[0].file"), "{e}");
    assert_eq!(e.message, "models/square.obj: the page cannot read it");
    // A bundled mesh scene's file exists on disk beside its scene, but
    // with given files nothing is read from there.
    let origin = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(super::bundled::SCENES_WITH_FILES_FOLDER)
        .join("glass_bunny.toml");
    let text = super::bundled::text("glass_bunny").unwrap();
    assert!(Scene::from_toml_str(text, Some(&origin)).is_ok());
    let e = Scene::from_toml_with_files(text, Some(&origin), &given).unwrap_err();
    assert!(e.message.starts_with("../../meshes/bunny.obj: "), "{e}");
}

#[test]
fn given_bytes_load_like_the_file_on_disk_and_their_errors_name_the_file_and_line() {
    let folder =
        Path::new(env!("CARGO_MANIFEST_DIR")).join(super::bundled::SCENES_WITH_FILES_FOLDER);
    let text = super::bundled::text("glass_bunny").unwrap();
    let from_disk = Scene::from_toml_str(text, Some(&folder.join("glass_bunny.toml"))).unwrap();
    let mut given = super::GivenFiles::new("not given");
    for file in Scene::files_named(text) {
        let bytes = std::fs::read(folder.join(&file)).unwrap();
        given.insert(file, bytes);
    }
    let from_bytes = Scene::from_toml_with_files(text, None, &given).unwrap();
    assert_eq!(from_bytes, from_disk, "same triangles, same smooth normals");

    let mut broken = super::GivenFiles::new("not given");
    broken.insert(
        PathBuf::from("models/square.obj"),
        b"v 0 0 0\nf 1 2 3\n".to_vec(),
    );
    let e = Scene::from_toml_with_files(NAMED_SQUARE, None, &broken).unwrap_err();
    assert_eq!(e.line, Some(5), "{e}");
    assert!(e.message.starts_with("models/square.obj:2:"), "{e}");
}
