//! The placement rows of the placed shapes (translate, scale, rotation;
//! docs/scene-format.md, "Implicit surfaces" and "`[[meshes]]`"), and the
//! rotation row that cubes show too.

use egui::Ui;
use glam::DVec3;

use crate::app::panel::field;
use crate::app::panel::widgets::{COORDINATES, MIN_POSITIVE, VALUE_LIMIT, number, vec3_row};
use crate::scene::{CubeSize, Placement, Scale};

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

impl ScaleRow for CubeSize {
    const HINT: &'static str = "One factor, or factors along the local x, y, z (> 0)";

    fn row(&mut self, ui: &mut Ui, speed: f64) {
        super::size_row(ui, self, speed);
    }
}

/// The three placement rows of a `Grid` of two columns.
pub(super) fn placement_rows<S: ScaleRow>(
    ui: &mut Ui,
    placement: &mut Placement<S>,
    scene_scale: f64,
) {
    field(ui, "translate", "Where the local origin is (x, y, z)");
    vec3_row(
        ui,
        &mut placement.translate,
        0.005 * scene_scale,
        COORDINATES,
    );
    ui.end_row();
    field(ui, "scale", S::HINT);
    placement.scale.row(ui, 0.002 * scene_scale);
    ui.end_row();
    rotation_row(ui, &mut placement.rotation);
}

/// The rotation row every rotated shape shows (Euler angles, x then y
/// then z, as docs/scene-format.md defines them).
pub(super) fn rotation_row(ui: &mut Ui, rotation: &mut DVec3) {
    field(
        ui,
        "rotation",
        "Degrees about the world x, then y, then z axis",
    );
    vec3_row(ui, rotation, 0.5, -360.0..=360.0);
    ui.end_row();
}
