//! Sandbox mode: the user's own fragment shader file (WGSL, or GLSL in the
//! GLSL Sandbox or Shadertoy style) run full screen, reloaded on every save,
//! with controls generated from annotated parameters; or rendered headless to
//! PNG files. docs/sandbox.md is the user's documentation.
//!
//! | module | what |
//! | --- | --- |
//! | `compose` | language and style, the preludes, the GLSL rewrite, validation (one file per language and step) |
//! | `include` | glslViewer's `#include "file"`, with the map back to each file's lines |
//! | `gaps` | small source rewrites for what naga's GLSL front end does not take |
//! | `params` | annotations, values, the bytes the GPU reads, the sidecar file (a file each) |
//! | `uniforms` | the per-frame values (time, mouse, resolution, date) |
//! | `mouse` | the mouse uniforms: Shadertoy's click and drag, GLSL Sandbox's surface |
//! | `clock` | pause, resume, restart, step |
//! | `repair` | workarounds for naga bugs, applied to the parsed module |
//! | `render` | the GPU passes: the user's shader into a canvas, the canvas shown, the previous frame kept |
//! | `bundled` | the example shaders, embedded (the page's menu) |
//! | `check` | `--check-all`: one frame of each file of a folder, the verdicts and warnings |
//! | `channels` | the images a shader samples: files, or the built-in noise |
//! | `channels_3d` | cube maps and volumes: the kinds of channel, the built-in cube map and noise volume |
//! | `multipass` | Shadertoy's Buffer A-D, Common and Image: a folder or a JSON export |
//! | `session` | one file: the last good pipeline, reloads, parameter values |
//! | `watchdog` | the window's trial frame that refuses shaders too slow to run |
//! | `constants` | the same parameters for the ray tracer's shader folder (annotated `const`s) |
//!
//! The window is `app::sandbox_window` (`app::run_sandbox`), built on this
//! module; it shares the viewer's window setup, error overlay and controls.

pub mod bundled;
pub mod channels;
pub mod channels_3d;
mod check;
pub mod clock;
pub mod compose;
mod gaps;
pub mod include;
pub mod mouse;
pub mod multipass;
pub mod render;
mod repair;
pub mod session;
pub mod uniforms;
pub mod watchdog;

use std::path::{Path, PathBuf};
use std::time::Instant;

use channels_3d::{ChannelKind, ChannelKinds};
pub use check::{Checked, Flat, Report, check_file};
pub use compose::{
    Compiled, Style, Warning, WarningKind, compile, compile_file, compile_file_with,
};
use render::{BuildFailed, FRAME_LIMIT, build_too_slow};
pub use render::{CanvasStats, NanColor, Offscreen, render_once};
pub use session::{ReloadError, Session};
pub use uniforms::FrameUniforms;

use crate::cli::parse_size;
use crate::gpu::{Gpu, GpuWaitError};
use crate::shader_params::{self, ParamSet};

