//! The quantities of the views at pixel centres (docs/views.md), in f64:
//! what the shader's `view_quantity` (`shaders/views.wgsl`) reports for the
//! first hit of the ray through the centre of a pixel and the lens centre.
//! The tests compare the two pixel by pixel.

use glam::{DVec2, DVec3};

use super::PreparedScene;
use super::camera::camera_ray;
use super::intersect::{ShapeId, nearest_hit};
use super::shapes::Shapes;

/// What the normals, depth, object id and barycentric views show of the
/// first hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewHit {
    /// The shape hit (the object id view).
    pub shape: ShapeId,
    /// The distance from the eye (the depth view).
    pub t: f64,
    /// The outward geometric normal (the geometric view).
    pub normal: DVec3,
    /// The outward shading normal (the normals view).
    pub shading: DVec3,
    /// A triangle's barycentric weights, a sphere's `(u, v, 0)`, zeros
    /// for the other shapes (the barycentric view; each kind's
    /// `Prepare::view_coordinates`).
    pub barycentric: [f64; 3],
}

/// The first hit of the ray through the centre of pixel `(i, j)` of a
/// `width x height` image (row 0 at the top), through the lens centre;
/// `None` where it hits nothing.
pub fn view_hit(scene: &PreparedScene, width: u32, height: u32, i: u32, j: u32) -> Option<ViewHit> {
    let scene = scene.sized(height);
    let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
    let ray = camera_ray(&scene.camera, width, height, x, y, DVec2::ZERO);
    let (shape, hit) = nearest_hit(&scene, &ray)?;
    let barycentric = Shapes::view_coordinates(shape, &hit);
    Some(ViewHit {
        shape,
        t: hit.t,
        normal: hit.n,
        shading: hit.shading,
        barycentric,
    })
}
