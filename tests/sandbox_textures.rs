//! Textures in sandbox mode (docs/sandbox.md, "Textures"): Shadertoy's
//! `iChannel0..3` from image files or the built-in noise, GLSL Sandbox's
//! `backbuffer` (the previous frame), and a wrong `--channel` path.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use image::RgbaImage;
use raysandbox::sandbox::channels;

fn temp_dir(name: &str) -> PathBuf {
    common::temp_dir("textures", name)
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    common::write_file(dir, name, text)
}

fn raysandbox(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raysandbox"))
        .args(args)
        .output()
        .expect("run raysandbox")
}

fn succeeded(output: &Output) {
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

fn open(path: &Path) -> RgbaImage {
    image::open(path).unwrap().to_rgba8()
}

/// Samples a channel at every pixel's centre, at the image's own size.
const SHOW_CHANNEL0: &str = "\
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    fragColor = texture(iChannel0, fragCoord / iResolution.xy);
}
";

/// The same in WebGL GLSL as old Shadertoy exports have it: the channel
/// declared, `texture2D`, a `sampler2D` parameter, `iChannelResolution`.
const SHOW_CHANNEL0_OLD: &str = "\
precision highp float;
uniform sampler2D iChannel0;
vec4 fetch(sampler2D image, vec2 uv) {
    return texture2D(image, uv);
}
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    fragColor = fetch(iChannel0, fragCoord / iChannelResolution[0].xy);
}
";

/// glslViewer's names (docs/sandbox.md, "glslViewer and The Book of
/// Shaders"): `u_tex1` is channel 1 whatever the order of declaration,
/// `u_tex1Resolution` its size, and `--tex1` gives its image.
const SHOW_TEX1: &str = "\
uniform sampler2D u_tex1;
uniform sampler2D u_tex0;
uniform vec2 u_tex1Resolution;
void main() {
    gl_FragColor = texture2D(u_tex1, gl_FragCoord.xy / u_tex1Resolution) + 0.0 * texture2D(u_tex0, vec2(0.0));
}
";

