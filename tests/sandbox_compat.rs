//! Sandbox mode on what people actually paste from GLSL Sandbox and
//! Shadertoy: naga's bugs worked around, never a crash, the old names and
//! the front-end gaps bridged (docs/sandbox.md, "What runs"). Renders are
//! small: lavapipe runs them on the CPU.

mod common;

use std::path::{Path, PathBuf};

use image::RgbaImage;
use raysandbox::gpu::Gpu;
use raysandbox::sandbox::render_file;

const SIZE: (u32, u32) = (32, 18);

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("raysandbox-compat-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Renders `text` as a file called `name` at time 1 and returns the image.
fn render_text(gpu: &Gpu, name: &str, text: &str) -> RgbaImage {
    let dir = temp_dir(name);
    let path = write(&dir, name, text);
    let result = render_file(gpu, &path, SIZE, 1.0, None);
    std::fs::remove_dir_all(&dir).unwrap();
    let (image, stats) = result.unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(stats.warning(), None, "{name}");
    image
}

/// Every pixel of `image` within one 8-bit step of `rgb`.
fn assert_every_pixel(image: &RgbaImage, rgb: [u8; 3], what: &str) {
    for (x, y, p) in image.enumerate_pixels() {
        let off = (0..3).any(|c| p.0[c].abs_diff(rgb[c]) > 1);
        assert!(
            !off,
            "{what}: pixel ({x}, {y}) is {:?}, expected {rgb:?}",
            p.0
        );
    }
}

#[test]
fn components_passed_to_inout_and_out_parameters_are_copied_in_and_back() {
    // naga alone panics on these calls ("Expression [N] is not cached!").
    let text = "\
void add_half(inout float x) { x += 0.5; }
void halve(inout vec2 x) { x *= 0.5; }
void quarter(out float x) { x = 0.25; }
struct S { float m; };
void mainImage(out vec4 c, in vec2 p) {
    vec3 r = vec3(0.0, 1.0, 0.5);
    float a[2] = float[2](0.0, 0.0);
    int i = int(p.x) % 2;
    S s = S(0.0);
    add_half(r.x);
    halve(r.zy);
    quarter(a[i]);
    for (int k = 0; k < 2; k++) { add_half(s.m); }
    c = vec4(r.x, r.y * s.m, r.z + a[i], 1.0);
}
";
    let Some(gpu) = common::gpu() else { return };
    let image = render_text(&gpu, "inout.glsl", text);
    assert_every_pixel(&image, [128, 128, 128], "r.x + 0.5, 0.5 * 1.0, 0.25 + 0.25");
}

#[test]
fn a_headless_frame_that_never_ends_is_stopped_with_exit_status_2() {
    if common::gpu().is_none() {
        return;
    }
    let dir = temp_dir("endless");
    let path = write(
        &dir,
        "endless.frag",
        "uniform float time;\nvoid main() {\n    float x = time;\n    \
         while (x < 2.0) { x = fract(x + sin(x * 7.0 + gl_FragCoord.y)); }\n    \
         gl_FragColor = vec4(x);\n}\n",
    );
    let out = dir.join("out.png");
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_raysandbox"))
        .args([
            "shader",
            path.to_str().unwrap(),
            "--render",
            out.to_str().unwrap(),
        ])
        .args(["--size", "1920x1080"])
        .output()
        .expect("run raysandbox");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("endless.frag: the shader did not finish a frame"),
        "{stderr}"
    );
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
