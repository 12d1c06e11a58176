//! An infinite plane as `shaders/shapes/plane.wgsl` reads it.

use super::{Frame, PackShape, f32x3, packed_struct};
use crate::scene::{self, Instance, Scene};

packed_struct! {
    pub struct Plane {
        pub point: [f32; 3],
        pub material: u32,
        pub normal: [f32; 3],
        pub _pad: u32,
    }
}

impl PackShape for scene::Plane {
    type Packed = Plane;
    const WGSL: &'static str = include_str!("../../../shaders/shapes/plane.wgsl");

    fn pack(_: &Scene, frame: &Frame, p: &Instance<scene::Plane>, material: u32) -> Plane {
        Plane {
            point: frame.point(p.point),
            material,
            normal: f32x3(p.normal),
            _pad: 0,
        }
    }
}
