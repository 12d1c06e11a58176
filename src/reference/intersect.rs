//! Ray-scene intersection (docs/rendering-model.md, "Shapes"; docs/implementation.md
//! "Intersections"): the nearest hit over the scene and the any-hit query of
//! shadow rays. Each kind's own hit test is in `shapes/` (re-exported here).
//!
//! Every routine accepts only hits with `0 < t < t_max` (the rendering model's
//! `0 < t < t_closest`) and returns the outward geometric normal, unit length.

use super::PreparedScene;
pub use super::hit::{Hit, foot, major_axis};
use super::ray::Ray;
pub use super::shapes::cube::{Cube, hit_cube, hit_cube_naive};
pub use super::shapes::plane::{Plane, hit_plane, hit_plane_naive};
pub use super::shapes::sphere::{Sphere, hit_sphere, hit_sphere_naive};
pub use crate::scene::ShapeId;

/// The nearest hit over the whole scene, and which shape it is.
///
/// Unbounded shapes (planes) by a loop, the others through the scene's bounding volume
/// hierarchy (`crate::bvh`), which skips every shape whose box the ray does
/// not meet before the nearest hit so far; the result is the same as a loop
/// over all shapes. Passing the current nearest `t` as `t_max` means a later
/// shape replaces the current hit only when strictly nearer (the shader's
/// order too: planes, then the BVH's).
pub fn nearest_hit(scene: &PreparedScene, ray: &Ray) -> Option<(ShapeId, Hit)> {
    let mut nearest = None;
    let mut t_closest = f64::INFINITY;
    for &id in &scene.unbounded {
        if let Some(h) = scene.shapes.hit(id, ray, t_closest, &scene.options) {
            t_closest = h.t;
            nearest = Some((id, h));
        }
    }
    scene
        .bvh
        .traverse(ray.origin, ray.dir, t_closest, |id, t_max| {
            if let Some(h) = scene.shapes.hit(id, ray, t_max, &scene.options) {
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
    let hit = |id, t| scene.shapes.hit(id, ray, t, &scene.options).is_some();
    if scene.unbounded.iter().any(|&id| hit(id, t_max)) {
        return true;
    }
    let mut blocked = false;
    scene.bvh.traverse(ray.origin, ray.dir, t_max, |id, t| {
        blocked = hit(id, t);
        (!blocked).then_some(t)
    });
    blocked
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene;
    use glam::DVec3;
    use proptest::prelude::*;

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray::new(DVec3::from(o), DVec3::from(d))
    }

    fn unit_sphere_at(c: [f64; 3]) -> Sphere {
        Sphere::new(DVec3::from(c), 1.0)
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
        let s = Sphere::new(DVec3::new(0.0, 0.0, -1e6), 1e-3);
        let hit = hit_sphere(&s, &ray([0.0, 5e-4, 0.0], [0.0, 0.0, -1.0]), f64::INFINITY).unwrap();
        let z = (1e-6_f64 - 25e-8).sqrt();
        // Points near z = -1e6 are only known to ~1e-10 (an ulp), which
        // limits t and, over a radius of 1e-3, the normal.
        assert!((hit.t - (1e6 - z)).abs() < 1e-9);
        let n = DVec3::new(0.0, 0.5, 0.75f64.sqrt());
        assert!((hit.n - n).length() < 1e-6);
    }

    fn floor_plane() -> Plane {
        Plane::new(DVec3::new(0.0, -1.0, 0.0), DVec3::Y)
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
        // Nearly parallel: t would exceed 1e38.
        assert!(hit_plane(&p, &ray([0.0; 3], [1.0, -1e-39, 0.0]), f64::INFINITY).is_none());
        // Going away.
        assert!(hit_plane(&p, &ray([0.0; 3], [0.0, 1.0, 0.0]), f64::INFINITY).is_none());
        // Beyond t_max.
        assert!(hit_plane(&p, &ray([0.0; 3], [0.0, -1.0, 0.0]), 1.0).is_none());
    }

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
            let s = Sphere::new(DVec3::new(1.0, 2.0, 3.0), radius);
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
