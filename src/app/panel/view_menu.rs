//! The View menu of the panel's Render section: what the picture shows,
//! the shaded picture or a view inside the tracer (docs/views.md); and the
//! lecture switches, which change the picture and are saved with the scene.

use egui::{ComboBox, Ui};

use crate::gpu::View;
use crate::scene::{NamedOption, RenderSettings};

/// One row of the render grid: shadow, reflected and refracted rays on or
/// off (docs/rendering-model.md, "Lecture switches").
pub(super) fn lecture_switches(ui: &mut Ui, render: &mut RenderSettings) {
    super::field(
        ui,
        "rays",
        "The lecture's switches, saved with the scene: turn shadow rays, reflected \
         rays or refracted rays off to show what each adds",
    );
    ui.horizontal(|ui| {
        ui.checkbox(&mut render.shadows, "shadows");
        ui.checkbox(&mut render.reflection, "reflection");
        ui.checkbox(&mut render.refraction, "refraction");
    });
    ui.end_row();
}

/// One row of the viewer's grid: the View combo box, each entry with what
/// its colours mean as a tooltip. `V` cycles through the same list.
pub(super) fn view_row(ui: &mut Ui, view: &mut View) {
    super::field(
        ui,
        "view",
        "What the picture shows: the Whitted picture, or a look inside the tracer \
         (normals, depth, cost, steps, bounces); V cycles through them",
    );
    ComboBox::from_id_salt("view menu")
        .selected_text(view.name())
        .show_ui(ui, |ui| {
            for v in View::ALL {
                ui.selectable_value(view, v, v.name())
                    .on_hover_text(v.legend(None));
            }
        });
    ui.end_row();
}
