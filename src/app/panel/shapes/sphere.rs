//! The sphere's editor: centre and radius.

use egui::Ui;

use super::{EditShape, Placement};
use crate::app::panel::field;
use crate::app::panel::widgets::{COORDINATES, MIN_POSITIVE, VALUE_LIMIT, number, vec3_row};
use crate::scene::Sphere;

impl EditShape for Sphere {
    /// Right of the target, a tenth of the scene scale in radius.
    fn new_near(at: &Placement) -> Self {
        Sphere {
            center: at.target + at.right * (0.25 * at.scale),
            radius: 0.1 * at.scale,
            material: None,
        }
    }

    /// Moved right by its diameter.
    fn beside(&self, at: &Placement) -> Self {
        let mut copy = self.clone();
        copy.center += at.right * (2.0 * self.radius);
        copy
    }

    fn edit(&mut self, ui: &mut Ui, scale: f64) -> bool {
        field(ui, "center", "Centre (x, y, z)");
        vec3_row(ui, &mut self.center, 0.005 * scale, COORDINATES);
        ui.end_row();
        field(ui, "radius", "Radius (> 0)");
        ui.add(number(
            &mut self.radius,
            0.002 * scale,
            MIN_POSITIVE..=VALUE_LIMIT,
        ));
        ui.end_row();
        false
    }
}
