//! The one drawing primitive of the project: a single triangle that covers
//! the viewport (no vertex buffer), run by a fragment shader per pixel.
//! Every pass uses these two helpers: the tracer's, the id pass, the
//! sandbox's.

/// A full-screen pipeline: a vertex entry point that makes the triangle
/// from the vertex index, a fragment entry point with its pipeline
/// constants, and one colour target without blending.
pub fn pipeline(
    device: &wgpu::Device,
    layout: &wgpu::PipelineLayout,
    (vs_module, vs): (&wgpu::ShaderModule, &str),
    (fs_module, fs): (&wgpu::ShaderModule, &str),
    constants: &[(&str, f64)],
    format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(fs),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module: vs_module,
            entry_point: Some(vs),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: fs_module,
            entry_point: Some(fs),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants,
                ..Default::default()
            },
            targets: &[Some(wgpu::ColorTargetState {
                format,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// The `ENCODE_SRGB` constant of the passes that write to `format`: false
/// for an `*Srgb` format, whose hardware conversion encodes.
pub fn encode_srgb(format: wgpu::TextureFormat) -> (&'static str, f64) {
    ("ENCODE_SRGB", if format.is_srgb() { 0.0 } else { 1.0 })
}

/// Encodes one full-screen pass into `target` (cleared first) with the bind
/// groups bound in order from group 0.
pub fn pass(
    encoder: &mut wgpu::CommandEncoder,
    pipeline: &wgpu::RenderPipeline,
    bind_groups: &[&wgpu::BindGroup],
    target: &wgpu::TextureView,
) {
    pass_rects(encoder, pipeline, bind_groups, target, &[], true, None);
}

/// Like [`pass`], limited to the scissor rectangles `rects` (`[x, y,
/// width, height]`, disjoint; none: the whole target): the other pixels
/// keep what the target holds, unless `clear` (then they are black). Not
/// cleared, the pixels the fragment shader discards keep their colour too
/// (the selection outline over the traced image). `timestamp_writes`
/// times the pass (`GpuTimer::pass_writes`).
pub fn pass_rects(
    encoder: &mut wgpu::CommandEncoder,
    pipeline: &wgpu::RenderPipeline,
    bind_groups: &[&wgpu::BindGroup],
    target: &wgpu::TextureView,
    rects: &[[u32; 4]],
    clear: bool,
    timestamp_writes: Option<wgpu::RenderPassTimestampWrites>,
) {
    let load = if clear {
        wgpu::LoadOp::Clear(wgpu::Color::BLACK)
    } else {
        wgpu::LoadOp::Load
    };
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: None,
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: target,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load,
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_pipeline(pipeline);
    for (group, bind_group) in bind_groups.iter().enumerate() {
        pass.set_bind_group(group as u32, *bind_group, &[]);
    }
    if rects.is_empty() {
        pass.draw(0..3, 0..1);
    }
    for &[x, y, w, h] in rects {
        pass.set_scissor_rect(x, y, w, h);
        pass.draw(0..3, 0..1);
    }
}

/// A uniform buffer at `binding`, read by the fragment stage: how the
/// passes get their few per-pass numbers (the selection, the sandbox's
/// uniforms, the ray tree's pixel).
pub fn uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A `texture_2d<u32>` at `binding`, read with `textureLoad` by the
/// fragment stage: the scene's data textures and the id pass's ids that
/// the selection outline reads.
pub fn uint_texture_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Uint,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

/// A bind group layout of one texture read with `textureLoad` in the
/// fragment stage (unfilterable, so `Rgba32Float` works everywhere): how a
/// pass reads the image an earlier pass wrote.
pub fn texture_layout(device: &wgpu::Device, label: &str) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        }],
    })
}
