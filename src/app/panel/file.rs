//! The panel's File section: save, open, the bundled examples.

use super::{PanelAction, PanelState};
use egui::{Button, Key, TextEdit, Ui};
use std::path::PathBuf;

/// A text field for a path with its button; Enter in the field also clicks.
/// Returns the trimmed path when clicked.
pub(super) fn path_row(
    ui: &mut Ui,
    button: &str,
    hint: &str,
    text: &mut String,
) -> Option<PathBuf> {
    ui.horizontal(|ui| {
        let path = text.trim();
        let clicked = ui
            .add_enabled(!path.is_empty(), Button::new(button))
            .clicked();
        let field = ui.add(
            TextEdit::singleline(text)
                .hint_text(hint)
                .desired_width(ui.available_width()),
        );
        let entered = field.lost_focus() && ui.input(|i| i.key_pressed(Key::Enter));
        let path = text.trim();
        ((clicked || entered) && !path.is_empty()).then(|| PathBuf::from(path))
    })
    .inner
}

pub(super) fn file_section(
    ui: &mut Ui,
    state: &mut PanelState,
    bundled: &[&'static str],
    actions: &mut Vec<PanelAction>,
) {
    ui.horizontal(|ui| {
        if ui
            .button("Save (Ctrl+S)")
            .on_hover_text("Write the scene to its file")
            .clicked()
        {
            actions.push(PanelAction::Save);
        }
        if ui
            .button("Screenshot (P)")
            .on_hover_text("Save the current image as a PNG")
            .clicked()
        {
            actions.push(PanelAction::Screenshot);
        }
    });
    if let Some(path) = path_row(ui, "Save as", "new/scene.toml", &mut state.save_as_path) {
        actions.push(PanelAction::SaveAs(path));
    }
    if let Some(path) = path_row(ui, "Open", "scenes/file.toml", &mut state.open_path) {
        actions.push(PanelAction::Open(path));
    }
    if !bundled.is_empty() {
        ui.horizontal_wrapped(|ui| {
            ui.label("Examples:");
            for &name in bundled {
                if ui
                    .button(name)
                    .on_hover_text("Switch to this bundled scene")
                    .clicked()
                {
                    actions.push(PanelAction::OpenBundled(name));
                }
            }
        });
    }
}
