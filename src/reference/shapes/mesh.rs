//! A triangle mesh for the f64 tracer (docs/rendering-model.md, "Triangle
//! meshes"): the ray is taken into the mesh's own coordinates, where its
//! triangles sit in a BVH built once per loaded geometry (`bvh::triangle_bvh`),
//! and each triangle is tested with the method [`ReferenceOptions`] names.

use std::sync::Arc;

use glam::{DMat3, DVec3};

use super::{Prepare, Trace};
use crate::bvh::{Bvh, triangle_bvh};
use crate::reference::ReferenceOptions;
use crate::reference::hit::Hit;
use crate::reference::ray::Ray;
use crate::scene::{self, Geometry, Instance, TriangleTest};

/// A placed mesh: its shared geometry and BVH, and the transform.
#[derive(Debug, Clone)]
pub struct Mesh {
    pub geometry: Arc<Geometry>,
    pub bvh: Arc<Bvh<u32>>,
    pub translate: DVec3,
    /// Local to world, `R * diag(scale)`, and its inverse.
    pub linear: DMat3,
    pub inverse: DMat3,
    /// The largest world coordinate of the mesh's box, see
    /// `Hit::error_scale`.
    pub error_scale: f64,
}

impl Prepare for scene::Mesh {
    type Traced = Mesh;

    fn prepare(shape: &Instance<Self>) -> Mesh {
        let [lo, hi] = shape.bounds();
        let linear = shape.placement.linear();
        Mesh {
            geometry: shape.geometry.0.clone(),
            bvh: triangle_bvh(&shape.geometry.0),
            translate: shape.placement.translate,
            linear,
            inverse: linear.inverse(),
            error_scale: lo.abs().max(hi.abs()).max_element(),
        }
    }
}

/// Where a ray meets one triangle: `t` and the barycentric weights of its
/// three vertices (they sum to 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriangleHit {
    pub t: f64,
    pub b: [f64; 3],
}

impl Trace for Mesh {
    fn hit(&self, ray: &Ray, t_max: f64, options: &ReferenceOptions) -> Option<Hit> {
        // The local ray o' + t d' passes the local point of world o + t d:
        // t is the same in both frames (d' is not unit length).
        let local = Ray {
            origin: self.inverse * (ray.origin - self.translate),
            dir: self.inverse * ray.dir,
        };
        let g = &self.geometry;
        let mut nearest: Option<(u32, TriangleHit)> = None;
        self.bvh.traverse(local.origin, local.dir, t_max, |tri, t| {
            let [a, b, c] = g.triangles[tri as usize].map(|v| g.positions[v as usize]);
            match hit_triangle(options.kinds.meshes, &local, [a, b, c], t) {
                Some(h) => {
                    nearest = Some((tri, h));
                    Some(h.t)
                }
                None => Some(t),
            }
        });
        let (tri, h) = nearest?;
        Some(self.surface(tri, h))
    }
}

impl Mesh {
    /// The world hit of triangle `tri`: the point from the barycentric
    /// weights, the geometric normal `cross(p1 - p0, p2 - p0)` and the
    /// shading normal (interpolated vertex normals when smooth), both
    /// turned into the world by the inverse transpose of `linear`.
    fn surface(&self, tri: u32, h: TriangleHit) -> Hit {
        let g = &self.geometry;
        let idx = g.triangles[tri as usize];
        let [p0, p1, p2] = idx.map(|v| g.positions[v as usize]);
        let local_point = h.b[0] * p0 + h.b[1] * p1 + h.b[2] * p2;
        let to_world_normal = self.inverse.transpose();
        let n = (to_world_normal * (p1 - p0).cross(p2 - p0)).normalize();
        let shading = if g.normals.is_empty() {
            n
        } else {
            let [n0, n1, n2] = idx.map(|v| g.normals[v as usize]);
            let local_n = h.b[0] * n0 + h.b[1] * n1 + h.b[2] * n2;
            (to_world_normal * local_n).try_normalize().unwrap_or(n)
        };
        Hit {
            t: h.t,
            p: self.translate + self.linear * local_point,
            n,
            shading,
            error_scale: self.error_scale,
            barycentric: Some(h.b),
        }
    }
}

/// The hit of the ray with the triangle `p` by `test`, with `0 < t < t_max`.
pub fn hit_triangle(
    test: TriangleTest,
    ray: &Ray,
    p: [DVec3; 3],
    t_max: f64,
) -> Option<TriangleHit> {
    match test {
        TriangleTest::Cramer => hit_cramer(ray, p, t_max),
        TriangleTest::MollerTrumbore => hit_moller_trumbore(ray, p, t_max),
        TriangleTest::Watertight => hit_watertight(ray, p, t_max),
    }
}

