//! Channels that are not flat images (docs/sandbox.md, "Cube maps and
//! volumes"): Shadertoy's "cubemap" and "volume" inputs, which a shader
//! reads as `samplerCube` and `sampler3D` with a direction or a 3-D point.
//! The sandbox has one of each built in, made here from nothing fetched:
//! a cube map whose colour is the direction looked in, and a volume of
//! noise like Shadertoy's "RGBA Noise3D".

use super::channels::{CHANNELS, hash, upload_texels};

/// What a channel holds, which decides the sampler type its name has in
/// the shader (`sampler2D`, `samplerCube`, `sampler3D`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum ChannelKind {
    /// A 2-D image (a file, the noise, a buffer, the keyboard).
    #[default]
    Flat,
    /// A cube map, sampled with a direction.
    Cube,
    /// A 3-D texture, sampled with a point in 0..1 (repeating).
    Volume,
}

/// The kind of each of the four channels.
pub type ChannelKinds = [ChannelKind; CHANNELS];

/// Side of each face of the built-in cube map, in pixels.
pub const CUBE_SIZE: u32 = 64;

/// Side of the built-in noise volume (Shadertoy's "RGBA Noise3D" is as big).
pub const VOLUME_SIZE: u32 = 32;

/// The colour of the built-in cube map in direction `d`: each component
/// of the normalised direction mapped from -1..1 to 0..1, so that a
/// reflection shows which way it looks (+x red, +y green, +z blue) and
/// each face and its orientation can be checked by numbers.
pub fn cube_colour(d: [f32; 3]) -> [f32; 3] {
    let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-30);
    d.map(|c| 0.5 + 0.5 * c / length)
}

/// The direction through texel centre `(s, t)` (0..1, t down the rows) of
/// cube face `face` (+X, -X, +Y, -Y, +Z, -Z, the layer order of Vulkan and
/// WebGPU): the inverse of the face selection of the Vulkan specification,
/// "Cube Map Face Selection" (sc, tc by major axis).
pub fn face_direction(face: usize, s: f32, t: f32) -> [f32; 3] {
    let (sc, tc) = (2.0 * s - 1.0, 2.0 * t - 1.0);
    match face {
        0 => [1.0, -tc, -sc],
        1 => [-1.0, -tc, sc],
        2 => [sc, 1.0, tc],
        3 => [sc, -1.0, -tc],
        4 => [sc, -tc, 1.0],
        _ => [-sc, -tc, -1.0],
    }
}

/// The six faces of the built-in cube map, layer after layer, RGBA8.
pub fn cube_faces() -> Vec<u8> {
    let n = CUBE_SIZE;
    let mut bytes = Vec::with_capacity((6 * n * n * 4) as usize);
    for face in 0..6 {
        for y in 0..n {
            for x in 0..n {
                let s = (x as f32 + 0.5) / n as f32;
                let t = (y as f32 + 0.5) / n as f32;
                let c = cube_colour(face_direction(face, s, t));
                bytes.extend(c.map(|v| (v * 255.0).round() as u8));
                bytes.push(255);
            }
        }
    }
    bytes
}

/// The built-in volume: every component of every texel an independent
/// uniform random byte, the same on every run (the hash of the 2-D noise,
/// continued past its texels).
pub fn noise_volume() -> Vec<u8> {
    let n = VOLUME_SIZE;
    let offset = super::channels::NOISE_SIZE * super::channels::NOISE_SIZE;
    (0..n * n * n)
        .flat_map(|i| hash(offset + i).to_le_bytes())
        .collect()
}

/// Uploads the built-in cube map; the view is a cube view.
pub fn upload_cube(device: &wgpu::Device, queue: &wgpu::Queue) -> wgpu::TextureView {
    let size = (CUBE_SIZE, CUBE_SIZE, 6);
    let d2 = wgpu::TextureDimension::D2;
    upload_texels(device, queue, "sandbox cube map", size, d2, &cube_faces()).create_view(
        &wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::Cube),
            ..Default::default()
        },
    )
}

/// Uploads the built-in noise volume.
pub fn upload_volume(device: &wgpu::Device, queue: &wgpu::Queue) -> wgpu::TextureView {
    let size = (VOLUME_SIZE, VOLUME_SIZE, VOLUME_SIZE);
    let d3 = wgpu::TextureDimension::D3;
    upload_texels(
        device,
        queue,
        "sandbox noise volume",
        size,
        d3,
        &noise_volume(),
    )
    .create_view(&Default::default())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The face a direction selects and its (s, t), as the Vulkan
    /// specification's table says: the inverse of [`face_direction`].
    fn select(d: [f32; 3]) -> (usize, f32, f32) {
        let [x, y, z] = d;
        let (face, sc, tc, ma) = if x.abs() >= y.abs() && x.abs() >= z.abs() {
            if x > 0.0 {
                (0, -z, -y, x)
            } else {
                (1, z, -y, -x)
            }
        } else if y.abs() >= z.abs() {
            if y > 0.0 {
                (2, x, z, y)
            } else {
                (3, x, -z, -y)
            }
        } else if z > 0.0 {
            (4, x, -y, z)
        } else {
            (5, -x, -y, -z)
        };
        (face, 0.5 * (sc / ma + 1.0), 0.5 * (tc / ma + 1.0))
    }

    #[test]
    fn face_directions_invert_the_face_selection() {
        for face in 0..6 {
            for (s, t) in [(0.5, 0.5), (0.2, 0.7), (0.9, 0.1)] {
                let (f, s2, t2) = select(face_direction(face, s, t));
                assert_eq!(f, face);
                assert!((s - s2).abs() < 1e-6 && (t - t2).abs() < 1e-6);
            }
        }
    }

    #[test]
    fn built_ins_are_deterministic_and_sized() {
        assert_eq!(cube_faces().len(), (6 * CUBE_SIZE * CUBE_SIZE * 4) as usize);
        let v = noise_volume();
        assert_eq!(v, noise_volume());
        assert_eq!(v.len(), (VOLUME_SIZE.pow(3) * 4) as usize);
        let mean = v.iter().map(|&b| f64::from(b)).sum::<f64>() / v.len() as f64;
        // 131072 uniform bytes: mean 127.5, standard error about 0.2.
        assert!((mean - 127.5).abs() < 1.5, "mean {mean}");
        assert_eq!(cube_colour([2.0, 0.0, 0.0]), [1.0, 0.5, 0.5]);
    }
}
