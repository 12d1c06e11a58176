//! The cube's editor: none of its own (its placement shows centre, size
//! and rotation), and the toggle between one edge length and three.

use egui::Ui;
use glam::DVec3;

use super::{EditShape, InView};
use crate::scene::{AxisScale, Centered, Cube, Instance, Placement};

/// A cube has no keys of its own: its rows are its placement's (centre,
/// size, rotation).
impl EditShape for Cube {
    /// Unrotated, left of the target (where a new sphere does not go).
    fn new_near(at: &InView) -> Instance<Cube> {
        let placement = Placement {
            translate: at.target - at.right * (0.25 * at.scale),
            scale: AxisScale::Uniform(0.15 * at.scale),
            rotation: DVec3::ZERO,
        };
        Instance::new(Cube {}, Centered(placement))
    }

    /// Right by its longest edge.
    fn beside(cube: &Instance<Cube>, at: &InView) -> DVec3 {
        at.right * cube.placement.scale.edges().max_element()
    }

    fn edit(&mut self, _ui: &mut Ui, _scale: f64) -> bool {
        false
    }
}

/// Switches a cube between one edge length and three. Going back to one keeps
/// the longest edge, so the cube encloses the box it was.
pub(super) fn toggle_per_axis(size: AxisScale) -> AxisScale {
    match size {
        AxisScale::Uniform(s) => AxisScale::PerAxis(DVec3::splat(s)),
        AxisScale::PerAxis(v) => AxisScale::Uniform(v.max_element()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_size_toggles_keep_positive_edges() {
        let uniform = AxisScale::Uniform(2.0);
        let per_axis = toggle_per_axis(uniform);
        assert_eq!(per_axis, AxisScale::PerAxis(DVec3::splat(2.0)));
        assert_eq!(toggle_per_axis(per_axis), uniform);
        let boxed = AxisScale::PerAxis(DVec3::new(1.0, 3.0, 2.0));
        assert_eq!(toggle_per_axis(boxed), AxisScale::Uniform(3.0));
    }
}
