//! A rotated box for the f64 tracer (docs/rendering-model.md, "Shapes").

use glam::{DMat3, DVec3};
use num_traits::Float;

use super::{Prepare, traced_by};
use crate::expr::wgsl_sign;
use crate::reference::hit::{Hit, foot};
use crate::reference::ray::Ray;
use crate::scene::{self, Instance};

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
    /// `|center|_max + |half|`, see [`Hit::error_scale`].
    pub error_scale: f64,
}

traced_by!(Cube: hit_cube, hit_cube_naive);

impl Cube {
    /// A box of edge lengths `edges` turned by the rotation matrix `rotation`.
    pub fn new(center: DVec3, edges: DVec3, rotation: DMat3) -> Self {
        let half = 0.5 * edges;
        Self {
            center,
            half,
            rotation,
            // A rotation's inverse is its transpose.
            inverse: rotation.transpose(),
            error_scale: center.abs().max_element() + half.length(),
        }
    }
}

impl Prepare for scene::Cube {
    type Traced = Cube;

    fn prepare(shape: &Instance<Self>) -> Cube {
        Cube::new(
            shape.placement.translate,
            shape.placement.scale.edges(),
            shape.placement.rotation_matrix(),
        )
    }
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
    Some(Hit::new(
        t,
        cube.center + cube.rotation * p_local,
        sign * cube.rotation.col(axis),
        cube.error_scale,
    ))
}

/// The plain slab test as usually taught (the naive variant, the shader's
/// `hit_cube_naive`): `inv = 1 / d'_i`, the entry and exit of every slab with
/// no special case for `d'_i = 0` (IEEE gives inf and, for an origin on a
/// slab plane, `0 * inf = NaN`, which the minima and maxima of
/// [`naive_slab`] drop or keep by the order of their operands), no
/// widening of the far bound, and the hit point `o + t d`, not re-projected.
pub fn hit_cube_naive(cube: &Cube, ray: &Ray, t_max: f64) -> Option<Hit> {
    let o = cube.inverse * (ray.origin - cube.center);
    let d = cube.inverse * ray.dir;
    let (t, axis, n) = naive_slab(o.to_array(), d.to_array(), cube.half.to_array(), t_max)?;
    let mut n_local = DVec3::ZERO;
    n_local[axis] = n;
    Some(Hit::new(t, ray.at(t), cube.rotation * n_local, 0.0))
}

/// The naive slab test in the box's frame (`o`, `d`: the ray there; `h`:
/// the half edges) in any float type (f64 here, f32 in the port of the
/// shader, `src/stress/f32_intersect.rs`): the hit's `t`, the axis of the
/// face it is on and the sign of the outward normal along that axis.
pub fn naive_slab<T: Float>(o: [T; 3], d: [T; 3], h: [T; 3], t_max: T) -> Option<(T, usize, T)> {
    let zero = T::zero();
    let ta: [T; 3] = std::array::from_fn(|i| (-h[i] - o[i]) * (T::one() / d[i]));
    let tb: [T; 3] = std::array::from_fn(|i| (h[i] - o[i]) * (T::one() / d[i]));
    // Minimum and maximum by one comparison, as glam's: with a NaN, the
    // second operand.
    let lo: [T; 3] = std::array::from_fn(|i| if ta[i] < tb[i] { ta[i] } else { tb[i] });
    let hi: [T; 3] = std::array::from_fn(|i| if ta[i] > tb[i] { ta[i] } else { tb[i] });
    let (mut t_near, mut near_axis) = (lo[0], 0);
    for (i, &x) in lo.iter().enumerate().skip(1) {
        if x > t_near {
            (t_near, near_axis) = (x, i);
        }
    }
    let (mut t_far, mut far_axis) = (hi[0], 0);
    for (i, &x) in hi.iter().enumerate().skip(1) {
        if x < t_far {
            (t_far, far_axis) = (x, i);
        }
    }
    if t_near > t_far {
        return None;
    }
    let (t, axis, side) = if t_near <= zero {
        (t_far, far_axis, T::one())
    } else {
        (t_near, near_axis, -T::one())
    };
    if t <= zero || t >= t_max {
        return None;
    }
    Some((t, axis, side * wgsl_sign(d[axis])))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::shapes::test_rays::{close, ray};
    use proptest::prelude::*;

    fn cube(center: [f64; 3], size: [f64; 3], rotation_deg: [f64; 3]) -> Cube {
        let rotation = scene::rotation_degrees(DVec3::from(rotation_deg));
        Cube::new(DVec3::from(center), DVec3::from(size), rotation)
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
    }
}
