//! The cube's editor: centre, one edge length or three, rotation.

use egui::Ui;
use glam::DVec3;

use super::{EditShape, Placement};
use crate::app::panel::field;
use crate::app::panel::widgets::{COORDINATES, vec3_row};
use crate::scene::{Cube, CubeSize};

impl EditShape for Cube {
    /// Unrotated, left of the target (where a new sphere does not go).
    fn new_near(at: &Placement) -> Self {
        Cube {
            center: at.target - at.right * (0.25 * at.scale),
            size: CubeSize::Uniform(0.15 * at.scale),
            rotation: DVec3::ZERO,
            material: None,
        }
    }

    /// Moved right by its longest edge.
    fn beside(&self, at: &Placement) -> Self {
        let mut copy = self.clone();
        copy.center += at.right * self.size.edges().max_element();
        copy
    }

    fn edit(&mut self, ui: &mut Ui, scale: f64) -> bool {
        field(ui, "center", "Centre (x, y, z)");
        vec3_row(ui, &mut self.center, 0.005 * scale, COORDINATES);
        ui.end_row();
        field(
            ui,
            "size",
            "Edge length, or lengths along the cube's own x, y, z",
        );
        super::size_row(ui, &mut self.size, 0.002 * scale);
        ui.end_row();
        super::placed::rotation_row(ui, &mut self.rotation);
        false
    }
}

/// Switches a cube between one edge length and three. Going back to one keeps
/// the longest edge, so the cube encloses the box it was.
pub(super) fn toggle_per_axis(size: CubeSize) -> CubeSize {
    match size {
        CubeSize::Uniform(s) => CubeSize::PerAxis(DVec3::splat(s)),
        CubeSize::PerAxis(v) => CubeSize::Uniform(v.max_element()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_size_toggles_keep_positive_edges() {
        let uniform = CubeSize::Uniform(2.0);
        let per_axis = toggle_per_axis(uniform);
        assert_eq!(per_axis, CubeSize::PerAxis(DVec3::splat(2.0)));
        assert_eq!(toggle_per_axis(per_axis), uniform);
        let boxed = CubeSize::PerAxis(DVec3::new(1.0, 3.0, 2.0));
        assert_eq!(toggle_per_axis(boxed), CubeSize::Uniform(3.0));
    }
}
