//! The panel's Camera section.

use super::widgets::{COORDINATES, MIN_POSITIVE, VALUE_LIMIT, number, vec3_row};
use super::{PanelAction, field, widgets};
use crate::app::layout;
use crate::scene::Camera;
use egui::{Grid, Slider, SliderClamping, Ui};

/// Camera fields. An edit that would make `from == to` or `up == 0` (which
/// leave the camera without a view direction) is ignored.
pub(super) fn camera_section(
    ui: &mut Ui,
    camera: &mut Camera,
    scale: f64,
    actions: &mut Vec<PanelAction>,
) {
    let speed = 0.005 * scale;
    Grid::new("camera").num_columns(2).show(ui, |ui| {
        field(ui, "from", "Eye position e (x, y, z)");
        let mut from = camera.from;
        if vec3_row(ui, &mut from, speed, COORDINATES).changed
            && (from - camera.to).try_normalize().is_some()
        {
            camera.from = from;
        }
        ui.end_row();

        field(ui, "to", "The point looked at; must differ from `from`");
        let mut to = camera.to;
        if vec3_row(ui, &mut to, speed, COORDINATES).changed
            && (camera.from - to).try_normalize().is_some()
        {
            camera.to = to;
        }
        ui.end_row();

        field(
            ui,
            "up",
            "Which way is up in the image (any non-zero length; \
             replaced by an axis if parallel to the view)",
        );
        let mut up = camera.up;
        if vec3_row(ui, &mut up, 0.01, COORDINATES).changed && up.try_normalize().is_some() {
            camera.up = up;
        }
        ui.end_row();

        field(ui, "fov", "Vertical field of view");
        let fov = ui.add(
            Slider::new(&mut camera.fov, 1.0..=179.0)
                .clamping(SliderClamping::Edits)
                .suffix("°"),
        );
        layout::note(ui.ctx(), "camera-fov", fov.rect);
        ui.end_row();

        field(
            ui,
            "aperture",
            "Lens radius: 0 is a pinhole (all sharp); larger blurs what is \
             not at the focus distance (needs several samples)",
        );
        ui.add(number(&mut camera.aperture, 0.1 * speed, 0.0..=VALUE_LIMIT));
        ui.end_row();

        field(ui, "focus", "Distance from the eye to the plane in focus");
        focus_row(ui, camera, speed);
        ui.end_row();
    });
    if ui
        .button("Reset camera")
        .on_hover_text("Back to the camera of the scene file")
        .clicked()
    {
        actions.push(PanelAction::ResetCamera);
    }
}

/// "auto" is `focus_distance = None`: the distance to `to`, following the
/// camera as it moves. Unticking it starts from that same distance.
pub(super) fn focus_row(ui: &mut Ui, camera: &mut Camera, speed: f64) {
    ui.horizontal(|ui| {
        let mut auto = camera.focus_distance.is_none();
        if ui.checkbox(&mut auto, "auto (|from - to|)").changed() {
            camera.focus_distance = (!auto).then(|| {
                camera
                    .focus_distance()
                    .clamp(MIN_POSITIVE, widgets::COORDINATE_LIMIT)
            });
        }
        if let Some(distance) = &mut camera.focus_distance {
            ui.add(number(
                distance,
                speed,
                MIN_POSITIVE..=widgets::COORDINATE_LIMIT,
            ));
        }
    });
}
