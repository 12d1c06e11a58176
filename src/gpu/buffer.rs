//! Buffers made with their contents.

/// A buffer of `usage` holding `contents`, made as wgpu's
/// `DeviceExt::create_buffer_init` makes it (mapped at creation, its size
/// rounded up to `COPY_BUFFER_ALIGNMENT`), except on a lost device: there
/// wgpu's helper panics because the new buffer cannot be mapped, while this
/// one returns the buffer unwritten. Nothing drawn with it is shown; the
/// loss itself is reported through [`super::Gpu::lost`] and the viewer
/// makes a new device.
pub fn with_contents(
    device: &wgpu::Device,
    label: &str,
    contents: &[u8],
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    let align = wgpu::COPY_BUFFER_ALIGNMENT;
    let size = (contents.len() as u64).next_multiple_of(align).max(align);
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage,
        mapped_at_creation: true,
    });
    match buffer.get_mapped_range_mut(..) {
        Ok(mut range) => range.slice(..contents.len()).copy_from_slice(contents),
        Err(e) => log::error!("buffer {label:?} not written: {e}"),
    }
    buffer.unmap();
    buffer
}
