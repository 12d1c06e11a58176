//! Headless rendering: the tracer into an offscreen texture, read back to the CPU.

use web_time::{Duration, Instant};

use super::context::{Gpu, GpuWaitError, SizeError};
use super::features::ShaderOptions;
use super::layout::PackedScene;
use super::limits::BufferLimitError;
use super::shaders::ShaderSource;
use super::texture::readback_target;
use super::timer::{GpuTimer, Timing};
use super::tracer::{
    Accumulator, FrameTarget, PipelineError, Pipelines, SceneBuffers, encode_frame,
};
use super::view::{ColourBar, View, colour_bar};
use crate::scene::Scene;

/// The offscreen target: 8-bit, and `fs_display` encodes sRGB itself so the
/// exact formula of docs/rendering-model.md, "Output" is used.
const OUTPUT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// Samples traced per submission. Long single draws can trip the watchdog of
/// a desktop GPU driver; a few samples per submission stay well clear of it.
const SAMPLES_PER_SUBMIT: u32 = 8;

/// Why an offscreen renderer could not be made or could not render.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The shader or pipeline (the user's input).
    #[error(transparent)]
    Pipeline(#[from] PipelineError),
    /// The image size (the user's input).
    #[error(transparent)]
    Size(#[from] SizeError),
    /// The scene does not fit in the GPU's buffers (the user's input).
    #[error(transparent)]
    Buffers(#[from] BufferLimitError),
    /// The GPU did not deliver the image (the machine, or a shader too slow).
    #[error(transparent)]
    Gpu(#[from] GpuWaitError),
}

impl RenderError {
    /// Whether the user's input caused it (exit status 2 on the command line).
    pub fn is_input(&self) -> bool {
        !matches!(self, RenderError::Gpu(_))
    }
}

/// Everything needed to render one scene at one size, again and again.
pub struct OffscreenRenderer {
    pipelines: Pipelines,
    scene: SceneBuffers,
    accum: Accumulator,
    target: wgpu::Texture,
    timer: Option<GpuTimer>,
    view: View,
}

impl OffscreenRenderer {
    pub fn new(
        gpu: &Gpu,
        source: &ShaderSource,
        options: &ShaderOptions,
        scene: &Scene,
        width: u32,
        height: u32,
    ) -> Result<Self, RenderError> {
        gpu.check_size((width, height))?;
        let device = &gpu.device;
        let pipelines = Pipelines::new(device, source, &[OUTPUT_FORMAT], options)?;
        let scene = SceneBuffers::new(
            (device, &gpu.queue),
            &pipelines,
            PackedScene::new(scene, width, height),
        )?;
        let accum = Accumulator::new(device, &pipelines, width, height);
        let target = readback_target(device, "offscreen image", (width, height), OUTPUT_FORMAT);
        Ok(OffscreenRenderer {
            pipelines,
            scene,
            accum,
            target,
            timer: GpuTimer::new(gpu),
            view: options.view,
        })
    }

    /// Takes a changed scene of the same features (as the viewer does while
    /// a slider moves): its buffers are made again, those whose contents
    /// did not change shared, and the pipelines kept. The samples so far
    /// are dropped. A scene too large for the device's buffers is refused
    /// and the last one stays.
    pub fn set_scene(&mut self, gpu: &Gpu, scene: &Scene) -> Result<(), BufferLimitError> {
        self.scene = self.scene.changed_to(
            (&gpu.device, &gpu.queue),
            &self.pipelines,
            scene,
            self.accum.size(),
        )?;
        self.accum.reset();
        Ok(())
    }

    /// How [`Self::render`] measures time.
    pub fn timing(&self) -> Timing {
        match self.timer {
            Some(_) => Timing::GpuTimestamps,
            None => Timing::SubmitToDone,
        }
    }

    /// Traces `spp` samples per pixel from scratch and waits for the GPU.
    /// Returns the GPU time of the work (see [`Self::timing`]: timestamps
    /// where the adapter has them, else submission to completion).
    pub fn render(&mut self, gpu: &Gpu, spp: u32) -> Result<Duration, GpuWaitError> {
        self.accum.reset();
        self.accumulate(gpu, spp)
    }

    /// Adds `spp` samples per pixel to those already accumulated (as the
    /// viewer does frame after frame) and waits for the GPU; returns the GPU
    /// time as [`Self::render`] does. Samples are traced in submissions of
    /// at most [`SAMPLES_PER_SUBMIT`], each waited for (see [`Gpu::wait`]).
    pub fn accumulate(&mut self, gpu: &Gpu, spp: u32) -> Result<Duration, GpuWaitError> {
        let start = Instant::now();
        let mut gpu_time = Duration::ZERO;
        let view = self.target.create_view(&Default::default());
        let target = FrameTarget {
            view: &view,
            format: OUTPUT_FORMAT,
            size: self.accum.size(),
        };
        let mut remaining = spp.max(1);
        while remaining > 0 {
            let batch = remaining.min(SAMPLES_PER_SUBMIT);
            let mut encoder = gpu.device.create_command_encoder(&Default::default());
            if let Some(timer) = &self.timer {
                timer.begin(&mut encoder);
            }
            encode_frame(
                &gpu.queue,
                &mut encoder,
                &self.pipelines,
                &self.scene,
                &mut self.accum,
                batch,
                &target,
            );
            if let Some(timer) = &self.timer {
                timer.end(&mut encoder);
            }
            gpu.queue.submit([encoder.finish()]);
            gpu.wait()?;
            if let Some(time) = self.timer.as_ref().and_then(|t| t.read(gpu)) {
                gpu_time += time;
            }
            remaining -= batch;
        }
        Ok(match self.timer {
            Some(_) => gpu_time,
            None => start.elapsed(),
        })
    }

    /// Samples per pixel accumulated so far.
    pub fn samples(&self) -> u32 {
        self.accum.samples()
    }

    /// For a scalar view (`View::scalar`), after a render: reads the
    /// quantities back, fits the colour bar to them and displays the image
    /// again with it; returns the bar (`None` for the other views, and
    /// where no pixel has a quantity).
    pub fn fit_colour_bar(&mut self, gpu: &Gpu) -> Result<Option<ColourBar>, GpuWaitError> {
        if !self.view.scalar() {
            return Ok(None);
        }
        let fitted = fit_colour_bar(gpu, &mut self.scene, &self.accum)?;
        if fitted.is_some() {
            // A view's later samples copy the first (`view_trace`): this
            // one only displays the image again, with the bar.
            self.accumulate(gpu, 1)?;
        }
        Ok(fitted)
    }

    /// Shows `quantities` (four floats per pixel, row by row) in place of
    /// the view's own, with a colour bar over `range`, or fitted to them
    /// for `None`: the error view's errors
    /// ([`crate::reference::ErrorImage::quantities`]). Returns the bar,
    /// `None` when nothing was shown (no quantities, another size).
    pub fn show_quantities(
        &mut self,
        gpu: &Gpu,
        quantities: &[f32],
        range: Option<[f32; 2]>,
    ) -> Result<Option<ColourBar>, GpuWaitError> {
        let shown = show_quantities(gpu, &mut self.scene, &self.accum, quantities, range);
        if shown.is_some() {
            // As in `fit_colour_bar`: this pass copies them and displays.
            self.accumulate(gpu, 1)?;
        }
        Ok(shown)
    }

    /// The per-pixel sums of the passes since the last [`Self::render`],
    /// four floats per pixel, row by row: the radiance (and 1 per pass), or
    /// in the ray-counting variant (`ShaderOptions::count_rays`) the rays
    /// traced by kind; in a view (`ShaderOptions::view`) its quantity at
    /// the pixel centre (`view_quantity` in `shaders/views.wgsl`).
    pub fn read_sums(&self, gpu: &Gpu) -> Result<Vec<f32>, GpuWaitError> {
        read_sums(gpu, &self.accum)
    }

    /// Copies the last rendered image back to the CPU.
    pub fn read_image(&self, gpu: &Gpu) -> Result<image::RgbaImage, GpuWaitError> {
        read_texture(gpu, &self.target)
    }
}

/// Reads a view's quantities back from `accum` (waiting for the GPU) and
/// sets `scene`'s colour bar to fit them ([`colour_bar`]); the next pass
/// encoded shows it. `None`, and nothing set, where no pixel has one.
pub(super) fn fit_colour_bar(
    gpu: &Gpu,
    scene: &mut SceneBuffers,
    accum: &Accumulator,
) -> Result<Option<ColourBar>, GpuWaitError> {
    Ok(fit_colour_bar_to(scene, &read_sums(gpu, accum)?))
}

/// Sets `scene`'s colour bar to fit a view's `quantities` ([`colour_bar`]);
/// the next pass encoded shows it. `None`, and nothing set, where no
/// pixel has one.
pub(super) fn fit_colour_bar_to(scene: &mut SceneBuffers, quantities: &[f32]) -> Option<ColourBar> {
    let fitted = colour_bar(quantities);
    if let Some(bar) = fitted {
        scene.set_view_range(bar.range);
    }
    fitted
}

/// The current sums of `accum`, four floats per pixel, row by row
/// (waited for).
pub(super) fn read_sums(gpu: &Gpu, accum: &Accumulator) -> Result<Vec<f32>, GpuWaitError> {
    Ok(bytemuck::pod_collect_to_vec(&read_texels(
        gpu,
        accum.sum(),
    )?))
}

/// Writes `quantities` into `accum` in place of the traced ones and sets
/// `scene`'s colour bar to `range`, or to fit them for `None`; the next
/// pass encoded shows them. `None`, and nothing written, where they have
/// no quantity or another size.
pub(super) fn show_quantities(
    gpu: &Gpu,
    scene: &mut SceneBuffers,
    accum: &Accumulator,
    quantities: &[f32],
    range: Option<[f32; 2]>,
) -> Option<ColourBar> {
    let mut bar = colour_bar(quantities)?;
    if let Some(range) = range {
        bar.range = range;
    }
    if !accum.write_sum(&gpu.queue, quantities) {
        return None;
    }
    scene.set_view_range(bar.range);
    Some(bar)
}

/// Copies an `Rgba8Unorm` texture back to the CPU and waits for it.
pub fn read_texture(gpu: &Gpu, texture: &wgpu::Texture) -> Result<image::RgbaImage, GpuWaitError> {
    let texels = read_texels(gpu, texture)?;
    Ok(
        image::RgbaImage::from_raw(texture.width(), texture.height(), texels)
            .expect("buffer holds the whole image"),
    )
}

/// Copies a texture back to the CPU and waits for it: its texels row by
/// row, without the padding a texture-to-buffer copy needs per row. A GPU
/// that does not finish (see [`Gpu::wait`]) or fails to map the copy is an
/// error, never a panic: a user's shader can cause it.
pub fn read_texels(gpu: &Gpu, texture: &wgpu::Texture) -> Result<Vec<u8>, GpuWaitError> {
    let read = TexelRead::start(gpu, texture);
    gpu.wait()?;
    read.try_take().unwrap_or_else(|| {
        Err(GpuWaitError::Lost(
            "the readback buffer was never mapped".into(),
        ))
    })
}

/// A copy of a texture on its way back to the CPU, without waiting: in
/// the browser a buffer is mapped only once control has returned to the
/// page's event loop, so a later frame picks the texels up
/// (docs/web.md, "Differences from the native program, and why");
/// natively [`Gpu::wait`] maps it.
pub struct TexelRead {
    buffer: wgpu::Buffer,
    mapped: std::sync::mpsc::Receiver<Result<(), wgpu::BufferAsyncError>>,
    row_bytes: u32,
    padded_row: u32,
}

impl TexelRead {
    /// Submits the copy of `texture` and asks for its buffer to be mapped.
    pub fn start(gpu: &Gpu, texture: &wgpu::Texture) -> Self {
        let height = texture.height();
        let texel_bytes = texture
            .format()
            .block_copy_size(None)
            .expect("a colour format");
        let row_bytes = texture.width() * texel_bytes;
        let padded_row = row_bytes.next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: u64::from(padded_row) * u64::from(height),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded_row),
                    rows_per_image: Some(height),
                },
            },
            texture.size(),
        );
        gpu.queue.submit([encoder.finish()]);
        let (sender, mapped) = std::sync::mpsc::channel();
        buffer
            .slice(..)
            .map_async(wgpu::MapMode::Read, move |result| {
                let _ = sender.send(result);
            });
        TexelRead {
            buffer,
            mapped,
            row_bytes,
            padded_row,
        }
    }

    /// The texels, row by row without padding, once the buffer is mapped;
    /// `None` before. A copy that failed to map is an error.
    pub fn try_take(&self) -> Option<Result<Vec<u8>, GpuWaitError>> {
        let mapped = self.mapped.try_recv().ok()?;
        Some(
            mapped
                .map_err(|e| GpuWaitError::Lost(e.to_string()))
                .and_then(|()| self.texels()),
        )
    }

    /// The mapped buffer's rows without their padding.
    fn texels(&self) -> Result<Vec<u8>, GpuWaitError> {
        let data = self
            .buffer
            .slice(..)
            .get_mapped_range()
            .map_err(|e| GpuWaitError::Lost(e.to_string()))?;
        let rows = data.chunks(self.padded_row as usize);
        let mut texels = Vec::with_capacity(rows.len() * self.row_bytes as usize);
        for row in rows {
            texels.extend_from_slice(&row[..self.row_bytes as usize]);
        }
        Ok(texels)
    }
}

/// Renders `scene` once at `spp` samples per pixel with the embedded shader.
pub fn render_image(
    gpu: &Gpu,
    scene: &Scene,
    width: u32,
    height: u32,
    spp: u32,
) -> Result<image::RgbaImage, RenderError> {
    let mut renderer = OffscreenRenderer::new(
        gpu,
        &ShaderSource::embedded(),
        &ShaderOptions::generic(scene),
        scene,
        width,
        height,
    )?;
    renderer.render(gpu, spp)?;
    Ok(renderer.read_image(gpu)?)
}
