//! Ray-scene intersection (docs/rendering-model.md, "Shapes"; docs/implementation.md
//! "Intersections"): the nearest hit over the scene and the any-hit query of
//! shadow rays. Each kind's own hit test is in its file in `shapes/`.
//!
//! Every routine accepts only hits with `0 < t < t_max` (the rendering model's
//! `0 < t < t_closest`) and returns the outward geometric normal, unit length.

use super::PreparedScene;
pub use super::hit::{Hit, foot, major_axis};
use super::ray::Ray;
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
    use crate::reference::shapes::test_rays::ray;
    use glam::DVec3;

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
}
