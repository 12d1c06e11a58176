//! What the packed placed shapes share: their matrices as WGSL's
//! `mat3x3<f32>` (docs/rendering-model.md, "Implicit surfaces").

use glam::DMat3;

use super::Frame;
use crate::scene::Placement;

/// `m` rounded to f32, as three columns padded to 16 bytes.
pub fn columns(m: DMat3) -> [[f32; 4]; 3] {
    [m.x_axis, m.y_axis, m.z_axis].map(|c| c.as_vec3().extend(0.0).to_array())
}

/// `Rz Ry Rx` as three columns padded to 16 bytes.
pub fn rotation_columns(placement: &Placement) -> [[f32; 4]; 3] {
    columns(placement.rotation_matrix())
}

/// The fields `center`, `scale` and `rotation` that a placed kind's struct
/// starts with (`packed_struct!`'s `placed`): the centre relative to the
/// frame origin, in f32.
pub fn pack(frame: &Frame, placement: &Placement) -> ([f32; 3], f32, [[f32; 4]; 3]) {
    (
        frame.point(placement.translate),
        placement.scale as f32,
        rotation_columns(placement),
    )
}
