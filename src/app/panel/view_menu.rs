//! The View menu of the panel's Render section: what the picture shows,
//! the shaded picture or a view inside the tracer (docs/views.md).

use egui::{ComboBox, Ui};

use crate::gpu::View;
use crate::scene::NamedOption;

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
