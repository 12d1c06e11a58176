//! The two full-screen passes of `shaders/main.wgsl` and the resources they
//! read: pipelines, scene buffers and the accumulation textures.
//!
//! Per frame: `fs_trace` adds new samples to the running radiance sum
//! (ping-pong between two `Rgba32Float` textures, so no float blending is
//! needed), then `fs_display` divides by the sample count and encodes it into
//! the output target.

use std::sync::Arc;

use super::features::{ShaderOptions, borrowed};
use super::fullscreen;
use super::jobs::span_rects;
use super::layout::{Globals, PackedScene};
use super::limits::{BufferLimitError, check_buffers};
use super::outline::OutlinePipelines;
use super::shaders::{ShaderError, ShaderSource};
use super::shapes::glue::{DATA_TEXTURE_WIDTH, DataAccess, FIRST_SHAPE_BINDING, is_bound};
use super::texture::{OwnedTexture, render_target};
use wgpu::util::DeviceExt;

/// Where the radiance sum is kept: full f32 precision, so 1000s of samples
/// add up without banding.
pub(super) const ACCUM_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// Pipelines for one shader source: the trace pass, and a display pass for
/// each output format asked for (e.g. the window's and PNG export's).
/// Cloning is cheap (wgpu handles are reference counted).
#[derive(Clone)]
pub struct Pipelines {
    trace: wgpu::RenderPipeline,
    display: Vec<(wgpu::TextureFormat, wgpu::RenderPipeline)>,
    scene_layout: wgpu::BindGroupLayout,
    /// The shape kinds whose arrays `scene_layout` binds (bit
    /// `ShapeKind::number` per kind).
    bound_kinds: u32,
    accum_layout: wgpu::BindGroupLayout,
    /// The id and outline passes of the viewer's selection outline; only
    /// a window's pipelines have them ([`Pipelines::with_outline`]).
    outline: Option<OutlinePipelines>,
}

#[derive(Debug, thiserror::Error)]
pub enum PipelineError {
    #[error("{0}")]
    Shader(#[from] ShaderError),
    #[error("wgpu rejected the shader or pipeline: {0}")]
    Wgpu(String),
}

/// What `build` makes, or the validation error wgpu raised while it ran:
/// a pass builds its pipelines inside an error scope, so that a shader
/// wgpu rejects is an error its caller reports rather than a panic.
pub(super) async fn in_error_scope<T>(
    device: &wgpu::Device,
    build: impl FnOnce() -> T,
) -> Result<T, PipelineError> {
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let built = build();
    match scope.pop().await {
        Some(error) => Err(PipelineError::Wgpu(error.to_string())),
        None => Ok(built),
    }
}

impl Pipelines {
    /// Validates `source` with naga, then builds the pipelines. On any error
    /// nothing is built, so a caller can keep its previous pipelines. The
    /// display pass applies the sRGB transfer function itself unless the
    /// format is an `*Srgb` one, whose hardware conversion does it.
    pub fn new(
        device: &wgpu::Device,
        source: &ShaderSource,
        output_formats: &[wgpu::TextureFormat],
        options: &ShaderOptions,
    ) -> Result<Self, PipelineError> {
        pollster::block_on(Self::create(device, source, output_formats, options, false))
    }

    /// As [`Pipelines::new`], with the passes of the selection outline too
    /// (the viewer's window): headless renders need not compile them.
    pub fn with_outline(
        device: &wgpu::Device,
        source: &ShaderSource,
        output_formats: &[wgpu::TextureFormat],
        options: &ShaderOptions,
    ) -> Result<Self, PipelineError> {
        pollster::block_on(Self::create(device, source, output_formats, options, true))
    }

    /// As [`Pipelines::with_outline`], without blocking: in the browser
    /// wgpu reports validation errors only once control returns to the
    /// page's event loop (docs/web.md).
    pub async fn with_outline_async(
        device: &wgpu::Device,
        source: &ShaderSource,
        output_formats: &[wgpu::TextureFormat],
        options: &ShaderOptions,
    ) -> Result<Self, PipelineError> {
        Self::create(device, source, output_formats, options, true).await
    }

