//! Multipass shaders without a window: `raysandbox shader DIR|FILE.json
//! --render OUT.png` or `--frames N --out DIR`, the lines of `--check-all`,
//! and [`MultipassOffscreen`] for tests.

use std::path::Path;
use std::time::Instant;

use super::compile::CompiledProject;
use super::gpu::{Buffers, PassDraw, pass_builder};
use super::{Project, compile_project};
use crate::gpu::{EXPORT_FORMAT, Gpu, GpuWaitError};
use crate::sandbox::render::{
    BuildFailed, Canvas, FRAME_LIMIT, NanColor, SandboxGpu, ShaderPipeline, TooSlow,
    build_too_slow, wait_for_frame,
};
use crate::sandbox::{CanvasStats, FrameUniforms, SandboxError, ShaderArgs, channels};

/// Why [`MultipassOffscreen::new`] gave nothing: a pipeline wgpu refused
/// (the message at the pass), or one the driver did not finish compiling
/// in [`FRAME_LIMIT`] (the device is busy: leaked by the caller).
#[derive(Debug)]
pub enum Unbuilt {
    Refused(String),
    TooSlow(String),
}

/// A compiled multipass shader drawn into textures, frame after frame.
pub struct MultipassOffscreen {
    sandbox: SandboxGpu,
    canvas: Canvas,
    buffers: Buffers,
    project: CompiledProject,
    pipelines: Vec<ShaderPipeline>,
}

impl MultipassOffscreen {
    /// Builds every pass's pipeline (each within [`FRAME_LIMIT`]).
    pub fn new(
        gpu: &Gpu,
        project: CompiledProject,
        size: (u32, u32),
        nan: NanColor,
    ) -> Result<Self, Unbuilt> {
        let sandbox = SandboxGpu::new(gpu, &[EXPORT_FORMAT], nan);
        let builder = sandbox.builder(&gpu.device);
        let mut pipelines = Vec::new();
        for pass in &project.passes {
            let builder = pass_builder(&builder, pass.kind);
            match builder.build_within(&pass.compiled, FRAME_LIMIT) {
                Ok(p) => pipelines.push(p),
                Err(BuildFailed::Refused(m)) => return Err(Unbuilt::Refused(m)),
                Err(BuildFailed::TooSlow) => {
                    std::mem::forget((sandbox, pipelines));
                    return Err(Unbuilt::TooSlow(build_too_slow(&pass.compiled.file)));
                }
            }
        }
        let mut buffers = Buffers::new(gpu, size);
        let bindings: Vec<_> = project
            .passes
            .iter()
            .map(|p| (p.kind, &p.channels))
            .collect();
        buffers
            .prepare(gpu, &bindings, &channels::load)
            .map_err(Unbuilt::Refused)?;
        Ok(MultipassOffscreen {
            canvas: Canvas::new(gpu, &sandbox, size),
            sandbox,
            buffers,
            project,
            pipelines,
        })
    }

    /// Draws one frame (every pass) and waits for it, at most
    /// [`FRAME_LIMIT`]; see [`crate::sandbox::Offscreen::draw`].
    pub fn draw(&mut self, gpu: &Gpu, frame: &FrameUniforms) -> Result<(), TooSlow> {
        let size = (frame.resolution[0] as u32, frame.resolution[1] as u32);
        self.canvas.resize(gpu, &self.sandbox, size);
        self.buffers.resize(gpu, size);
        let draws: Vec<PassDraw> = self
            .project
            .passes
            .iter()
            .zip(&self.pipelines)
            .map(|(pass, pipeline)| PassDraw {
                kind: pass.kind,
                channels: &pass.channels,
                pipeline,
                params: &pass.compiled.params,
            })
            .collect();
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        self.buffers.draw(
            gpu,
            &self.sandbox,
            &mut encoder,
            &draws,
            frame,
            &mut self.canvas,
        );
        let submission = gpu.queue.submit([encoder.finish()]);
        wait_for_frame(gpu, submission)
    }

