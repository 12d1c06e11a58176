//! The id/depth pass: which shape the ray through each pixel centre hits
//! first, and at which distance. `fs_id` of `shaders/main.wgsl` writes
//! `(kind, index, bits of t, 1)` into an `Rgba32Uint` target that is read
//! back here. The accuracy measurements (`raysandbox stress`) compare it with
//! the reference's `first_hits`, to tell a shape that is wrongly hit from a
//! colour that is merely a little off.

use super::context::Gpu;
use super::features::ShaderOptions;
use super::fullscreen;
use super::layout::PackedScene;
use super::offscreen::RenderError;
use super::offscreen::read_texels;
use super::outline::{ID_FORMAT, id_pipeline};
use super::shaders::ShaderSource;
use super::shapes::glue::{ALL_KINDS_BOUND, DataAccess};
use super::texture::readback_target;
use super::tracer::{PipelineError, SceneBuffers, in_error_scope, scene_layout_entries};
use crate::scene::{Scene, ShapeId};

/// What the ray through one pixel centre hits first.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FirstHit {
    /// The shader's `KIND_*`: 0 nothing, else the kind's
    /// `ShapeKind::number` (1 sphere, 2 plane, 3 cube, in registry order).
    pub kind: u32,
    /// Index into the array of that kind.
    pub index: u32,
    /// Distance along the (unit) ray; the shader's `T_FAR` on a miss.
    pub t: f32,
}

impl FirstHit {
    pub const NONE: u32 = 0;

    /// The kind number and index the shader reports for the reference's
    /// first hit (`NONE` and 0 for a miss).
    pub fn id_of(shape: Option<ShapeId>) -> (u32, u32) {
        shape.map_or((Self::NONE, 0), |id| {
            (id.kind().number(), id.index() as u32)
        })
    }
}

/// The `fs_id` pipeline, built once and run on any scene at any size.
pub struct IdRenderer {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    /// The naive variant packs in world coordinates, as its image pass does
    /// (`PackedScene::in_world`).
    robust: bool,
}

impl IdRenderer {
    /// Validates `source` and builds the pass. `options` sets the pipeline
    /// constants (robust or naive intersection).
    pub fn new(
        gpu: &Gpu,
        source: &ShaderSource,
        options: &ShaderOptions,
    ) -> Result<Self, PipelineError> {
        // The WGSL the kinds write for the scene is part of the source.
        let source = &source.with_generated(&options.kinds);
        source.validate()?;
        let device = &gpu.device;
        pollster::block_on(in_error_scope(device, || {
            Self::build(device, source, options)
        }))
    }

    fn build(device: &wgpu::Device, source: &ShaderSource, options: &ShaderOptions) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("raysandbox id pass"),
            source: wgpu::ShaderSource::Wgsl(source.text().into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("scene (id pass)"),
            // The source as given: its data textures are sampled
            // (`ShaderSource::embedded`, `ShaderSource::from_dir`).
            entries: &scene_layout_entries(ALL_KINDS_BOUND, DataAccess::Sampled),
        });
        IdRenderer {
            pipeline: id_pipeline(device, &module, &layout, options),
            layout,
            robust: options.robust,
        }
    }

    /// Runs the pass on `scene` at `width x height` and reads the result
    /// back: one [`FirstHit`] per pixel, row-major, the top row first.
    pub fn render(
        &self,
        gpu: &Gpu,
        scene: &Scene,
        width: u32,
        height: u32,
    ) -> Result<Vec<FirstHit>, RenderError> {
        let device = &gpu.device;
        let packed = if self.robust {
            PackedScene::new(scene, width, height)
        } else {
            PackedScene::in_world(scene, width, height)
        };
        let scene = SceneBuffers::with_layout(
            (device, &gpu.queue),
            (&self.layout, ALL_KINDS_BOUND),
            packed,
            None,
        )?;
        let bind_group = &scene.bind_group;
        let target = readback_target(device, "first hits", (width, height), ID_FORMAT);
        let view = target.create_view(&Default::default());
        let mut encoder = device.create_command_encoder(&Default::default());
        fullscreen::pass(&mut encoder, &self.pipeline, &[bind_group], &view);
        gpu.queue.submit([encoder.finish()]);
        let data = read_texels(gpu, &target)?;
        let mut hits = Vec::with_capacity(width as usize * height as usize);
        for texel in data.chunks_exact(16) {
            let [kind, index, t, _]: [u32; 4] = bytemuck::pod_read_unaligned(texel);
            hits.push(FirstHit {
                kind,
                index,
                t: f32::from_bits(t),
            });
        }
        Ok(hits)
    }
}
