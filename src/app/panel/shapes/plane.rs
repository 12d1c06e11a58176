//! The plane's editor: a point and a normal, made unit length once the edit
//! of the normal is done.

use egui::Ui;
use glam::DVec3;

use super::{EditShape, InView};
use crate::app::panel::field;
use crate::app::panel::widgets::{VALUE_LIMIT, position_row, vec3_row};
use crate::scene::{Instance, Plane, Unplaced};

/// How far from 1 the squared length of a normal may be for it to count as
/// unit length already (as the scene loader does): normalising it again could
/// move its last bit, and the app would then see a change that is none.
const UNIT_TOLERANCE: f64 = 8.0 * f64::EPSILON;

/// A direction the renderers can use as a plane normal: unit length, and
/// kept bit for bit if it is already. `None` for a zero (or unnormalisable)
/// vector, which the panel never writes.
fn unit_normal(n: DVec3) -> Option<DVec3> {
    if (n.length_squared() - 1.0).abs() <= UNIT_TOLERANCE {
        Some(n)
    } else {
        n.try_normalize()
    }
}

impl EditShape for Plane {
    /// A floor: facing the camera's up, a little below the target.
    fn new_near(at: &InView) -> Instance<Plane> {
        let plane = Plane {
            point: at.target - at.up * (0.2 * at.scale),
            normal: at.up,
        };
        Instance::new(plane, Unplaced)
    }

    /// Along its normal by a tenth of the scene scale.
    fn beside(plane: &Instance<Plane>, at: &InView) -> DVec3 {
        plane.normal * (0.1 * at.scale)
    }

    /// While the user drags or types a component of the normal the raw
    /// numbers stay, so the field does not jump under the cursor.
    fn edit(&mut self, ui: &mut Ui, scale: f64) -> bool {
        let point = "Any point on the plane (x, y, z)";
        position_row(ui, "point", point, &mut self.point, scale);
        field(
            ui,
            "normal",
            "Direction the plane faces; made unit length when the edit is done",
        );
        let mut normal = self.normal;
        let row = vec3_row(ui, &mut normal, 0.01, -VALUE_LIMIT..=VALUE_LIMIT);
        if row.changed && unit_normal(normal).is_some() {
            self.normal = normal;
        }
        ui.end_row();
        row.active
    }

    fn settle(&mut self) {
        if let Some(n) = unit_normal(self.normal) {
            self.normal = n;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_and_tiny_normals_have_no_direction() {
        assert_eq!(unit_normal(DVec3::ZERO), None);
        assert_eq!(unit_normal(DVec3::splat(1e-300)), None);
        assert_eq!(unit_normal(DVec3::Y), Some(DVec3::Y));
    }
}
