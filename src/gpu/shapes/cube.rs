//! A rotated box as `shaders/shapes/cube.wgsl` reads it.

use bytemuck::Zeroable;

use super::{Frame, PackShape, f32x3, packed_struct, placement};
use crate::scene::{self, Instance, Scene};

packed_struct! {
    pub struct Cube for scene::Cube, "../../../shaders/shapes/cube.wgsl" {
        pub center: [f32; 3],
        pub material: u32,
        /// `mat3x3<f32>`: three columns, each padded to 16 bytes; after
        /// 16 bytes, where its 16-byte alignment needs no padding.
        pub rotation: [[f32; 4]; 3],
        pub half_size: [f32; 3],
    }
}

impl PackShape for scene::Cube {
    fn pack(_: &Scene, frame: &Frame, c: &Instance<scene::Cube>, material: u32) -> Cube {
        let placement = &c.placement;
        Cube {
            center: frame.point(placement.translate),
            material,
            rotation: placement::columns(placement.rotation_matrix()),
            half_size: f32x3(placement.scale.edges() * 0.5),
            ..Zeroable::zeroed()
        }
    }
}
