//! One file per shape kind: the `#[repr(C)]` twin of the kind's WGSL struct
//! (field for field, same names), how one scene shape is packed into it, and
//! the kind's WGSL file (`shaders/shapes/<kind>.wgsl`). Adding a kind here is
//! one file plus one line in [`for_each_packed_shape!`] (see
//! docs/implementation.md, "Adding a shape kind"); the buffers, bindings,
//! counts, feature flags and WGSL loops follow from [`kinds`].

use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use crate::scene::{Camera, Scene, ShapeKind, ShapeList};

mod cube;
pub mod implicit;
mod julia;
mod placed;
mod plane;
mod sphere;
mod torus;

pub use cube::Cube;
pub use implicit::Implicit;
pub use julia::Julia;
pub use plane::Plane;
pub use sphere::Sphere;
pub use torus::Torus;

/// The registry of packed shape kinds: calls `$m!` with `(Rust type, WGSL
/// struct name)` for every kind, so that code that must visit every kind
/// (today: the layout test) cannot forget one.
#[macro_export]
#[doc(hidden)]
macro_rules! for_each_packed_shape {
    ($m:ident) => {
        $m!(Sphere, "Sphere");
        $m!(Plane, "Plane");
        $m!(Cube, "Cube");
        $m!(Torus, "Torus");
        $m!(Implicit, "Implicit");
        $m!(Julia, "Julia");
    };
}
pub use for_each_packed_shape;

/// The frame that packed positions are measured in. Positions are made
/// relative to `origin` in f64 *before* rounding to f32, so that a scene far
/// from the world origin keeps its f32 precision near the camera
/// (docs/implementation.md, "Camera-relative coordinates"). The renderer
/// packs around the camera target ([`Frame::around_target`]); the naive
/// variant keeps the world frame ([`Frame::WORLD`]) to show what that fixes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    pub origin: DVec3,
}

impl Frame {
    /// The world frame: positions packed as they are in the scene file.
    pub const WORLD: Frame = Frame {
        origin: DVec3::ZERO,
    };

    /// The frame centred on the camera's target (`Camera::frame_origin`).
    pub fn around_target(camera: &Camera) -> Frame {
        Frame {
            origin: camera.frame_origin(),
        }
    }

    /// A point, relative to the frame, rounded to the f32 triple the shader reads.
    pub fn point(&self, p: DVec3) -> [f32; 3] {
        f32x3(p - self.origin)
    }
}

/// A GPU struct packed from one scene shape of its kind.
pub trait PackShape: Pod + Zeroable {
    /// The scene's description of one shape of this kind.
    type Source: ShapeList;

    /// The kind's WGSL: its struct and `hit_<kind>` (embedded; hot reload
    /// reads `shapes/<kind>.wgsl` of the shader folder instead).
    const WGSL: &'static str;

    /// Packs `shape`; `scene` resolves its material name to a slot, `frame`
    /// says where positions are measured from.
    fn pack(scene: &Scene, frame: &Frame, shape: &Self::Source) -> Self;
}

/// Rounds an f64 vector (a direction, a size, a colour) to the f32 triple the
/// shader reads. Positions go through [`Frame::point`] instead.
pub(crate) fn f32x3(v: DVec3) -> [f32; 3] {
    v.as_vec3().to_array()
}

/// A packed kind as the shader composer and the buffers see it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KindInfo {
    pub kind: ShapeKind,
    /// The WGSL struct name, e.g. `Sphere`.
    pub wgsl_struct: &'static str,
    /// The embedded `shaders/shapes/<kind>.wgsl`.
    pub wgsl: &'static str,
}

impl KindInfo {
    /// `sphere`: the kind's WGSL file stem and the suffix of `hit_<name>`.
    pub fn name(&self) -> String {
        self.kind.name().to_lowercase()
    }

    /// The file of the shader folder that holds its WGSL.
    pub fn file(&self) -> String {
        format!("shapes/{}.wgsl", self.name())
    }
}

/// The name of a kind's pipeline flag (`override` in WGSL): `HAS_SPHERES`.
pub fn has_flag(kind: ShapeKind) -> String {
    format!("HAS_{}", kind.key().to_uppercase())
}

/// Every packed kind, in registry order (which is also the order of their
/// buffers' bindings, from `FIRST_SHAPE_BINDING`).
pub fn kinds() -> Vec<KindInfo> {
    let mut kinds = Vec::new();
    macro_rules! info {
        ($t:ident, $wgsl:literal) => {
            kinds.push(KindInfo {
                kind: <<$t as PackShape>::Source as ShapeList>::KIND,
                wgsl_struct: $wgsl,
                wgsl: <$t as PackShape>::WGSL,
            });
        };
    }
    for_each_packed_shape!(info);
    kinds
}

/// The shapes of one kind packed as `u32` words (every packed struct is
/// made of 4-byte fields), at least one zeroed element, since a storage
/// buffer may not be empty.
pub fn pack_kind<T: PackShape>(scene: &Scene, frame: &Frame) -> Vec<u32> {
    let mut shapes: Vec<T> = T::Source::list(scene)
        .iter()
        .map(|s| T::pack(scene, frame, s))
        .collect();
    if shapes.is_empty() {
        shapes.push(T::zeroed());
    }
    bytemuck::cast_slice(&shapes).to_vec()
}

/// Every kind's buffer contents, in registry order.
pub fn pack_all(scene: &Scene, frame: &Frame) -> Vec<Vec<u32>> {
    let mut buffers = Vec::new();
    macro_rules! pack {
        ($t:ident, $wgsl:literal) => {
            buffers.push(pack_kind::<$t>(scene, frame));
        };
    }
    for_each_packed_shape!(pack);
    buffers
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scene kind without a packed twin would never reach the GPU.
    #[test]
    fn every_scene_kind_is_packed_once() {
        let packed: Vec<ShapeKind> = kinds().iter().map(|k| k.kind).collect();
        for kind in ShapeKind::ALL {
            let times = packed.iter().filter(|k| *k == kind).count();
            assert_eq!(
                times,
                1,
                "{} is packed {times} times in gpu/shapes",
                kind.name()
            );
        }
        assert_eq!(packed.len(), ShapeKind::ALL.len());
    }
}
