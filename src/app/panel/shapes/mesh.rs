//! The mesh's editor: its placement (translate, scale, rotation); the
//! geometry stays as loaded, so editing never rebuilds its BVH.

use egui::Ui;
use glam::DVec3;

use super::{EditShape, InView};
use crate::app::panel::field;
use crate::app::panel::widgets::named_row;
use crate::bvh::{MAX_DEPTH, triangle_bvh_built};
use crate::scene::{AxisScale, Instance, Mesh, MeshSettings, Placement};

impl EditShape for Mesh {
    /// A tetrahedron below the right of the target, a fifth of the scene
    /// scale across.
    fn new_near(at: &InView) -> Instance<Mesh> {
        let positions = [
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(-1.0, 0.0, 1.0),
            DVec3::new(0.0, 0.0, -1.0),
            DVec3::new(0.0, 1.5, 0.0),
        ];
        let triangles = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
        let mesh = Mesh::inline(&positions, &triangles)
            .expect("the tetrahedron has four non-degenerate faces");
        let placement = Placement {
            translate: at.target + at.right * (0.25 * at.scale) - at.up * (0.1 * at.scale),
            scale: AxisScale::Uniform(0.1 * at.scale),
            rotation: DVec3::ZERO,
        };
        Instance::new(mesh, placement)
    }

    /// Right by its size.
    fn beside(mesh: &Instance<Mesh>, at: &InView) -> DVec3 {
        let [lo, hi] = mesh.bounds();
        at.right * (hi - lo).max_element()
    }

    fn edit(&mut self, ui: &mut Ui, _scale: f64) -> bool {
        geometry_rows(ui, self);
        false
    }

    /// `triangles`, a lecture switch saved with the scene
    /// (docs/rendering-model.md, "Lecture switches").
    fn edit_settings(ui: &mut Ui, settings: &mut MeshSettings) {
        named_row(
            ui,
            "triangle test",
            "The ray-triangle test of meshes, saved with the scene: watertight (no ray \
             slips between two triangles that share an edge), or Cramer's rule or \
             Möller-Trumbore, the lecture's, whose rounding can let a ray through an \
             edge (what is behind shows in the crack)",
            &mut settings.triangles,
        );
    }
}

/// Where the triangles come from, how many there are, and their BVH: its
/// depth (against the traversal stack's limit) and how long it took to
/// build. Moving, turning and scaling keep this tree ([`triangle_bvh_built`]).
fn geometry_rows(ui: &mut Ui, mesh: &Mesh) {
    field(
        ui,
        "file",
        "The OBJ or PLY file, relative to the scene file",
    );
    match &mesh.file {
        Some(file) => ui.label(file.display().to_string()),
        None => ui.weak("(inline positions and triangles)"),
    };
    ui.end_row();
    let geometry = &mesh.geometry.0;
    field(
        ui,
        "triangles",
        "Triangles of non-zero area (degenerate ones are dropped on load)",
    );
    ui.label(geometry.triangles.len().to_string());
    ui.end_row();
    let built = triangle_bvh_built(&mesh.geometry.0);
    field(
        ui,
        "BVH",
        "The tree over the triangles: its depth, of the most the shader's \
         traversal stack allows, and its build time on this machine",
    );
    ui.label(format!(
        "depth {}/{MAX_DEPTH}, built in {:.1} ms",
        built.depth,
        built.build_time.as_secs_f64() * 1e3
    ))
    .on_hover_text(format!("{} nodes", built.bvh.nodes.len()));
    ui.end_row();
}
