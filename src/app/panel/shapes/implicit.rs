//! The implicit surface's editor: the function in a text field (a mistake is
//! shown under it while the last good function keeps rendering), a gallery
//! of presets from the lecture, the box, the number of steps and the
//! placement.

use egui::{Color32, Ui};
use glam::DVec3;

use super::{EditShape, InView};
use crate::app::panel::field;
use crate::app::panel::widgets::{COORDINATES, vec3_row};
use crate::expr::Function;
use crate::scene::implicit::MAX_STEPS;
use crate::scene::{Implicit, Instance, Placement};

/// A preset: name, function, local box.
pub struct Preset {
    pub name: &'static str,
    pub f: &'static str,
    pub bounds: [[f64; 3]; 2],
}

/// The gallery: the lecture's list, from quadrics to a gyroid.
pub const PRESETS: [Preset; 8] = [
    Preset {
        name: "plane",
        f: "y",
        bounds: [[-1.0, -0.5, -1.0], [1.0, 0.5, 1.0]],
    },
    Preset {
        name: "sphere",
        f: "x^2 + y^2 + z^2 - 1",
        bounds: [[-1.1, -1.1, -1.1], [1.1, 1.1, 1.1]],
    },
    Preset {
        name: "ellipsoid",
        f: "(x / 1.2)^2 + (y / 0.6)^2 + (z / 0.8)^2 - 1",
        bounds: [[-1.3, -0.7, -0.9], [1.3, 0.7, 0.9]],
    },
    Preset {
        name: "cylinder",
        f: "x^2 + z^2 - 0.5^2",
        bounds: [[-0.6, -1.0, -0.6], [0.6, 1.0, 0.6]],
    },
    Preset {
        name: "monkey saddle (cubic)",
        f: "x^3 - 3 * x * z^2 - y",
        bounds: [[-1.0, -2.0, -1.0], [1.0, 2.0, 1.0]],
    },
    Preset {
        name: "Goursat's surface (quartic)",
        f: "x^4 + y^4 + z^4 - 5 * (x^2 + y^2 + z^2) + 11.8",
        bounds: [[-2.5, -2.5, -2.5], [2.5, 2.5, 2.5]],
    },
    Preset {
        name: "heart (Taubin's sextic)",
        f: "(x^2 + 9/4 * z^2 + y^2 - 1)^3 - x^2 * y^3 - 9/80 * z^2 * y^3",
        bounds: [[-1.5, -1.5, -1.5], [1.5, 1.5, 1.5]],
    },
    Preset {
        name: "gyroid in a box",
        f: "max(abs(sin(4*x)*cos(4*y) + sin(4*y)*cos(4*z) + sin(4*z)*cos(4*x)) - 0.3, \
            max(abs(x), max(abs(y), abs(z))) - 0.9)",
        bounds: [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]],
    },
];

/// The text being typed, kept apart from the shape's function until it
/// parses, so the last good surface keeps rendering meanwhile.
#[derive(Clone, Default)]
struct Draft {
    text: String,
    /// The shape's function when the draft was made: another value means the
    /// shape changed elsewhere (another selection, a reload), and the draft
    /// starts again from it.
    from: String,
    error: Option<String>,
}

impl EditShape for Implicit {
    /// The sphere preset at the target, a tenth of the scene scale.
    fn new_near(at: &InView) -> Instance<Implicit> {
        let preset = &PRESETS[1];
        let implicit = Implicit {
            f: preset.f.to_string(),
            bounds: preset.bounds.map(DVec3::from_array),
            steps: 256,
        };
        let placement = Placement {
            translate: at.target,
            scale: 0.1 * at.scale,
            rotation: DVec3::ZERO,
        };
        Instance::new(implicit, placement)
    }

    /// Right by its box's width.
    fn beside(implicit: &Instance<Implicit>, at: &InView) -> DVec3 {
        at.right * ((implicit.bounds[1].x - implicit.bounds[0].x) * implicit.placement.scale)
    }

    fn edit(&mut self, ui: &mut Ui, _scale: f64) -> bool {
        field(
            ui,
            "f",
            "f(x, y, z): the surface is where it is 0, outside where > 0",
        );
        let held = function_field(ui, &mut self.f);
        ui.end_row();
        field(ui, "preset", "Surfaces from the lecture");
        egui::ComboBox::from_id_salt("implicit preset")
            .selected_text("choose…")
            .show_ui(ui, |ui| {
                for preset in &PRESETS {
                    if ui
                        .selectable_label(self.f == preset.f, preset.name)
                        .clicked()
                    {
                        self.f = preset.f.to_string();
                        self.bounds = preset.bounds.map(DVec3::from_array);
                    }
                }
            });
        ui.end_row();
        field(
            ui,
            "bounds",
            "The local box searched: min, then max (x, y, z)",
        );
        ui.vertical(|ui| {
            vec3_row(ui, &mut self.bounds[0], 0.01, COORDINATES);
            vec3_row(ui, &mut self.bounds[1], 0.01, COORDINATES);
        });
        ui.end_row();
        field(ui, "steps", "Samples along the ray inside the box");
        ui.add(egui::Slider::new(&mut self.steps, 1..=MAX_STEPS).logarithmic(true));
        ui.end_row();
        held
    }

    /// A box dragged inside out is put right: min below max on each axis.
    fn settle(&mut self) {
        for axis in 0..3 {
            let (lo, hi) = (self.bounds[0][axis], self.bounds[1][axis]);
            if lo >= hi {
                self.bounds[0][axis] = hi.min(lo);
                self.bounds[1][axis] = hi.max(lo) + 1e-3;
            }
        }
    }
}

/// The text field of `f` and, under it, what is wrong with it. Writes `f`
/// only when the text parses. True while the text holds a mistake.
fn function_field(ui: &mut Ui, f: &mut String) -> bool {
    let id = ui.scope_id().with("implicit function");
    let mut draft: Draft = ui.data_mut(|d| d.get_temp(id)).unwrap_or_default();
    if draft.from != *f {
        draft = Draft {
            text: f.clone(),
            from: f.clone(),
            error: None,
        };
    }
    ui.vertical(|ui| {
        let edit = ui.add(
            egui::TextEdit::multiline(&mut draft.text)
                .code_editor()
                .desired_rows(1)
                .desired_width(f32::INFINITY),
        );
        if edit.changed() {
            match Function::parse(&draft.text) {
                Ok(_) => {
                    *f = draft.text.clone();
                    draft.from = f.clone();
                    draft.error = None;
                }
                Err(e) => draft.error = Some(e.to_string()),
            }
        }
        if let Some(error) = &draft.error {
            ui.colored_label(Color32::from_rgb(230, 80, 80), error);
        }
    });
    let held = draft.error.is_some();
    ui.data_mut(|d| d.insert_temp(id, draft));
    held
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_parses_and_has_a_proper_box() {
        for preset in &PRESETS {
            Function::parse(preset.f).unwrap_or_else(|e| panic!("{}: {e}", preset.name));
            let [lo, hi] = preset.bounds;
            assert!((0..3).all(|i| lo[i] < hi[i]), "{}", preset.name);
        }
    }
}