/// Arguments of `raysandbox shader`.
#[derive(Debug, Clone, clap::Args)]
pub struct ShaderArgs {
    /// The shader file: WGSL (`.wgsl`, with `fn main_image`) or GLSL (`.glsl`,
    /// `.frag`) in the GLSL Sandbox (`void main`) or Shadertoy (`mainImage`)
    /// style; or a multipass Shadertoy shader: a folder (`image.glsl`,
    /// `buffer_a.glsl`, ..., `channels.toml`) or a Shadertoy JSON export.
    /// See docs/sandbox.md.
    pub file: PathBuf,
    /// FILE is a folder: check every shader file in it (compile, render one
    /// frame at --size, default 64x36) and print pass or the error for each,
    /// then the totals. Exit status 2 if any fails.
    #[arg(long, conflicts_with_all = ["render", "frames"])]
    pub check_all: bool,
    /// Render one frame to this PNG file instead of opening a window.
    #[arg(long, value_name = "OUT.png", conflicts_with = "frames")]
    pub render: Option<PathBuf>,
    /// Render N frames to a numbered PNG sequence in --out DIR.
    #[arg(long, value_name = "N", requires = "out", value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub frames: Option<u32>,
    /// The folder of the PNG sequence (frame-00000.png, ...).
    #[arg(long, value_name = "DIR", requires = "frames")]
    pub out: Option<PathBuf>,
    /// Clock time in seconds of the (first) headless frame.
    #[arg(long, default_value_t = 0.0, value_name = "SECONDS")]
    pub time: f64,
    /// Frames per second of a PNG sequence.
    #[arg(long, default_value_t = 60.0, value_parser = parse_fps)]
    pub fps: f64,
    /// Image size of headless renders (default 1280x720), or the window's
    /// initial inner size.
    #[arg(long, value_parser = parse_size, value_name = "WxH")]
    pub size: Option<(u32, u32)>,
    /// Open the window with the clock paused at 0 (Space resumes).
    #[arg(long)]
    pub start_paused: bool,
    /// Render resolution as a fraction of the window's (0.25..1), for heavy
    /// shaders on weak GPUs.
    #[arg(long, default_value_t = 1.0, value_parser = parse_scale)]
    pub scale: f32,
    /// How NaN and infinite pixels are drawn: black as in browsers (so as
    /// the shader's author saw it), or magenta to find them.
    #[arg(long, value_enum, default_value_t = NanColor::Black)]
    pub nan_color: NanColor,
    /// The image of Shadertoy's `iChannel0` (PNG, JPEG, ...), also the
    /// first `uniform sampler2D` of a GLSL Sandbox file other than
    /// `backbuffer`, and glslViewer's `u_tex0` (so also `--tex0`, as
    /// glslViewer spells it). Without it, a built-in noise image. `cube`
    /// or `volume`: the built-in cube map or noise volume, and iChannel0
    /// is a samplerCube or sampler3D.
    #[arg(long, value_name = "IMAGE", visible_alias = "tex0")]
    pub channel0: Option<PathBuf>,
    /// The image of `iChannel1` and `u_tex1` (see --channel0).
    #[arg(long, value_name = "IMAGE", visible_alias = "tex1")]
    pub channel1: Option<PathBuf>,
    /// The image of `iChannel2` and `u_tex2` (see --channel0).
    #[arg(long, value_name = "IMAGE", visible_alias = "tex2")]
    pub channel2: Option<PathBuf>,
    /// The image of `iChannel3` and `u_tex3` (see --channel0).
    #[arg(long, value_name = "IMAGE", visible_alias = "tex3")]
    pub channel3: Option<PathBuf>,
    /// Print one line per event (ready, shader-reloaded, shader-error, ...)
    /// on stdout, for scripts and tests that drive the window.
    #[arg(long, hide = true)]
    pub print_events: bool,
}

fn parse_scale(text: &str) -> Result<f32, String> {
    text.parse::<f32>()
        .ok()
        .filter(|s| (0.25..=1.0).contains(s))
        .ok_or_else(|| format!("expected a scale from 0.25 to 1, got {text:?}"))
}

fn parse_fps(text: &str) -> Result<f64, String> {
    text.parse::<f64>()
        .ok()
        .filter(|s| *s > 0.0 && s.is_finite())
        .ok_or_else(|| format!("expected frames per second > 0, got {text:?}"))
}

/// A failure of `raysandbox shader`: the user's input (exit status 2) or the
/// machine (exit status 1).
#[derive(Debug)]
pub enum SandboxError {
    Input(String),
    Runtime(String),
}

impl ShaderArgs {
    /// The image paths of `--channel0 .. --channel3` (not `cube` or
    /// `volume`, the built-ins).
    pub fn channel_paths(&self) -> [Option<PathBuf>; channels::CHANNELS] {
        self.channel_values()
            .map(|p| p.filter(|p| built_in_kind(p).is_none()))
    }

    fn channel_values(&self) -> [Option<PathBuf>; channels::CHANNELS] {
        [
            self.channel0.clone(),
            self.channel1.clone(),
            self.channel2.clone(),
            self.channel3.clone(),
        ]
    }

    /// What each channel holds: `--channel0 cube` and `volume` name the
    /// built-in cube map and noise volume (docs/sandbox.md, "Cube maps and
    /// volumes"); anything else is a 2-D image.
    pub fn channel_kinds(&self) -> ChannelKinds {
        self.channel_values()
            .map(|p| p.as_deref().and_then(built_in_kind).unwrap_or_default())
    }

