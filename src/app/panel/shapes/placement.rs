//! The rows of a shape's placement (translate, scale, rotation;
//! docs/scene-format.md, "Implicit surfaces" and "`[[meshes]]`"; a cube's
//! center, size, rotation), shown once for every kind after its own rows.

use egui::Ui;

use crate::app::panel::field;
use crate::app::panel::widgets::{COORDINATES, MIN_POSITIVE, VALUE_LIMIT, number, vec3_row};
use crate::scene::{AxisScale, Centered, Placement, Scale, Unplaced};

/// The row of a placement's `scale`: its hover text and its widget.
pub(super) trait ScaleRow: Scale {
    const HINT: &'static str;

    fn row(&mut self, ui: &mut Ui, speed: f64);
}

impl ScaleRow for f64 {
    const HINT: &'static str = "Local units to world units (> 0)";

    fn row(&mut self, ui: &mut Ui, speed: f64) {
        ui.add(number(self, speed, MIN_POSITIVE..=VALUE_LIMIT));
    }
}

impl ScaleRow for AxisScale {
    const HINT: &'static str = "One factor, or factors along the local x, y, z (> 0)";

    fn row(&mut self, ui: &mut Ui, speed: f64) {
        super::size_row(ui, self, speed);
    }
}

/// The rows of one form of placement in a `Grid` of two columns.
pub(in crate::app::panel) trait EditPlacement {
    fn rows(&mut self, ui: &mut Ui, scene_scale: f64);
}

impl<S: ScaleRow + serde::de::DeserializeOwned> EditPlacement for Placement<S> {
    fn rows(&mut self, ui: &mut Ui, scene_scale: f64) {
        let translate = ("translate", "Where the local origin is (x, y, z)");
        placement_rows(ui, self, [translate, ("scale", S::HINT)], scene_scale);
    }
}

impl EditPlacement for Centered {
    fn rows(&mut self, ui: &mut Ui, scene_scale: f64) {
        let size = (
            "size",
            "Edge length, or lengths along the cube's own x, y, z",
        );
        placement_rows(
            ui,
            &mut self.0,
            [("center", "Centre (x, y, z)"), size],
            scene_scale,
        );
    }
}

/// A kind placed by its own keys shows them in its own rows.
impl EditPlacement for Unplaced {
    fn rows(&mut self, _ui: &mut Ui, _scene_scale: f64) {}
}

/// The three rows of a placement, the first two named and explained by
/// `keys` (the scene file's words for translate and scale).
fn placement_rows<S: ScaleRow>(
    ui: &mut Ui,
    placement: &mut Placement<S>,
    [(translate, translate_hint), (scale, scale_hint)]: [(&str, &str); 2],
    scene_scale: f64,
) {
    field(ui, translate, translate_hint);
    vec3_row(
        ui,
        &mut placement.translate,
        0.005 * scene_scale,
        COORDINATES,
    );
    ui.end_row();
    field(ui, scale, scale_hint);
    placement.scale.row(ui, 0.002 * scene_scale);
    ui.end_row();
    field(
        ui,
        "rotation",
        "Degrees about the world x, then y, then z axis",
    );
    vec3_row(ui, &mut placement.rotation, 0.5, -360.0..=360.0);
    ui.end_row();
}
