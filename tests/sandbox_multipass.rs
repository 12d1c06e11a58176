//! Multipass Shadertoy shaders (docs/sandbox.md, "Multipass"): a
//! progressive average in Buffer A converges, a cycle Buffer A <- Buffer B
//! <- Buffer A reads as on Shadertoy, reset clears the buffers, and both
//! input forms (a folder, a JSON export) bind what they say; errors name
//! the file and the key or line; the bundled path tracer converges and the
//! window's watchdog lets it run.

mod common;

use std::path::{Path, PathBuf};

use raysandbox::gpu::Gpu;
use raysandbox::sandbox::channels_3d::{VOLUME_SIZE, cube_colour, noise_volume};
use raysandbox::sandbox::multipass::headless::MultipassOffscreen;
use raysandbox::sandbox::multipass::{Input, PassKind, Project, compile_project};
use raysandbox::sandbox::watchdog::Probe;
use raysandbox::sandbox::{FrameUniforms, NanColor};

fn shaders() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/shaders/multipass")
}

fn offscreen(gpu: &Gpu, path: &Path, size: (u32, u32)) -> MultipassOffscreen {
    let project = Project::load(path).unwrap();
    let compiled = compile_project(&project).unwrap_or_else(|e| panic!("{e}"));
    MultipassOffscreen::new(gpu, compiled, size, NanColor::Black)
        .unwrap_or_else(|e| panic!("{e:?}"))
}

fn draw(gpu: &Gpu, o: &mut MultipassOffscreen, frame: u32, size: (u32, u32)) {
    let uniforms = FrameUniforms::at(f64::from(frame) / 60.0, frame, size);
    o.draw(gpu, &uniforms).expect("the frame finishes");
}

/// The red channel of every pixel of the Image pass.
fn red(gpu: &Gpu, o: &MultipassOffscreen) -> Vec<f64> {
    o.texels(gpu)
        .unwrap()
        .iter()
        .map(|t| f64::from(t[0]))
        .collect()
}

fn rms(a: &[f64], b: impl Fn(usize) -> f64) -> f64 {
    (a.iter()
        .enumerate()
        .map(|(i, x)| (x - b(i)).powi(2))
        .sum::<f64>()
        / a.len() as f64)
        .sqrt()
}

/// tests/shaders/multipass/progressive averages, per pixel, one Bernoulli
/// sample a frame with p = pi/4 (a random point inside the quarter disc):
/// after N frames each pixel's error has standard deviation
/// sqrt(p (1 - p) / N). So the change from frame N to 2N shrinks as
/// 1/sqrt(N), and the mean over the image matches pi/4 within its noise.
#[test]
fn a_progressive_average_in_buffer_a_converges_to_pi_over_4() {
    let gpu = common::gpu();
    let size = (64, 36);
    let mut o = offscreen(&gpu, &shaders().join("progressive"), size);
    let p = std::f64::consts::FRAC_PI_4;
    let variance = p * (1.0 - p);
    let mut at = std::collections::BTreeMap::new();
    for frame in 0..256 {
        draw(&gpu, &mut o, frame, size);
        if [16, 32, 64, 128, 256].contains(&(frame + 1)) {
            at.insert(frame + 1, red(&gpu, &o));
        }
    }
    let change = |n: u32| rms(&at[&n], |i| at[&(2 * n)][i]);
    // Expected: sqrt(variance / (2 N)): 0.073 for N = 16, 0.026 for 128.
    let (early, late) = (change(16), change(128));
    eprintln!("rms change 16 -> 32: {early:.4}, 128 -> 256: {late:.4}");
    assert!(late < 0.5 * early, "{late} vs {early}");
    for n in [16, 128] {
        let expected = (variance / (2.0 * f64::from(n))).sqrt();
        let c = change(n);
        assert!(
            (0.7..1.3).contains(&(c / expected)),
            "N {n}: {c} vs {expected}"
        );
    }
    let last = &at[&256];
    let error = rms(last, |_| p);
    let expected = (variance / 256.0).sqrt();
    assert!(
        (0.8..1.2).contains(&(error / expected)),
        "{error} vs {expected}"
    );
    let mean = last.iter().sum::<f64>() / last.len() as f64;
    // Standard error of the mean: sqrt(variance / (256 * 2304)) = 0.00049.
    let sigma = (variance / (256.0 * last.len() as f64)).sqrt();
    assert!((mean - p).abs() < 5.0 * sigma, "mean {mean}, pi/4 {p}");
}

