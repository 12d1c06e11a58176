//! The Julia set's editor: four sliders for c, the slice, the iteration
//! count, epsilon (fixed or grown with the pixel footprint) and the
//! placement.

use egui::Ui;
use glam::{DVec3, DVec4};

use super::{EditShape, InView};
use crate::app::panel::field;
use crate::scene::julia::MAX_ITERATIONS;
use crate::scene::{Instance, Julia, Placement};

impl EditShape for Julia {
    /// Crane's example c, a tenth of the scene scale in size.
    fn new_near(at: &InView) -> Instance<Julia> {
        let julia = Julia {
            c: [-0.2, 0.6, 0.2, 0.2],
            slice: 0.0,
            iterations: 10,
            epsilon: 1e-3,
            footprint: false,
        };
        let placement = Placement {
            translate: at.target + at.up * (0.25 * at.scale),
            scale: 0.1 * at.scale,
            rotation: DVec3::ZERO,
        };
        Instance::new(julia, placement)
    }

    /// Right by its width.
    fn beside(julia: &Instance<Julia>, at: &InView) -> DVec3 {
        at.right * (4.0 * julia.placement.scale)
    }

    fn edit(&mut self, ui: &mut Ui, _scale: f64) -> bool {
        let mut held = false;
        for (i, name) in ["c (real)", "c (i)", "c (j)", "c (k)"]
            .into_iter()
            .enumerate()
        {
            field(ui, name, "The constant of z <- z^2 + c; |c| <= 2");
            let slider = ui.add(egui::Slider::new(&mut self.c[i], -2.0..=2.0));
            if slider.changed() {
                self.keep_c_inside(i);
            }
            held |= slider.dragged() || slider.has_focus();
            ui.end_row();
        }
        field(ui, "slice", "The fourth coordinate of the 3-D cut");
        ui.add(egui::Slider::new(&mut self.slice, -2.0..=2.0));
        ui.end_row();
        field(ui, "iterations", "Iterations of z <- z^2 + c (1..=64)");
        ui.add(egui::Slider::new(&mut self.iterations, 1..=MAX_ITERATIONS));
        ui.end_row();
        field(
            ui,
            "epsilon",
            "Distance that counts as on the surface, local units",
        );
        ui.add(egui::Slider::new(&mut self.epsilon, 1e-5..=1e-1).logarithmic(true));
        ui.end_row();
        field(
            ui,
            "footprint",
            "Grow epsilon with distance to one pixel's width, so detail stays one pixel \
             wide at any zoom (docs/scene-format.md)",
        );
        ui.checkbox(&mut self.footprint, "epsilon at least one pixel");
        ui.end_row();
        held
    }
}

impl Julia {
    /// |c| <= 2 (docs/scene-format.md) at every frame, also while a slider
    /// is dragged: the component just moved stops where |c| reaches 2, so
    /// the other three keep the values the user gave them.
    fn keep_c_inside(&mut self, moved: usize) {
        let c = DVec4::from_array(self.c);
        if c.length() > 2.0 {
            let others = c.length_squared() - self.c[moved] * self.c[moved];
            // A hair inside, so that rounding cannot land |c| above 2.
            let room = (4.0 - others).max(0.0).sqrt() * (1.0 - 1e-12);
            self.c[moved] = room.copysign(self.c[moved]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A slider pushed past |c| = 2 stops on the sphere of radius 2 and
    /// leaves the other components alone; the scene stays valid.
    #[test]
    fn a_component_dragged_past_two_stops_on_the_sphere() {
        let at = InView {
            target: DVec3::ZERO,
            right: DVec3::X,
            up: DVec3::Y,
            scale: 1.0,
        };
        let mut julia = Julia::new_near(&at).shape;
        julia.c = [1.5, -1.9, 0.25, 0.0];
        julia.keep_c_inside(1);
        assert_eq!([julia.c[0], julia.c[2], julia.c[3]], [1.5, 0.25, 0.0]);
        assert!(julia.c[1] < 0.0);
        let length = DVec4::from_array(julia.c).length();
        assert!(length <= 2.0 && length > 2.0 - 1e-9, "{length}");
    }
}
