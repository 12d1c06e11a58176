//! The command line as a user meets it: exit statuses, messages, files.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn raysandbox(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raysandbox"))
        .args(args)
        .output()
        .expect("run raysandbox")
}

fn temp_path(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("raysandbox-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn write_scene(name: &str, text: &str) -> PathBuf {
    let path = temp_path(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn check_accepts_every_bundled_scene_with_a_summary() {
    for path in common::toml_files(&common::scenes_dir()) {
        let out = raysandbox(&["check", path.to_str().unwrap()]);
        let stdout = text(&out.stdout);
        assert!(
            out.status.success(),
            "{}: {}",
            path.display(),
            text(&out.stderr)
        );
        assert!(
            stdout.contains("spheres") && stdout.contains("lights"),
            "{stdout}"
        );
        assert_eq!(stdout.lines().count(), 1, "one line: {stdout}");
    }
}

#[test]
fn check_rejects_a_bad_value_with_status_2_naming_file_and_key() {
    let path = write_scene(
        "bad_radius.toml",
        "[camera]\nfrom = [0, 0, 5]\nto = [0, 0, 0]\n\n[[spheres]]\ncenter = [0, 0, 0]\nradius = -1\n",
    );
    let out = raysandbox(&["check", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = text(&out.stderr);
    assert!(stderr.contains("bad_radius.toml"), "{stderr}");
    assert!(stderr.contains("spheres[0].radius"), "{stderr}");
    assert!(stderr.contains("got -1"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn bad_input_never_panics() {
    let cases = [
        ("garbage.toml", "this is = not [ toml"),
        ("empty.toml", ""),
        ("nan.toml", "[camera]\nfrom = [0, 0, nan]\nto = [0, 0, 0]\n"),
        (
            "unknown.toml",
            "[camera]\nfrom = [0, 0, 5]\nto = [0, 0, 0]\nzoom = 2\n",
        ),
    ];
    for (name, body) in cases {
        let path = write_scene(name, body);
        for command in ["check", "render"] {
            let mut args = vec![command, path.to_str().unwrap()];
            if command == "render" {
                args.extend(["-o", "/nonexistent/never.png"]);
            }
            let out = raysandbox(&args);
            let stderr = text(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{command} {name}: {stderr}");
            assert!(stderr.contains(name), "{command} {name}: {stderr}");
            assert!(!stderr.contains("panicked"), "{command} {name}: {stderr}");
        }
    }
    let missing = raysandbox(&["check", "/nonexistent/scene.toml"]);
    assert_eq!(missing.status.code(), Some(2));
    assert!(text(&missing.stderr).contains("/nonexistent/scene.toml"));
}

#[test]
fn render_reference_writes_a_png_of_the_requested_size() {
    let out_path = temp_path("reference.png");
    let scene = common::scenes_dir().join("whitted.toml");
    let out = raysandbox(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        out_path.to_str().unwrap(),
        "--width",
        "64",
        "--height",
        "36",
        "--reference",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("reference"));
    let image = image::open(&out_path).expect("a PNG").to_rgba8();
    assert_eq!(image.dimensions(), (64, 36));
}

#[test]
fn render_on_the_gpu_prints_adapter_and_time() {
    common::require_gpu();
    let out_path = temp_path("gpu.png");
    let scene = common::scenes_dir().join("whitted.toml");
    let out = raysandbox(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        out_path.to_str().unwrap(),
        "--width",
        "64",
        "--height",
        "36",
    ]);
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(stdout.contains("adapter:"), "{stdout}");
    assert!(stdout.contains(" ms"), "{stdout}");
    assert_eq!(image::open(&out_path).unwrap().width(), 64);
}

#[test]
fn broken_shader_folder_is_reported_with_file_and_line() {
    let dir = temp_path("broken_shaders");
    std::fs::create_dir_all(&dir).unwrap();
    let shaders = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
    common::copy_dir(&shaders, &dir);
    let shade = dir.join("shade.wgsl");
    let broken =
        std::fs::read_to_string(&shade)
            .unwrap()
            .replacen("return color;", "return color", 1);
    std::fs::write(&shade, broken).unwrap();
    let scene = common::scenes_dir().join("whitted.toml");
    let out = raysandbox(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        temp_path("never.png").to_str().unwrap(),
        "--shaders",
        dir.to_str().unwrap(),
    ]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("shade.wgsl:"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// Sizes the GPU cannot draw end with exit status 2 and a message naming
/// the limit, never a panic: one pixel beyond the adapter's largest texture,
/// and zero, for every command that takes a size.
#[test]
fn sizes_beyond_the_gpu_or_zero_exit_2_naming_the_limit() {
    let gpu = common::gpu();
    let max = gpu.device.limits().max_texture_dimension_2d;
    let too_big = (max + 1).to_string();
    let too_wide = format!("{too_big}x8");
    let scene = common::scenes_dir().join("whitted.toml");
    let scene = scene.to_str().unwrap();
    let png = temp_path("too_big.png");
    let png = png.to_str().unwrap();
    let shader = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/shaders/mirror_cube.frag");
    let shader = shader.to_str().unwrap();
    let over_limit: [Vec<&str>; 3] = [
        vec![
            "render", scene, "-o", png, "--width", &too_big, "--height", "8",
        ],
        vec![
            "render", scene, "-o", png, "--width", "8", "--height", &too_big,
        ],
        vec!["shader", shader, "--render", png, "--size", &too_wide],
    ];
    for args in &over_limit {
        let out = raysandbox(args);
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains(&format!("1 to {max} pixels")),
            "{args:?}: {stderr}"
        );
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    }
    let zero: [Vec<&str>; 5] = [
        vec!["render", scene, "-o", png, "--width", "0"],
        vec!["render", scene, "-o", png, "--height", "0"],
        vec!["shader", shader, "--render", png, "--size", "0x8"],
        vec!["view", scene, "--size", "8x0"],
        vec!["stress", "--width", "0"],
    ];
    for args in &zero {
        let out = raysandbox(args);
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        // clap names the range, e.g. "0 is not in 1..=16384", the size
        // parser its first value: "expected a size from 1 to 16384".
        assert!(
            stderr.contains("1..=") || stderr.contains("8..=") || stderr.contains("from 1 to"),
            "{args:?}: {stderr}"
        );
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    }
    assert!(!Path::new(png).exists(), "nothing is written");
}

/// Bad input in the implicit surfaces (docs/scene-format.md, "Implicit
/// surfaces"): exit status 2, and the message names the file, the key and,
/// for a function, the column in it.
#[test]
fn bad_implicit_surfaces_exit_2_naming_key_and_column() {
    let camera = "[camera]\nfrom = [0, 0, 5]\nto = [0, 0, 0]\n\n";
    let implicit = |f: &str, bounds: &str, extra: &str| {
        format!("{camera}[[implicits]]\nf = \"{f}\"\nbounds = {bounds}\n{extra}")
    };
    let box_ = "[[-1, -1, -1], [1, 1, 1]]";
    let julia = |c: &str, extra: &str| format!("{camera}[[julias]]\nc = {c}\n{extra}");
    let torus = |major: &str, minor: &str| {
        format!("{camera}[[tori]]\nmajor_radius = {major}\nminor_radius = {minor}\n")
    };
    let cases = [
        (
            implicit("x + foo(y)", box_, ""),
            vec!["implicits[0].f", "column 5", "unknown function `foo`"],
        ),
        (
            implicit("(x + 1", box_, ""),
            vec!["implicits[0].f", "column 1", "unbalanced parenthesis"],
        ),
        (
            implicit("x * y) - 1", box_, ""),
            vec!["implicits[0].f", "column 6", "unbalanced parenthesis"],
        ),
        (
            implicit("x", "[[-1, 2, -1], [1, 1, 1]]", ""),
            vec!["implicits[0].bounds", "min y must be < max y"],
        ),
        (
            implicit("x", box_, "steps = 0\n"),
            vec!["implicits[0].steps", "1..="],
        ),
        (
            implicit("x", "[[-1, -1, -1], [1, nan, 1]]", ""),
            vec!["implicits[0].bounds[1]", "finite"],
        ),
        (
            julia("[2, 1, 0, 0]", ""),
            vec!["julias[0].c", "|c| must be <= 2"],
        ),
        (
            julia("[0.2, 0.1, 0, 0]", "iterations = 0\n"),
            vec!["julias[0].iterations", "1..=64"],
        ),
        (
            julia("[0.2, nan, 0, 0]", ""),
            vec!["julias[0].c[1]", "finite"],
        ),
        (
            julia("[0.2, 0.1, 0, 0]", "epsilon = -1e-3\n"),
            vec!["julias[0].epsilon", "> 0"],
        ),
        (torus("1", "nan"), vec!["tori[0].minor_radius"]),
        (
            torus("1", "1.5"),
            vec!["tori[0].minor_radius", "must be < major_radius"],
        ),
    ];
    for (i, (scene, words)) in cases.iter().enumerate() {
        let path = write_scene(&format!("bad_implicit_{i}.toml"), scene);
        let out = raysandbox(&["check", path.to_str().unwrap()]);
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{scene}\n{stderr}");
        assert!(
            stderr.contains(&format!("bad_implicit_{i}.toml")),
            "{stderr}"
        );
        for word in words {
            assert!(
                stderr.contains(word),
                "{scene}\nexpected {word:?} in: {stderr}"
            );
        }
    }
}