    async fn create(
        device: &wgpu::Device,
        source: &ShaderSource,
        output_formats: &[wgpu::TextureFormat],
        options: &ShaderOptions,
        outline: bool,
    ) -> Result<Self, PipelineError> {
        let (source, access) = &pipeline_source(device, source, options);
        source.validate()?;
        in_error_scope(device, || {
            Self::build(device, source, output_formats, options, outline, *access)
        })
        .await
    }

    fn build(
        device: &wgpu::Device,
        source: &ShaderSource,
        output_formats: &[wgpu::TextureFormat],
        options: &ShaderOptions,
        outline: bool,
        access: DataAccess,
    ) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("raysandbox tracer"),
            source: wgpu::ShaderSource::Wgsl(source.text().into()),
        });
        let scene_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("scene"),
            entries: &scene_layout_entries(options.features.shape_kinds, access),
        });
        let accum_layout = fullscreen::texture_layout(device, "accumulated radiance");
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("tracer"),
            bind_group_layouts: &[Some(&scene_layout), Some(&accum_layout)],
            immediate_size: 0,
        });
        let trace_constants = options.constants();
        let pass = |entry: &str, format, constants: &[(&str, f64)]| {
            fullscreen::pipeline(
                device,
                &layout,
                (&module, "vs_fullscreen"),
                (&module, entry),
                constants,
                format,
            )
        };
        let display = output_formats
            .iter()
            .map(|&format| {
                (
                    format,
                    pass(
                        "fs_display",
                        format,
                        &[
                            fullscreen::encode_srgb(format),
                            ("VIEW", f64::from(options.view.number())),
                        ],
                    ),
                )
            })
            .collect();
        Pipelines {
            trace: pass("fs_trace", ACCUM_FORMAT, &borrowed(&trace_constants)),
            display,
            outline: outline.then(|| {
                OutlinePipelines::new(device, &module, &scene_layout, output_formats, options)
            }),
            scene_layout,
            bound_kinds: options.features.shape_kinds,
            accum_layout,
        }
    }

    /// The layout of the scene's bind group, and the kinds whose arrays it binds.
    pub(super) fn scene_layout(&self) -> (&wgpu::BindGroupLayout, u32) {
        (&self.scene_layout, self.bound_kinds)
    }

    /// The selection outline's passes, if these pipelines have them.
    pub(super) fn outline(&self) -> Option<&OutlinePipelines> {
        self.outline.as_ref()
    }

    fn display(&self, format: wgpu::TextureFormat) -> &wgpu::RenderPipeline {
        self.display
            .iter()
            .find(|(f, _)| *f == format)
            .map(|(_, p)| p)
            .unwrap_or_else(|| panic!("no display pipeline was built for {format:?}"))
    }
}

/// `source` as a pipeline for `options` compiles it on `device` (the
/// tracer's, the ray tree's): specialised for the scene, and with its data
/// textures read as the device allows ([`DataAccess::for_device`]).
pub(super) fn pipeline_source(
    device: &wgpu::Device,
    source: &ShaderSource,
    options: &ShaderOptions,
) -> (ShaderSource, DataAccess) {
    let access = DataAccess::for_device(device);
    let source = source
        .specialised(options.stack_size, options.features.shape_kinds, access)
        .with_generated(&options.kinds);
    (source, access)
}

/// Binding 0: the globals (see `scene.wgsl`); 1..=5: materials, lights,
/// BVH nodes, BVH shape list and shape counts; from
/// [`FIRST_SHAPE_BINDING`] on, one array per shape kind in the registry
/// order of `gpu::shapes`, each followed by its shared data if the kind has
/// one (`mesh_data`), of which only those of `bound_kinds` are bound (see
/// [`ShaderSource::specialised`]). Every one is a data texture
/// (`Rgba32Uint`, read by the loaders `shapes::glue` generates), bound as
/// `access` says.
pub(super) fn scene_layout_entries(
    bound_kinds: u32,
    access: DataAccess,
) -> Vec<wgpu::BindGroupLayoutEntry> {
    bound_bindings(bound_kinds)
        .into_iter()
        .map(|binding| access.layout_entry(binding))
        .collect()
}

