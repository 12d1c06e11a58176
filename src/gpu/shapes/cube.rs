//! A rotated box as `shaders/shapes/cube.wgsl` reads it.

use super::{Frame, PackShape, f32x3, packed_struct, placement};
use crate::scene::{self, Instance, Scene};

packed_struct! {
    pub struct Cube {
        pub center: [f32; 3],
        pub material: u32,
        pub half_size: [f32; 3],
        pub _pad: u32,
        /// `mat3x3<f32>`: three columns, each padded to 16 bytes.
        pub rotation: [[f32; 4]; 3],
    }
}

impl PackShape for scene::Cube {
    type Packed = Cube;
    const WGSL: &'static str = include_str!("../../../shaders/shapes/cube.wgsl");

    fn pack(_: &Scene, frame: &Frame, c: &Instance<scene::Cube>, material: u32) -> Cube {
        let placement = &c.placement;
        Cube {
            center: frame.point(placement.translate),
            material,
            half_size: f32x3(placement.scale.edges() * 0.5),
            _pad: 0,
            rotation: placement::columns(placement.rotation_matrix()),
        }
    }
}
