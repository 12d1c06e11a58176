//! Messages drawn over the image, shared by the viewer and the sandbox
//! window: the shader error (copyable, with file, line, column and the
//! offending line) and warnings about the shader's output.

use super::layout;

/// The colour of error text.
pub const ERROR_COLOR: egui::Color32 = egui::Color32::from_rgb(255, 120, 100);
/// The colour of warning text.
pub const WARNING_COLOR: egui::Color32 = egui::Color32::from_rgb(255, 200, 80);

/// A copyable error message in a monospace font, anchored at `anchor`.
pub fn error_window(ctx: &egui::Context, title: &str, text: &str, anchor: egui::Align2) {
    let offset = match anchor.y() {
        egui::Align::Max => [0.0, -10.0],
        _ => [0.0, 10.0],
    };
    let window = egui::Window::new(title)
        .id(egui::Id::unique("shader error overlay"))
        .anchor(anchor, offset)
        .collapsible(false)
        .resizable(true)
        .default_width(640.0)
        .show(ctx, |ui| {
            let mut copy = text.to_string();
            ui.add(
                egui::TextEdit::multiline(&mut copy)
                    .font(egui::TextStyle::Monospace)
                    .text_color(ERROR_COLOR)
                    .desired_width(f32::INFINITY)
                    .desired_rows(4),
            );
            if ui.button("Copy").clicked() {
                ui.ctx().copy_text(text.to_string());
            }
            ui.is_sizing_pass()
        });
    layout::note_window(ctx, "shader-error", window);
}

/// A one-line warning in a small frame, anchored at `anchor`.
pub fn warning(ctx: &egui::Context, text: &str, anchor: egui::Align2) {
    egui::Area::new(egui::Id::unique("shader warning"))
        .anchor(anchor, [0.0, 10.0])
        .interactable(false)
        .show(ctx, |ui| {
            egui::Frame::popup(ui.style()).show(ui, |ui| {
                ui.label(egui::RichText::new(format!("⚠ {text}")).color(WARNING_COLOR));
            });
        });
}
