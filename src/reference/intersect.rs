//! Ray-shape intersection (docs/rendering-model.md, "Shapes"; docs/implementation.md
//! "Intersections"): spheres, planes and boxes, the nearest hit over the
//! scene, and the any-hit query of shadow rays.
//!
//! Every routine accepts only hits with `0 < t < t_max` (the rendering model's
//! `0 < t < t_closest`) and returns the outward geometric normal, unit length.

use glam::{DMat3, DVec3};

use super::PreparedScene;
use super::ray::Ray;
use crate::bvh::Prim;

/// A point where a ray meets a surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Distance along the (unit) ray direction.
    pub t: f64,
    /// The hit point.
    pub p: DVec3,
    /// Outward unit normal at `p`: for a plane the declared normal.
    pub n: DVec3,
    /// The magnitude of the numbers that computing `p` involved and that a
    /// later test of a ray from `p` against the same shape will involve (for
    /// a box its position and size, for a plane its point; for a sphere see
    /// [`hit_sphere`]): the rounding error of `p` along the normal, and of
    /// that test, is a few eps times the larger of this and `|p|`. It sizes
    /// the offset of secondary rays (`offset_ray`).
    pub error_scale: f64,
}

/// Which shape of the scene: the index into the scene's `spheres`, `planes`
/// or `cubes`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ShapeId {
    Sphere(usize),
    Plane(usize),
    Cube(usize),
}

/// A sphere; `material` indexes `PreparedScene::materials`.
#[derive(Debug, Clone)]
pub struct Sphere {
    pub center: DVec3,
    pub radius: f64,
    pub material: usize,
}

impl Sphere {
    pub fn new(center: DVec3, radius: f64, material: usize) -> Self {
        Self {
            center,
            radius,
            material,
        }
    }
}

/// An infinite, two-sided, thin plane with unit `normal`.
#[derive(Debug, Clone)]
pub struct Plane {
    pub point: DVec3,
    pub normal: DVec3,
    pub material: usize,
    /// `|point|_max`, see [`Hit::error_scale`].
    pub error_scale: f64,
}

impl Plane {
    /// `normal` is normalised here; a zero normal (which validation rejects)
    /// gives a plane that every ray misses.
    pub fn new(point: DVec3, normal: DVec3, material: usize) -> Self {
        Self {
            point,
            normal: normal.normalize_or_zero(),
            material,
            error_scale: point.abs().max_element(),
        }
    }
}

/// A box `center + rotation * p_local` for `p_local` in `[-half, half]`.
#[derive(Debug, Clone)]
pub struct Cube {
    pub center: DVec3,
    /// Half the edge lengths, along the local axes.
    pub half: DVec3,
    /// `Rz Ry Rx`: local to world.
    pub rotation: DMat3,
    /// Its transpose (= inverse): world to local.
    pub inverse: DMat3,
    pub material: usize,
    /// `|center|_max + |half|`, see [`Hit::error_scale`].
    pub error_scale: f64,
}

