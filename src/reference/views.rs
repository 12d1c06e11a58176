//! The quantities of the views at pixel centres (docs/views.md), in f64:
//! what the shader's `view_quantity` (`shaders/views.wgsl`) reports for the
//! first hit of the ray through the centre of a pixel and the lens centre.
//! The tests compare the two pixel by pixel.

use glam::{DVec2, DVec3};

use super::PreparedScene;
use super::camera::camera_ray;
use super::intersect::{ShapeId, nearest_hit};
use crate::scene::ShapeKind;

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
    /// A triangle's barycentric weights; a sphere's `(u, v, 0)`
    /// ([`sphere_uv`]); zeros for the other shapes (the barycentric view).
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
    let barycentric = match (hit.barycentric, shape.kind()) {
        (Some(b), _) => b,
        (None, ShapeKind::Sphere) => sphere_uv(hit.n),
        (None, _) => [0.0; 3],
    };
    Some(ViewHit {
        shape,
        t: hit.t,
        normal: hit.n,
        shading: hit.shading,
        barycentric,
    })
}

/// A sphere's texture coordinates at the outward normal `n`: `u` the
/// longitude about +y from -x (`0.5 + atan2(n.z, n.x) / 2 pi`), `v` the
/// colatitude from +y (`acos(n.y) / pi`); the third is 0.
pub fn sphere_uv(n: DVec3) -> [f64; 3] {
    use std::f64::consts::PI;
    [
        0.5 + n.z.atan2(n.x) / (2.0 * PI),
        n.y.clamp(-1.0, 1.0).acos() / PI,
        0.0,
    ]
}
