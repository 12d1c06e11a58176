//! An infinite plane as `shaders/shapes/plane.wgsl` reads it.

use bytemuck::{Pod, Zeroable};

use super::{Frame, PackShape, f32x3};
use crate::scene::{self, Scene};

#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct Plane {
    pub point: [f32; 3],
    pub material: u32,
    pub normal: [f32; 3],
    pub _pad: u32,
}

impl PackShape for Plane {
    type Source = scene::Plane;
    const WGSL: &'static str = include_str!("../../../shaders/shapes/plane.wgsl");

    fn pack(scene: &Scene, frame: &Frame, p: &scene::Plane) -> Self {
        Plane {
            point: frame.point(p.point),
            material: scene.material_slot(p.material.as_deref()),
            normal: f32x3(p.normal),
            _pad: 0,
        }
    }
}