impl Cube {
    /// A box of edge lengths `edges` turned by the rotation matrix `rotation`.
    pub fn new(center: DVec3, edges: DVec3, rotation: DMat3, material: usize) -> Self {
        let half = 0.5 * edges;
        Self {
            center,
            half,
            rotation,
            // A rotation's inverse is its transpose.
            inverse: rotation.transpose(),
            material,
            error_scale: center.abs().max_element() + half.length(),
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

/// The sphere hit nearest to the ray origin with `0 < t < t_max`.
///
/// Numerics (docs/implementation.md, docs/accuracy.md; Haines, Günther and
/// Akenine-Möller, "Precision Improvements for Ray/Sphere Intersection", Ray
/// Tracing Gems ch. 7): with unit `d` and `f = o - c` the quadratic is
/// `t^2 + 2 b t + c = 0`, `b = f.d`. The textbook discriminant `b^2 - c`
/// cancels catastrophically for small spheres far away; the equivalent
/// `r^2 - |g|^2` with `g = f - b d` (Hearn and Baker) measures the squared
/// distance from the centre to the ray directly. The roots come from
/// `q = -(b + sign(b) sqrt(disc))` as `q` and `c / q`, which never subtracts
/// nearly equal numbers (Press et al., Numerical Recipes 5.6).
///
/// Refinements for scenes with large numbers, the same as the shader's:
/// - `g` is perpendicular to `d`, so one Gram-Schmidt step (`g -= (g.d) d`)
///   removes the rounding error of `f - b d` along `d`;
/// - `c = |f|^2 - r^2` is formed as `(f - r u).(f + r u) = |s|^2 + 2 r s.u`
///   with `u` the major axis of `f` and `s = o - (centre + r u)`, the origin
///   relative to the sphere's nearest pole: on a huge ground sphere `f` is
///   rounded at the scale of the radius, `s` is not;
/// - with `c` that accurate, the textbook `b^2 - c` has the rounding error
///   `eps (b^2 + |c|)` against `eps r^2` for `r^2 - |g|^2`; the smaller wins
///   (near a huge sphere, e.g. at its horizon, the first);
/// - the normal is `normalize(g -+ sqrt(disc) d)` (`f + t d` for the near and
///   the far root, `t = -b -+ sqrt(disc)`), and the hit point is `o + t d`
///   when those numbers are smaller than the centre's, else the re-projection
///   `centre + r n`.
///
/// From inside (`c < 0`) the roots have opposite signs and the far one is
/// hit. `error_scale` is the size of the numbers the hit point and a later
/// test against this sphere involve (see [`Hit::error_scale`]).
pub fn hit_sphere(sphere: &Sphere, ray: &Ray, t_max: f64) -> Option<Hit> {
    let (d, r, centre) = (ray.dir, sphere.radius, sphere.center);
    let f = ray.origin - centre;
    let b = f.dot(d);
    let g = foot(ray, centre).0;
    let u = major_axis(f);
    let from_pole = ray.origin - (centre + r * u);
    let c = from_pole.length_squared() + 2.0 * r * from_pole.dot(u);
    // Of the discriminant's two forms, the one with the smaller rounding
    // error: eps r^2 for r^2 - |g|^2, eps (b^2 + |c|) for b^2 - c.
    let disc = if b * b + c.abs() < r * r {
        b * b - c
    } else {
        r * r - g.length_squared()
    };
    if disc < 0.0 || r * r == 0.0 {
        return None;
    }
    let h = disc.sqrt();
    let sign_b = if b >= 0.0 { 1.0 } else { -1.0 }; // sign(0) = +1
    let q = -(b + sign_b * h);
    if q == 0.0 {
        return None;
    }
    let (t0, t1) = (c / q, q);
    let (near, far) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
    // The near root is -b - sqrt(disc), the far one -b + sqrt(disc).
    let (t, along) = if near > 0.0 && near < t_max {
        (near, -h)
    } else if far > 0.0 && far < t_max {
        (far, h)
    } else {
        return None;
    };
    let n = (g + along * d).normalize();
    let ray_scale = ray.origin.abs().max_element() + t;
    let centre_scale = centre.abs().max_element() + r;
    let p = if ray_scale < centre_scale {
        ray.at(t)
    } else {
        centre + r * n
    };
    let pole_scale = (centre + r * major_axis(n)).abs().max_element();
    Some(Hit {
        t,
        p,
        n,
        error_scale: pole_scale.max(ray_scale.min(centre_scale)),
    })
}

/// The lecture's sphere (the naive variant, `ReferenceOptions::robust =
/// false`, the shader's `hit_sphere_naive`): `a t^2 + b t + c = 0` with
/// `a = d.d`, `b = 2 f.d`, `c = f.f - r^2`, `disc = b^2 - 4ac` and
/// `t = (-b -+ sqrt(disc)) / 2a`; the hit point `o + t d` and the normal
/// `(p - c) / r`, as on the slides.
pub fn hit_sphere_naive(sphere: &Sphere, ray: &Ray, t_max: f64) -> Option<Hit> {
    let d = ray.dir;
    let f = ray.origin - sphere.center;
    let a = d.dot(d);
    let b = 2.0 * f.dot(d);
    let c = f.dot(f) - sphere.radius * sphere.radius;
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return None;
    }
    let mut t = (-b - disc.sqrt()) / (2.0 * a);
    if t <= 0.0 {
        t = (-b + disc.sqrt()) / (2.0 * a);
    }
    if t <= 0.0 || t >= t_max {
        return None;
    }
    let p = ray.at(t);
    Some(Hit {
        t,
        p,
        n: (p - sphere.center) / sphere.radius,
        error_scale: 0.0,
    })
}

/// The plane hit with `0 < t < t_max`.
///
/// `t = ((point - o).n) / (n.d)`. A ray parallel to the plane (`n.d = 0`, or
/// so small that `t` would be astronomically large) misses: the test
/// `|num| < |denom| 1e30` rejects it without ever forming inf or NaN. The hit
/// point is `o + t d` or, when that involves larger numbers (a plane seen from
/// far away), `point + q` from the foot of the perpendicular from `point`
/// ([`foot`]), then re-projected onto the plane. `t` stays the plain
/// quotient, so that a box face lying in the plane ties with it exactly.
pub fn hit_plane(plane: &Plane, ray: &Ray, t_max: f64) -> Option<Hit> {
    let n = plane.normal;
    let denom = n.dot(ray.dir);
    let num = (plane.point - ray.origin).dot(n);
    // A hit needs |num| < |denom| 1e30; with denom = 0 nothing is below 0.
    if num.abs() >= denom.abs() * 1e30 {
        return None;
    }
    let t = num / denom;
    if t <= 0.0 || t >= t_max {
        return None;
    }
    let (g, _) = foot(ray, plane.point);
    let t_foot = -g.dot(n) / denom;
    let mut p =
        if ray.origin.abs().max_element() + t > plane.point.abs().max_element() + t_foot.abs() {
            plane.point + (g + t_foot * ray.dir)
        } else {
            ray.at(t)
        };
    p -= (p - plane.point).dot(n) * n;
    Some(Hit {
        t,
        p,
        n,
        error_scale: plane.error_scale,
    })
}

/// The lecture's plane (the naive variant, the shader's `hit_plane_naive`):
/// parallel when `|n.d| < 1e-6`, else `t = ((point - o).n) / (n.d)` and the
/// hit point `o + t d`, not re-projected.
pub fn hit_plane_naive(plane: &Plane, ray: &Ray, t_max: f64) -> Option<Hit> {
    let n = plane.normal;
    let denom = n.dot(ray.dir);
    if denom.abs() < 1e-6 {
        return None;
    }
    let t = (plane.point - ray.origin).dot(n) / denom;
    if t <= 0.0 || t >= t_max {
        return None;
    }
    Some(Hit {
        t,
        p: ray.at(t),
        n,
        error_scale: 0.0,
    })
}

/// `eps = 2^-53`, half the f64 machine epsilon (the unit roundoff).
const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;
/// pbrt-v4's `gamma(3) = 3 eps / (1 - 3 eps)`: a bound on the relative error
/// of three rounded operations.
const GAMMA_3: f64 = 3.0 * UNIT_ROUNDOFF / (1.0 - 3.0 * UNIT_ROUNDOFF);

/// The box hit with `0 < t < t_max`: the entry face, or the exit face for a
/// ray that starts inside.
///
/// The ray is taken into the box frame (`o' = R^T (o - center)`,
/// `d' = R^T d`), where the box is the intersection of the three slabs
/// `|x_i| <= h_i` (Kay and Kajiya; Williams et al. 2005). The ray is inside
/// slab `i` for `t` between `(-h_i - o'_i) / d'_i` and `(h_i - o'_i) / d'_i`;
/// it is inside the box from `t_near`, the largest entry, to `t_far`, the
/// smallest exit. Why the details:
/// - from an origin more than 16 half edges away the test starts at the foot
///   of the perpendicular from the centre ([`foot`]), at ray parameter `s`,
///   so that the far origin is not rotated into the box frame as a large,
///   rounded vector; from nearby at the origin (`s = 0`), so that a face in a
///   plane gets exactly the plane's `t`;
/// - an axis with `d'_i = 0` is a branch (inside the slab for all `t`, or
///   never) instead of dividing by zero into inf and NaN;
/// - each exit is widened by `2 gamma(3)` of its size as in pbrt-v4
///   (`t_far *= 1 + 2 gamma(3)`, written for either sign), so rounding
///   cannot make a ray through an edge or corner miss (`t_near > t_far`);
/// - on a tie between axes the lowest axis (x, then y, then z) wins, the same
///   choice as the shader;
/// - the hit point is re-projected onto the face (its local coordinate on the
///   face's axis set to exactly `±h_i`), so that its error does not grow with
///   the distance the ray travelled; the offset of secondary rays relies on
///   that (see `offset_ray`).
pub fn hit_cube(cube: &Cube, ray: &Ray, t_max: f64) -> Option<Hit> {
    // From far away (16 half edges) the test starts at the foot of the
    // perpendicular from the centre, at ray parameter s; from nearby at the
    // origin (s = 0), where a face in a plane gets exactly the plane's t.
    let mut rel = ray.origin - cube.center;
    let mut s = 0.0;
    if rel.abs().max_element() > 16.0 * cube.half.max_element() {
        (rel, s) = foot(ray, cube.center);
    }
    let o = cube.inverse * rel;
    let d = cube.inverse * ray.dir;
    let (mut t_near, mut near_axis) = (f64::NEG_INFINITY, 0);
    let (mut t_far, mut far_axis) = (f64::INFINITY, 0);
    for i in 0..3 {
        let h = cube.half[i];
        if d[i] == 0.0 {
            if o[i].abs() > h {
                return None;
            }
            continue;
        }
        let t_minus = (-h - o[i]) / d[i];
        let t_plus = (h - o[i]) / d[i];
        let (enter, exit) = if d[i] > 0.0 {
            (t_minus, t_plus)
        } else {
            (t_plus, t_minus)
        };
        let exit = exit + 2.0 * GAMMA_3 * exit.abs();
        if enter > t_near {
            (t_near, near_axis) = (enter, i);
        }
        if exit < t_far {
            (t_far, far_axis) = (exit, i);
        }
    }
    if t_near > t_far {
        return None;
    }
    // Entry face: normal against the ray, -sign(d'_i) e_i. Exit face (ray
    // starting inside): normal along the ray, sign(d'_i) e_i. The ray
    // parameter is s + the one from where the test started.
    let (t_local, axis, sign) = if s + t_near > 0.0 && s + t_near < t_max {
        (t_near, near_axis, -d[near_axis].signum())
    } else if s + t_far > 0.0 && s + t_far < t_max {
        (t_far, far_axis, d[far_axis].signum())
    } else {
        return None;
    };
    let t = s + t_local;
    // Re-project onto the face, as for the sphere: o + t d is off by the
    // rounding of t times |d|, which grows with the distance travelled.
    let mut p_local = o + t_local * d;
    p_local[axis] = sign * cube.half[axis];
    Some(Hit {
        t,
        p: cube.center + cube.rotation * p_local,
        n: sign * cube.rotation.col(axis),
        error_scale: cube.error_scale,
    })
}

/// WGSL's `sign`: -1, 0 or +1 (Rust's `signum` gives +1 for +0).
fn wgsl_sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// The plain slab test as usually taught (the naive variant, the shader's
/// `hit_cube_naive`): `inv = 1 / d'_i`, the entry and exit of every slab with
/// no special case for `d'_i = 0` (IEEE gives inf and, for an origin on a
/// slab plane, `0 * inf = NaN`, which `f64::min`/`max` then skip), no
/// widening of the far bound, and the hit point `o + t d`, not re-projected.
pub fn hit_cube_naive(cube: &Cube, ray: &Ray, t_max: f64) -> Option<Hit> {
    let o = cube.inverse * (ray.origin - cube.center);
    let d = cube.inverse * ray.dir;
    let h = cube.half;
    let inv = DVec3::ONE / d;
    let ta = (-h - o) * inv;
    let tb = (h - o) * inv;
    let lo = ta.min(tb);
    let hi = ta.max(tb);
    let (mut t_near, mut near_axis) = (lo.x, 0);
    for i in 1..3 {
        if lo[i] > t_near {
            (t_near, near_axis) = (lo[i], i);
        }
    }
    let (mut t_far, mut far_axis) = (hi.x, 0);
    for i in 1..3 {
        if hi[i] < t_far {
            (t_far, far_axis) = (hi[i], i);
        }
    }
    if t_near > t_far {
        return None;
    }
    let (t, axis, side) = if t_near <= 0.0 {
        (t_far, far_axis, 1.0)
    } else {
        (t_near, near_axis, -1.0)
    };
    if t <= 0.0 || t >= t_max {
        return None;
    }
    let mut n_local = DVec3::ZERO;
    n_local[axis] = side * wgsl_sign(d[axis]);
    Some(Hit {
        t,
        p: ray.at(t),
        n: cube.rotation * n_local,
        error_scale: 0.0,
    })
}

/// The intersection routines of one variant, robust or naive.
struct Routines {
    sphere: fn(&Sphere, &Ray, f64) -> Option<Hit>,
    plane: fn(&Plane, &Ray, f64) -> Option<Hit>,
    cube: fn(&Cube, &Ray, f64) -> Option<Hit>,
}

fn routines(robust: bool) -> Routines {
    if robust {
        Routines {
            sphere: hit_sphere,
            plane: hit_plane,
            cube: hit_cube,
        }
    } else {
        Routines {
            sphere: hit_sphere_naive,
            plane: hit_plane_naive,
            cube: hit_cube_naive,
        }
    }
}

/// The nearest hit over the whole scene, and which shape it is.
///
/// Planes by a loop, spheres and boxes through the scene's bounding volume
/// hierarchy (`crate::bvh`), which skips every shape whose box the ray does
/// not meet before the nearest hit so far; the result is the same as a loop
/// over all shapes. Passing the current nearest `t` as `t_max` means a later
/// shape replaces the current hit only when strictly nearer (the shader's
/// order too: planes, then the BVH's).
pub fn nearest_hit(scene: &PreparedScene, ray: &Ray) -> Option<(ShapeId, Hit)> {
    let hit = routines(scene.robust);
    let mut nearest = None;
    let mut t_closest = f64::INFINITY;
    for (i, plane) in scene.planes.iter().enumerate() {
        if let Some(h) = (hit.plane)(plane, ray, t_closest) {
            t_closest = h.t;
            nearest = Some((ShapeId::Plane(i), h));
        }
    }
    scene
        .bvh
        .traverse(ray.origin, ray.dir, t_closest, |prim, t_max| {
            if let Some((id, h)) = hit_prim(scene, &hit, prim, ray, t_max) {
                nearest = Some((id, h));
                return Some(h.t);
            }
            Some(t_max)
        });
    nearest
}

/// Whether any shape is hit with `0 < t < t_max` (shadow rays: every shape
/// blocks fully, so the first hit found is enough).
pub fn any_hit(scene: &PreparedScene, ray: &Ray, t_max: f64) -> bool {
    let hit = routines(scene.robust);
    if scene
        .planes
        .iter()
        .any(|p| (hit.plane)(p, ray, t_max).is_some())
    {
        return true;
    }
    let mut blocked = false;
    scene.bvh.traverse(ray.origin, ray.dir, t_max, |prim, t| {
        blocked = hit_prim(scene, &hit, prim, ray, t).is_some();
        (!blocked).then_some(t)
    });
    blocked
}

/// The hit of one bounded shape of the BVH.
fn hit_prim(
    scene: &PreparedScene,
    hit: &Routines,
    prim: Prim,
    ray: &Ray,
    t_max: f64,
) -> Option<(ShapeId, Hit)> {
    match prim {
        Prim::Sphere(i) => (hit.sphere)(&scene.spheres[i as usize], ray, t_max)
            .map(|h| (ShapeId::Sphere(i as usize), h)),
        Prim::Cube(i) => {
            (hit.cube)(&scene.cubes[i as usize], ray, t_max).map(|h| (ShapeId::Cube(i as usize), h))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene;
    use proptest::prelude::*;

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray::new(DVec3::from(o), DVec3::from(d))
    }

    fn unit_sphere_at(c: [f64; 3]) -> Sphere {
        Sphere::new(DVec3::from(c), 1.0, 0)
    }

    #[test]
    fn sphere_from_outside() {
        let s = unit_sphere_at([0.0, 0.0, -5.0]);
        let hit = hit_sphere(&s, &ray([0.0; 3], [0.0, 0.0, -1.0]), f64::INFINITY).unwrap();
        assert_eq!(hit.t, 4.0);
        assert_eq!(hit.p, DVec3::new(0.0, 0.0, -4.0));
        assert_eq!(hit.n, DVec3::Z);
        // Off centre: x = 0.6 meets the sphere where z = -5 + 0.8.
        let hit = hit_sphere(&s, &ray([0.6, 0.0, 0.0], [0.0, 0.0, -1.0]), 10.0).unwrap();
        assert!((hit.t - 4.2).abs() < 1e-14);
        assert!(close(hit.n, DVec3::new(0.6, 0.0, 0.8)));
        // Nearer than t_max only.
        assert!(hit_sphere(&s, &ray([0.0; 3], [0.0, 0.0, -1.0]), 4.0).is_none());
    }

    #[test]
    fn sphere_from_inside_hits_the_far_side() {
        let s = unit_sphere_at([1.0, 2.0, 3.0]);
        let hit = hit_sphere(&s, &ray([1.0, 2.0, 3.0], [1.0, 0.0, 0.0]), f64::INFINITY).unwrap();
        assert_eq!(hit.t, 1.0);
        assert_eq!(hit.n, DVec3::X, "outward, along the ray");
        let hit = hit_sphere(&s, &ray([1.0, 2.0, 2.5], [0.0, 0.0, 1.0]), f64::INFINITY).unwrap();
        assert!((hit.t - 1.5).abs() < 1e-15);
        assert!(close(hit.p, DVec3::new(1.0, 2.0, 4.0)));
    }

    #[test]
    fn sphere_tangent_ish() {
        let s = unit_sphere_at([0.0, 0.0, -5.0]);
        let y: f64 = 1.0 - 1e-9;
        let hit = hit_sphere(&s, &ray([0.0, y, 0.0], [0.0, 0.0, -1.0]), f64::INFINITY).unwrap();
        // z^2 = 1 - y^2 = (1 - y)(1 + y), the near root at t = 5 - |z|.
        let z = ((1.0 - y) * (1.0 + y)).sqrt();
        // Near tangency t is ill-conditioned: 1 - y^2 has a relative error
        // of ~1e-16 / 2e-9, and z of half that.
        assert!(
            (hit.t - (5.0 - z)).abs() < 1e-10,
            "{} vs {}",
            hit.t,
            5.0 - z
        );
        assert!(hit.n.y > 0.999_999 && (hit.n.length() - 1.0).abs() < 1e-15);
        assert!(
            hit_sphere(
                &s,
                &ray([0.0, 1.0 + 1e-9, 0.0], [0.0, 0.0, -1.0]),
                f64::INFINITY
            )
            .is_none()
        );
    }

    #[test]
    fn sphere_behind_the_ray_is_missed() {
        let s = unit_sphere_at([0.0, 0.0, 5.0]);
        assert!(hit_sphere(&s, &ray([0.0; 3], [0.0, 0.0, -1.0]), f64::INFINITY).is_none());
        // Starting on the surface and leaving: the root at t = 0 is rejected.
        let s = unit_sphere_at([0.0, 0.0, -1.0]);
        assert!(hit_sphere(&s, &ray([0.0; 3], [0.0, 0.0, 1.0]), f64::INFINITY).is_none());
    }

    #[test]
    fn small_sphere_far_away() {
        // The textbook b^2 - c loses every digit here; r^2 - |f - b d|^2 does not.
        let s = Sphere::new(DVec3::new(0.0, 0.0, -1e6), 1e-3, 0);
        let hit = hit_sphere(&s, &ray([0.0, 5e-4, 0.0], [0.0, 0.0, -1.0]), f64::INFINITY).unwrap();
        let z = (1e-6_f64 - 25e-8).sqrt();
        // Points near z = -1e6 are only known to ~1e-10 (an ulp), which
        // limits t and, over a radius of 1e-3, the normal.
        assert!((hit.t - (1e6 - z)).abs() < 1e-9);
        let n = DVec3::new(0.0, 0.5, 0.75f64.sqrt());
        assert!((hit.n - n).length() < 1e-6);
    }

    fn floor_plane() -> Plane {
        Plane::new(DVec3::new(0.0, -1.0, 0.0), DVec3::Y, 0)
    }

    #[test]
    fn plane_hit_from_either_side() {
        let p = floor_plane();
        let hit = hit_plane(&p, &ray([0.0; 3], [0.0, -1.0, 0.0]), f64::INFINITY).unwrap();
        assert_eq!((hit.t, hit.p, hit.n), (1.0, -DVec3::Y, DVec3::Y));
        // From behind: the normal is still the declared (outward) one.
        let hit = hit_plane(&p, &ray([2.0, -3.0, 0.0], [0.0, 1.0, 0.0]), f64::INFINITY).unwrap();
        assert_eq!(
            (hit.t, hit.p, hit.n),
            (2.0, DVec3::new(2.0, -1.0, 0.0), DVec3::Y)
        );
        // Oblique: 45 degrees down, t = sqrt(2).
        let hit = hit_plane(&p, &ray([0.0; 3], [1.0, -1.0, 0.0]), f64::INFINITY).unwrap();
        assert!((hit.t - 2f64.sqrt()).abs() < 1e-15);
        assert_eq!(hit.p.y, -1.0, "re-projected exactly onto the plane");
    }

    #[test]
    fn plane_misses() {
        let p = floor_plane();
        // Parallel, above and inside the plane.
        assert!(hit_plane(&p, &ray([0.0; 3], [1.0, 0.0, 0.0]), f64::INFINITY).is_none());
        assert!(hit_plane(&p, &ray([0.0, -1.0, 0.0], [1.0, 0.0, 1.0]), f64::INFINITY).is_none());
        // Nearly parallel: t would exceed 1e30.
        assert!(hit_plane(&p, &ray([0.0; 3], [1.0, -1e-31, 0.0]), f64::INFINITY).is_none());
        // Going away.
        assert!(hit_plane(&p, &ray([0.0; 3], [0.0, 1.0, 0.0]), f64::INFINITY).is_none());
        // Beyond t_max.
        assert!(hit_plane(&p, &ray([0.0; 3], [0.0, -1.0, 0.0]), 1.0).is_none());
    }

    fn cube(center: [f64; 3], size: [f64; 3], rotation_deg: [f64; 3]) -> Cube {
        let c = scene::Cube {
            center: DVec3::from(center),
            size: scene::CubeSize::PerAxis(DVec3::from(size)),
            rotation: DVec3::from(rotation_deg),
            material: None,
        };
        Cube::new(c.center, c.size.edges(), c.rotation_matrix(), 0)
    }

    #[test]
    fn axis_aligned_box_each_face() {
        let b = cube([1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0; 3]);
        let c = b.center;
        for axis in 0..3 {
            for sign in [-1.0, 1.0] {
                let mut e = DVec3::ZERO;
                e[axis] = sign;
                // These directions have two zero components.
                let hit = hit_cube(&b, &Ray::new(c + 10.0 * e, -e), f64::INFINITY).unwrap();
                assert_eq!(hit.t, 10.0 - b.half[axis], "axis {axis} sign {sign}");
                assert_eq!(hit.p, c + b.half[axis] * e);
                assert_eq!(hit.n, e);
            }
        }
    }

    #[test]
    fn box_misses() {
        let b = cube([1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0; 3]);
        // d_y = 0 with o_y outside the y slab.
        assert!(hit_cube(&b, &ray([1.0, 4.5, 13.0], [0.0, 0.0, -1.0]), f64::INFINITY).is_none());
        // Passing beside it.
        assert!(hit_cube(&b, &ray([3.0, 2.0, 13.0], [0.0, 0.3, -1.0]), f64::INFINITY).is_none());
        // Behind.
        assert!(hit_cube(&b, &ray([1.0, 2.0, 13.0], [0.0, 0.0, 1.0]), f64::INFINITY).is_none());
        // Beyond t_max.
        assert!(hit_cube(&b, &ray([1.0, 2.0, 13.0], [0.0, 0.0, -1.0]), 7.0).is_none());
    }

    #[test]
    fn box_from_inside_hits_the_exit_face() {
        let b = cube([1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0; 3]);
        let hit = hit_cube(&b, &ray([1.0, 2.0, 3.0], [1.0, 0.0, 0.0]), f64::INFINITY).unwrap();
        assert!((hit.t - 1.0).abs() < 1e-15);
        assert_eq!(hit.n, DVec3::X, "outward, along the ray");
        // Diagonal: the x slab (half 1) is left first, at t = sqrt(3).
        let hit = hit_cube(&b, &ray([1.0, 2.0, 3.0], [1.0, 1.0, 1.0]), f64::INFINITY).unwrap();
        assert!((hit.t - 3f64.sqrt()).abs() < 1e-14);
        assert_eq!(hit.n, DVec3::X);
        let hit = hit_cube(&b, &ray([1.0, 2.0, 3.0], [0.0, 0.0, -1.0]), f64::INFINITY).unwrap();
        assert_eq!(hit.n, -DVec3::Z);
    }

    #[test]
    fn box_ray_starting_on_a_slab_plane() {
        let b = cube([1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0; 3]);
        // On the -x face going in: t_near = 0 is rejected, the +x face is hit.
        let hit = hit_cube(&b, &ray([0.0, 2.0, 3.0], [1.0, 0.0, 0.0]), f64::INFINITY).unwrap();
        assert!((hit.t - 2.0).abs() < 1e-14);
        assert_eq!(hit.n, DVec3::X);
        // On the -x face going out: nothing.
        assert!(hit_cube(&b, &ray([0.0, 2.0, 3.0], [-1.0, 0.0, 0.0]), f64::INFINITY).is_none());
        // In the plane of the top face (|o_y| = h_y, d_y = 0): still inside
        // the closed slab, so the +x face is hit, grazing along the top.
        let hit = hit_cube(&b, &ray([5.0, 4.0, 3.0], [-1.0, 0.0, 0.0]), f64::INFINITY).unwrap();
        assert_eq!((hit.t, hit.n), (3.0, DVec3::X));
    }

    #[test]
    fn box_edge_tie_prefers_the_lowest_axis() {
        // Through the edge x = 1, z = 1 along (-1, 0, -1): both slabs are
        // entered at the same t; x wins.
        let b = cube([0.0; 3], [2.0; 3], [0.0; 3]);
        let hit = hit_cube(&b, &ray([3.0, 0.0, 3.0], [-1.0, 0.0, -1.0]), f64::INFINITY).unwrap();
        assert!((hit.t - 2.0 * 2f64.sqrt()).abs() < 1e-14);
        assert_eq!(hit.n, DVec3::X);
    }

    #[test]
    fn rz_90_maps_x_to_y() {
        let b = cube([0.0; 3], [2.0, 0.5, 0.5], [0.0, 0.0, 90.0]);
        assert!(close(b.rotation * DVec3::X, DVec3::Y));
        // The long local x axis now lies along world y.
        let hit = hit_cube(&b, &ray([0.0, 5.0, 0.0], [0.0, -1.0, 0.0]), f64::INFINITY).unwrap();
        assert!((hit.t - 4.0).abs() < 1e-14);
        assert!(close(hit.n, DVec3::Y));
        let hit = hit_cube(&b, &ray([5.0, 0.0, 0.0], [-1.0, 0.0, 0.0]), f64::INFINITY).unwrap();
        assert!((hit.t - 4.75).abs() < 1e-14);
        assert!(close(hit.n, DVec3::X));
    }

    #[test]
    fn rotated_box_hit_point_and_normal() {
        // A 2 x 2 x 2 cube turned 45 degrees about y: Ry(45) maps local +z to
        // (s, 0, s) and +x to (s, 0, -s), s = 1/sqrt(2). The local +z face is
        // the plane x + z = sqrt(2); a ray along -x at z = 0.3 meets it at
        // x = sqrt(2) - 0.3 (the +x face plane, x - z = sqrt(2), is farther).
        let b = cube([0.0; 3], [2.0; 3], [0.0, 45.0, 0.0]);
        let hit = hit_cube(&b, &ray([5.0, 0.0, 0.3], [-1.0, 0.0, 0.0]), f64::INFINITY).unwrap();
        let x = 2f64.sqrt() - 0.3;
        assert!((hit.t - (5.0 - x)).abs() < 1e-14);
        assert!(close(hit.p, DVec3::new(x, 0.0, 0.3)));
        let s = std::f64::consts::FRAC_1_SQRT_2;
        assert!(close(hit.n, DVec3::new(s, 0.0, s)));
        // And at z = -0.3 the +x face.
        let hit = hit_cube(&b, &ray([5.0, 0.0, -0.3], [-1.0, 0.0, 0.0]), f64::INFINITY).unwrap();
        assert!(close(hit.n, DVec3::new(s, 0.0, -s)));
    }

    fn scene_with_everything() -> PreparedScene {
        PreparedScene::new(
            &toml::from_str(
                r#"
                camera = { from = [0, 0, 10], to = [0, 0, 0] }
                [[spheres]]
                center = [0, 0, 0]
                radius = 1
                [[planes]]
                point = [0, 0, -3]
                normal = [0, 0, 2]
                [[cubes]]
                center = [0, 0, 2]
                size = 1
                "#,
            )
            .unwrap(),
        )
    }

    #[test]
    fn nearest_hit_over_the_scene() {
        let scene = scene_with_everything();
        let down_z = ray([0.0, 0.0, 10.0], [0.0, 0.0, -1.0]);
        let (id, hit) = nearest_hit(&scene, &down_z).unwrap();
        assert_eq!(id, ShapeId::Cube(0));
        assert_eq!(hit.t, 7.5);
        // Beside the cube, the sphere; beside that, the plane (unit normal).
        let (id, hit) = nearest_hit(&scene, &ray([0.0, 0.8, 10.0], [0.0, 0.0, -1.0])).unwrap();
        assert_eq!(id, ShapeId::Sphere(0));
        assert!((hit.t - 9.4).abs() < 1e-14);
        let (id, hit) = nearest_hit(&scene, &ray([0.0, 1.5, 10.0], [0.0, 0.0, -1.0])).unwrap();
        assert_eq!((id, hit.t, hit.n), (ShapeId::Plane(0), 13.0, DVec3::Z));
        assert!(nearest_hit(&scene, &ray([0.0, 0.0, 10.0], [0.0, 0.0, 1.0])).is_none());
        assert!(any_hit(&scene, &down_z, 7.6));
        assert!(!any_hit(&scene, &down_z, 7.5), "t < t_max strictly");
    }

    proptest! {
        /// Rays from outside aimed at a point inside a randomly rotated box
        /// hit its surface, with a unit normal facing the ray.
        #[test]
        fn rotated_box_hits_lie_on_the_surface(
            rot in prop::array::uniform3(-180.0..180.0f64),
            size in prop::array::uniform3(0.1..4.0f64),
            target in prop::array::uniform3(-0.49..0.49f64),
            dir in prop::array::uniform3(-1.0..1.0f64),
        ) {
            let dir = DVec3::from(dir);
            prop_assume!(dir.length() > 0.1);
            let b = cube([0.5, -1.0, 2.0], size, rot);
            let aim = b.center + b.rotation * (DVec3::from(target) * b.half * 2.0);
            let r = Ray::new(aim - 20.0 * dir.normalize(), dir);
            let hit = hit_cube(&b, &r, f64::INFINITY).unwrap();
            let local = b.inverse * (hit.p - b.center);
            let on_face = (local.abs() - b.half).max_element();
            prop_assert!(on_face.abs() < 1e-12, "{local} {}", b.half);
            prop_assert!((hit.n.length() - 1.0).abs() < 1e-12);
            prop_assert!(hit.n.dot(r.dir) < 0.0);
        }

        /// Likewise for spheres, from outside and from inside.
        #[test]
        fn sphere_hits_lie_on_the_surface(
            origin in prop::array::uniform3(-10.0..10.0f64),
            dir in prop::array::uniform3(-1.0..1.0f64),
            radius in 0.01..5.0f64,
        ) {
            let dir = DVec3::from(dir);
            prop_assume!(dir.length() > 0.1);
            let s = Sphere::new(DVec3::new(1.0, 2.0, 3.0), radius, 0);
            let r = Ray::new(DVec3::from(origin), dir);
            if let Some(hit) = hit_sphere(&s, &r, f64::INFINITY) {
                prop_assert!(hit.t > 0.0);
                prop_assert!(((hit.p - s.center).length() - radius).abs() < 1e-12 * 10.0);
                prop_assert!((r.at(hit.t) - hit.p).length() < 1e-9);
                let inside = (r.origin - s.center).length() < radius;
                prop_assert_eq!(hit.n.dot(r.dir) > 0.0, inside);
            }
        }
    }
}
