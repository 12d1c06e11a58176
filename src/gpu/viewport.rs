//! The tracer drawing into a window surface, with progressive refinement, a
//! resolution scale and the selection outline. Knows nothing of egui: whoever draws on top of the
//! image gets the frame's encoder and view through a callback.

use std::sync::{Arc, Mutex, PoisonError};

use web_time::{Duration, Instant};

use super::context::{Gpu, GpuWaitError};
use super::id_pass::FirstHit;
use super::interaction::MIN_SCALE;
use super::layout::PackedScene;
use super::outline::Outline;
use super::texture::render_target;
use super::timer::{GpuTimer, Timing};
use super::tracer::{Accumulator, FrameTarget, Pipelines, SceneBuffers, encode_frame};
use crate::scene::{Scene, ShapeId};

/// Format of screenshots: 8-bit RGBA with the exact sRGB formula of the rendering model.
pub const EXPORT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// What happened to a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameStatus {
    /// Drawn and presented.
    Presented,
    /// Not drawn: the window is minimised or the surface was busy or had to
    /// be reconfigured; draw again later.
    Skipped,
}

/// A window's surface and everything the tracer needs to draw into it.
pub struct Viewport {
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    pipelines: Pipelines,
    scene: SceneBuffers,
    accum: Accumulator,
    /// Fraction of the window resolution that is traced (MIN_SCALE..=1).
    scale: f32,
    /// GPU time of the last frame that traced samples (see [`Self::timing`]).
    /// Shared with the queue's work-done callback, which writes it without
    /// timestamps: natively during the blocking wait after submission, in
    /// the browser (which cannot block) when the GPU reports the work done.
    last_frame_time: Arc<Mutex<Option<Duration>>>,
    timer: Option<GpuTimer>,
    /// The selected shape's outline, drawn over the image.
    outline: Outline,
}

impl Viewport {
    /// Configures `surface` for a window of `size` physical pixels.
    pub fn new(
        gpu: &Gpu,
        surface: wgpu::Surface<'static>,
        size: (u32, u32),
        pipelines: Pipelines,
        scene: &Scene,
    ) -> Self {
        let config = surface_config(gpu, &surface, size);
        if size.0 > 0 && size.1 > 0 {
            surface.configure(&gpu.device, &config);
        }
        let scene = SceneBuffers::new(
            (&gpu.device, &gpu.queue),
            &pipelines,
            PackedScene::new(scene, 1, 1),
        );
        let accum = Accumulator::new(&gpu.device, &pipelines, size.0.max(1), size.1.max(1));
        Viewport {
            surface,
            config,
            pipelines,
            scene,
            accum,
            scale: 1.0,
            last_frame_time: Arc::default(),
            timer: GpuTimer::new(gpu),
            outline: Outline::new(&gpu.device),
        }
    }

    /// The surface format: pipelines must have a display pass for it.
    pub fn surface_format(&self) -> wgpu::TextureFormat {
        self.config.format
    }

    /// The formats a [`Pipelines`] for this viewport must support.
    pub fn output_formats(gpu: &Gpu, surface: &wgpu::Surface) -> [wgpu::TextureFormat; 2] {
        [surface_config(gpu, surface, (1, 1)).format, EXPORT_FORMAT]
    }

    /// Follows a window resize; a zero size (minimised) just stops drawing.
    pub fn resize(&mut self, gpu: &Gpu, size: (u32, u32)) {
        self.config.width = size.0;
        self.config.height = size.1;
        if size.0 > 0 && size.1 > 0 {
            self.surface.configure(&gpu.device, &self.config);
            self.resize_accumulator(gpu);
        }
    }

    /// Sets the traced fraction of the window resolution; restarts refinement
    /// when the traced size changes.
    pub fn set_scale(&mut self, gpu: &Gpu, scale: f32) {
        let scale = scale.clamp(MIN_SCALE, 1.0);
        if scale != self.scale {
            self.scale = scale;
            self.resize_accumulator(gpu);
        }
    }

