//! The panel's "Ray tree" section: the tree of the pixel Shift+clicked (or
//! under the mouse when `T` was pressed), the f64 reference's and the
//! GPU's side by side with their difference, in the text that
//! `raysandbox ray-tree` prints (docs/ray-tree.md).

use egui::{RichText, Ui};

use super::super::layout;
use super::super::ray_tree::PixelTree;

/// The most height the tree's text takes in the panel, in points; it
/// scrolls beyond.
const TEXT_HEIGHT: f32 = 320.0;

/// Draws the section; returns true when "Clear" was clicked.
pub fn ray_tree_section(ui: &mut Ui, tree: &PixelTree) -> bool {
    let mut clear = false;
    let shown = egui::CollapsingHeader::new(RichText::new("Ray tree").strong())
        .default_open(true)
        .show(ui, |ui| {
            ui.label(tree.summary());
            ui.horizontal(|ui| {
                clear = ui
                    .button("Clear")
                    .on_hover_text("Forget the tree and its rays over the picture (Esc)")
                    .clicked();
                ui.weak("reference (f64), gpu (f32) and |difference|");
            });
            egui::ScrollArea::both()
                .id_salt("ray tree text")
                .max_height(TEXT_HEIGHT)
                .show(ui, |ui| {
                    // Unwrapped: the columns of both trees line up.
                    ui.add(egui::Label::new(RichText::new(&tree.text).monospace()).extend());
                });
        });
    layout::note(ui.ctx(), "ray-tree", shown.header_response.rect);
    clear
}
