//! Headless rendering: the tracer into an offscreen texture, read back to the CPU.

use std::time::{Duration, Instant};

use super::context::Gpu;
use super::features::ShaderOptions;
use super::layout::PackedScene;
use super::shaders::ShaderSource;
use super::texture::render_target;
use super::timer::{GpuTimer, Timing};
use super::tracer::{
    Accumulator, FrameTarget, PipelineError, Pipelines, SceneBuffers, encode_frame,
};
use crate::scene::Scene;

/// The offscreen target: 8-bit, and `fs_display` encodes sRGB itself so the
/// exact formula of docs/rendering-model.md, "Output" is used.
const OUTPUT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// Samples traced per submission. Long single draws can trip the watchdog of
/// a desktop GPU driver; a few samples per submission stay well clear of it.
const SAMPLES_PER_SUBMIT: u32 = 8;

/// Everything needed to render one scene at one size, again and again.
pub struct OffscreenRenderer {
    pipelines: Pipelines,
    scene: SceneBuffers,
    accum: Accumulator,
    target: wgpu::Texture,
    timer: Option<GpuTimer>,
}

impl OffscreenRenderer {
    pub fn new(
        gpu: &Gpu,
        source: &ShaderSource,
        options: &ShaderOptions,
        scene: &Scene,
        width: u32,
        height: u32,
    ) -> Result<Self, PipelineError> {
        let device = &gpu.device;
        let pipelines = Pipelines::new(device, source, &[OUTPUT_FORMAT], options)?;
        let scene = SceneBuffers::new(device, &pipelines, PackedScene::new(scene, width, height));
        let accum = Accumulator::new(device, &pipelines, width, height);
        let target = render_target(
            device,
            "offscreen image",
            (width, height),
            OUTPUT_FORMAT,
            wgpu::TextureUsages::COPY_SRC,
        );
        Ok(OffscreenRenderer {
            pipelines,
            scene,
            accum,
            target,
            timer: GpuTimer::new(gpu),
        })
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
    pub fn render(&mut self, gpu: &Gpu, spp: u32) -> Duration {
        let start = Instant::now();
        let mut gpu_time = Duration::ZERO;
        self.accum.reset();
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
            if let Some(time) = self.timer.as_ref().and_then(|t| t.read(gpu)) {
                gpu_time += time;
            }
            remaining -= batch;
        }
        gpu.device
            .poll(wgpu::PollType::wait_indefinitely())
            .expect("waiting for the GPU");
        match self.timer {
            Some(_) => gpu_time,
            None => start.elapsed(),
        }
    }

    /// Copies the last rendered image back to the CPU.
    pub fn read_image(&self, gpu: &Gpu) -> image::RgbaImage {
        read_texture(gpu, &self.target)
    }
}

/// Copies an `Rgba8Unorm` texture back to the CPU and waits for it.
pub fn read_texture(gpu: &Gpu, texture: &wgpu::Texture) -> image::RgbaImage {
    image::RgbaImage::from_raw(texture.width(), texture.height(), read_texels(gpu, texture))
        .expect("buffer holds the whole image")
}

/// Copies a texture back to the CPU and waits for it: its texels row by
/// row, without the padding a texture-to-buffer copy needs per row.
pub fn read_texels(gpu: &Gpu, texture: &wgpu::Texture) -> Vec<u8> {
    let (width, height) = (texture.width(), texture.height());
    let texel_bytes = texture
        .format()
        .block_copy_size(None)
        .expect("a colour format");
    let row_bytes = width * texel_bytes;
    let padded_row = row_bytes.next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let readback = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: u64::from(padded_row) * u64::from(height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &readback,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded_row),
                rows_per_image: Some(height),
            },
        },
        texture.size(),
    );
    gpu.queue.submit([encoder.finish()]);
    let slice = readback.slice(..);
    slice.map_async(wgpu::MapMode::Read, |result| {
        result.expect("mapping the readback buffer")
    });
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .expect("waiting for the GPU");
    let data = slice.get_mapped_range().expect("mapped readback buffer");
    let mut texels = Vec::with_capacity((row_bytes * height) as usize);
    for row in data.chunks(padded_row as usize) {
        texels.extend_from_slice(&row[..row_bytes as usize]);
    }
    texels
}

/// Renders `scene` once at `spp` samples per pixel with the embedded shader.
pub fn render_image(
    gpu: &Gpu,
    scene: &Scene,
    width: u32,
    height: u32,
    spp: u32,
) -> Result<image::RgbaImage, PipelineError> {
    let mut renderer = OffscreenRenderer::new(
        gpu,
        &ShaderSource::embedded(),
        &ShaderOptions::default(),
        scene,
        width,
        height,
    )?;
    renderer.render(gpu, spp);
    Ok(renderer.read_image(gpu))
}
