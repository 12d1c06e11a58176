//! The scene edits behind the panel's buttons, as plain functions on a
//! [`Scene`], so that their rules are tested without a UI: material names stay
//! unique and in order, no shape ever names a missing material, the selection
//! never points past the end of a list, and a plane normal is never zero.

use glam::DVec3;

use super::shapes::{self, InView};
use crate::scene::{Camera, Checker, Light, Material, Scene, ShapeId, ShapeKind};

/// A power of ten near a fifth of the scene scale: a round size for new
/// checker cells (1 for the bundled scenes).
fn round_size(scale: f64) -> f64 {
    10f64.powi((scale / 5.0).log10().round() as i32)
}

/// The checker a material gets when the checkbox is ticked: dark cells of a
/// round size, so the effect is obvious at once.
pub(super) fn default_checker(scene_scale: f64) -> Checker {
    Checker {
        color: DVec3::splat(0.15),
        size: round_size(scene_scale),
    }
}

/// Sets every shape's material named `old` to `new`, whatever its kind.
fn replace_material(scene: &mut Scene, old: &str, new: Option<&str>) {
    for id in scene.shape_ids() {
        if let Some(slot) = scene.shape_material_mut(id)
            && slot.as_deref() == Some(old)
        {
            *slot = new.map(str::to_owned);
        }
    }
}

/// How many shapes name the material `name` (shown before removing it).
pub(super) fn material_users(scene: &Scene, name: &str) -> usize {
    shape_ids(scene)
        .filter(|&id| shape_material(scene, id) == Some(name))
        .count()
}

/// The first of "material", "material 2", "material 3"... not yet taken.
pub(super) fn unique_material_name(scene: &Scene) -> String {
    let mut name = "material".to_owned();
    let mut n = 1;
    while scene.materials.contains_key(&name) {
        n += 1;
        name = format!("material {n}");
    }
    name
}

/// Appends a default material under a fresh name and returns the name.
pub(super) fn add_material(scene: &mut Scene) -> String {
    let name = unique_material_name(scene);
    scene.materials.insert(name.clone(), Material::default());
    name
}

/// Removes a material, keeping the order of the others (it fixes the GPU
/// slots and the order in the saved file); its shapes fall back to the
/// default material.
pub(super) fn remove_material(scene: &mut Scene, name: &str) {
    if scene.materials.shift_remove(name).is_none() {
        return;
    }
    replace_material(scene, name, None);
}

/// Renames a material in place (same position in the list) and every shape
/// that uses it. `new` is trimmed; an empty or taken name is refused with a
/// message for the user.
pub(super) fn rename_material(scene: &mut Scene, old: &str, new: &str) -> Result<(), String> {
    let new = new.trim();
    if new.is_empty() {
        return Err("A material needs a name.".to_owned());
    }
    if !scene.materials.contains_key(old) {
        return Err(format!("There is no material named {old:?}."));
    }
    if new == old {
        return Ok(());
    }
    if scene.materials.contains_key(new) {
        return Err(format!("{new:?} is taken: material names must be unique."));
    }
    scene.materials = std::mem::take(&mut scene.materials)
        .into_iter()
        .map(|(name, material)| {
            let name = if name == old { new.to_owned() } else { name };
            (name, material)
        })
        .collect();
    replace_material(scene, old, Some(new));
    Ok(())
}

/// Appends a white light of intensity 1 above the target, one scene scale
/// up (the camera's `up`).
pub(super) fn add_light(scene: &mut Scene) {
    let up = camera_up(&scene.camera);
    scene.lights.push(Light {
        position: scene.camera.to + up * scene.view_scale(),
        color: DVec3::ONE,
        intensity: 1.0,
    });
}

/// Every shape, kind by kind in registry order (the order of the scene
/// file).
pub(super) fn shape_ids(scene: &Scene) -> impl Iterator<Item = ShapeId> + use<> {
    scene.shape_ids().into_iter()
}

/// The material a shape names, `None` for the default material or a shape
/// that does not exist.
pub(super) fn shape_material(scene: &Scene, id: ShapeId) -> Option<&str> {
    scene.shape_material(id).and_then(|name| name.as_deref())
}

/// The material slot of a shape, if the shape exists.
pub(super) fn shape_material_mut(scene: &mut Scene, id: ShapeId) -> Option<&mut Option<String>> {
    scene.shape_material_mut(id)
}

/// The name of a shape in lists and headers: "Sphere 0 (glass)".
pub(super) fn shape_label(scene: &Scene, id: ShapeId) -> String {
    let material = shape_material(scene, id).unwrap_or("default");
    format!("{} {} ({material})", id.kind().name(), id.index())
}

