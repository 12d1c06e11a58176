//! The torus's editor: the two radii and the placement.

use super::placed::placement_rows;
use super::{EditShape, Placement};
use crate::app::panel::field;
use crate::app::panel::widgets::{MIN_POSITIVE, VALUE_LIMIT, number};
use crate::scene::{self, Torus};
use egui::Ui;

impl EditShape for Torus {
    /// Below the target, lying flat, a fifth of the scene scale across.
    fn new_near(at: &Placement) -> Self {
        Torus {
            major_radius: 0.1 * at.scale,
            minor_radius: 0.03 * at.scale,
            placement: scene::Placement {
                translate: at.target - at.up * (0.25 * at.scale),
                ..Default::default()
            },
            material: None,
        }
    }

    /// Moved right by its width.
    fn beside(&self, at: &Placement) -> Self {
        let mut copy = self.clone();
        copy.placement.translate +=
            at.right * (2.0 * (self.major_radius + self.minor_radius) * self.placement.scale);
        copy
    }

    fn edit(&mut self, ui: &mut Ui, scale: f64) -> bool {
        field(ui, "major_radius", "Radius R of the ring (> r)");
        ui.add(number(
            &mut self.major_radius,
            0.002 * scale,
            MIN_POSITIVE..=VALUE_LIMIT,
        ));
        ui.end_row();
        field(ui, "minor_radius", "Radius r of the tube (0 < r < R)");
        ui.add(number(
            &mut self.minor_radius,
            0.001 * scale,
            MIN_POSITIVE..=self.major_radius * (1.0 - 1e-6),
        ));
        ui.end_row();
        placement_rows(ui, &mut self.placement, scale);
        false
    }

    /// The ring may have been shrunk below the tube: keep r < R.
    fn settle(&mut self) {
        self.minor_radius = self.minor_radius.min(self.major_radius * 0.999);
    }
}
