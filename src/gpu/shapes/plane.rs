//! An infinite plane as `shaders/shapes/plane.wgsl` reads it.

use bytemuck::Zeroable;

use super::{Frame, PackShape, f32x3, packed_struct};
use crate::scene::{self, Instance, Scene};

packed_struct! {
    pub struct Plane for scene::Plane, "../../../shaders/shapes/plane.wgsl" {
        pub point: [f32; 3],
        pub material: u32,
        pub normal: [f32; 3],
    }
}

impl PackShape for scene::Plane {
    fn pack(_: &Scene, frame: &Frame, p: &Instance<scene::Plane>, material: u32) -> Plane {
        Plane {
            point: frame.point(p.point),
            material,
            normal: f32x3(p.normal),
            ..Zeroable::zeroed()
        }
    }
}