/// The bundled path tracer (assets/shaders/pathtracer) averages one path
/// per pixel per frame in Buffer A: its noise shrinks as 1/sqrt(N), so the
/// change from frame N to 2N halves when N grows four times; the lamp seen
/// directly is white in every frame and the open front of the box black.
#[test]
fn the_bundled_path_tracer_converges_at_the_monte_carlo_rate() {
    let gpu = common::gpu();
    let size = (64, 36);
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/shaders/pathtracer");
    let mut o = offscreen(&gpu, &folder, size);
    let mut at = std::collections::BTreeMap::new();
    for frame in 0..256 {
        draw(&gpu, &mut o, frame, size);
        let texels = o.texels(&gpu).unwrap();
        let (lamp, corner) = (texels[5 * 64 + 32], texels[0]);
        assert_eq!(lamp[..3], [1.0; 3], "frame {frame}: the lamp");
        assert_eq!(corner[..3], [0.0; 3], "frame {frame}: outside the box");
        if [8, 16, 32, 64, 128, 256].contains(&(frame + 1)) {
            let channels = texels.iter().flat_map(|t| t[..3].to_vec());
            at.insert(frame + 1, channels.map(f64::from).collect::<Vec<_>>());
        }
    }
    let change = |n: u32| rms(&at[&n], |i| at[&(2 * n)][i]);
    for n in [8, 16, 32] {
        let ratio = change(n) / change(4 * n);
        eprintln!(
            "rms change {n} -> {}: {:.4}, ratio to 4N: {ratio:.2}",
            2 * n,
            change(n)
        );
        assert!(
            (1.5..2.7).contains(&ratio),
            "N {n}: ratio {ratio}, expected 2"
        );
    }
}

/// The window's watchdog times a trial frame to refuse shaders that would
/// freeze it; the first frame of a pipeline also pays for the driver's
/// compilation, which alone made it refuse the path tracer at 480x270. Its
/// frames take milliseconds: each pass is let run at 640x360.
#[test]
fn the_watchdog_lets_the_bundled_path_tracer_run_in_the_window() {
    let _gpu = common::gpu();
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/shaders/pathtracer");
    let project = Project::load(&folder).unwrap();
    let compiled = compile_project(&project).unwrap_or_else(|e| panic!("{e}"));
    let mut probe = Probe::default();
    for pass in &compiled.passes {
        probe
            .check(&pass.compiled, (640, 360))
            .unwrap_or_else(|e| panic!("{e}"));
    }
}

/// cycle.json: Buffer A = Buffer B's previous frame + 1, Buffer B = Buffer
/// A's (this frame, drawn before it) + 10, so A = 11 f + 1 and B = 11 f +
/// 11 at frame f, as on Shadertoy. Image shows A, B, A's fragCoord.y read
/// with texture() and the height of A's texture (iChannelResolution).
#[test]
fn a_buffer_cycle_reads_the_previous_frame_and_reset_clears_it() {
    let gpu = common::gpu();
    let size = (8, 6);
    let mut o = offscreen(&gpu, &shaders().join("cycle.json"), size);
    for frame in 0..3 {
        draw(&gpu, &mut o, frame, size);
        let texels = o.texels(&gpu).unwrap();
        let f = frame as f32;
        for (i, t) in texels.iter().enumerate() {
            let row_from_top = (i / size.0 as usize) as f32;
            let y = size.1 as f32 - row_from_top - 0.5;
            assert_eq!(
                *t,
                [11.0 * f + 1.0, y, 11.0 * f + 11.0, 6.0],
                "frame {frame}, texel {i}"
            );
        }
    }
    o.reset(&gpu);
    draw(&gpu, &mut o, 0, size);
    assert_eq!(o.texels(&gpu).unwrap()[0][..3], [1.0, 5.5, 11.0]);
}

