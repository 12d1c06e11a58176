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

/// A texture and its view, destroyed when dropped.
///
/// Natively wgpu frees a dropped texture at once (after the submissions
/// that use it). In the browser dropping frees nothing: the GPU process
/// keeps the texture until JavaScript's garbage collector finalises its
/// wrapper, which the page's small JS heap seldom needs, so the
/// accumulation textures replaced at every resize and the data textures
/// replaced at every edit would pile up there (docs/web.md, "GPU memory").
pub struct OwnedTexture {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
}

impl OwnedTexture {
    pub fn new(texture: wgpu::Texture) -> Self {
        let view = texture.create_view(&Default::default());
        OwnedTexture { texture, view }
    }

    pub fn texture(&self) -> &wgpu::Texture {
        &self.texture
    }

    pub fn view(&self) -> &wgpu::TextureView {
        &self.view
    }
}

impl Drop for OwnedTexture {
    fn drop(&mut self) {
        self.texture.destroy();
    }
}
