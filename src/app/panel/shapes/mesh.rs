//! The mesh's editor: its placement (translate, scale, rotation); the
//! geometry stays as loaded, so editing never rebuilds its BVH.

use egui::Ui;
use glam::DVec3;

use super::{EditShape, Placement, size_row};
use crate::app::panel::field;
use crate::app::panel::widgets::{COORDINATES, vec3_row};
use crate::scene::{CubeSize, Mesh};

impl EditShape for Mesh {
    /// A tetrahedron below the right of the target, a fifth of the scene
    /// scale across.
    fn new_near(at: &Placement) -> Self {
        let positions = [
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(-1.0, 0.0, 1.0),
            DVec3::new(0.0, 0.0, -1.0),
            DVec3::new(0.0, 1.5, 0.0),
        ];
        let triangles = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
        let mut mesh = Mesh::inline(&positions, &triangles)
            .expect("the tetrahedron has four non-degenerate faces");
        mesh.translate = at.target + at.right * (0.25 * at.scale) - at.up * (0.1 * at.scale);
        mesh.scale = CubeSize::Uniform(0.1 * at.scale);
        mesh
    }

    /// Moved right by its size.
    fn beside(&self, at: &Placement) -> Self {
        let mut copy = self.clone();
        let [lo, hi] = crate::scene::Shape::bounds(self);
        copy.translate += at.right * (hi - lo).max_element();
        copy
    }

    fn edit(&mut self, ui: &mut Ui, scale: f64) -> bool {
        field(ui, "triangles", "Loaded from the file or the inline arrays");
        let source = match &self.file {
            Some(file) => file.display().to_string(),
            None => "inline".to_owned(),
        };
        ui.label(format!("{} ({source})", self.geometry.0.triangles.len()));
        ui.end_row();
        field(ui, "translate", "Where the mesh's origin goes (x, y, z)");
        vec3_row(ui, &mut self.translate, 0.005 * scale, COORDINATES);
        ui.end_row();
        field(
            ui,
            "scale",
            "One factor, or factors along the mesh's own x, y, z",
        );
        size_row(ui, &mut self.scale, 0.002 * scale);
        ui.end_row();
        field(
            ui,
            "rotation",
            "Degrees about the world x, then y, then z axis",
        );
        vec3_row(ui, &mut self.rotation, 0.5, -360.0..=360.0);
        ui.end_row();
        false
    }
}