/// The signed volume `det(a, b, c) = a . (b x c)`.
fn det(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    a.dot(b.cross(c))
}

/// Cramer's rule (Shirley and Marschner, "Fundamentals of Computer
/// Graphics", 4.4.2): the hit `o + t d = p0 + b1 e1 + b2 e2` (`e1 = p1 -
/// p0`, `e2 = p2 - p0`) is the linear system
/// `[-d e1 e2] (t, b1, b2) = s` with `s = o - p0`, solved by Cramer's rule:
/// each unknown is a ratio of determinants, the signed volumes of the
/// parallelepipeds spanned by the columns with `s` put in its place.
/// `D = det(-d, e1, e2) = 0` means the ray is parallel to the plane.
/// Derivation: Shirley and Marschner, "Fundamentals of Computer Graphics",
/// 4.4.2 (Cramer's rule for the ray-triangle system).
pub fn hit_cramer(ray: &Ray, [p0, p1, p2]: [DVec3; 3], t_max: f64) -> Option<TriangleHit> {
    let (e1, e2, s, d) = (p1 - p0, p2 - p0, ray.origin - p0, -ray.dir);
    let volume = det(d, e1, e2);
    if volume == 0.0 {
        return None;
    }
    let t = det(s, e1, e2) / volume;
    let b1 = det(d, s, e2) / volume;
    let b2 = det(d, e1, s) / volume;
    inside(t, [1.0 - b1 - b2, b1, b2], t_max)
}

/// Möller and Trumbore, "Fast, Minimum Storage Ray/Triangle Intersection"
/// (JGT 1997): the same system as [`hit_cramer`], with the determinants
/// written as scalar triple products that share two cross products,
/// `p = d x e2` and `q = s x e1`, and early exits on the barycentrics.
pub fn hit_moller_trumbore(ray: &Ray, [p0, p1, p2]: [DVec3; 3], t_max: f64) -> Option<TriangleHit> {
    let (e1, e2) = (p1 - p0, p2 - p0);
    let p = ray.dir.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 {
        return None;
    }
    let inv = 1.0 / det;
    let s = ray.origin - p0;
    let b1 = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&b1) {
        return None;
    }
    let q = s.cross(e1);
    let b2 = ray.dir.dot(q) * inv;
    if b2 < 0.0 || b1 + b2 > 1.0 {
        return None;
    }
    inside(e2.dot(q) * inv, [1.0 - b1 - b2, b1, b2], t_max)
}

/// Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection" (JCGT
/// 2013), as pbrt-v4 writes it (`IntersectTriangle`): the vertices are moved
/// into a frame where the ray starts at the origin and runs along +z (a
/// translation, a permutation of axes that makes z the largest component
/// of d, and a shear), so the test becomes 2D: the signs of the three edge
/// functions `e_i` (twice the signed areas of the triangles the origin makes
/// with each edge). A point on a shared edge gets `e = 0` from both
/// triangles, computed from the same numbers, so it is inside at least one
/// of them: no ray slips through.
pub fn hit_watertight(ray: &Ray, p: [DVec3; 3], t_max: f64) -> Option<TriangleHit> {
    let d = ray.dir;
    let kz = d.abs().max_position();
    let kx = (kz + 1) % 3;
    let ky = (kx + 1) % 3;
    let permute = |v: DVec3| DVec3::new(v[kx], v[ky], v[kz]);
    let d = permute(d);
    let [a, b, c] = p.map(|v| permute(v - ray.origin));
    let (sx, sy, sz) = (-d.x / d.z, -d.y / d.z, 1.0 / d.z);
    let shear = |v: DVec3| DVec3::new(v.x + sx * v.z, v.y + sy * v.z, v.z);
    let [a, b, c] = [shear(a), shear(b), shear(c)];
    let e0 = b.x * c.y - b.y * c.x;
    let e1 = c.x * a.y - c.y * a.x;
    let e2 = a.x * b.y - a.y * b.x;
    if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
        return None;
    }
    let det = e0 + e1 + e2;
    if det == 0.0 {
        return None;
    }
    let t_scaled = e0 * a.z * sz + e1 * b.z * sz + e2 * c.z * sz;
    let t = t_scaled / det;
    inside(t, [e0 / det, e1 / det, e2 / det], t_max)
}

/// A hit if the weights are all >= 0 (they sum to 1) and `0 < t < t_max`.
fn inside(t: f64, b: [f64; 3], t_max: f64) -> Option<TriangleHit> {
    let on_triangle = b.iter().all(|&w| w >= 0.0);
    (on_triangle && t > 0.0 && t < t_max).then_some(TriangleHit { t, b })
}
