//! The panel's Materials section: add, rename, remove, and every field.

use super::widgets::{MIN_POSITIVE, VALUE_LIMIT, colour_field, length_row, slider};
use super::{PanelState, Rename, edit, field};
use crate::scene::{Material, Scene};
use egui::{CollapsingHeader, Grid, Key, TextEdit, Ui};

/// What a material's buttons asked for, applied after the list is drawn
/// (the list borrows the materials).
pub(super) enum MaterialOp {
    StartRename(String),
    CancelRename,
    Rename(String, String),
    Remove(String),
}

pub(super) fn materials_section(
    ui: &mut Ui,
    scene: &mut Scene,
    state: &mut PanelState,
    scale: f64,
) {
    let users: Vec<usize> = scene
        .materials
        .keys()
        .map(|name| edit::material_users(scene, name))
        .collect();
    let mut op = None;
    for ((name, material), users) in scene.materials.iter_mut().zip(users) {
        CollapsingHeader::new(name.as_str())
            .id_salt(("material", name.as_str()))
            .show(ui, |ui| {
                let rename = state.rename.as_mut().filter(|r| r.material == *name);
                if let Some(new_op) = material_buttons(ui, name, users, rename) {
                    op = Some(new_op);
                }
                material_grid(ui, material, scale);
            });
    }
    match op {
        Some(MaterialOp::StartRename(name)) => {
            state.rename = Some(Rename {
                text: name.clone(),
                material: name,
                error: None,
                focus: true,
            });
        }
        Some(MaterialOp::CancelRename) => state.rename = None,
        Some(MaterialOp::Rename(old, new)) => match edit::rename_material(scene, &old, &new) {
            Ok(()) => state.rename = None,
            Err(message) => {
                if let Some(rename) = &mut state.rename {
                    rename.error = Some(message);
                }
            }
        },
        Some(MaterialOp::Remove(name)) => {
            edit::remove_material(scene, &name);
            state.rename = state.rename.take().filter(|r| r.material != name);
        }
        None => {}
    }
    if ui
        .button("Add material")
        .on_hover_text("A new material with the default values")
        .clicked()
    {
        edit::add_material(scene);
    }
}

/// Rename and Remove, or the rename field while a rename is typed.
pub(super) fn material_buttons(
    ui: &mut Ui,
    name: &str,
    users: usize,
    rename: Option<&mut Rename>,
) -> Option<MaterialOp> {
    let Some(rename) = rename else {
        return ui
            .horizontal(|ui| {
                if ui.small_button("Rename").clicked() {
                    return Some(MaterialOp::StartRename(name.to_owned()));
                }
                let remove = ui.small_button("Remove").on_hover_text(format!(
                    "{users} shape(s) use it; they will get the default material"
                ));
                remove
                    .clicked()
                    .then(|| MaterialOp::Remove(name.to_owned()))
            })
            .inner;
    };
    let op = ui
        .horizontal(|ui| {
            let field = ui.add(TextEdit::singleline(&mut rename.text).desired_width(120.0));
            if std::mem::take(&mut rename.focus) {
                field.request_focus();
            }
            let entered = field.lost_focus() && ui.input(|i| i.key_pressed(Key::Enter));
            if ui.small_button("OK").clicked() || entered {
                Some(MaterialOp::Rename(name.to_owned(), rename.text.clone()))
            } else if ui.small_button("Cancel").clicked() {
                Some(MaterialOp::CancelRename)
            } else {
                None
            }
        })
        .inner;
    if let Some(error) = &rename.error {
        ui.colored_label(ui.visuals().error_fg_color, error);
    }
    op
}

/// The fields of docs/rendering-model.md, "Materials". Weights show a 0..1 slider but take larger
/// typed values: the rendering model only asks for >= 0.
pub(super) fn material_grid(ui: &mut Ui, m: &mut Material, scale: f64) {
    Grid::new("material").num_columns(2).show(ui, |ui| {
        let albedo = "Albedo; also tints light passing through (linear RGB)";
        colour_field(ui, "colour", albedo, &mut m.color);

        let weights = [
            ("diffuse", "kd: Lambert (matte) weight, also of the ambient light", &mut m.diffuse),
            ("specular", "ks: weight of the white Blinn-Phong highlight", &mut m.specular),
            ("mirror", "kr: perfect mirror weight (untinted)", &mut m.mirror),
            (
                "transparency",
                "kt: weight of the glass part; Fresnel splits it into reflected and refracted light",
                &mut m.transparency,
            ),
        ];
        for (name, tooltip, value) in weights {
            field(ui, name, tooltip);
            slider(ui, value, 0.0..=1.0, 0.0..=VALUE_LIMIT, false);
            ui.end_row();
        }

        field(
            ui,
            "shininess",
            "Blinn-Phong exponent: larger gives a smaller, sharper highlight",
        );
        slider(ui, &mut m.shininess, 1.0..=10000.0, MIN_POSITIVE..=VALUE_LIMIT, true);
        ui.end_row();

        field(
            ui,
            "ior",
            "Index of refraction of the inside: 1 air (no bending), 1.33 water, 1.5 glass, 2.42 diamond",
        );
        slider(ui, &mut m.ior, 1.0..=3.0, MIN_POSITIVE..=100.0, false);
        ui.end_row();

        checker_rows(ui, m, scale);
    });
}

pub(super) fn checker_rows(ui: &mut Ui, m: &mut Material, scale: f64) {
    field(
        ui,
        "checker",
        "A 3D checkerboard: the colour above on even cells, the checker colour on odd ones",
    );
    let mut on = m.checker.is_some();
    if ui.checkbox(&mut on, "").changed() {
        m.checker = on.then(|| edit::default_checker(scale));
    }
    ui.end_row();
    if let Some(checker) = &mut m.checker {
        let odd = "Colour of the odd cells (linear RGB)";
        colour_field(ui, "  colour", odd, &mut checker.color);

        let size = "Edge length of a cell";
        length_row(ui, "  size", size, &mut checker.size, 0.002 * scale);
    }
}