    /// Clears the buffers, as `R` in the window.
    pub fn reset(&mut self, gpu: &Gpu) {
        self.buffers.reset(gpu);
    }

    /// The Image pass's last frame as 8-bit RGBA.
    pub fn image(&self, gpu: &Gpu) -> Result<image::RgbaImage, GpuWaitError> {
        self.canvas.capture(gpu, &self.sandbox)
    }

    /// The Image pass's last frame as it wrote it (f32 RGBA, top row
    /// first).
    pub fn texels(&self, gpu: &Gpu) -> Result<Vec<[f32; 4]>, GpuWaitError> {
        self.canvas.texels(gpu)
    }

    pub fn stats(&self, gpu: &Gpu) -> Result<CanvasStats, GpuWaitError> {
        self.canvas.stats(gpu)
    }
}

/// Reads and compiles a folder or JSON file; the error names the file.
pub fn load(path: &Path) -> Result<(Project, CompiledProject), String> {
    let project = Project::load(path)?;
    let compiled = compile_project(&project).map_err(|e| e.to_string())?;
    Ok((project, compiled))
}

/// `--render` and `--frames` of a multipass shader: frame k at time
/// `--time + k / fps`, with `iFrame` = k, the buffers carried from frame to
/// frame.
pub fn run(args: &ShaderArgs) -> Result<(), SandboxError> {
    let (project, compiled) = load(&args.file).map_err(SandboxError::Input)?;
    for w in &project.warnings {
        eprintln!("warning: {w}");
    }
    for pass in &compiled.passes {
        for w in &pass.compiled.warnings {
            eprintln!("{w}");
        }
    }
    let gpu = Gpu::headless().map_err(|e| SandboxError::Runtime(e.to_string()))?;
    println!("adapter: {}", gpu.describe());
    let size = args.size.unwrap_or((1280, 720));
    gpu.check_size(size)
        .map_err(|e| SandboxError::Input(format!("--size: {e}")))?;
    let count = args.frames.unwrap_or(1);
    let out_dir = args.out.as_deref().filter(|_| args.frames.is_some());
    if let Some(dir) = out_dir {
        std::fs::create_dir_all(dir)
            .map_err(|e| SandboxError::Runtime(format!("{}: {e}", dir.display())))?;
    }
    let start = Instant::now();
    let mut offscreen = match MultipassOffscreen::new(&gpu, compiled, size, args.nan_color) {
        Ok(o) => o,
        Err(Unbuilt::Refused(m)) => return Err(SandboxError::Input(m)),
        Err(Unbuilt::TooSlow(m)) => {
            std::mem::forget(gpu);
            return Err(SandboxError::Input(m));
        }
    };
    for k in 0..count {
        let mut frame = FrameUniforms::at(args.time + f64::from(k) / args.fps, k, size);
        frame.time_delta = (1.0 / args.fps) as f32;
        frame.frame_rate = args.fps as f32;
        if let Err(stopped) = offscreen.draw(&gpu, &frame) {
            std::mem::forget((offscreen, gpu));
            return Err(SandboxError::Input(format!(
                "{}: {stopped}",
                args.file.display()
            )));
        }
        let path = match (out_dir, &args.render) {
            (Some(dir), _) => dir.join(format!("frame-{k:05}.png")),
            (None, Some(path)) => path.clone(),
            (None, None) => unreachable!("run_headless renders with --render or --frames"),
        };
        let image = offscreen
            .image(&gpu)
            .map_err(|e| SandboxError::Runtime(e.to_string()))?;
        image
            .save(&path)
            .map_err(|e| SandboxError::Runtime(format!("{}: {e}", path.display())))?;
        if out_dir.is_none() {
            println!("wrote {}", path.display());
        }
    }
    crate::sandbox::report_rendered(out_dir, count, size, start);
    Ok(())
}
