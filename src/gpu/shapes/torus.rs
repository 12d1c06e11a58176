//! A torus as `shaders/shapes/torus.wgsl` reads it.

use bytemuck::Zeroable;
use glam::DVec3;

use super::{Frame, PackShape, packed_struct};
use crate::scene::{self, Instance, Scene};

packed_struct! {
    /// The torus in world units: a surface of revolution needs only its centre,
    /// its axis and its two radii (turning it about its own axis changes
    /// nothing), so the shader reads 8 numbers instead of a whole placement
    /// (docs/implementation.md, "Torus").
    pub struct Torus for scene::Torus, "../../../shaders/shapes/torus.wgsl" {
        pub center: [f32; 3],
        /// R, the ring's radius, times the scale.
        pub major: f32,
        /// The local y axis turned by the rotation, unit length.
        pub axis: [f32; 3],
        /// r, the tube's radius, times the scale.
        pub minor: f32,
        pub material: u32,
    }
}

impl PackShape for scene::Torus {
    const OCCLUDES: bool = true;

    fn constants(method: &scene::TorusMethod) -> Vec<(&'static str, u32)> {
        vec![("TORUS_METHOD", method.number())]
    }

    fn pack(_: &Scene, frame: &Frame, t: &Instance<scene::Torus>, material: u32) -> Torus {
        let placement = &t.placement;
        let axis = (placement.rotation_matrix() * DVec3::Y).normalize();
        Torus {
            center: frame.point(placement.translate),
            major: (placement.scale * t.major_radius) as f32,
            axis: axis.as_vec3().to_array(),
            minor: (placement.scale * t.minor_radius) as f32,
            material,
            ..Zeroable::zeroed()
        }
    }
}
