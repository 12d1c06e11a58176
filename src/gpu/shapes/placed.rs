//! What the packed implicit surfaces share: their rotation as WGSL's
//! `mat3x3<f32>` (docs/rendering-model.md, "Implicit surfaces").

use crate::scene::Placement;

/// `Rz Ry Rx` as three columns padded to 16 bytes.
pub fn rotation_columns(placement: &Placement) -> [[f32; 4]; 3] {
    let m = placement.rotation_matrix();
    [m.x_axis, m.y_axis, m.z_axis].map(|c| c.as_vec3().extend(0.0).to_array())
}