/// The selection if it names an existing shape, else `None`: the app may swap
/// the scene (open a file) or pick a shape without knowing the lists.
pub(super) fn checked_selection(scene: &Scene, selection: Option<ShapeId>) -> Option<ShapeId> {
    selection.filter(|&id| scene.shape_material(id).is_some())
}

/// The camera's `up`, unit length (a floor faces it), or +y for a zero one.
fn camera_up(camera: &Camera) -> DVec3 {
    camera.up.try_normalize().unwrap_or(DVec3::Y)
}

/// Where new shapes go in this scene's view: beside the target along the
/// film's right (`Camera::film`), above it along the camera's `up`.
fn in_view(scene: &Scene) -> InView {
    let (right, up) = (scene.camera.film().u, camera_up(&scene.camera));
    InView {
        target: scene.camera.to,
        right,
        up,
        scale: scene.view_scale(),
    }
}

/// Appends a new shape of `kind` near the target (each kind's
/// `EditShape::new_near`); returns its id.
pub(super) fn add_shape(scene: &mut Scene, kind: ShapeKind) -> ShapeId {
    let at = in_view(scene);
    shapes::add(scene, kind, &at)
}

/// Copies the selected shape to the end of its list, moved to the right of
/// the view by its own size (a plane: along its normal) so that both stay
/// visible, and selects the copy.
pub(super) fn duplicate_selected(scene: &mut Scene, selection: &mut Option<ShapeId>) {
    let at = in_view(scene);
    let Some(id) = checked_selection(scene, *selection) else {
        return;
    };
    if let Some(copy) = shapes::duplicate(scene, id, &at) {
        *selection = Some(copy);
    }
}

/// Removes a shape. The selection follows the shape it named (the indices
/// after the removed one shift down by one) and is cleared if that shape was
/// the one removed. A shape that does not exist is ignored.
pub(super) fn remove_shape(scene: &mut Scene, id: ShapeId, selection: &mut Option<ShapeId>) {
    if !scene.remove_shape(id) {
        return;
    }
    *selection = selection.and_then(|selected| selection_after_removal(selected, id));
}

