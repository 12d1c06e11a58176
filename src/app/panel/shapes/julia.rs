//! The Julia set's editor: four sliders for c, the slice, the iteration
//! count, epsilon (fixed or grown with the pixel footprint) and the
//! placement.

use egui::Ui;
use glam::{DVec3, DVec4};

use super::placed::placement_rows;
use super::{EditShape, Placement};
use crate::app::panel::field;
use crate::scene::Julia;
use crate::scene::julia::MAX_ITERATIONS;

impl EditShape for Julia {
    /// Crane's example c, a tenth of the scene scale in size.
    fn new_near(at: &Placement) -> Self {
        Julia {
            c: [-0.2, 0.6, 0.2, 0.2],
            slice: 0.0,
            iterations: 10,
            epsilon: 1e-3,
            footprint: false,
            translate: at.target + at.up * (0.25 * at.scale),
            scale: 0.1 * at.scale,
            rotation: DVec3::ZERO,
            material: None,
        }
    }

    /// Moved right by its width.
    fn beside(&self, at: &Placement) -> Self {
        let mut copy = self.clone();
        copy.translate += at.right * (4.0 * self.scale);
        copy
    }

    fn edit(&mut self, ui: &mut Ui, scale: f64) -> bool {
        let mut held = false;
        for (i, name) in ["c (real)", "c (i)", "c (j)", "c (k)"]
            .into_iter()
            .enumerate()
        {
            field(ui, name, "The constant of z <- z^2 + c; |c| <= 2");
            let slider = ui.add(egui::Slider::new(&mut self.c[i], -2.0..=2.0));
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
        placement_rows(
            ui,
            &mut self.translate,
            &mut self.scale,
            &mut self.rotation,
            scale,
        );
        held
    }

    /// |c| <= 2: a c dragged past it is brought back to length 2.
    fn settle(&mut self) {
        let c = DVec4::from_array(self.c);
        if c.length() > 2.0 {
            self.c = (c * (2.0 / c.length())).to_array();
        }
    }
}
