//! A sphere as `shaders/shapes/sphere.wgsl` reads it.

use bytemuck::Zeroable;

use super::{Frame, PackShape, packed_struct};
use crate::scene::{self, Instance, Scene};

packed_struct! {
    pub struct Sphere for scene::Sphere, "../../../shaders/shapes/sphere.wgsl" {
        pub center: [f32; 3],
        pub radius: f32,
        pub material: u32,
    }
}

impl PackShape for scene::Sphere {
    const VIEW_COORDINATES: bool = true;

    fn pack(_: &Scene, frame: &Frame, s: &Instance<scene::Sphere>, material: u32) -> Sphere {
        Sphere {
            center: frame.point(s.center),
            radius: s.radius as f32,
            material,
            ..Zeroable::zeroed()
        }
    }
}
