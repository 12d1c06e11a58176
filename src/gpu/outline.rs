//! The viewer's selection outline (docs/implementation.md, "Selection
//! outline"): the id pass (`fs_id`) tells per traced pixel which shape is
//! seen first; `fs_outline` (`shaders/outline.wgsl`) draws a band around
//! the selected shape's silhouette over the displayed image. Any shape kind
//! the shader can hit is outlined the same way, by its (kind, index).

use super::buffer;
use super::features::{ShaderOptions, borrowed};
use super::fullscreen;
use super::layout::Selection;
use super::texture::{OwnedTexture, render_target};

/// The outline colour, sRGB-encoded: an orange that none of the bundled
/// scenes' materials comes close to, as in Blender.
pub const OUTLINE_COLOR: [u8; 3] = [255, 153, 0];

/// The id image: (kind, index, bits of t, 1) per pixel.
pub(super) const ID_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Uint;

/// The `fs_id` pass of `module` into an [`ID_FORMAT`] target, reading the
/// scene bind group of `scene_layout` (group 0). `options` sets the
/// pipeline constants, as for the image it goes with. Also the pass of
/// `IdRenderer`, which reads its image back.
pub(super) fn id_pipeline(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    scene_layout: &wgpu::BindGroupLayout,
    options: &ShaderOptions,
) -> wgpu::RenderPipeline {
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("id pass"),
        bind_group_layouts: &[Some(scene_layout)],
        immediate_size: 0,
    });
    let constants = options.constants();
    fullscreen::pipeline(
        device,
        &pipeline_layout,
        (module, "vs_fullscreen"),
        (module, "fs_id"),
        &borrowed(&constants),
        ID_FORMAT,
    )
}

/// The passes of one shader source: the id pass into the id image, and the
/// outline pass for each output format.
#[derive(Clone)]
pub(super) struct OutlinePipelines {
    id: wgpu::RenderPipeline,
    outline: Vec<(wgpu::TextureFormat, wgpu::RenderPipeline)>,
    /// Group 1 of the outline pass: the id image and the [`Selection`].
    layout: wgpu::BindGroupLayout,
}

impl OutlinePipelines {
    /// Built from the tracer's `module`, whose group 0 is `scene_layout`.
    pub(super) fn new(
        device: &wgpu::Device,
        module: &wgpu::ShaderModule,
        scene_layout: &wgpu::BindGroupLayout,
        output_formats: &[wgpu::TextureFormat],
        options: &ShaderOptions,
    ) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("selection outline"),
            entries: &[
                fullscreen::uint_texture_entry(1),
                fullscreen::uniform_entry(2),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("selection outline"),
            bind_group_layouts: &[Some(scene_layout), Some(&layout)],
            immediate_size: 0,
        });
        let outline = output_formats
            .iter()
            .map(|&format| {
                let pipeline = fullscreen::pipeline(
                    device,
                    &pipeline_layout,
                    (module, "vs_fullscreen"),
                    (module, "fs_outline"),
                    &[fullscreen::encode_srgb(format)],
                    format,
                );
                (format, pipeline)
            })
            .collect();
        OutlinePipelines {
            id: id_pipeline(device, module, scene_layout, options),
            outline,
            layout,
        }
    }

    fn outline(&self, format: wgpu::TextureFormat) -> Option<&wgpu::RenderPipeline> {
        self.outline
            .iter()
            .find(|(f, _)| *f == format)
            .map(|(_, p)| p)
    }
}

/// A viewport's id image and selection, kept between frames: the id pass
/// runs again only after the image it describes changed.
pub(super) struct Outline {
    selection: Selection,
    uniform: wgpu::Buffer,
    image: Option<IdImage>,
}

/// The id image at the traced resolution, with the outline's bind group.
struct IdImage {
    texture: OwnedTexture,
    bind_group: wgpu::BindGroup,
    size: (u32, u32),
    /// Whether it shows the current scene and view.
    current: bool,
}

impl Outline {
    pub(super) fn new(device: &wgpu::Device) -> Self {
        let selection = Selection {
            color: {
                let [r, g, b] = OUTLINE_COLOR.map(|c| f32::from(c) / 255.0);
                [r, g, b, 1.0]
            },
            ..bytemuck::Zeroable::zeroed()
        };
        let uniform = buffer::with_contents(
            device,
            "selection",
            bytemuck::bytes_of(&selection),
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        Outline {
            selection,
            uniform,
            image: None,
        }
    }

    /// Outlines the shape `(kind, index)` (the id pass's numbers; kind 0:
    /// nothing), with a band `radius` output pixels wide.
    pub(super) fn select(&mut self, queue: &wgpu::Queue, (kind, index): (u32, u32), radius: u32) {
        let selection = Selection {
            kind,
            index,
            radius,
            ..self.selection
        };
        if selection != self.selection {
            self.selection = selection;
            queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&selection));
        }
    }

    /// The traced image changed (scene, view or size): the id image is
    /// drawn again before the next outline.
    pub(super) fn invalidate(&mut self) {
        if let Some(image) = &mut self.image {
            image.current = false;
        }
    }

    /// The pipelines changed: their layouts too, so the bind group is made
    /// anew.
    pub(super) fn forget_layouts(&mut self) {
        self.image = None;
    }

    /// Encodes the outline over `target`, after the tracer's passes of
    /// the same frame (whose scene bind group and globals it reads); the id
    /// pass first if the id image is out of date. Nothing is drawn without
    /// a selection.
    pub(super) fn encode(
        &mut self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        pipelines: &OutlinePipelines,
        scene: &wgpu::BindGroup,
        traced_size: (u32, u32),
        target: (&wgpu::TextureView, wgpu::TextureFormat),
    ) {
        if self.selection.kind == 0 {
            return;
        }
        let Some(outline) = pipelines.outline(target.1) else {
            return;
        };
        if self.image.as_ref().is_none_or(|i| i.size != traced_size) {
            self.image = Some(self.id_image(device, pipelines, traced_size));
        }
        let image = self.image.as_mut().expect("made above");
        if !image.current {
            fullscreen::pass(encoder, &pipelines.id, &[scene], image.texture.view());
            image.current = true;
        }
        // Over the traced image, which the pixels the outline discards keep.
        let groups = [scene, &image.bind_group];
        fullscreen::pass_rects(encoder, outline, &groups, target.0, &[], false, None);
    }

    fn id_image(
        &self,
        device: &wgpu::Device,
        pipelines: &OutlinePipelines,
        size: (u32, u32),
    ) -> IdImage {
        let texture = OwnedTexture::new(render_target(
            device,
            "first hits (outline)",
            size,
            ID_FORMAT,
            wgpu::TextureUsages::TEXTURE_BINDING,
        ));
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("selection outline"),
            layout: &pipelines.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(texture.view()),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: self.uniform.as_entire_binding(),
                },
            ],
        });
        IdImage {
            texture,
            bind_group,
            size,
            current: false,
        }
    }
}