/// The binding numbers of [`scene_layout_entries`], in order.
fn bound_bindings(bound_kinds: u32) -> Vec<u32> {
    let mut bindings: Vec<u32> = (0..FIRST_SHAPE_BINDING).collect();
    let mut binding = FIRST_SHAPE_BINDING;
    for k in super::shapes::kinds() {
        if is_bound(bound_kinds, k.kind) {
            bindings.push(binding);
            if k.data.is_some() {
                bindings.push(binding + 1);
            }
        }
        binding += 1 + u32::from(k.data.is_some());
    }
    bindings
}

/// An array as an `Rgba32Uint` texture [`DATA_TEXTURE_WIDTH`] texels wide,
/// its last row padded with zeros (the loaders and `<name>_texel` of the
/// generated WGSL read it).
fn data_texture(device: &wgpu::Device, queue: &wgpu::Queue, words: &[u32]) -> OwnedTexture {
    let texels = words.len().div_ceil(4).max(1) as u32;
    let width = texels.min(DATA_TEXTURE_WIDTH);
    let rows = texels.div_ceil(width);
    let mut padded = words.to_vec();
    padded.resize((4 * width * rows) as usize, 0);
    OwnedTexture::new(device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some("shape data"),
            size: wgpu::Extent3d {
                width,
                height: rows,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba32Uint,
            usage: DATA_TEXTURE_USAGE,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(&padded),
    ))
}

/// The globals' data texture: one row, written before every pass
/// ([`write_globals`]).
fn globals_texture(device: &wgpu::Device) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("globals"),
        size: globals_extent(),
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba32Uint,
        usage: DATA_TEXTURE_USAGE.union(wgpu::TextureUsages::COPY_DST),
        view_formats: &[],
    })
}

/// A data texture is bound as a sampled or a read-only storage texture
/// ([`DataAccess`]); `Rgba32Uint` allows both on every WebGPU device.
const DATA_TEXTURE_USAGE: wgpu::TextureUsages =
    wgpu::TextureUsages::TEXTURE_BINDING.union(wgpu::TextureUsages::STORAGE_BINDING);

/// The size of the globals' texture: a texel per 16 bytes.
fn globals_extent() -> wgpu::Extent3d {
    wgpu::Extent3d {
        width: (size_of::<Globals>() / 16) as u32,
        height: 1,
        depth_or_array_layers: 1,
    }
}

/// Writes `globals` into their texture through `queue` (taking effect at
/// the next submission, as a buffer write would).
fn write_globals(queue: &wgpu::Queue, texture: &wgpu::Texture, globals: &Globals) {
    queue.write_texture(
        texture.as_image_copy(),
        bytemuck::bytes_of(globals),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(size_of::<Globals>() as u32),
            rows_per_image: None,
        },
        globals_extent(),
    );
}

/// The scene in GPU buffers, with the CPU copy it was made from.
pub struct SceneBuffers {
    packed: PackedScene,
    globals: OwnedTexture,
    /// Materials, lights, the BVH's nodes and shape list, the shape counts:
    /// read through `bind_group`, held here to be destroyed with the scene.
    _fixed: [OwnedTexture; 5],
    /// One per entry of `packed.shapes`; shared with the scene before when
    /// its contents are ([`SceneBuffers::reusing`]).
    shape_textures: Vec<Arc<OwnedTexture>>,
    pub(super) bind_group: wgpu::BindGroup,
}

impl SceneBuffers {
    pub fn new(
        (device, queue): (&wgpu::Device, &wgpu::Queue),
        pipelines: &Pipelines,
        packed: PackedScene,
    ) -> Result<Self, BufferLimitError> {
        Self::with_layout((device, queue), pipelines.scene_layout(), packed, None)
    }

    /// The buffers of `packed`, keeping those of `previous` whose contents
    /// are shared with it (a moved mesh's triangles: nothing is uploaded
    /// again).
    pub fn reusing(
        (device, queue): (&wgpu::Device, &wgpu::Queue),
        pipelines: &Pipelines,
        packed: PackedScene,
        previous: &SceneBuffers,
    ) -> Result<Self, BufferLimitError> {
        Self::with_layout(
            (device, queue),
            pipelines.scene_layout(),
            packed,
            Some(previous),
        )
    }