    fn traced_size(&self) -> (u32, u32) {
        let scaled = |n: u32| ((n as f32 * self.scale).round() as u32).clamp(1, n.max(1));
        (scaled(self.config.width), scaled(self.config.height))
    }

    fn resize_accumulator(&mut self, gpu: &Gpu) {
        let (w, h) = self.traced_size();
        if self.accum.size() != (w, h) {
            self.accum = Accumulator::new(&gpu.device, &self.pipelines, w, h);
        }
        self.accum.reset();
    }

    /// Uploads a changed scene and restarts refinement.
    pub fn set_scene(&mut self, gpu: &Gpu, scene: &Scene) {
        let packed = PackedScene::new(scene, 1, 1);
        self.scene = SceneBuffers::reusing(
            (&gpu.device, &gpu.queue),
            &self.pipelines,
            packed,
            &self.scene,
        );
        self.accum.reset();
    }

    /// Takes a scene whose shapes, materials and lights are unchanged (only
    /// camera or render settings differ): no buffers are rebuilt.
    pub fn set_view(&mut self, scene: &Scene) {
        self.scene.set_view(scene);
        self.accum.reset();
    }

    /// Swaps in new pipelines (after a shader reload) and restarts refinement.
    /// The scene buffers and accumulator are rebuilt against their layouts.
    pub fn set_pipelines(&mut self, gpu: &Gpu, pipelines: Pipelines) {
        self.pipelines = pipelines;
        self.scene = SceneBuffers::new(
            (&gpu.device, &gpu.queue),
            &self.pipelines,
            self.scene.packed().clone(),
        );
        let (w, h) = self.accum.size();
        self.accum = Accumulator::new(&gpu.device, &self.pipelines, w, h);
        self.outline.forget_layouts();
    }

    /// Outlines `shape` (or nothing) with a band `radius` pixels wide; only
    /// with pipelines made [`Pipelines::with_outline`].
    pub fn set_selection(&mut self, gpu: &Gpu, shape: Option<ShapeId>, radius: u32) {
        self.outline
            .select(&gpu.queue, FirstHit::id_of(shape), radius);
    }

    /// Forgets the accumulated samples (e.g. the camera moved).
    pub fn restart(&mut self) {
        self.accum.reset();
    }

    /// Samples per pixel accumulated so far.
    pub fn samples(&self) -> u32 {
        self.accum.samples()
    }

    /// The traced fraction of the window resolution.
    pub fn scale(&self) -> f32 {
        self.scale
    }

    /// Size of the traced image in pixels.
    pub fn traced_resolution(&self) -> (u32, u32) {
        self.accum.size()
    }

    /// How frame times are measured: timestamps where the adapter has them.
    pub fn timing(&self) -> Timing {
        match self.timer {
            Some(_) => Timing::GpuTimestamps,
            None => Timing::SubmitToDone,
        }
    }

    /// GPU time of the last frame that traced samples.
    pub fn last_frame_time(&self) -> Option<Duration> {
        *self
            .last_frame_time
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
    }

