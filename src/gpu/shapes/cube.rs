//! A rotated box as `shaders/shapes/cube.wgsl` reads it.

use super::{Frame, PackShape, f32x3, placed};
use crate::scene::{self, Scene};
use bytemuck::{Pod, Zeroable};

#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct Cube {
    pub center: [f32; 3],
    pub material: u32,
    pub half_size: [f32; 3],
    pub _pad: u32,
    /// `mat3x3<f32>`: three columns, each padded to 16 bytes.
    pub rotation: [[f32; 4]; 3],
}

impl PackShape for Cube {
    type Source = scene::Cube;
    const WGSL: &'static str = include_str!("../../../shaders/shapes/cube.wgsl");

    fn pack(scene: &Scene, frame: &Frame, c: &scene::Cube) -> Self {
        Cube {
            center: frame.point(c.center),
            material: scene.material_slot(c.material.as_deref()),
            half_size: f32x3(c.size.edges() * 0.5),
            _pad: 0,
            rotation: placed::rotation_columns(&c.placement()),
        }
    }
}
