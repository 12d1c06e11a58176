//! The sphere's editor: centre and radius.

use egui::Ui;

use glam::DVec3;

use super::{EditShape, InView};
use crate::app::panel::field;
use crate::app::panel::widgets::{COORDINATES, MIN_POSITIVE, VALUE_LIMIT, number, vec3_row};
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
