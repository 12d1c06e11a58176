//! Sandbox mode without a window: the shipped examples, the three shader
//! styles drawing the same thing, errors at the user's line numbers, reloads
//! that keep the last good shader, and parameters from annotations. Renders
//! are small (128x72): lavapipe runs them on the CPU.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use image::RgbaImage;
use raysandbox::compare::diff_images;
use raysandbox::gpu::{Gpu, render_image};
use raysandbox::sandbox::{
    FrameUniforms, NanColor, Offscreen, Session, Style, compile_file, render_file,
};
use raysandbox::scene::Scene;
use raysandbox::shader_params::Control;

const SIZE: (u32, u32) = (128, 72);

fn shaders_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/shaders")
}

fn temp_dir(name: &str) -> PathBuf {
    common::temp_dir("sandbox", name)
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    common::write_file(dir, name, text)
}

fn distinct_colors(image: &RgbaImage) -> usize {
    let mut colors: Vec<[u8; 4]> = image.pixels().map(|p| p.0).collect();
    colors.sort_unstable();
    colors.dedup();
    colors.len()
}

fn render(gpu: &Gpu, path: &Path, time: f64) -> RgbaImage {
    let (image, stats) = render_file(gpu, path, SIZE, time, None).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(stats.warning(), None, "{}", path.display());
    image
}

#[test]
fn every_shipped_example_compiles_and_renders_a_real_image() {
    let gpu = common::gpu();
    let mut examples: Vec<PathBuf> = std::fs::read_dir(shaders_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        // Subfolders are multipass shaders (tests/sandbox_multipass.rs).
        .filter(|p| p.is_file() && !p.to_string_lossy().ends_with(".toml"))
        .collect();
    examples.sort();
    let styles: Vec<Style> = examples
        .iter()
        .map(|p| compile_file(p).unwrap_or_else(|e| panic!("{e}")).style)
        .collect();
    for style in [Style::Wgsl, Style::GlslSandbox, Style::Shadertoy] {
        assert!(styles.contains(&style), "an example in {style:?}");
    }
    for path in &examples {
        let (image, stats) =
            render_file(&gpu, path, SIZE, 1.0, None).unwrap_or_else(|e| panic!("{e}"));
        println!("{}: {stats:?}", path.display());
        assert_eq!(stats.non_finite, 0, "{}: NaN or inf", path.display());
        assert_eq!(stats.warning(), None, "{}", path.display());
        let colors = distinct_colors(&image);
        assert!(colors > 50, "{}: only {colors} colours", path.display());
    }
}

#[test]
fn the_whitted_examples_draw_what_the_ray_tracer_draws() {
    let gpu = common::gpu();
    let scene = Scene::load(&common::scenes_dir().join("whitted.toml")).unwrap();
    let tracer = render_image(&gpu, &scene, SIZE.0, SIZE.1, 1).unwrap();
    let glsl = render(&gpu, &shaders_dir().join("whitted.frag"), 0.0);
    let wgsl = render(&gpu, &shaders_dir().join("whitted.wgsl"), 0.0);
    let d = diff_images(&glsl, &wgsl);
    assert!(d.max_abs <= 1, "GLSL and WGSL versions differ: {d:?}");
    let d = diff_images(&glsl, &tracer);
    println!("whitted.frag vs the tracer: {d:?}");
    // The same model; the tracer's robust intersection and ray offsets move
    // a few edge pixels.
    assert!(d.mean_abs < 1.0 && d.frac_over_8 < 0.02, "{d:?}");
}

const SANDBOX_RINGS: &str = "\
#ifdef GL_ES
precision mediump float;
#endif
uniform float time;
uniform vec2 resolution;

void main() {
    vec2 p = gl_FragCoord.xy / resolution;
    float r = length(p - vec2(0.3, 0.6));
    gl_FragColor = vec4(p.x, p.y, 0.5 + 0.5 * sin(40.0 * r - time), 1.0);
}
";

const SHADERTOY_RINGS: &str = "\
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 p = fragCoord / iResolution.xy;
    float r = length(p - vec2(0.3, 0.6));
    fragColor = vec4(p.x, p.y, 0.5 + 0.5 * sin(40.0 * r - iTime), 1.0);
}
";

const WGSL_RINGS: &str = "\
fn main_image(frag_coord: vec2<f32>) -> vec4<f32> {
    let p = frag_coord / u.resolution;
    let r = length(p - vec2(0.3, 0.6));
    return vec4(p.x, p.y, 0.5 + 0.5 * sin(40.0 * r - u.time), 1.0);
}
";

