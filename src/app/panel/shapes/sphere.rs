//! The sphere's editor: centre and radius.

use egui::Ui;

use glam::DVec3;

use super::{EditShape, InView};
use crate::app::panel::widgets::{length_row, position_row};
use crate::scene::{Instance, Sphere, Unplaced};

impl EditShape for Sphere {
    /// Right of the target, a tenth of the scene scale in radius.
    fn new_near(at: &InView) -> Instance<Sphere> {
        let sphere = Sphere {
            center: at.target + at.right * (0.25 * at.scale),
            radius: 0.1 * at.scale,
        };
        Instance::new(sphere, Unplaced)
    }

    /// Right by its diameter.
    fn beside(sphere: &Instance<Sphere>, at: &InView) -> DVec3 {
        at.right * (2.0 * sphere.radius)
    }

    fn edit(&mut self, ui: &mut Ui, scale: f64) -> bool {
        position_row(ui, "center", "Centre (x, y, z)", &mut self.center, scale);
        length_row(
            ui,
            "radius",
            "Radius (> 0)",
            &mut self.radius,
            0.002 * scale,
        );
        false
    }
}
