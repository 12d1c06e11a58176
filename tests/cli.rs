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
    if common::gpu().is_none() {
        return;
    }
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
