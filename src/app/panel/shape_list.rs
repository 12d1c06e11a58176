//! The panel's Shapes section (add, duplicate, remove, shapes from files) and
//! the Selected section, which edits the selected shape.

use super::file::path_row;
use super::{PanelAction, PanelState, edit, shapes};
use crate::app::layout;
use crate::app::shape_files::kinds_from_files;
use crate::scene::{Scene, ShapeId, ShapeKind};
use egui::{CollapsingHeader, ComboBox, Grid, Ui};

pub(super) fn shapes_section(
    ui: &mut Ui,
    scene: &mut Scene,
    state: &mut PanelState,
    actions: &mut Vec<PanelAction>,
) {
    ui.horizontal_wrapped(|ui| {
        for &kind in ShapeKind::ALL {
            let label = format!("Add {}", kind.name().to_lowercase());
            if ui.button(label).clicked() {
                state.selection = Some(edit::add_shape(scene, kind));
            }
        }
    })
    .response
    .on_hover_text("A new shape near the target, selected for editing");
    shape_file_rows(ui, state, actions);
    for id in edit::shape_ids(scene) {
        let selected = state.selection == Some(id);
        if ui
            .selectable_label(selected, edit::shape_label(scene, id))
            .clicked()
        {
            // Picked in this list, which is in view: no need to scroll.
            state.selection = Some(id);
            state.shown_selection = Some(id);
        }
    }
    if scene.shape_count() == 0 {
        ui.weak("No shapes yet.");
    }
}

/// "Add mesh from file": the system's file dialog, or a typed path, for
/// the kinds made from files ([`crate::scene::Shape::FILE_EXTENSIONS`]).
fn shape_file_rows(ui: &mut Ui, state: &mut PanelState, actions: &mut Vec<PanelAction>) {
    let extensions: Vec<String> = ShapeKind::ALL
        .iter()
        .flat_map(|kind| kind.file_extensions())
        .map(|e| e.to_ascii_uppercase())
        .collect();
    if ui
        .button(format!("Add {} from file…", kinds_from_files()))
        .on_hover_text(format!(
            "An {} file, placed at the target (or drop the file on the window)",
            extensions.join(" or ")
        ))
        .clicked()
    {
        actions.push(PanelAction::PickShapeFile);
    }
    let row = ui.scope(|ui| path_row(ui, "Add file", "models/bunny.obj", &mut state.shape_path));
    layout::note(ui.ctx(), "add-file", row.response.rect);
    if let Some(path) = row.inner {
        actions.push(PanelAction::AddShapeFile(path));
    }
}

/// Why the last file a shape reads could not be read, outside the
/// (folded) Shapes section so that it is seen; the scene keeps what it
/// showed.
pub(super) fn file_error_row(ui: &mut Ui, state: &mut PanelState) {
    let Some(error) = &state.file_error else {
        return;
    };
    let mut dismiss = false;
    ui.horizontal_wrapped(|ui| {
        let kinds = kinds_from_files();
        let label = format!("{}{} file: {error}", kinds[..1].to_uppercase(), &kinds[1..]);
        ui.colored_label(ui.visuals().error_fg_color, label);
        dismiss = ui.small_button("OK").clicked();
    });
    if dismiss {
        state.file_error = None;
    }
}

/// The editor of the selected shape. Returns the shape if an edit holds one
/// of its values (a plane's normal being dragged), so that it is made
/// canonical only once the edit is done.
pub(super) fn selected_shape_section(
    ui: &mut Ui,
    scene: &mut Scene,
    state: &mut PanelState,
    scale: f64,
) -> Option<ShapeId> {
    let reveal = state.selection.is_some() && state.selection != state.shown_selection;
    state.shown_selection = state.selection;
    let title = match state.selection {
        Some(id) => format!("Selected: {}", edit::shape_label(scene, id)),
        None => "Selected shape".to_owned(),
    };
    let response = CollapsingHeader::new(title)
        .id_salt("selected shape")
        .default_open(true)
        .open(reveal.then_some(true))
        .show(ui, |ui| {
            let Some(id) = state.selection else {
                ui.weak("Click a shape in the view or in the Shapes list.");
                return None;
            };
            let held = Grid::new("shape")
                .num_columns(2)
                .show(ui, |ui| shapes::edit(ui, scene, id, scale))
                .inner;
            material_combo(ui, scene, id);
            ui.horizontal(|ui| {
                if ui
                    .button("Duplicate")
                    .on_hover_text("Copy it beside itself and select the copy")
                    .clicked()
                {
                    edit::duplicate_selected(scene, &mut state.selection);
                }
                if ui.button("Remove").clicked() {
                    edit::remove_shape(scene, id, &mut state.selection);
                }
            });
            held.then_some(id)
        });
    if reveal {
        response
            .header_response
            .scroll_to_me(Some(egui::Align::TOP));
    }
    response.body_returned.flatten()
}

/// The shape's material: the default one or any named material.
pub(super) fn material_combo(ui: &mut Ui, scene: &mut Scene, id: ShapeId) {
    let names: Vec<String> = scene.materials.keys().cloned().collect();
    let Some(slot) = edit::shape_material_mut(scene, id) else {
        return;
    };
    ui.horizontal(|ui| {
        ui.label("material")
            .on_hover_text("Shapes without a material use the default one");
        ComboBox::from_id_salt("shape material")
            .selected_text(slot.as_deref().unwrap_or("(default)"))
            .show_ui(ui, |ui| {
                ui.selectable_value(slot, None, "(default)");
                for name in names {
                    let label = name.clone();
                    ui.selectable_value(slot, Some(name), label);
                }
            });
    });
}
