//! A torus as `shaders/shapes/torus.wgsl` reads it.

use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use super::{Frame, PackShape};
use crate::scene::{self, Scene};

/// The torus in world units: a surface of revolution needs only its centre,
/// its axis and its two radii (turning it about its own axis changes
/// nothing), so the shader reads 8 numbers instead of a whole placement
/// (docs/implementation.md, "Torus").
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct Torus {
    pub center: [f32; 3],
    /// R, the ring's radius, times the scale.
    pub major: f32,
    /// The local y axis turned by the rotation, unit length.
    pub axis: [f32; 3],
    /// r, the tube's radius, times the scale.
    pub minor: f32,
    pub material: u32,
    pub _pad0: u32,
    pub _pad1: u32,
    pub _pad2: u32,
}

impl PackShape for Torus {
    type Source = scene::Torus;
    const WGSL: &'static str = include_str!("../../../shaders/shapes/torus.wgsl");
    const OCCLUDES: bool = true;

    fn pack(scene: &Scene, frame: &Frame, t: &scene::Torus) -> Self {
        let placement = &t.placement;
        let axis = (placement.rotation_matrix() * DVec3::Y).normalize();
        Torus {
            center: frame.point(placement.translate),
            major: (placement.scale * t.major_radius) as f32,
            axis: axis.as_vec3().to_array(),
            minor: (placement.scale * t.minor_radius) as f32,
            material: scene.material_slot(t.material.as_deref()),
            ..Zeroable::zeroed()
        }
    }
}