    /// The buffers of a changed `scene` packed for an image of `size`,
    /// sharing this scene's buffers whose contents did not change (see
    /// [`SceneBuffers::reusing`]): what a slider's edit costs.
    pub fn changed_to(
        &self,
        (device, queue): (&wgpu::Device, &wgpu::Queue),
        pipelines: &Pipelines,
        scene: &crate::scene::Scene,
        (width, height): (u32, u32),
    ) -> Result<Self, BufferLimitError> {
        let packed = PackedScene::new(scene, width, height);
        Self::reusing((device, queue), pipelines, packed, self)
    }

    /// The buffers and their bind group for any pipeline whose group 0 is
    /// [`scene_layout_entries`] (the tracer's, the id pass's). A scene with
    /// an array larger than the device allows is refused before any buffer
    /// is made (wgpu would otherwise fail validation).
    pub(super) fn with_layout(
        (device, queue): (&wgpu::Device, &wgpu::Queue),
        (layout, bound_kinds): (&wgpu::BindGroupLayout, u32),
        packed: PackedScene,
        previous: Option<&SceneBuffers>,
    ) -> Result<Self, BufferLimitError> {
        check_buffers(&device.limits(), &packed)?;
        let globals = OwnedTexture::new(globals_texture(device));
        write_globals(queue, globals.texture(), &packed.globals);
        let texture = |words: &[u32]| data_texture(device, queue, words);
        let fixed = [
            texture(bytemuck::cast_slice(&packed.materials)),
            texture(bytemuck::cast_slice(&packed.lights)),
            texture(bytemuck::cast_slice(&packed.bvh_nodes)),
            texture(&packed.bvh_prims),
            texture(&packed.shape_counts),
        ];
        let shape_textures: Vec<Arc<OwnedTexture>> = packed
            .shapes
            .iter()
            .enumerate()
            .map(|(i, words)| {
                let shared = previous.and_then(|p| {
                    let same = Arc::ptr_eq(p.packed.shapes.get(i)?, words);
                    same.then(|| p.shape_textures[i].clone())
                });
                shared.unwrap_or_else(|| Arc::new(texture(words)))
            })
            .collect();
        let resource = |i: u32| -> wgpu::BindingResource {
            let i = i as usize;
            match i.checked_sub(FIRST_SHAPE_BINDING as usize) {
                None if i == 0 => wgpu::BindingResource::TextureView(globals.view()),
                None => wgpu::BindingResource::TextureView(fixed[i - 1].view()),
                Some(j) => wgpu::BindingResource::TextureView(shape_textures[j].view()),
            }
        };
        let entries: Vec<wgpu::BindGroupEntry> = bound_bindings(bound_kinds)
            .into_iter()
            .map(|i| wgpu::BindGroupEntry {
                binding: i,
                resource: resource(i),
            })
            .collect();
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("scene"),
            layout,
            entries: &entries,
        });
        Ok(SceneBuffers {
            packed,
            globals,
            _fixed: fixed,
            shape_textures,
            bind_group,
        })
    }

    /// The packed scene currently on the GPU.
    pub fn packed(&self) -> &PackedScene {
        &self.packed
    }

    /// Takes a new camera and render settings; the shapes stay as they are.
    pub fn set_view(&mut self, scene: &crate::scene::Scene) {
        self.packed.set_view(&scene.camera, &scene.render);
    }

    /// Sets the colour bar of a scalar view (`shaders/views.wgsl`): the
    /// quantities shown blue and red, from [`super::colour_bar`]. Takes
    /// effect at the next pass encoded.
    pub fn set_view_range(&mut self, range: [f32; 2]) {
        self.packed.globals.view_range = range;
    }
}