#[test]
fn buffers_are_32_bit_floats_where_the_device_filters_them() {
    let gpu = common::gpu();
    let format = raysandbox::sandbox::multipass::gpu::buffer_format(&gpu.device);
    let filterable = gpu
        .device
        .features()
        .contains(wgpu::Features::FLOAT32_FILTERABLE);
    let expected = if filterable {
        wgpu::TextureFormat::Rgba32Float
    } else {
        wgpu::TextureFormat::Rgba16Float
    };
    eprintln!("float32 filterable: {filterable}");
    assert_eq!(format, expected);
}

/// `--frames` carries the buffers from frame to frame: the progressive
/// average's first frame is 0 or 1 in each pixel, later ones in between.
#[test]
fn frames_of_a_multipass_folder_render_and_check_all_takes_folders_and_json() {
    common::require_gpu();
    let out = common::temp_dir("multipass", "frames");
    let dir = shaders().join("progressive");
    let output = common::raysandbox(&[
        "shader",
        dir.to_str().unwrap(),
        "--frames",
        "8",
        "--out",
        out.to_str().unwrap(),
        "--size",
        "32x18",
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let grey = |k: u32| {
        let image = image::open(out.join(format!("frame-{k:05}.png")))
            .unwrap()
            .to_rgba8();
        image.pixels().filter(|p| p[0] != 0 && p[0] != 255).count()
    };
    assert_eq!(grey(0), 0, "frame 0 is one sample: 0 or 1");
    assert!(grey(7) > 32 * 18 / 2, "frame 7 averages 8 samples");

    let folder = common::temp_dir("multipass", "check-all");
    common::copy_dir(&shaders(), &folder);
    let broken = folder.join("broken");
    std::fs::create_dir_all(&broken).unwrap();
    common::write_file(
        &broken,
        "image.glsl",
        "void mainImage(out vec4 c, in vec2 p) {\n    c = vec4(x);\n}\n",
    );
    let output = common::raysandbox(&["shader", "--check-all", folder.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(output.status.code(), Some(2), "{stdout}");
    assert!(
        stdout.contains("pass  ") && stdout.contains("cycle.json"),
        "{stdout}"
    );
    assert!(stdout.contains("progressive"), "{stdout}");
    assert!(stdout.contains("broken/image.glsl:2:"), "{stdout}");
    assert!(stdout.contains("cube_volume"), "{stdout}");
    assert!(stdout.contains("3 of 4 pass"), "{stdout}");
}

fn temp(name: &str) -> PathBuf {
    common::temp_dir("multipass", name)
}

#[test]
fn the_folder_form_binds_what_channels_toml_says() {
    let dir = temp("folder");
    common::write_file(
        &dir,
        "image.glsl",
        "void mainImage(out vec4 c, in vec2 p) { c = vec4(1.0); }\n",
    );
    common::write_file(
        &dir,
        "buffer_b.glsl",
        "void mainImage(out vec4 c, in vec2 p) { c = vec4(1.0); }\n",
    );
    common::write_file(&dir, "common.glsl", "float k() { return 1.0; }\n");
    image::RgbaImage::new(2, 2)
        .save(dir.join("wood.png"))
        .unwrap();
    common::write_file(
        &dir,
        "channels.toml",
        "[image]\niChannel0 = \"buffer_b\"\niChannel3 = \"wood.png\"\n\
         [buffer_b]\niChannel1 = \"keyboard\"\niChannel2 = \"noise\"\niChannel0 = \"buffer_b\"\n",
    );
    let project = Project::load(&dir).unwrap();
    let kinds: Vec<PassKind> = project.passes.iter().map(|p| p.kind).collect();
    assert_eq!(kinds, [PassKind::Buffer(1), PassKind::Image]);
    let b = &project.passes[0].channels;
    assert_eq!(
        b,
        &[
            Some(Input::Buffer(1)),
            Some(Input::Keyboard),
            Some(Input::Noise),
            None
        ]
    );
    let image = &project.passes[1].channels;
    assert_eq!(image[0], Some(Input::Buffer(1)));
    assert_eq!(image[3], Some(Input::Texture(dir.join("wood.png"))));
    assert!(project.common.is_some());
    assert!(project.files().contains(&dir.join("channels.toml")));
}

/// Each mistake of channels.toml is an error naming the file and the key.
#[test]
fn folder_errors_name_the_file_and_the_key() {
    let dir = temp("folder-errors");
    common::write_file(
        &dir,
        "image.glsl",
        "void mainImage(out vec4 c, in vec2 p) { c = vec4(1.0); }\n",
    );
    let cases = [
        ("[buffer_e]\niChannel0 = \"noise\"\n", "[buffer_e]"),
        ("[image]\niChannel7 = \"noise\"\n", "[image] iChannel7"),
        (
            "[image]\niChannel0 = \"buffer_c\"\n",
            "[image] iChannel0: reads Buffer C",
        ),
        (
            "[image]\niChannel1 = 3\n",
            "[image] iChannel1: expected a string",
        ),
        (
            "[image]\niChannel2 = \"nothere.png\"\n",
            "[image] iChannel2: \"nothere.png\"",
        ),
        (
            "[buffer_a]\niChannel0 = \"noise\"\n",
            "[buffer_a]: there is no buffer_a.glsl",
        ),
        ("[image\n", "line 1"),
        ("image = 1\n", "`image` must be a table"),
    ];
    for (text, expected) in cases {
        common::write_file(&dir, "channels.toml", text);
        let e = Project::load(&dir).unwrap_err();
        assert!(
            e.contains("channels.toml") && e.contains(expected),
            "{text:?}: {e}"
        );
    }
    std::fs::remove_file(dir.join("image.glsl")).unwrap();
    let e = Project::load(&dir).unwrap_err();
    assert!(e.contains("needs image.glsl"), "{e}");
}

/// A compile error is at the line of the file it is in: a pass's own file,
/// common.glsl, or the pass inside a JSON file.
#[test]
fn compile_errors_are_at_the_passes_own_file_and_line() {
    let dir = temp("compile-errors");
    common::write_file(&dir, "common.glsl", "float k() {\n    return 1.0;\n}\n");
    common::write_file(
        &dir,
        "image.glsl",
        "void mainImage(out vec4 c, in vec2 p) {\n    c = vec4(k());\n}\n",
    );
    common::write_file(
        &dir,
        "buffer_a.glsl",
        "// A\nvoid mainImage(out vec4 c, in vec2 p) {\n    c = vec4(nope);\n}\n",
    );
    let project = Project::load(&dir).unwrap();
    let e = compile_project(&project).unwrap_err();
    assert_eq!(
        (e.file.as_str(), e.line),
        (dir.join("buffer_a.glsl").to_str().unwrap(), 3),
        "{e}"
    );
    common::write_file(
        &dir,
        "buffer_a.glsl",
        "void mainImage(out vec4 c, in vec2 p) { c = vec4(k()); }\n",
    );
    common::write_file(&dir, "common.glsl", "float k() {\n    return 1.0 +;\n}\n");
    let e = compile_project(&Project::load(&dir).unwrap()).unwrap_err();
    assert_eq!(
        (e.file.as_str(), e.line),
        (dir.join("common.glsl").to_str().unwrap(), 2),
        "{e}"
    );

    let json = shaders().join("cycle.json");
    let text = std::fs::read_to_string(&json)
        .unwrap()
        .replace("+ 10.0", "+ ten");
    let broken = common::write_file(&temp("json-errors"), "cycle.json", &text);
    let e = compile_project(&Project::load(&broken).unwrap()).unwrap_err();
    assert_eq!(e.file, format!("{} [Buffer B]", broken.display()), "{e}");
    assert_eq!(e.line, 3, "{e}");
}

#[test]
fn the_json_form_binds_buffers_by_output_id() {
    let project = Project::load(&shaders().join("cycle.json")).unwrap();
    let kinds: Vec<PassKind> = project.passes.iter().map(|p| p.kind).collect();
    assert_eq!(
        kinds,
        [PassKind::Buffer(0), PassKind::Buffer(1), PassKind::Image]
    );
    assert_eq!(project.passes[0].channels[0], Some(Input::Buffer(1)));
    assert_eq!(project.passes[1].channels[0], Some(Input::Buffer(0)));
    assert_eq!(
        project.passes[2].channels[..2],
        [Some(Input::Buffer(0)), Some(Input::Buffer(1))]
    );
    assert!(project.common.is_some());
}

/// Each mistake of a JSON export is an error naming the file and the key.
#[test]
fn json_errors_name_the_file_and_the_key() {
    let dir = temp("json-keys");
    let pass = |inputs: &str, kind: &str| {
        format!(
            "{{\"Shader\": {{\"renderpass\": [{{\"type\": \"{kind}\", \"name\": \"Image\", \
             \"code\": \"void mainImage(out vec4 c, in vec2 p) {{ c = vec4(1.0); }}\", \
             \"inputs\": [{inputs}], \"outputs\": [{{\"id\": 37}}]}}]}}}}"
        )
    };
    let cases = [
        ("{\"Shader\": {}}".to_string(), "no \"renderpass\" list"),
        ("[1, 2".to_string(), "line 1"),
        (
            pass("{\"channel\": 5, \"ctype\": \"keyboard\"}", "image"),
            "renderpass[0].inputs[0].channel",
        ),
        (
            pass("{\"channel\": 0}", "image"),
            "renderpass[0].inputs[0].ctype",
        ),
        (
            pass(
                "{\"channel\": 0, \"ctype\": \"buffer\", \"id\": 999}",
                "image",
            ),
            "renderpass[0].inputs[0].id: `999`",
        ),
        (
            pass(
                "{\"channel\": 0, \"ctype\": \"buffer\", \"id\": 257}",
                "image",
            ),
            "reads Buffer A",
        ),
        (pass("", "cubemap"), "renderpass[0].type: `cubemap`"),
        (pass("", "buffer"), "no pass of type \"image\""),
        (
            "{\"renderpass\": [{\"type\": \"image\"}]}".to_string(),
            "renderpass[0].code",
        ),
    ];
    for (text, expected) in cases {
        let file = common::write_file(&dir, "toy.json", &text);
        let e = Project::load(&file).unwrap_err();
        assert!(
            e.starts_with(&file.display().to_string()) && e.contains(expected),
            "{text}: {e}"
        );
    }
    // A texture of Shadertoy's site that is not next to the file: noise,
    // and a warning that names the key.
    let file = common::write_file(
        &dir,
        "toy.json",
        &pass(
            "{\"channel\": 2, \"ctype\": \"texture\", \"src\": \"/media/a/abc.png\"}",
            "image",
        ),
    );
    let project = Project::load(&file).unwrap();
    assert_eq!(project.passes[0].channels[2], Some(Input::Noise));
    assert!(
        project.warnings[0].contains("renderpass[0].inputs[0].src"),
        "{:?}",
        project.warnings
    );
}

/// tests/shaders/multipass/cube_volume samples the built-in cube map
/// (`iChannel0 = "cube"`) in 1024 directions all round, with `texture()`
/// and `textureLod()`, and the built-in noise volume (`"volume"`) at 2048
/// texels, with `texelFetch()` and `texture()`; each value is compared with
/// what the built-ins hold (docs/sandbox.md, "Cube maps and volumes").
#[test]
fn the_built_in_cube_map_and_noise_volume_read_as_they_are_made() {
    let gpu = common::gpu();
    let size = (64, 49);
    let mut o = offscreen(&gpu, &shaders().join("cube_volume"), size);
    draw(&gpu, &mut o, 0, size);
    let texels = o.texels(&gpu).unwrap();
    // Rows of `texels` run from the top; the shader's y from the bottom.
    let at = |x: usize, y: usize| texels[(48 - y) * 64 + x];
    let mut worst = 0.0f32;
    for y in 0..16 {
        for x in 0..64 {
            let longitude = 2.0 * std::f32::consts::PI * (x as f32 + 0.5) / 64.0;
            let latitude = 0.9 * std::f32::consts::PI * ((y as f32 + 0.5) / 16.0 - 0.5);
            let d = [
                longitude.cos() * latitude.cos(),
                latitude.sin(),
                longitude.sin() * latitude.cos(),
            ];
            let got = at(x, y);
            for (g, e) in got.iter().zip(cube_colour(d)) {
                worst = worst.max((g - e).abs());
            }
        }
    }
    eprintln!("cube map: largest difference {worst:.4}");
    // 8-bit texels of 64-pixel faces, filtered linearly: within 1%.
    assert!(worst < 0.01, "the cube map differs by {worst}");
    let volume = noise_volume();
    let n = VOLUME_SIZE as usize;
    let mut sum = 0.0f64;
    for y in 0..32 {
        for x in 0..64 {
            let (tx, tz) = if x < 32 { (x, 0) } else { (x - 32, 1) };
            let texel = &volume[4 * (tx + n * (y + n * tz))..][..4];
            let got = at(x, y + 16);
            for c in 0..4 {
                let expected = f32::from(texel[c]) / 255.0;
                assert!(
                    (got[c] - expected).abs() < 1e-3,
                    "volume texel ({tx}, {y}, {tz}) component {c}: {} not {expected}",
                    got[c]
                );
                sum += f64::from(got[c]);
            }
        }
    }
    // 8192 uniform values: mean 0.5, standard error 0.0032.
    let mean = sum / 8192.0;
    assert!((mean - 0.5).abs() < 0.02, "mean {mean}");
    assert_eq!(at(0, 48), [64.0, 64.0, 1.0, 32.0], "iChannelResolution[0]");
    assert_eq!(at(1, 48)[..3], [32.0, 32.0, 32.0], "iChannelResolution[1]");
}

/// A JSON export's "cubemap" and "volume" inputs read the built-ins, the
/// cube map with a warning that Shadertoy's own is not in the file.
#[test]
fn json_cube_maps_and_volumes_read_the_built_ins() {
    let dir = temp("json-cube");
    let text = r#"{"renderpass": [{"type": "image", "code": "void mainImage(out vec4 c, in vec2 p) { c = texture(iChannel0, vec3(1.0, 0.0, 0.0)) + texture(iChannel3, vec3(0.5)); }",
        "inputs": [{"channel": 0, "ctype": "cubemap", "src": "/media/a/sky.png"}, {"channel": 3, "ctype": "volume", "src": "/media/a/noise.bin"}],
        "outputs": [{"id": 37, "channel": 0}]}]}"#;
    let file = common::write_file(&dir, "toy.json", text);
    let project = Project::load(&file).unwrap();
    assert_eq!(project.passes[0].channels[0], Some(Input::Cube));
    assert_eq!(project.passes[0].channels[3], Some(Input::Volume));
    assert!(
        project.warnings.len() == 1 && project.warnings[0].contains("inputs[0].src"),
        "{:?}",
        project.warnings
    );
    compile_project(&project).unwrap_or_else(|e| panic!("{e}"));
}

/// A Restart or a new size replaces every buffer's two textures, and the
/// old ones are destroyed once the canvas is bound to the new ones
/// (docs/web.md, "GPU memory"): many of them in a row leave the cycle
/// drawing what it drew the first time (a texture destroyed too early
/// would be a validation error, a panic here).
#[test]
fn restarts_and_resizes_destroy_the_old_buffers_and_keep_drawing() {
    let gpu = common::gpu();
    let sizes = [(8, 6), (5, 3), (9, 7)];
    let mut o = offscreen(&gpu, &shaders().join("cycle.json"), sizes[0]);
    for round in 0..60 {
        // Even rounds change the size, odd ones keep it and Restart.
        let size = sizes[(round / 2) % sizes.len()];
        if round % 2 == 1 {
            o.reset(&gpu);
        }
        draw(&gpu, &mut o, 0, size);
        draw(&gpu, &mut o, 1, size);
        let h = size.1 as f32;
        // The second frame after the buffers were cleared.
        let expected = [12.0, h - 0.5, 22.0, h];
        assert_eq!(
            o.texels(&gpu).unwrap()[0],
            expected,
            "round {round}, size {size:?}"
        );
    }
}
