//! The panel's Lights section.

use super::widgets::{VALUE_LIMIT, colour_field, position_row, slider};
use super::{edit, field};
use crate::scene::{Light, Scene};
use egui::{Grid, Ui};

pub(super) fn lights_section(ui: &mut Ui, scene: &mut Scene, scale: f64) {
    let mut remove = None;
    for (i, light) in scene.lights.iter_mut().enumerate() {
        ui.push_id(("light", i), |ui| {
            ui.horizontal(|ui| {
                ui.strong(format!("Light {i}"));
                if ui.small_button("Remove").clicked() {
                    remove = Some(i);
                }
            });
            light_grid(ui, light, scale);
        });
        ui.separator();
    }
    if let Some(i) = remove.filter(|&i| i < scene.lights.len()) {
        scene.lights.remove(i);
    }
    if scene.lights.is_empty() {
        ui.weak("No lights: only the ambient term lights the scene.");
    }
    if ui
        .button("Add light")
        .on_hover_text("A white light above the target")
        .clicked()
    {
        edit::add_light(scene);
    }
}

pub(super) fn light_grid(ui: &mut Ui, light: &mut Light, scale: f64) {
    Grid::new("light").num_columns(2).show(ui, |ui| {
        position_row(
            ui,
            "position",
            "A point light (x, y, z)",
            &mut light.position,
            scale,
        );

        colour_field(ui, "colour", "Light colour (linear RGB)", &mut light.color);

        field(
            ui,
            "intensity",
            "Multiplies the colour; lights do not fall off with distance",
        );
        slider(
            ui,
            &mut light.intensity,
            0.0..=2.0,
            0.0..=VALUE_LIMIT,
            false,
        );
        ui.end_row();
    });
}