/// The default progressive refinement limit of the viewer, in samples per
/// pixel: the fewest samples of `raysandbox bench`'s series at which every
/// bundled scene is within 40 dB PSNR of the converged reference, an error
/// hard to see (docs/performance.md, "The defaults"). The thin-lens scene
/// needs all 64; the others reach 44 to 54 dB there. Samples come one frame
/// at a time while the view is still, so only waiting pays for them.
pub const DEFAULT_MAX_SAMPLES: u32 = 64;
/// The default samples per pixel of `raysandbox render`: the fewest at which
/// every bundled scene is within 35 dB (an error seen only on close
/// inspection) in the same series, at a quarter of the viewer's time: a
/// render is waited for as a whole (docs/performance.md, "The defaults").
pub const DEFAULT_RENDER_SAMPLES: u32 = 16;
/// The viewer's default floor on `min_weight`, chosen from `raysandbox bench`
/// (docs/performance.md): it leaves no visible difference.
pub const DEFAULT_MIN_WEIGHT: f64 = 1e-3;

/// Two radiance-sum textures used in turn, and how many samples they hold.
pub struct Accumulator {
    textures: [OwnedTexture; 2],
    bind_groups: [wgpu::BindGroup; 2],
    /// Index of the texture that holds the current sum.
    front: usize,
    samples: u32,
    /// Pixels of the next sample already traced into the other texture,
    /// in row-major order ([`encode_job`]); 0 when no sample is in progress.
    pixels_done: u32,
    size: (u32, u32),
}

impl Accumulator {
    pub fn new(device: &wgpu::Device, pipelines: &Pipelines, width: u32, height: u32) -> Self {
        // COPY_SRC: the ray-counting variant's counts are read back;
        // COPY_DST: the error view's errors are written in (`write_sum`).
        let textures: [OwnedTexture; 2] = std::array::from_fn(|_| {
            OwnedTexture::new(render_target(
                device,
                "accumulated radiance",
                (width, height),
                ACCUM_FORMAT,
                wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC
                    | wgpu::TextureUsages::COPY_DST,
            ))
        });
        let bind_groups = std::array::from_fn(|i| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("accumulated radiance"),
                layout: &pipelines.accum_layout,
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(textures[i].view()),
                }],
            })
        });
        Accumulator {
            textures,
            bind_groups,
            front: 0,
            samples: 0,
            pixels_done: 0,
            size: (width, height),
        }
    }

    /// Samples per pixel accumulated so far.
    pub fn samples(&self) -> u32 {
        self.samples
    }

    /// Size in pixels.
    pub fn size(&self) -> (u32, u32) {
        self.size
    }

    /// Pixels of the next sample traced so far by [`encode_job`], in
    /// row-major order.
    pub fn pixels_done(&self) -> u32 {
        self.pixels_done
    }

    /// The texture that holds the current sum.
    pub fn sum(&self) -> &wgpu::Texture {
        self.textures[self.front].texture()
    }

    /// Replaces the current sum with `texels`, four floats per pixel, row
    /// by row: the error view's errors, computed on the CPU from the view's
    /// read-back (docs/views.md, "The error view"). Returns false, writing
    /// nothing, when they are not of this size (resized meanwhile).
    pub fn write_sum(&self, queue: &wgpu::Queue, texels: &[f32]) -> bool {
        let (width, height) = self.size;
        if texels.len() != 4 * width as usize * height as usize {
            return false;
        }
        queue.write_texture(
            self.sum().as_image_copy(),
            bytemuck::cast_slice(texels),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(16 * width),
                rows_per_image: Some(height),
            },
            self.sum().size(),
        );
        true
    }

    /// Forgets the accumulated samples, and the sample in progress (the
    /// scene or view changed).
    pub fn reset(&mut self) {
        self.samples = 0;
        self.pixels_done = 0;
    }
}

/// A texture view to display into, with its format and size in pixels.
pub struct FrameTarget<'a> {
    pub view: &'a wgpu::TextureView,
    pub format: wgpu::TextureFormat,
    pub size: (u32, u32),
}