#[test]
fn a_shader_sampling_a_channel_reproduces_the_given_image() {
    common::require_gpu();
    let dir = temp_dir("channel");
    // Not a multiple of 64 wide, and every pixel different.
    let input = RgbaImage::from_fn(37, 23, |x, y| {
        image::Rgba([(x * 7) as u8, (y * 11) as u8, ((x * y) % 256) as u8, 255])
    });
    let input_path = dir.join("input.png");
    input.save(&input_path).unwrap();
    for (name, text, flag) in [
        ("show.glsl", SHOW_CHANNEL0, "--channel0"),
        ("show_old.glsl", SHOW_CHANNEL0_OLD, "--channel0"),
        ("show_tex1.frag", SHOW_TEX1, "--tex1"),
    ] {
        let shader = write(&dir, name, text);
        let out = dir.join(format!("{name}.png"));
        succeeded(&raysandbox(&[
            "shader",
            shader.to_str().unwrap(),
            flag,
            input_path.to_str().unwrap(),
            "--render",
            out.to_str().unwrap(),
            "--size",
            "37x23",
        ]));
        assert_eq!(open(&out), input, "{name}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn without_a_channel_image_the_channel_is_the_built_in_noise() {
    common::require_gpu();
    let dir = temp_dir("noise");
    let shader = write(&dir, "show.glsl", SHOW_CHANNEL0);
    let out = dir.join("noise.png");
    let size = format!("{0}x{0}", channels::NOISE_SIZE);
    succeeded(&raysandbox(&[
        "shader",
        shader.to_str().unwrap(),
        "--render",
        out.to_str().unwrap(),
        "--size",
        &size,
    ]));
    // The alpha of the noise is drawn opaque, as every colour is.
    let mut noise = channels::noise_image();
    for p in noise.pixels_mut() {
        p.0[3] = 255;
    }
    assert_eq!(open(&out), noise);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Frame 0 draws a gradient; every later frame shows the previous frame.
const GRADIENT_THEN_BACKBUFFER: &str = "\
uniform vec2 resolution;
uniform float time;
uniform sampler2D backbuffer;
void main() {
    vec2 uv = gl_FragCoord.xy / resolution;
    if (time < 0.01) {
        gl_FragColor = vec4(uv, 0.25, 1.0);
    } else {
        gl_FragColor = texture2D(backbuffer, uv);
    }
}
";

/// Adds 0.1 to the previous frame.
const ACCUMULATE: &str = "\
#ifdef GL_ES
precision mediump float;
#endif
uniform vec2 resolution;
uniform sampler2D backbuffer;
void main() {
    vec4 previous = texture2D(backbuffer, gl_FragCoord.xy / resolution);
    gl_FragColor = vec4(previous.rgb + 0.1, 1.0);
}
";

fn frames(dir: &Path, shader: &Path, count: u32, size: &str) -> Vec<RgbaImage> {
    let out = dir.join(shader.file_stem().unwrap());
    succeeded(&raysandbox(&[
        "shader",
        shader.to_str().unwrap(),
        "--frames",
        &count.to_string(),
        "--out",
        out.to_str().unwrap(),
        "--size",
        size,
    ]));
    (0..count)
        .map(|k| open(&out.join(format!("frame-{k:05}.png"))))
        .collect()
}

#[test]
fn backbuffer_is_the_previous_frame_upright_and_accumulates() {
    common::require_gpu();
    let dir = temp_dir("backbuffer");
    let gradient = write(&dir, "gradient.frag", GRADIENT_THEN_BACKBUFFER);
    let images = frames(&dir, &gradient, 3, "40x24");
    // Not flipped, not shifted: the same image frame after frame.
    assert_eq!(images[1], images[0]);
    assert_eq!(images[2], images[0]);
    let bottom_left = images[0].get_pixel(0, 23).0;
    let top_right = images[0].get_pixel(39, 0).0;
    assert!(
        bottom_left[0] < 10 && bottom_left[1] < 10,
        "{bottom_left:?}"
    );
    assert!(top_right[0] > 245 && top_right[1] > 245, "{top_right:?}");

    let accumulate = write(&dir, "accumulate.frag", ACCUMULATE);
    let images = frames(&dir, &accumulate, 4, "16x16");
    // Black at first, as on GLSL Sandbox, then 0.1 (25.5 in 8 bits) more
    // per frame; the previous frame is stored in 8 bits, so each step adds
    // 25.5 rounded.
    let grey: Vec<u8> = images.iter().map(|i| i.get_pixel(5, 5).0[0]).collect();
    let mut previous = 0;
    for g in &grey {
        assert!((25..=26).contains(&(g - previous)), "{grey:?}");
        previous = *g;
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_channel_image_that_cannot_be_read_exits_2_naming_the_file() {
    let dir = temp_dir("bad-channel");
    let shader = write(&dir, "show.glsl", SHOW_CHANNEL0);
    let not_an_image = write(&dir, "notes.png", "not a PNG");
    let missing = dir.join("missing.png");
    for (flag, path) in [("--channel0", &missing), ("--channel2", &not_an_image)] {
        let result = raysandbox(&[
            "shader",
            shader.to_str().unwrap(),
            flag,
            path.to_str().unwrap(),
            "--render",
            dir.join("out.png").to_str().unwrap(),
        ]);
        assert_eq!(result.status.code(), Some(2), "{flag}");
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(
            stderr.contains(&format!("{}: cannot read the image", path.display())),
            "{stderr}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--channel0 cube --channel1 volume` (docs/sandbox.md, "Cube maps and
/// volumes"): a Shadertoy shader that does not declare its channels reads
/// the built-in cube map (the direction's colour) as a `samplerCube` and
/// the built-in noise volume as a `sampler3D`, whose size it is told.
#[test]
fn channels_given_as_cube_and_volume_are_the_built_ins() {
    common::require_gpu();
    let dir = temp_dir("cube-volume");
    let shader = write(
        &dir,
        "sky.glsl",
        "void mainImage(out vec4 c, in vec2 p) {\n\
         \x20   vec3 d = p.x < 8.0 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, -1.0, 0.0);\n\
         \x20   float depth = iChannelResolution[1].z / 32.0;\n\
         \x20   c = vec4(texture(iChannel0, d).rgb * depth * step(0.0, texture(iChannel1, vec3(0.5)).r), 1.0);\n\
         }\n",
    );
    let out = dir.join("sky.png");
    let output = raysandbox(&[
        "shader",
        shader.to_str().unwrap(),
        "--channel0",
        "cube",
        "--channel1",
        "volume",
        "--render",
        out.to_str().unwrap(),
        "--size",
        "16x4",
    ]);
    succeeded(&output);
    let image = open(&out);
    // +x is (1, 0.5, 0.5), -y (0.5, 0, 0.5): within two levels (filtering).
    for (x, expected) in [(2, [255, 128, 128]), (12, [128, 0, 128])] {
        let got = image.get_pixel(x, 1).0;
        for c in 0..3 {
            assert!(
                (i32::from(got[c]) - expected[c]).abs() <= 2,
                "pixel {x}: {got:?}, expected {expected:?}"
            );
        }
    }
    // Without --channel0 cube the same shader is a 2-D channel's: an error.
    let output = raysandbox(&[
        "shader",
        shader.to_str().unwrap(),
        "--render",
        out.to_str().unwrap(),
    ]);
    assert_eq!(output.status.code(), Some(2));
}