    /// The channel images, read now: a wrong path is the user's error
    /// (exit status 2), reported before a GPU or window is opened.
    pub fn channel_images(
        &self,
    ) -> Result<[Option<image::RgbaImage>; channels::CHANNELS], SandboxError> {
        channels::load_all(&self.channel_paths()).map_err(SandboxError::Input)
    }

    /// `--render` or `--frames`: no window ([`run_headless`]); otherwise the
    /// window, which `app::run_sandbox` owns.
    pub fn is_headless(&self) -> bool {
        self.check_all || self.render.is_some() || self.frames.is_some()
    }
}

/// The kind a `--channelN` value names, if it is a built-in's name.
fn built_in_kind(value: &Path) -> Option<ChannelKind> {
    match value.to_str()? {
        "cube" => Some(ChannelKind::Cube),
        "volume" => Some(ChannelKind::Volume),
        _ => None,
    }
}

/// The shader file (or multipass folder) must exist before anything else
/// is tried (a GPU, a window): a mistyped name is the user's error.
pub fn require_file(path: &Path) -> Result<(), SandboxError> {
    if path.is_file() || path.is_dir() {
        Ok(())
    } else {
        Err(SandboxError::Input(format!(
            "{}: no such file",
            path.display()
        )))
    }
}

/// `raysandbox shader FILE --render OUT.png` or `--frames N --out DIR`, or
/// `raysandbox shader --check-all DIR`.
pub fn run_headless(args: &ShaderArgs) -> Result<(), SandboxError> {
    if args.check_all {
        return check::check_all(args);
    }
    require_file(&args.file)?;
    if multipass::is_multipass(&args.file) {
        return multipass::headless::run(args);
    }
    let images = args.channel_images()?;
    let compiled = compile_file_with(&args.file, &args.channel_kinds())
        .map_err(|e| SandboxError::Input(e.to_string()))?;
    for warning in &compiled.warnings {
        eprintln!("{warning}");
    }
    let mut params = compiled.params.clone();
    let sidecar = shader_params::sidecar_path(&args.file);
    if let Ok(text) = std::fs::read_to_string(&sidecar) {
        let warnings = params
            .apply_toml(&text)
            .map_err(|e| SandboxError::Input(format!("{}: {e}", sidecar.display())))?;
        for w in warnings {
            eprintln!("warning: {}: {w}", sidecar.display());
        }
        println!("parameters from {}", sidecar.display());
    }
    let gpu = Gpu::headless().map_err(|e| SandboxError::Runtime(e.to_string()))?;
    println!("adapter: {}", gpu.describe());
    let size = args.size.unwrap_or((1280, 720));
    gpu.check_size(size)
        .map_err(|e| SandboxError::Input(format!("--size: {e}")))?;
    let (count, out_dir) = match (&args.render, args.frames, &args.out) {
        (Some(_), _, _) => (1, None),
        (None, Some(n), Some(dir)) => {
            std::fs::create_dir_all(dir)
                .map_err(|e| SandboxError::Runtime(format!("{}: {e}", dir.display())))?;
            (n, Some(dir.as_path()))
        }
        _ => unreachable!("clap requires --out with --frames"),
    };
    let start = Instant::now();
    let mut warned = false;
    let rendered = render_sequence(
        &gpu,
        images,
        &compiled,
        &params,
        size,
        args.time,
        args.fps,
        count,
        args.nan_color,
        |k, image, stats| {
            let path = match (out_dir, &args.render) {
                (Some(dir), _) => dir.join(format!("frame-{k:05}.png")),
                (None, Some(path)) => path.clone(),
                (None, None) => unreachable!(),
            };
            if let Some(warning) = stats.warning().filter(|_| !warned) {
                eprintln!("warning: {}: {warning}", args.file.display());
                warned = true;
            }
            image
                .save(&path)
                .map_err(|e| SandboxError::Runtime(format!("{}: {e}", path.display())))?;
            if out_dir.is_none() {
                println!("wrote {}", path.display());
            }
            Ok(())
        },
    );
    rendered.map_err(|e| match e {
        RenderError::Gpu(m) => SandboxError::Input(m),
        RenderError::Wait(m) => SandboxError::Runtime(m),
        RenderError::Stopped(m) => {
            // Dropping the device would wait for the frame that never ends.
            std::mem::forget(gpu);
            SandboxError::Input(m)
        }
        RenderError::Output(e) => e,
    })?;
    report_rendered(out_dir, count, size, start);
    Ok(())
}