    /// Draws a frame: `new_samples` more samples per pixel (0 = only show the
    /// image again), then `overlay` draws on top into the same view; the
    /// command buffers it returns are submitted before the frame's own.
    pub fn frame(
        &mut self,
        gpu: &Gpu,
        new_samples: u32,
        overlay: impl FnOnce(&mut wgpu::CommandEncoder, &wgpu::TextureView) -> Vec<wgpu::CommandBuffer>,
    ) -> FrameStatus {
        if self.config.width == 0 || self.config.height == 0 {
            return FrameStatus::Skipped;
        }
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame) => frame,
            wgpu::CurrentSurfaceTexture::Suboptimal(frame) => {
                // Usable this once; reconfigure for the next frame.
                self.surface.configure(&gpu.device, &self.config);
                frame
            }
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&gpu.device, &self.config);
                return FrameStatus::Skipped;
            }
            other => {
                log::debug!("surface not ready: {other:?}");
                return FrameStatus::Skipped;
            }
        };
        let view = frame
            .texture
            .create_view(&wgpu::TextureViewDescriptor::default());
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        if self.accum.samples() == 0 {
            // Refinement starts over: what the image shows changed.
            self.outline.invalidate();
        }
        let timer = self.timer.as_ref().filter(|_| new_samples > 0);
        if let Some(timer) = timer {
            timer.begin(&mut encoder);
        }
        encode_frame(
            &gpu.queue,
            &mut encoder,
            &self.pipelines,
            &self.scene,
            &mut self.accum,
            new_samples,
            &FrameTarget {
                view: &view,
                format: self.config.format,
                size: (self.config.width, self.config.height),
            },
        );
        if let Some(timer) = timer {
            timer.end(&mut encoder);
        }
        if let Some(outline) = self.pipelines.outline() {
            self.outline.encode(
                &gpu.device,
                &mut encoder,
                outline,
                &self.scene.bind_group,
                self.accum.size(),
                (&view, self.config.format),
            );
        }
        let mut buffers = overlay(&mut encoder, &view);
        buffers.push(encoder.finish());
        let start = Instant::now();
        gpu.queue.submit(buffers);
        if new_samples > 0 && timer.is_none() {
            let slot = Arc::clone(&self.last_frame_time);
            gpu.queue.on_submitted_work_done(move || {
                *slot.lock().unwrap_or_else(PoisonError::into_inner) = Some(start.elapsed());
            });
        }
        // Waiting here keeps the frame time honest and input latency low;
        // frames are only drawn on demand, so nothing else is waiting for us.
        // (The browser cannot wait: there this returns at once.)
        let _ = gpu.device.poll(wgpu::PollType::wait_indefinitely());
        if let Some(timer) = timer {
            let time = timer.read(gpu);
            *self
                .last_frame_time
                .lock()
                .unwrap_or_else(PoisonError::into_inner) = time;
        }
        gpu.queue.present(frame);
        FrameStatus::Presented
    }

    /// The current image at the traced resolution, without anything drawn
    /// on top, as 8-bit sRGB (for screenshots and tests).
    pub fn capture(&mut self, gpu: &Gpu) -> Result<image::RgbaImage, GpuWaitError> {
        let size = self.accum.size();
        let texture = render_target(
            &gpu.device,
            "screenshot",
            size,
            EXPORT_FORMAT,
            wgpu::TextureUsages::COPY_SRC,
        );
        let view = texture.create_view(&Default::default());
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encode_frame(
            &gpu.queue,
            &mut encoder,
            &self.pipelines,
            &self.scene,
            &mut self.accum,
            0,
            &FrameTarget {
                view: &view,
                format: EXPORT_FORMAT,
                size,
            },
        );
        gpu.queue.submit([encoder.finish()]);
        super::offscreen::read_texture(gpu, &texture)
    }
}

/// Surface settings: a plain (non-sRGB) 8-bit format when there is one, so
/// the display pass encodes with the exact formula of the rendering model, as in PNG
/// output, and egui's colours (already sRGB) are written unchanged; FIFO
/// presentation (no tearing, and supported everywhere).
fn surface_config(
    gpu: &Gpu,
    surface: &wgpu::Surface,
    size: (u32, u32),
) -> wgpu::SurfaceConfiguration {
    let caps = surface.get_capabilities(&gpu.adapter);
    let format = caps
        .formats
        .iter()
        .copied()
        .find(|f| {
            matches!(
                f,
                wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm
            )
        })
        .unwrap_or(caps.formats[0]);
    wgpu::SurfaceConfiguration {
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        format,
        color_space: wgpu::SurfaceColorSpace::Auto,
        width: size.0,
        height: size.1,
        present_mode: wgpu::PresentMode::Fifo,
        desired_maximum_frame_latency: 2,
        alpha_mode: wgpu::CompositeAlphaMode::Auto,
        view_formats: vec![],
    }
}
