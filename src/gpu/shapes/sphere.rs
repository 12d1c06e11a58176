//! A sphere as `shaders/shapes/sphere.wgsl` reads it.

use bytemuck::{Pod, Zeroable};

use super::{Frame, PackShape};
use crate::scene::{self, Scene};

#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct Sphere {
    pub center: [f32; 3],
    pub radius: f32,
    pub material: u32,
    pub _pad0: u32,
    pub _pad1: u32,
    pub _pad2: u32,
}

impl PackShape for Sphere {
    type Source = scene::Sphere;
    const WGSL: &'static str = include_str!("../../../shaders/shapes/sphere.wgsl");

    fn pack(scene: &Scene, frame: &Frame, s: &scene::Sphere) -> Self {
        Sphere {
            center: frame.point(s.center),
            radius: s.radius as f32,
            material: scene.material_slot(s.material.as_deref()),
            ..Zeroable::zeroed()
        }
    }
}