/// The last lines of a headless render: where the frames went, how long
/// they took.
pub(crate) fn report_rendered(
    out_dir: Option<&Path>,
    count: u32,
    size: (u32, u32),
    start: Instant,
) {
    if let Some(dir) = out_dir {
        println!(
            "wrote {count} frames to {} (frame-00000.png ...)",
            dir.display()
        );
    }
    println!(
        "rendered {count} frame(s) of {}x{} in {:.1} ms",
        size.0,
        size.1,
        start.elapsed().as_secs_f64() * 1e3
    );
}

/// Why a headless render stopped: the shader's pipeline (the user's input),
/// a frame stopped by the watchdog, the readback of a frame failing (a lost
/// device), or the caller's handling of a frame (writing the file).
enum RenderError<E> {
    Gpu(String),
    /// Reading the frame back failed ([`GpuWaitError`]).
    Wait(String),
    /// The watchdog stopped a frame ([`render::TooSlow`]): the GPU is still
    /// busy with it.
    Stopped(String),
    Output(E),
}

/// Renders `count` frames at `fps` from `time`, handing each to `each`
/// with its index. One pipeline and canvas serve all frames.
#[allow(clippy::too_many_arguments)]
fn render_sequence<E>(
    gpu: &Gpu,
    images: [Option<image::RgbaImage>; channels::CHANNELS],
    compiled: &Compiled,
    params: &ParamSet,
    size: (u32, u32),
    time: f64,
    fps: f64,
    count: u32,
    nan: NanColor,
    mut each: impl FnMut(u32, image::RgbaImage, CanvasStats) -> Result<(), E>,
) -> Result<(), RenderError<E>> {
    let offscreen = Offscreen::with_nan_color(gpu, nan).with_channels(images);
    let pipeline = match offscreen.builder(gpu).build_within(compiled, FRAME_LIMIT) {
        Ok(pipeline) => pipeline,
        Err(BuildFailed::Refused(m)) => return Err(RenderError::Gpu(m)),
        Err(BuildFailed::TooSlow) => {
            std::mem::forget(offscreen);
            return Err(RenderError::Stopped(build_too_slow(&compiled.file)));
        }
    };
    let mut offscreen = offscreen;
    for k in 0..count {
        let mut frame = FrameUniforms::at(time + f64::from(k) / fps, k, size);
        frame.time_delta = (1.0 / fps) as f32;
        frame.frame_rate = fps as f32;
        if let Err(stopped) = offscreen.draw(gpu, &pipeline, params, &frame) {
            std::mem::forget((offscreen, pipeline));
            return Err(RenderError::Stopped(format!(
                "{}: {stopped}",
                compiled.file
            )));
        }
        let wait = |e: GpuWaitError| RenderError::Wait(e.to_string());
        let stats = if k == 0 {
            offscreen.stats(gpu).map_err(wait)?
        } else {
            CanvasStats::default()
        };
        let image = offscreen.image(gpu).map_err(wait)?;
        each(k, image, stats).map_err(RenderError::Output)?;
    }
    Ok(())
}

/// Compiles `path` and renders one frame at `time` seconds (frame 0) with
/// the default parameters, or `params` if given.
pub fn render_file(
    gpu: &Gpu,
    path: &Path,
    size: (u32, u32),
    time: f64,
    params: Option<&ParamSet>,
) -> Result<(image::RgbaImage, CanvasStats), String> {
    let compiled = compile_file(path).map_err(|e| e.to_string())?;
    let params = params.unwrap_or(&compiled.params);
    render_once(gpu, &compiled, params, &FrameUniforms::at(time, 0, size))
}
