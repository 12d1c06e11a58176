//! The one kind of texture the passes draw into: 2D, one mip level, one
//! sample, no extra view formats.

/// A `width` x `height` texture that a render pass draws into, also usable
/// as `usage` says (`COPY_SRC` to read it back, `TEXTURE_BINDING` to sample
/// it in a later pass).
pub fn render_target(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | usage,
        view_formats: &[],
    })
}

/// A [`render_target`] that the CPU reads back (`COPY_SRC`): the images of
/// the headless renders, screenshots and id passes.
pub fn readback_target(
    device: &wgpu::Device,
    label: &str,
    size: (u32, u32),
    format: wgpu::TextureFormat,
) -> wgpu::Texture {
    render_target(device, label, size, format, wgpu::TextureUsages::COPY_SRC)
}
