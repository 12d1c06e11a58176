//! A user's implicit surface as `shaders/shapes/implicit.wgsl` reads it,
//! and the scene's distinct functions, which the shader gets as generated
//! WGSL (`src/gpu/shaders.rs`).

use bytemuck::Zeroable;

use super::{Frame, PackShape, f32x3, packed_struct, placement};
use crate::scene::{self, Instance, Scene};

packed_struct! {
    pub struct Implicit {
        pub center: [f32; 3],
        pub scale: f32,
        /// `mat3x3<f32>`: three columns, each padded to 16 bytes.
        pub rotation: [[f32; 4]; 3],
        pub bounds_min: [f32; 3],
        /// Index into [`functions`] of the scene.
        pub function: u32,
        pub bounds_max: [f32; 3],
        pub steps: u32,
        pub material: u32,
        pub _pad0: u32,
        pub _pad1: u32,
        pub _pad2: u32,
    }
}

/// The scene's distinct functions (as written), in order of first use: the
/// shader has one WGSL function per entry, and a scene whose functions are
/// the same set reuses its pipeline.
pub fn functions(scene: &Scene) -> Vec<String> {
    let mut distinct: Vec<String> = Vec::new();
    for implicit in &scene.implicits {
        if !distinct.contains(&implicit.f) {
            distinct.push(implicit.f.clone());
        }
    }
    distinct
}

impl PackShape for scene::Implicit {
    type Packed = Implicit;
    const WGSL: &'static str = include_str!("../../../shaders/shapes/implicit.wgsl");

    fn pack(
        scene: &Scene,
        frame: &Frame,
        i: &Instance<scene::Implicit>,
        material: u32,
    ) -> Implicit {
        let (center, scale, rotation) = placement::pack(frame, &i.placement);
        let function = functions(scene)
            .iter()
            .position(|f| *f == i.f)
            .expect("every implicit's function is in the set") as u32;
        Implicit {
            center,
            scale,
            rotation,
            bounds_min: f32x3(i.bounds[0]),
            function,
            bounds_max: f32x3(i.bounds[1]),
            steps: i.steps,
            material,
            ..Zeroable::zeroed()
        }
    }
}