#[test]
fn glsl_sandbox_shadertoy_and_wgsl_shaders_of_the_same_thing_draw_the_same_image() {
    let gpu = common::gpu();
    let dir = temp_dir("same");
    let sandbox = write(&dir, "rings.frag", SANDBOX_RINGS);
    let toy = write(&dir, "rings.glsl", SHADERTOY_RINGS);
    let wgsl = write(&dir, "rings.wgsl", WGSL_RINGS);
    assert_eq!(compile_file(&sandbox).unwrap().style, Style::GlslSandbox);
    assert_eq!(compile_file(&toy).unwrap().style, Style::Shadertoy);
    let a = render(&gpu, &sandbox, 2.5);
    let b = render(&gpu, &toy, 2.5);
    let c = render(&gpu, &wgsl, 2.5);
    assert_eq!(diff_images(&a, &b).max_abs, 0, "Sandbox vs Shadertoy");
    assert!(diff_images(&a, &c).max_abs <= 1, "GLSL vs WGSL");
    // y is up in all three: the top row has p.y near 1 (green), the bottom near 0.
    assert!(a.get_pixel(5, 0)[1] > 250, "top: {:?}", a.get_pixel(5, 0));
    assert!(a.get_pixel(5, SIZE.1 - 1)[1] < 5, "bottom");
    // Time moves the rings.
    assert!(diff_images(&a, &render(&gpu, &sandbox, 3.0)).max_abs > 50);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The line (1-based) of the first line containing `marker`.
fn line_of(text: &str, marker: &str) -> u32 {
    text.lines().position(|l| l.contains(marker)).unwrap() as u32 + 1
}

#[test]
fn errors_name_the_users_file_line_and_column() {
    let dir = temp_dir("errors");
    let cases = [
        // An unknown name: naga's span is the name itself.
        (
            "sandbox.frag",
            SANDBOX_RINGS.replace("float r = length", "float r = lenght"),
            "lenght",
        ),
        (
            "toy.glsl",
            SHADERTOY_RINGS.replace("iTime)", "iTme)"),
            "iTme",
        ),
        ("w.wgsl", WGSL_RINGS.replace("u.time", "u.tme"), "u.tme"),
        // A missing `;` is reported after the token that wants it, on its
        // line, not at the next line's first token.
        (
            "semicolon.frag",
            SANDBOX_RINGS.replace(
                "vec2 p = gl_FragCoord.xy / resolution;",
                "vec2 p = gl_FragCoord.xy / resolution",
            ),
            "vec2 p = gl_FragCoord.xy / resolution",
        ),
        (
            "semicolon.wgsl",
            WGSL_RINGS.replace(
                "let p = frag_coord / u.resolution;",
                "let p = frag_coord / u.resolution",
            ),
            "let p = frag_coord",
        ),
    ];
    for (name, text, marker) in cases {
        let path = write(&dir, name, &text);
        let e = compile_file(&path).expect_err(name);
        let line = line_of(&text, marker);
        assert_eq!(e.file, path.display().to_string(), "{e}");
        assert_eq!(e.line, line, "{e}");
        assert_eq!(e.source_line, text.lines().nth(line as usize - 1).unwrap());
        if !name.starts_with("semicolon") {
            let column = text
                .lines()
                .nth(line as usize - 1)
                .unwrap()
                .find(marker)
                .unwrap()
                + 1;
            let column = if name == "w.wgsl" { column + 2 } else { column };
            assert_eq!(e.column as usize, column, "{e}");
        }
        let shown = e.to_string();
        assert!(
            shown.starts_with(&format!("{}:{line}:", path.display())),
            "{shown}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_failed_reload_keeps_the_last_good_frame_and_the_fix_renders_again() {
    let gpu = common::gpu();
    let dir = temp_dir("reload");
    let path = write(&dir, "live.frag", SANDBOX_RINGS);
    let mut offscreen = Offscreen::new(&gpu);
    let builder = offscreen.builder(&gpu);
    let mut session = Session::new(&path);
    session.reload(&builder).unwrap();
    let frame = FrameUniforms::at(1.0, 0, SIZE);
    let mut draw = |session: &Session| {
        offscreen
            .draw(&gpu, session.pipeline().unwrap(), &session.params, &frame)
            .unwrap();
        offscreen.image(&gpu).unwrap_or_else(|e| panic!("{e}"))
    };
    let good = draw(&session);

    let broken = SANDBOX_RINGS.replace("gl_FragColor = vec4(", "gl_FragColor = vec4((");
    std::fs::write(&path, &broken).unwrap();
    let error = session.reload(&builder).expect_err("a syntax error");
    assert!(
        error.location().starts_with(&format!(
            "{}:{}:",
            path.display(),
            line_of(&broken, "gl_FragColor =")
        )),
        "{error}"
    );
    assert!(session.error.is_some());
    assert_eq!(draw(&session), good, "the last good shader still draws");

    let fixed = SANDBOX_RINGS.replace("0.5 + 0.5 * sin", "0.25 + 0.5 * sin");
    std::fs::write(&path, &fixed).unwrap();
    session.reload(&builder).unwrap();
    assert!(session.error.is_none(), "the error is gone");
    let after = draw(&session);
    assert!(diff_images(&good, &after).max_abs > 50, "the fix draws");
    let (expected, _) = render_file(&gpu, &path, SIZE, 1.0, None).unwrap();
    assert_eq!(after, expected);
    std::fs::remove_dir_all(&dir).unwrap();
}

const PARAMS_SHADER: &str = "\
uniform float time;
uniform vec2 resolution;
uniform float speed = 1.5;        // @slider(0.0, 5.0, 0.1) how fast
uniform vec3 tint;                // @color
uniform bool invert;              // @checkbox
// @select(circle, square, star)
uniform int shape = 1;
uniform float eps = 0.01;         // @log(1e-4, 1)
uniform vec2 offset;

void main() {
    vec2 p = gl_FragCoord.xy / resolution + offset;
    vec3 c = tint * p.x * speed + eps * float(shape);
    gl_FragColor = vec4(invert ? 1.0 - c : c, 1.0);
}
";

#[test]
fn annotations_become_controls_and_values_survive_a_reload() {
    let dir = temp_dir("params");
    let path = write(&dir, "params.frag", PARAMS_SHADER);
    let compiled = compile_file(&path).unwrap_or_else(|e| panic!("{e}"));
    let specs = &compiled.params.specs;
    let summary: Vec<(&str, &str, usize, f64)> = specs
        .iter()
        .map(|s| (s.name.as_str(), s.control.kind(), s.ty.len, s.default[0]))
        .collect();
    assert_eq!(
        summary,
        [
            ("speed", "slider", 1, 1.5),
            ("tint", "color", 3, 1.0),
            ("invert", "checkbox", 1, 0.0),
            ("shape", "select", 1, 1.0),
            ("eps", "log", 1, 0.01),
            ("offset", "drag", 2, 0.0),
        ]
    );
    assert_eq!(
        specs[0].control,
        Control::Slider {
            min: 0.0,
            max: 5.0,
            step: Some(0.1)
        }
    );
    assert_eq!(specs[0].help, "how fast");
    assert_eq!(
        specs[3].control,
        Control::Select(vec!["circle".into(), "square".into(), "star".into()])
    );
    assert_eq!(
        specs[4].control,
        Control::Log {
            min: 1e-4,
            max: 1.0
        }
    );

    let gpu = common::gpu();
    let offscreen = Offscreen::new(&gpu);
    let builder = offscreen.builder(&gpu);
    let mut session = Session::new(&path);
    session.reload(&builder).unwrap();
    session.params.set("speed", &[3.0]);
    session.params.set("tint", &[0.2, 0.4, 0.6]);
    session.params.set("shape", &[2.0]);
    // The edit: `invert` goes, `gain` comes, the slider's range changes.
    let edited = PARAMS_SHADER
        .replace(
            "uniform bool invert;              // @checkbox\n",
            "uniform float gain = 2.0; // @slider(0, 4)\n",
        )
        .replace("invert ? 1.0 - c : c", "gain * c")
        .replace("@slider(0.0, 5.0, 0.1)", "@slider(0.0, 2.5, 0.1)");
    std::fs::write(&path, &edited).unwrap();
    session.reload(&builder).unwrap_or_else(|e| panic!("{e}"));
    let p = &session.params;
    assert_eq!(
        p.value("speed"),
        Some(&[2.5][..]),
        "kept, clamped to the new range"
    );
    assert_eq!(p.value("tint"), Some(&[0.2, 0.4, 0.6][..]));
    assert_eq!(p.value("shape"), Some(&[2.0][..]));
    assert_eq!(
        p.value("gain"),
        Some(&[2.0][..]),
        "a new parameter starts at its default"
    );
    assert_eq!(p.value("invert"), None);

    // Saved next to the shader and loaded back.
    let saved = session.save_params().unwrap();
    assert_eq!(saved, dir.join("params.frag.params.toml"));
    session.params.reset();
    assert_eq!(session.params.value("speed"), Some(&[1.5][..]));
    assert!(session.load_params().unwrap().is_empty());
    assert_eq!(session.params.value("tint"), Some(&[0.2, 0.4, 0.6][..]));
    // A new session (the window opened again) starts from the sidecar.
    let mut again = Session::new(&path);
    again.reload(&builder).unwrap();
    assert_eq!(again.params.value("shape"), Some(&[2.0][..]));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_shader_that_writes_nan_gets_a_warning_and_black_or_magenta_pixels() {
    let gpu = common::gpu();
    let dir = temp_dir("nan");
    let nan = write(
        &dir,
        "nan.frag",
        "uniform float time;\nvoid main() { gl_FragColor = vec4(sqrt(-1.0 - time)); }\n",
    );
    let (image, stats) = render_file(&gpu, &nan, SIZE, 1.0, None).unwrap();
    assert_eq!(stats.non_finite, stats.pixels);
    assert!(stats.warning().unwrap().contains("NaN"), "{stats:?}");
    assert_eq!(
        image.get_pixel(0, 0).0,
        [0, 0, 0, 255],
        "black, as browsers show NaN"
    );
    let compiled = compile_file(&nan).unwrap();
    let mut offscreen = Offscreen::with_nan_color(&gpu, NanColor::Magenta);
    let pipeline = offscreen.builder(&gpu).build(&compiled).unwrap();
    let frame = FrameUniforms::at(1.0, 0, SIZE);
    offscreen
        .draw(&gpu, &pipeline, &compiled.params, &frame)
        .unwrap();
    assert_eq!(
        offscreen.image(&gpu).unwrap().get_pixel(0, 0).0,
        [255, 0, 255, 255]
    );
    let silent = write(
        &dir,
        "silent.glsl",
        "void mainImage(out vec4 c, in vec2 p) {}\n",
    );
    let (_, stats) = render_file(&gpu, &silent, SIZE, 1.0, None).unwrap();
    assert!(
        stats.warning().unwrap().contains("(0, 0, 0, 0)"),
        "{stats:?}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

fn raysandbox(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_raysandbox"))
        .args(args)
        .output()
        .expect("run raysandbox")
}

#[test]
fn headless_renders_one_png_or_a_numbered_sequence() {
    common::require_gpu();
    let dir = temp_dir("cli");
    let shader = shaders_dir().join("mirror_cube.frag");
    let out = dir.join("one.png");
    let result = raysandbox(&[
        "shader",
        shader.to_str().unwrap(),
        "--render",
        out.to_str().unwrap(),
        "--time",
        "1.5",
        "--size",
        "96x54",
    ]);
    assert!(
        result.status.success(),
        "{}",
        String::from_utf8_lossy(&result.stderr)
    );
    assert_eq!(image::open(&out).unwrap().to_rgba8().dimensions(), (96, 54));

    let frames = dir.join("frames");
    let result = raysandbox(&[
        "shader",
        shader.to_str().unwrap(),
        "--frames",
        "3",
        "--out",
        frames.to_str().unwrap(),
        "--size",
        "64x36",
        "--fps",
        "2",
    ]);
    assert!(
        result.status.success(),
        "{}",
        String::from_utf8_lossy(&result.stderr)
    );
    let images: Vec<RgbaImage> = (0..3)
        .map(|k| {
            image::open(frames.join(format!("frame-{k:05}.png")))
                .unwrap()
                .to_rgba8()
        })
        .collect();
    assert!(!frames.join("frame-00003.png").exists());
    assert_ne!(images[0], images[1], "the cube turns between frames");

    let broken = write(
        &dir,
        "broken.wgsl",
        "fn main_image(p: vec2<f32>) -> vec4<f32> {\n    return vec4(1.0)\n}\n",
    );
    let result = raysandbox(&[
        "shader",
        broken.to_str().unwrap(),
        "--render",
        out.to_str().unwrap(),
    ]);
    assert_eq!(result.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        stderr.contains(&format!("{}:2:21: error", broken.display())),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
