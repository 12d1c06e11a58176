//! The placement rows the implicit surfaces share (translate, scale,
//! rotation; docs/scene-format.md, "Implicit surfaces"), and the rotation
//! row that cubes and meshes show too.

use egui::Ui;
use glam::DVec3;

use crate::app::panel::edit::MIN_POSITIVE;
use crate::app::panel::field;
use crate::app::panel::widgets::{COORDINATES, VALUE_LIMIT, number, vec3_row};

/// The three placement rows of a `Grid` of two columns.
pub(super) fn placement_rows(
    ui: &mut Ui,
    translate: &mut DVec3,
    scale: &mut f64,
    rotation: &mut DVec3,
    scene_scale: f64,
) {
    field(ui, "translate", "Where the local origin is (x, y, z)");
    vec3_row(ui, translate, 0.005 * scene_scale, COORDINATES);
    ui.end_row();
    field(ui, "scale", "Local units to world units (> 0)");
    ui.add(number(
        scale,
        0.002 * scene_scale,
        MIN_POSITIVE..=VALUE_LIMIT,
    ));
    ui.end_row();
    rotation_row(ui, rotation);
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
