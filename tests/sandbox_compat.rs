//! Sandbox mode on what people actually paste from GLSL Sandbox and
//! Shadertoy: naga's bugs worked around, never a crash, the old names and
//! the front-end gaps bridged (docs/sandbox.md, "What runs"). Renders are
//! small: lavapipe runs them on the CPU.

mod common;

use std::path::{Path, PathBuf};

use image::RgbaImage;
use raysandbox::gpu::Gpu;
use raysandbox::sandbox::{Checked, Flat, check_file, render_file};

const SIZE: (u32, u32) = (32, 18);

fn temp_dir(name: &str) -> PathBuf {
    common::temp_dir("compat", name)
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    common::write_file(dir, name, text)
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

/// The first pixel of `image` more than one 8-bit step from `rgb`, if any.
fn pixel_off(image: &RgbaImage, rgb: [u8; 3]) -> Option<String> {
    image.enumerate_pixels().find_map(|(x, y, p)| {
        (0..3)
            .any(|c| p.0[c].abs_diff(rgb[c]) > 1)
            .then(|| format!("pixel ({x}, {y}) is {:?}, expected {rgb:?}", p.0))
    })
}

/// Every pixel of `image` within one 8-bit step of `rgb`.
fn assert_every_pixel(image: &RgbaImage, rgb: [u8; 3], what: &str) {
    if let Some(off) = pixel_off(image, rgb) {
        panic!("{what}: {off}");
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
    let gpu = common::gpu();
    let image = render_text(&gpu, "inout.glsl", text);
    assert_every_pixel(&image, [128, 128, 128], "r.x + 0.5, 0.5 * 1.0, 0.25 + 0.25");
}

#[test]
fn a_headless_frame_that_never_ends_is_stopped_with_exit_status_2() {
    common::require_gpu();
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

#[test]
fn gl_es_is_defined_and_precision_statements_for_any_type_are_accepted() {
    let text = "\
#ifdef GL_ES
precision mediump float;
precision lowp sampler2D;
#endif
#ifndef GL_ES
#error GL_ES is not defined
#endif
uniform float time;
void main() { gl_FragColor = vec4(time * 0.5, 0.25, 1.0, 1.0); }
";
    let gpu = common::gpu();
    let image = render_text(&gpu, "gles.frag", text);
    assert_every_pixel(&image, [128, 64, 255], "time 1");
}

#[test]
fn surface_position_spans_the_plane_glsl_sandbox_shows() {
    // At rest the plane's part shown is 1 high, centred on the origin.
    let text = "\
varying vec2 surfacePosition;
uniform vec2 surfaceSize;
void main() {
    gl_FragColor = vec4(surfacePosition + 0.5, surfaceSize.y * 0.5, 1.0);
}
";
    let gpu = common::gpu();
    let image = render_text(&gpu, "surface.frag", text);
    let (w, h) = SIZE;
    let aspect = w as f32 / h as f32;
    for (x, y, p) in image.enumerate_pixels() {
        let u = (x as f32 + 0.5) / w as f32 - 0.5;
        let v = (h as f32 - y as f32 - 0.5) / h as f32 - 0.5;
        let expected =
            [u * aspect + 0.5, v + 0.5, 0.5].map(|c| (c.clamp(0.0, 1.0) * 255.0).round());
        for c in 0..3 {
            let d = (f32::from(p.0[c]) - expected[c]).abs();
            assert!(
                d <= 1.0,
                "pixel ({x}, {y}) is {:?}, expected {expected:?}",
                p.0
            );
        }
    }
}

#[test]
fn old_shadertoy_names_and_a_main_of_the_files_own_work() {
    // An export for other sites: the uniforms declared, a `main` calling
    // `mainImage`, the names from before 2017.
    let text = "\
uniform vec3 iResolution;
uniform float iGlobalTime;
uniform float iChannelTime[4];
uniform float iSampleRate;
uniform vec4 iDate;
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    float year = iDate.x > 2000.0 ? 1.0 : 0.0;
    fragColor = vec4(iGlobalTime * 0.5, iChannelTime[1] * 0.25, iSampleRate / 88200.0, year);
}
void main(void) { mainImage(gl_FragColor, gl_FragCoord.xy); }
";
    let gpu = common::gpu();
    let image = render_text(&gpu, "old.frag", text);
    assert_every_pixel(
        &image,
        [128, 64, 128],
        "iGlobalTime 1, iChannelTime 1, 44100 Hz",
    );
}

#[test]
fn the_style_is_read_from_the_preprocessor_branch_taken() {
    let text = "\
#ifdef SOMETHING_NOT_DEFINED
void main() {
    gl_FragColor = vec4(1.0);
#else
void mainImage(out vec4 c, in vec2 p) {
    c = vec4(iTime * 0.25);
#endif
}
";
    let gpu = common::gpu();
    let image = render_text(&gpu, "branches.glsl", text);
    assert_every_pixel(&image, [64, 64, 64], "mainImage at time 1");
}

#[test]
fn webgl_constructs_naga_lacks_are_rewritten_and_errors_keep_the_users_columns() {
    // mat2(vec4), `const in` parameters, a prototype with unnamed parameters.
    let text = "\
float half_of(const in float, float);
void mainImage(out vec4 c, in vec2 p) {
    mat2 m = mat2(vec4(0.5, 0.0, 0.0, 0.25));
    vec2 v = m * vec2(1.0, 1.0);
    c = vec4(v, half_of(1.0, 0.0), 1.0);
}
float half_of(const in float x, float unused) { return x * 0.5 + unused; }
";
    let gpu = common::gpu();
    let image = render_text(&gpu, "gaps.glsl", text);
    assert_every_pixel(
        &image,
        [128, 64, 128],
        "mat2 columns (0.5, 0) and (0, 0.25)",
    );
    // A mistake after a rewritten call on the same line: the user's column.
    let broken = text.replace(
        "    vec2 v = m",
        "    vec2 v = mat2(vec4(1.0)) * lenght(p) * m",
    );
    let e = raysandbox::sandbox::compile("gaps.glsl", &broken).expect_err("lenght");
    let line = broken.lines().nth(3).unwrap();
    assert_eq!(
        (e.line, e.column as usize),
        (4, line.find("lenght").unwrap() + 1),
        "{e}"
    );
}

#[test]
fn a_function_that_can_end_without_a_return_returns_zero_and_is_warned_of() {
    // `f` has no return for x <= 0.5 (GLSL leaves the value undefined);
    // `sampler`, a type in Vulkan GLSL, names a parameter.
    let text = "\
uniform vec2 resolution;
float f(float x) {
    if (x > 0.5) { return 1.0; }
}
float halve(float sampler) { return sampler * 0.5; }
void main() { gl_FragColor = vec4(f(gl_FragCoord.x / resolution.x), halve(1.0), 0.0, 1.0); }
";
    let compiled =
        raysandbox::sandbox::compile("ends.frag", text).unwrap_or_else(|e| panic!("{e}"));
    let warnings: Vec<String> = compiled.warnings.iter().map(|w| w.to_string()).collect();
    assert_eq!(
        warnings,
        [
            "ends.frag:2: warning: function `f` can end without returning a value: it returns 0 there"
        ]
    );
    let gpu = common::gpu();
    let image = render_text(&gpu, "ends.frag", text);
    let (w, h) = image.dimensions();
    let left = image::imageops::crop_imm(&image, 0, 0, w / 2 - 1, h).to_image();
    let right = image::imageops::crop_imm(&image, w / 2 + 1, 0, w - w / 2 - 1, h).to_image();
    assert_every_pixel(&left, [0, 128, 0], "f = 0 where it has no return");
    assert_every_pixel(&right, [255, 128, 0], "f = 1");
}

#[test]
fn mix_in_a_global_const_draws_its_value() {
    // naga cannot evaluate mix() as a constant: it becomes its definition.
    let text = "\
const vec3 A = vec3(1.0, 0.0, 0.0);
const vec3 C = mix(A, vec3(0.0, 0.0, 1.0), 0.25);
void main() { gl_FragColor = vec4(C, 1.0); }
";
    let gpu = common::gpu();
    let image = render_text(&gpu, "mix.frag", text);
    assert_every_pixel(&image, [191, 0, 64], "mix(red, blue, 0.25)");
}

#[test]
fn a_function_may_call_one_defined_below_it_through_a_prototype() {
    // naga adds `a` where its prototype is, but its definition calls `c`,
    // defined later: the functions are reordered for the validator.
    let text = "\
uniform float time;
float a(float x);
float b(float x) { return a(x) * 2.0; }
void main() { gl_FragColor = vec4(vec3(b(time * 0.25)), 1.0); }
float c(float x) { return x * 0.5; }
float a(float x) { return c(x) + 0.125; }
";
    let gpu = common::gpu();
    let image = render_text(&gpu, "order.frag", text);
    assert_every_pixel(&image, [128, 128, 128], "(0.25 / 2 + 0.125) * 2");
}

#[test]
fn a_glsl_sandbox_port_of_a_shadertoy_shader_stays_glsl_sandbox() {
    // mainImage and main, with GLSL Sandbox's uniforms and its own defines
    // of the Shadertoy names.
    let text = "\
uniform float time;
uniform vec2 resolution;
#define iGlobalTime time
#define iResolution resolution
void mainImage(out vec4 c, in vec2 p) { c = vec4(p / iResolution.xy, iGlobalTime * 0.5, 1.0); }
void main() { mainImage(gl_FragColor, gl_FragCoord.xy); }
";
    let compiled =
        raysandbox::sandbox::compile("port.frag", text).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(compiled.style, raysandbox::sandbox::Style::GlslSandbox);
}

/// What the first line of a suite file expects (tests/shaders/compat/README.md).
#[derive(Debug)]
enum Expected {
    /// It compiles and draws a frame; with a colour, every pixel of the
    /// frame at time 1 is that colour.
    Pass(Option<[u8; 3]>),
    /// It fails: the start of the error's first line after the file name.
    Error(String),
}

fn expectation(path: &Path) -> Expected {
    let text = std::fs::read_to_string(path).unwrap();
    let first = text.lines().next().unwrap_or_default();
    let expect = first
        .strip_prefix("// expect: ")
        .unwrap_or_else(|| panic!("{}: no `// expect:` line", path.display()));
    if let Some(error) = expect.strip_prefix("error ") {
        return Expected::Error(error.to_string());
    }
    let colour = expect
        .strip_prefix("pass")
        .unwrap_or_else(|| panic!("{}: `pass` or `error ...`", path.display()));
    let channels: Vec<u8> = colour
        .split_whitespace()
        .map(|c| {
            c.parse()
                .unwrap_or_else(|e| panic!("{}: {c}: {e}", path.display()))
        })
        .collect();
    match channels[..] {
        [] => Expected::Pass(None),
        [r, g, b] => Expected::Pass(Some([r, g, b])),
        _ => panic!("{}: `pass` takes no colour or R G B", path.display()),
    }
}

#[test]
fn the_compatibility_suite_gives_the_expected_result_per_file() {
    let gpu = common::gpu();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/shaders/compat");
    let files = common::shader_files(&dir);
    assert!(files.len() >= 10, "{files:?}");
    let mut wrong = Vec::new();
    for path in &files {
        let verdict = check_file(&gpu, path, SIZE, 1.0);
        let name = path.display().to_string();
        match (expectation(path), verdict) {
            (Expected::Pass(_), Ok(_)) => {}
            (Expected::Error(expected), Err(Checked::Failed(error))) => {
                let first = error.lines().next().unwrap_or_default();
                let after_name = first.strip_prefix(&format!("{name}:")).unwrap_or(first);
                if !after_name.trim_start().starts_with(&expected) {
                    wrong.push(format!("{name}: expected `{expected}`, got `{first}`"));
                }
            }
            (expected, verdict) => {
                wrong.push(format!("{name}: expected {expected:?}, got {verdict:?}"))
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn check_all_prints_a_verdict_per_file_and_the_totals() {
    common::require_gpu();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/shaders/compat");
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_raysandbox"))
        .args(["shader", "--check-all", dir.to_str().unwrap()])
        .output()
        .expect("run raysandbox");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(
        output.status.code(),
        Some(2),
        "some files are broken on purpose"
    );
    assert!(
        stdout.contains(
            "41 of 46 pass (89.1%), 5 fail; of those 11 drew a picture, 30 one flat colour, \
         0 every pixel NaN; 1 with uniforms nothing sets (silent zeros)"
        ),
        "{stdout}"
    );
    let typo = stdout
        .lines()
        .find(|l| l.contains("broken_typo.frag"))
        .unwrap();
    assert!(
        typo.starts_with("FAIL  ") && typo.ends_with(":6:15: error: Unknown function 'lenght'"),
        "{typo}"
    );
    assert!(
        stdout
            .lines()
            .any(|l| l.starts_with("pass  ") && l.ends_with("surface.frag")),
        "{stdout}"
    );
    // The warning column: a flat picture, and the uniform nothing sets.
    let silent = stdout
        .lines()
        .find(|l| l.contains("silent_zero.frag"))
        .unwrap();
    assert!(
        silent.starts_with("pass  ")
            && silent.ends_with(&format!(
                "silent_zero.frag  | one flat colour (0, 0, 0)  | \
                 {}/silent_zero.frag:10: warning: uniform `u_speed` is not set \
                 by raysandbox: it stays 0; annotate it to get a control (docs/sandbox.md, \
                 \"Parameters\") (and 1 more)",
                dir.display()
            )),
        "{silent}"
    );
}

/// No silent zeros: each uniform that nothing sets is a warning at its
/// line, only those (docs/sandbox.md, "Uniforms nobody sets"); a picture
/// entirely NaN is told apart from one flat colour.
#[test]
fn uniforms_nothing_sets_and_flat_or_nan_pictures_are_reported() {
    let gpu = common::gpu();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/shaders/compat/silent_zero.frag");
    let report = check_file(&gpu, &path, SIZE, 1.0).unwrap();
    let lines: Vec<(u32, &str)> = report
        .warnings
        .iter()
        .map(|w| (w.line, w.message.as_str()))
        .collect();
    assert_eq!(
        lines,
        [
            (
                10,
                "uniform `u_speed` is not set by raysandbox: it stays 0; annotate it to get a \
                 control (docs/sandbox.md, \"Parameters\")"
            ),
            (
                13,
                "uniform `u_rotation` is not set by raysandbox: it stays 0; a matrix gets no \
                 control: give it a value in the code"
            )
        ]
    );
    assert_eq!(report.flat(), Some(Flat::Colour([0, 0, 0])));
    let dir = temp_dir("nan");
    let nan = write(
        &dir,
        "nan.frag",
        "uniform float u_time;\nvoid main() { gl_FragColor = vec4(sqrt(-1.0 - u_time)); }\n",
    );
    let report = check_file(&gpu, &nan, SIZE, 1.0).unwrap();
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    assert_eq!(report.flat(), Some(Flat::Nan));
    let picture = write(
        &dir,
        "picture.frag",
        "uniform vec2 u_resolution;\nvoid main() { gl_FragColor = vec4(gl_FragCoord.xy / u_resolution, 0.0, 1.0); }\n",
    );
    let report = check_file(&gpu, &picture, SIZE, 1.0).unwrap();
    assert_eq!(report.flat(), None);
    assert_eq!(report.column(), "");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The suite's files that pass draw with no warning, and those that state
/// a colour draw every pixel in it: the features of real shaders each file
/// exercises (its comment names them) compile *and* compute what GLSL says.
#[test]
fn passing_suite_files_render_without_warning_in_the_colour_they_state() {
    let gpu = common::gpu();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/shaders/compat");
    let mut wrong = Vec::new();
    let mut coloured = 0;
    for path in common::shader_files(&dir) {
        let Expected::Pass(colour) = expectation(&path) else {
            continue;
        };
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        match render_file(&gpu, &path, SIZE, 1.0, None) {
            Ok((_, stats)) if stats.warning().is_some() => {
                wrong.push(format!("{name}: {:?}", stats.warning()))
            }
            Ok((image, _)) => {
                if let Some(rgb) = colour {
                    coloured += 1;
                    if let Some(off) = pixel_off(&image, rgb) {
                        wrong.push(format!("{name}: {off}"));
                    }
                }
            }
            Err(e) => wrong.push(format!("{name}: {e}")),
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    assert!(coloured >= 15, "only {coloured} files state a colour");
}
