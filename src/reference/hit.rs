//! A ray's hit on a surface, and the two constructions that several shapes'
//! hit tests share (docs/implementation.md, "Intersections").

use glam::DVec3;

use super::ray::Ray;

/// A point where a ray meets a surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Distance along the (unit) ray direction.
    pub t: f64,
    /// The hit point.
    pub p: DVec3,
    /// Outward unit (geometric) normal at `p`: for a plane the declared
    /// normal. It decides whether a ray enters or leaves, and secondary rays
    /// start off the surface along it.
    pub n: DVec3,
    /// The outward unit shading normal: `n`, but for smooth meshes the
    /// interpolated vertex normal (docs/rendering-model.md, "Triangle
    /// meshes"). Lighting and the mirror direction use it.
    pub shading: DVec3,
    /// The magnitude of the numbers that computing `p` involved and that a
    /// later test of a ray from `p` against the same shape will involve (for
    /// a box its position and size, for a plane its point; for a sphere see
    /// [`hit_sphere`]): the rounding error of `p` along the normal, and of
    /// that test, is a few eps times the larger of this and `|p|`. It sizes
    /// the offset of secondary rays (`offset_ray`).
    pub error_scale: f64,
    /// For a triangle of a mesh, the barycentric weights of its three
    /// vertices at `p` (the barycentric view, docs/views.md).
    pub barycentric: Option<[f64; 3]>,
}

impl Hit {
    /// A hit whose shading normal is its geometric normal.
    pub fn new(t: f64, p: DVec3, n: DVec3, error_scale: f64) -> Hit {
        Hit {
            t,
            p,
            n,
            shading: n,
            error_scale,
            barycentric: None,
        }
    }
}

/// The foot of the perpendicular from `anchor` to the ray, relative to the
/// anchor, and its ray parameter `s` (`o + s d = anchor + g`, `g`
/// perpendicular to `d`; the shader's `foot`). The decomposition behind
/// Hearn and Baker's discriminant: intersecting from the foot keeps the
/// numbers at the size of the shape however far the origin is, and one
/// Gram-Schmidt step removes the error of `f + s d` along `d`.
pub fn foot(ray: &Ray, anchor: DVec3) -> (DVec3, f64) {
    let f = ray.origin - anchor;
    let s = -f.dot(ray.dir);
    let g0 = f + s * ray.dir;
    (g0 - g0.dot(ray.dir) * ray.dir, s)
}

/// The unit axis along the largest component of `v`, with its sign:
/// `sign(v_i) e_i`, x before y before z on a tie, +1 for 0 (the shader's
/// `major_axis`).
pub fn major_axis(v: DVec3) -> DVec3 {
    let a = v.abs();
    let e = if a.x >= a.y && a.x >= a.z {
        DVec3::X
    } else if a.y >= a.z {
        DVec3::Y
    } else {
        DVec3::Z
    };
    if v.dot(e) >= 0.0 { e } else { -e }
}
