//! One file per shape kind: the `#[repr(C)]` twin of the kind's WGSL struct
//! (field for field, same names) and how one scene shape is packed into it.
//! Adding a kind here is one file plus one line in [`for_each_packed_shape!`]
//! (see docs/implementation.md, "Adding a shape kind").

use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use crate::scene::{Camera, Scene};

mod cube;
mod plane;
mod sphere;

pub use cube::Cube;
pub use plane::Plane;
pub use sphere::Sphere;

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
    type Source;

    /// Packs `shape`; `scene` resolves its material name to a slot, `frame`
    /// says where positions are measured from.
    fn pack(scene: &Scene, frame: &Frame, shape: &Self::Source) -> Self;
}

/// Rounds an f64 vector (a direction, a size, a colour) to the f32 triple the
/// shader reads. Positions go through [`Frame::point`] instead.
pub(crate) fn f32x3(v: DVec3) -> [f32; 3] {
    v.as_vec3().to_array()
}
