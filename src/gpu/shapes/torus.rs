//! A torus as `shaders/shapes/torus.wgsl` reads it.

use bytemuck::{Pod, Zeroable};

use super::{Frame, PackShape, placed};
use crate::scene::{self, Scene};

#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct Torus {
    pub center: [f32; 3],
    pub scale: f32,
    /// `mat3x3<f32>`: three columns, each padded to 16 bytes.
    pub rotation: [[f32; 4]; 3],
    pub major: f32,
    pub minor: f32,
    pub material: u32,
    pub _pad: u32,
}

impl PackShape for Torus {
    type Source = scene::Torus;
    const WGSL: &'static str = include_str!("../../../shaders/shapes/torus.wgsl");
    const OCCLUDES: bool = true;

    fn pack(scene: &Scene, frame: &Frame, t: &scene::Torus) -> Self {
        let (center, scale, rotation) = placed::pack(frame, &t.placement);
        Torus {
            center,
            scale,
            rotation,
            major: t.major_radius as f32,
            minor: t.minor_radius as f32,
            material: scene.material_slot(t.material.as_deref()),
            _pad: 0,
        }
    }
}