/// Encodes one frame: `new_samples` more samples per pixel (none: only
/// display again) are traced into the accumulator, and the average is shown
/// in `target`, scaled up if the accumulator is smaller. The globals are
/// written through `queue`: submit the encoder before encoding another frame.
pub fn encode_frame(
    queue: &wgpu::Queue,
    encoder: &mut wgpu::CommandEncoder,
    pipelines: &Pipelines,
    scene: &SceneBuffers,
    accum: &mut Accumulator,
    new_samples: u32,
    target: &FrameTarget,
) {
    let mut globals = scene.packed.globals;
    globals.resolution = [accum.size.0, accum.size.1];
    globals.output_size = [target.size.0, target.size.1];
    globals.sample_start = accum.samples;
    globals.sample_count = new_samples;
    write_globals(queue, scene.globals.texture(), &globals);

    if new_samples > 0 {
        let back = 1 - accum.front;
        fullscreen::pass(
            encoder,
            &pipelines.trace,
            &[&scene.bind_group, &accum.bind_groups[accum.front]],
            accum.textures[back].view(),
        );
        accum.front = back;
        accum.samples += new_samples;
        accum.pixels_done = 0;
    }
    fullscreen::pass(
        encoder,
        pipelines.display(target.format),
        &[&scene.bind_group, &accum.bind_groups[accum.front]],
        target.view,
    );
}

/// Encodes the trace of the pixels `span` (row-major indices) of the next
/// sample (one sample per pixel), continuing where the last call stopped: a
/// sample cut into short GPU jobs (docs/performance.md, "Short GPU jobs").
/// The sample counts once its last pixel is traced. The globals are written
/// through `queue`: submit before encoding anything else. `timestamp_writes`
/// times the job's pass.
pub fn encode_job(
    queue: &wgpu::Queue,
    encoder: &mut wgpu::CommandEncoder,
    (pipelines, scene): (&Pipelines, &SceneBuffers),
    accum: &mut Accumulator,
    span: std::ops::Range<u32>,
    timestamp_writes: Option<wgpu::RenderPassTimestampWrites>,
) {
    let (width, height) = accum.size;
    let total = width * height;
    let span = span.start.min(total)..span.end.min(total);
    let mut globals = scene.packed.globals;
    globals.resolution = [width, height];
    globals.output_size = [width, height];
    globals.sample_start = accum.samples;
    globals.sample_count = 1;
    write_globals(queue, scene.globals.texture(), &globals);
    let back = 1 - accum.front;
    // The first sample's pixels not traced yet show black, not an old image.
    let clear = accum.samples == 0 && accum.pixels_done == 0;
    fullscreen::pass_rects(
        encoder,
        &pipelines.trace,
        &[&scene.bind_group, &accum.bind_groups[accum.front]],
        accum.textures[back].view(),
        &span_rects(&span, width),
        clear,
        timestamp_writes,
    );
    accum.pixels_done = span.end;
    if span.end == total {
        accum.front = back;
        accum.samples += 1;
        accum.pixels_done = 0;
    }
}

/// Encodes the display of the accumulated samples into `target`; during the
/// first sample, of the pixels traced so far. The globals are written through
/// `queue`: submit before encoding anything else.
pub fn encode_display(
    queue: &wgpu::Queue,
    encoder: &mut wgpu::CommandEncoder,
    (pipelines, scene): (&Pipelines, &SceneBuffers),
    accum: &Accumulator,
    target: &FrameTarget,
) {
    let first_in_progress = accum.samples == 0 && accum.pixels_done > 0;
    let (shown, samples) = if first_in_progress {
        (1 - accum.front, 1)
    } else {
        (accum.front, accum.samples)
    };
    let mut globals = scene.packed.globals;
    globals.resolution = [accum.size.0, accum.size.1];
    globals.output_size = [target.size.0, target.size.1];
    globals.sample_start = samples;
    globals.sample_count = 0;
    write_globals(queue, scene.globals.texture(), &globals);
    fullscreen::pass(
        encoder,
        pipelines.display(target.format),
        &[&scene.bind_group, &accum.bind_groups[shown]],
        target.view,
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::shapes::glue::{ALL_KINDS_BOUND, data_texture_count};

    /// `DataAccess::for_device` and the device's limits count the generic
    /// pipeline's data textures: every binding its layout has.
    #[test]
    fn the_generic_pipeline_binds_data_texture_count_textures() {
        assert_eq!(
            bound_bindings(ALL_KINDS_BOUND).len(),
            data_texture_count() as usize
        );
        assert_eq!(data_texture_count(), 14);
    }
}
