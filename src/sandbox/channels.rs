//! The images a shader samples (docs/sandbox.md, "Textures"): Shadertoy's
//! `iChannel0..3`, given as PNG or JPEG files on the command line or in the panel,
//! and, where none is given, a noise image made here, as Shadertoy's
//! default channels are often noise.

use std::path::Path;

use wgpu::util::DeviceExt;

/// Channels are numbered 0 to 3, as on Shadertoy.
pub const CHANNELS: usize = 4;

/// Side of the built-in noise image in pixels (Shadertoy's "RGBA Noise
/// Medium" is as big).
pub const NOISE_SIZE: u32 = 256;

/// The format of channel images: the 8-bit values as stored in the file,
/// not decoded from sRGB (as WebGL uploads them).
pub const CHANNEL_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// The built-in channel image: every component of every pixel an
/// independent uniform random byte, the same on every run (a hash of the
/// pixel's position, no random generator state).
pub fn noise_image() -> image::RgbaImage {
    image::RgbaImage::from_fn(NOISE_SIZE, NOISE_SIZE, |x, y| {
        let h = hash(x + y * NOISE_SIZE);
        image::Rgba(h.to_le_bytes())
    })
}

/// A 32-bit integer hash (Chris Wellons' "lowbias32"): every output bit
/// depends on every input bit, so neighbouring pixels are unrelated.
pub(crate) fn hash(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    x
}

/// Reads a channel image; the error names the file.
pub fn load(path: &Path) -> Result<image::RgbaImage, String> {
    image::open(path)
        .map(|i| i.to_rgba8())
        .map_err(|e| format!("{}: cannot read the image: {e}", path.display()))
}

/// The channel images given for `--channel0 .. --channel3` (None: noise),
/// each read now so that a wrong path is reported before anything runs.
pub fn load_all(
    paths: &[Option<std::path::PathBuf>; CHANNELS],
) -> Result<[Option<image::RgbaImage>; CHANNELS], String> {
    let mut images = [None, None, None, None];
    for (image, path) in images.iter_mut().zip(paths) {
        if let Some(path) = path {
            *image = Some(load(path)?);
        }
    }
    Ok(images)
}

/// Uploads `image` as a channel texture. Its bottom row becomes texture
/// coordinate v = 0, so that `texture(iChannel0, fragCoord / iResolution.xy)`
/// shows the image upright in the y-up coordinates of the sandbox (as
/// Shadertoy flips images on upload).
pub fn upload(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    image: &image::RgbaImage,
) -> wgpu::Texture {
    let flipped = image::imageops::flip_vertical(image);
    let size = (image.width().max(1), image.height().max(1), 1);
    upload_texels(
        device,
        queue,
        "sandbox channel",
        size,
        wgpu::TextureDimension::D2,
        flipped.as_raw(),
    )
}

/// Uploads `bytes` ([`CHANNEL_FORMAT`], layer after layer) as a texture of
/// `size` (width, height, layers or depth) that shaders sample.
pub(crate) fn upload_texels(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    (width, height, layers): (u32, u32, u32),
    dimension: wgpu::TextureDimension,
    bytes: &[u8],
) -> wgpu::Texture {
    device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: layers,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension,
            format: CHANNEL_FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytes,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_is_deterministic_and_covers_the_byte_range_evenly() {
        let a = noise_image();
        assert_eq!(a, noise_image());
        let bytes = a.as_raw();
        let mean = bytes.iter().map(|&b| f64::from(b)).sum::<f64>() / bytes.len() as f64;
        // 262144 uniform bytes: mean 127.5, standard error about 0.14.
        assert!((mean - 127.5).abs() < 1.0, "mean {mean}");
        let mut seen = [false; 256];
        for &b in bytes {
            seen[b as usize] = true;
        }
        assert!(seen.iter().all(|&s| s), "every byte value occurs");
        assert_ne!(a.get_pixel(0, 0), a.get_pixel(1, 0));
    }
}
