//! A quaternion Julia set as `shaders/shapes/julia.wgsl` reads it.

use super::{Frame, PackShape, packed_struct, placement};
use crate::scene::{self, Instance, Scene};

packed_struct! {
    pub struct Julia {
        pub center: [f32; 3],
        pub scale: f32,
        /// `mat3x3<f32>`: three columns, each padded to 16 bytes.
        pub rotation: [[f32; 4]; 3],
        pub c: [f32; 4],
        pub slice: f32,
        pub iterations: u32,
        pub epsilon: f32,
        pub material: u32,
        /// 1: epsilon grows with the pixel footprint.
        pub footprint: u32,
        pub _pad0: u32,
        pub _pad1: u32,
        pub _pad2: u32,
    }
}

impl PackShape for scene::Julia {
    type Packed = Julia;
    const WGSL: &'static str = include_str!("../../../shaders/shapes/julia.wgsl");

    fn pack(_: &Scene, frame: &Frame, j: &Instance<scene::Julia>, material: u32) -> Julia {
        let (center, scale, rotation) = placement::pack(frame, &j.placement);
        Julia {
            center,
            scale,
            rotation,
            c: j.c.map(|x| x as f32),
            slice: j.slice as f32,
            iterations: j.iterations,
            epsilon: j.epsilon as f32,
            material,
            footprint: u32::from(j.footprint),
            _pad0: 0,
            _pad1: 0,
            _pad2: 0,
        }
    }
}