fn selection_after_removal(selected: ShapeId, removed: ShapeId) -> Option<ShapeId> {
    if selected == removed {
        None
    } else if selected.kind() == removed.kind() && selected.index() > removed.index() {
        Some(ShapeId::new(selected.kind(), selected.index() - 1))
    } else {
        Some(selected)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Mesh, NewShape};

    fn scene() -> Scene {
        let text = r#"
            [camera]
            from = [0, 1.5, 6]
            to = [0, 1, 0]

            [materials.glass]
            transparency = 0.9
            [materials.floor]
            diffuse = 0.5
            [materials.metal]
            mirror = 0.8

            [[spheres]]
            center = [0, 1, 0]
            radius = 1
            material = "glass"
            [[spheres]]
            center = [2, 1, 0]
            radius = 0.5
            material = "metal"
            [[spheres]]
            center = [-2, 1, 0]
            radius = 0.5

            [[planes]]
            point = [0, 0, 0]
            normal = [0, 1, 0]
            material = "floor"

            [[cubes]]
            center = [0, 0.5, -2]
            size = [1, 2, 1]
            material = "glass"
        "#;
        Scene::from_toml_str(text, None).unwrap()
    }

    fn names(scene: &Scene) -> Vec<&str> {
        scene.materials.keys().map(String::as_str).collect()
    }

    #[test]
    fn rename_updates_every_user_and_keeps_order() {
        let mut s = scene();
        let glass = s.materials["glass"].clone();
        let mesh = add_shape(&mut s, ShapeKind::Mesh);
        *s.shape_material_mut(mesh).unwrap() = Some("glass".to_owned());
        rename_material(&mut s, "glass", "  crystal ").unwrap();
        assert_eq!(s.meshes[0].material.as_deref(), Some("crystal"));
        assert_eq!(names(&s), ["crystal", "floor", "metal"]);
        assert_eq!(s.materials["crystal"], glass);
        assert_eq!(s.spheres[0].material.as_deref(), Some("crystal"));
        assert_eq!(s.cubes[0].material.as_deref(), Some("crystal"));
        assert_eq!(s.spheres[1].material.as_deref(), Some("metal"));
        assert_eq!(s.spheres[2].material, None);
        assert_eq!(s.planes[0].material.as_deref(), Some("floor"));
        assert_eq!(s.material_slot(Some("crystal")), 1);
    }

    #[test]
    fn rename_refuses_empty_duplicate_and_unknown_names() {
        let mut s = scene();
        let before = s.clone();
        assert!(rename_material(&mut s, "glass", "   ").is_err());
        assert!(rename_material(&mut s, "glass", "floor").is_err());
        assert!(rename_material(&mut s, "nothing", "new").is_err());
        assert_eq!(s, before);
        rename_material(&mut s, "glass", "glass").unwrap();
        assert_eq!(s, before);
    }

    #[test]
    fn removing_a_material_resets_its_users_and_keeps_order() {
        let mut s = scene();
        assert_eq!(material_users(&s, "glass"), 2);
        remove_material(&mut s, "glass");
        assert_eq!(names(&s), ["floor", "metal"]);
        assert_eq!(s.spheres[0].material, None);
        assert_eq!(s.cubes[0].material, None);
        assert_eq!(s.spheres[1].material.as_deref(), Some("metal"));
        assert_eq!(s.planes[0].material.as_deref(), Some("floor"));
        // Every name a shape uses still exists.
        for id in shape_ids(&s) {
            if let Some(name) = shape_material(&s, id) {
                assert!(s.materials.contains_key(name), "{name}");
            }
        }
        remove_material(&mut s, "glass");
        assert_eq!(names(&s), ["floor", "metal"]);
    }

    #[test]
    fn new_material_names_are_unique() {
        let mut s = scene();
        assert_eq!(add_material(&mut s), "material");
        assert_eq!(add_material(&mut s), "material 2");
        assert_eq!(add_material(&mut s), "material 3");
        remove_material(&mut s, "material 2");
        assert_eq!(unique_material_name(&s), "material 2");
        assert_eq!(
            names(&s),
            ["glass", "floor", "metal", "material", "material 3"]
        );
        assert_eq!(s.materials["material"], Material::default());
    }

    #[test]
    fn removing_a_shape_fixes_the_selection() {
        let mut s = scene();
        // A later sphere: its index shifts down with the list.
        let mut selection = Some(ShapeId::Sphere(2));
        remove_shape(&mut s, ShapeId::Sphere(0), &mut selection);
        assert_eq!(selection, Some(ShapeId::Sphere(1)));
        assert_eq!(s.spheres[1].center, DVec3::new(-2.0, 1.0, 0.0));
        // Another kind, or an earlier index: unchanged.
        let mut selection = Some(ShapeId::Plane(0));
        remove_shape(&mut s, ShapeId::Sphere(1), &mut selection);
        assert_eq!(selection, Some(ShapeId::Plane(0)));
        let mut selection = Some(ShapeId::Sphere(0));
        remove_shape(&mut s, ShapeId::Cube(0), &mut selection);
        assert_eq!(selection, Some(ShapeId::Sphere(0)));
        // The selected shape itself, the last of its list: cleared.
        remove_shape(&mut s, ShapeId::Sphere(0), &mut selection);
        assert_eq!(selection, None);
        assert!(s.spheres.is_empty() && s.cubes.is_empty());
        // Removing what is not there changes nothing.
        let mut selection = Some(ShapeId::Plane(0));
        let before = s.clone();
        remove_shape(&mut s, ShapeId::Sphere(0), &mut selection);
        remove_shape(&mut s, ShapeId::Plane(7), &mut selection);
        assert_eq!((s, selection), (before, Some(ShapeId::Plane(0))));
    }

    #[test]
    fn a_selection_past_the_end_is_dropped() {
        let s = scene();
        assert_eq!(
            checked_selection(&s, Some(ShapeId::Sphere(2))),
            Some(ShapeId::Sphere(2))
        );
        assert_eq!(checked_selection(&s, Some(ShapeId::Sphere(3))), None);
        assert_eq!(checked_selection(&s, Some(ShapeId::Cube(1))), None);
        assert_eq!(checked_selection(&s, None), None);
    }

    #[test]
    fn duplicate_offsets_the_copy_and_selects_it() {
        let mut s = scene();
        let mut selection = Some(ShapeId::Sphere(0));
        duplicate_selected(&mut s, &mut selection);
        assert_eq!(selection, Some(ShapeId::Sphere(3)));
        let (original, copy) = (&s.spheres[0], &s.spheres[3]);
        assert_eq!(
            (copy.radius, &copy.material),
            (original.radius, &original.material)
        );
        // Camera looks down -z with y up: right is +x. Touching, not overlapping.
        let offset = copy.center - original.center;
        assert!(
            (offset - DVec3::new(2.0, 0.0, 0.0)).length() < 1e-12,
            "{offset}"
        );

        let mut selection = Some(ShapeId::Cube(0));
        duplicate_selected(&mut s, &mut selection);
        assert_eq!(selection, Some(ShapeId::Cube(1)));
        let offset = s.cubes[1].placement.translate - s.cubes[0].placement.translate;
        assert!(
            (offset - DVec3::new(2.0, 0.0, 0.0)).length() < 1e-12,
            "{offset}"
        );

        let mut selection = Some(ShapeId::Plane(0));
        duplicate_selected(&mut s, &mut selection);
        assert_eq!(selection, Some(ShapeId::Plane(1)));
        assert_eq!(s.planes[1].normal, s.planes[0].normal);
        assert!(s.planes[1].point.y > s.planes[0].point.y);

        let before = s.clone();
        let mut selection = None;
        duplicate_selected(&mut s, &mut selection);
        assert_eq!((s, selection), (before, None));
    }

    #[test]
    fn new_shapes_are_valid_and_near_the_target() {
        let mut s = scene();
        let ids: Vec<ShapeId> = ShapeKind::ALL
            .iter()
            .map(|&k| add_shape(&mut s, k))
            .collect();
        assert_eq!(
            ids,
            [
                ShapeId::Sphere(3),
                ShapeId::Plane(1),
                ShapeId::Cube(1),
                ShapeId::Torus(0),
                ShapeId::Implicit(0),
                ShapeId::Julia(0),
                ShapeId::Mesh(0)
            ]
        );
        let scale = s.view_scale();
        assert!(s.spheres[3].radius > 0.0);
        assert!((s.spheres[3].center - s.camera.to).length() < scale);
        assert_eq!(s.planes[1].normal, DVec3::Y);
        assert!((s.cubes[1].placement.translate - s.camera.to).length() < scale);
        add_light(&mut s);
        let light = s.lights.last().unwrap();
        assert!(light.position.y > s.camera.to.y);
        assert_eq!((light.color, light.intensity), (DVec3::ONE, 1.0));
        // The result is a scene the loader accepts.
        assert_eq!(Scene::from_toml_str(&s.to_toml_string(), None).unwrap(), s);
    }

    #[test]
    fn new_shapes_survive_a_degenerate_camera_up() {
        let mut s = scene();
        s.camera.up = DVec3::new(0.0, -1.5, -6.0); // parallel to the view
        add_shape(&mut s, ShapeKind::Sphere);
        add_light(&mut s);
        assert!(s.spheres.last().unwrap().center.is_finite());
        assert!(s.lights.last().unwrap().position.is_finite());
    }

    #[test]
    fn normals_are_normalised_except_while_edited() {
        let mut s = scene();
        s.planes.push(s.planes[0].clone());
        s.planes[0].normal = DVec3::new(0.0, 2.0, 0.0);
        s.planes[1].normal = DVec3::new(3.0, 0.0, 4.0);
        shapes::settle(&mut s, Some(ShapeId::Plane(0)));
        assert_eq!(s.planes[0].normal, DVec3::new(0.0, 2.0, 0.0));
        assert!((s.planes[1].normal - DVec3::new(0.6, 0.0, 0.8)).length() < 1e-15);
        shapes::settle(&mut s, None);
        assert_eq!(s.planes[0].normal, DVec3::Y);
    }

    #[test]
    fn a_mesh_from_a_file_is_centred_on_the_target_at_the_scene_scale() {
        let mut s = scene();
        // A box from (10, 0, 0) to (14, 2, 1): far away and large.
        let positions = [
            DVec3::new(10.0, 0.0, 0.0),
            DVec3::new(14.0, 0.0, 0.0),
            DVec3::new(10.0, 2.0, 0.0),
            DVec3::new(10.0, 0.0, 1.0),
        ];
        let mesh = Mesh::inline(&positions, &[[0, 1, 2], [0, 2, 3]]).unwrap();
        let id = s.add_in_view(NewShape::Mesh(Box::new(mesh)));
        assert_eq!(id, ShapeId::Mesh(0));
        let [lo, hi] = s.meshes[0].bounds();
        let centre = 0.5 * (lo + hi);
        assert!((centre - s.camera.to).length() < 1e-9, "{centre}");
        let longest = (hi - lo).max_element();
        assert!((longest - crate::scene::NEW_SHAPE_SIZE * s.view_scale()).abs() < 1e-9);
        assert!(Scene::from_toml_str(&s.to_toml_string(), None).is_ok());
    }

    #[test]
    fn checker_cells_have_a_round_size() {
        assert_eq!(default_checker(6.0).size, 1.0);
        assert_eq!(default_checker(0.05).size, 0.01);
        assert_eq!(default_checker(1e6).size, 1e5);
    }
}
