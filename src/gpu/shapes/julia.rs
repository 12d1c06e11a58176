//! A quaternion Julia set as `shaders/shapes/julia.wgsl` reads it.

use bytemuck::Zeroable;

use super::{Frame, PackShape, packed_struct, placement};
use crate::scene::{self, Instance, Scene};

packed_struct! {
    pub struct Julia for scene::Julia, "../../../shaders/shapes/julia.wgsl", placed {
        pub c: [f32; 4],
        pub slice: f32,
        pub iterations: u32,
        pub epsilon: f32,
        pub material: u32,
        /// 1: epsilon grows with the pixel footprint.
        pub footprint: u32,
    }
}

impl PackShape for scene::Julia {
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
            ..Zeroable::zeroed()
        }
    }
}
