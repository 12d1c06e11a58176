//! The torus's editor: the two radii and the placement.

use super::{EditShape, InView};
use crate::app::panel::field;
use crate::app::panel::widgets::{MIN_POSITIVE, length_row, number};
use crate::scene::{Instance, Placement, Torus};
use egui::Ui;
use glam::DVec3;

impl EditShape for Torus {
    /// Below the target, lying flat, a fifth of the scene scale across.
    fn new_near(at: &InView) -> Instance<Torus> {
        let torus = Torus {
            major_radius: 0.1 * at.scale,
            minor_radius: 0.03 * at.scale,
        };
        let placement = Placement {
            translate: at.target - at.up * (0.25 * at.scale),
            ..Default::default()
        };
        Instance::new(torus, placement)
    }

    /// Right by its width.
    fn beside(torus: &Instance<Torus>, at: &InView) -> DVec3 {
        at.right * (2.0 * (torus.major_radius + torus.minor_radius) * torus.placement.scale)
    }

    fn edit(&mut self, ui: &mut Ui, scale: f64) -> bool {
        let major = "Radius R of the ring (> r)";
        length_row(
            ui,
            "major_radius",
            major,
            &mut self.major_radius,
            0.002 * scale,
        );
        field(ui, "minor_radius", "Radius r of the tube (0 < r < R)");
        ui.add(number(
            &mut self.minor_radius,
            0.001 * scale,
            MIN_POSITIVE..=self.major_radius * (1.0 - 1e-6),
        ));
        ui.end_row();
        false
    }

    /// The ring may have been shrunk below the tube: keep r < R.
    fn settle(&mut self) {
        self.minor_radius = self.minor_radius.min(self.major_radius * 0.999);
    }
}
