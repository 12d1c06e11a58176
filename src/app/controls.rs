//! Controls shared by the windows: the clock (pause, restart, step) and the
//! parameters generated from a shader's annotations.

use egui::{Grid, RichText, Ui};

use crate::sandbox::clock::Tick;
use crate::shader_params::{Control, ParamSet, ParamSpec, Scalar};

/// What the user asked of the clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ClockAction {
    Toggle,
    Restart,
    Step,
}

/// Play/pause, restart and step buttons with the time and frame number.
pub fn clock_controls(ui: &mut Ui, paused: bool, tick: &Tick) -> Option<ClockAction> {
    let mut action = None;
    ui.horizontal(|ui| {
        let (icon, hint) = if paused {
            ("Resume", "Resume the clock (Space)")
        } else {
            ("Pause", "Pause the clock (Space)")
        };
        if ui.button(icon).on_hover_text(hint).clicked() {
            action = Some(ClockAction::Toggle);
        }
        if ui
            .button("Restart")
            .on_hover_text("Time and frame back to 0 (Backspace)")
            .clicked()
        {
            action = Some(ClockAction::Restart);
        }
        if ui
            .button("Step")
            .on_hover_text("Pause and advance one frame, 1/60 s (Right arrow)")
            .clicked()
        {
            action = Some(ClockAction::Step);
        }
    });
    ui.label(
        RichText::new(format!(
            "time {:.3} s   frame {}{}",
            tick.time,
            tick.frame,
            if paused { "   (paused)" } else { "" }
        ))
        .monospace(),
    );
    action
}

/// One row per parameter; returns true when a value changed.
pub fn params_ui(ui: &mut Ui, params: &mut ParamSet) -> bool {
    let mut changed = false;
    Grid::new("shader parameters")
        .num_columns(2)
        .striped(true)
        .show(ui, |ui| {
            for (spec, value) in params.specs.iter().zip(params.values.iter_mut()) {
                let label = ui.label(&spec.name);
                let hover = format!(
                    "{}{}line {}: {} {}",
                    spec.help,
                    if spec.help.is_empty() { "" } else { "\n" },
                    spec.line,
                    spec.ty.name(),
                    annotation_text(&spec.control)
                );
                label.on_hover_text(hover);
                let mut v = *value;
                if control(ui, spec, &mut v) {
                    let v = spec.clamp(v);
                    if v != *value {
                        *value = v;
                        changed = true;
                    }
                }
                ui.end_row();
            }
        });
    changed
}

fn annotation_text(control: &Control) -> String {
    match control {
        Control::Drag { .. } => "(no annotation: drag)".into(),
        Control::Slider { min, max, step } => match step {
            Some(s) => format!("@slider({min}, {max}, {s})"),
            None => format!("@slider({min}, {max})"),
        },
        Control::Log { min, max } => format!("@log({min}, {max})"),
        Control::Color { linear: true } => "@color(linear)".into(),
        Control::Color { linear: false } => "@color".into(),
        Control::Checkbox => "@checkbox".into(),
        Control::Select(labels) => format!("@select({})", labels.join(", ")),
        Control::Fixed(t) => format!("{t}: no control"),
    }
}

/// The control for one parameter; true when the user changed it.
fn control(ui: &mut Ui, spec: &ParamSpec, value: &mut [f64; 4]) -> bool {
    let integer = !spec.ty.is_float();
    let n = spec.ty.len;
    match &spec.control {
        Control::Fixed(type_name) => {
            ui.weak(format!("{type_name}: no control (stays 0)"));
            false
        }
        Control::Checkbox => {
            let mut on = value[0] != 0.0;
            let changed = ui.checkbox(&mut on, "").changed();
            value[0] = f64::from(u8::from(on));
            changed
        }
        Control::Select(labels) => {
            let mut index = (value[0].max(0.0) as usize).min(labels.len() - 1);
            let before = index;
            egui::ComboBox::from_id_salt(("select", &spec.name))
                .selected_text(&labels[index])
                .show_ui(ui, |ui| {
                    for (i, label) in labels.iter().enumerate() {
                        ui.selectable_value(&mut index, i, label);
                    }
                });
            value[0] = index as f64;
            index != before
        }
        Control::Color { linear } => color(ui, value, n, *linear),
        Control::Slider { min, max, step } => components(ui, n, |ui, i| {
            let mut slider = egui::Slider::new(&mut value[i], *min..=*max);
            if let Some(step) = step {
                slider = slider.step_by(*step);
            }
            if integer {
                slider = slider.integer();
            }
            ui.add(slider).changed()
        }),
        Control::Log { min, max } => components(ui, n, |ui, i| {
            ui.add(egui::Slider::new(&mut value[i], *min..=*max).logarithmic(true))
                .changed()
        }),
        Control::Drag { speed } => components(ui, n, |ui, i| {
            let speed = speed.unwrap_or(if integer {
                0.25
            } else {
                (value[i].abs() * 0.01).max(0.001)
            });
            let mut drag = egui::DragValue::new(&mut value[i]).speed(speed);
            if spec.ty.scalar == Scalar::U32 {
                drag = drag.range(0.0..=f64::from(u32::MAX));
            }
            if !integer {
                drag = drag.max_decimals(6);
            }
            ui.add(drag).changed()
        }),
    }
}

/// One widget per component, side by side.
fn components(ui: &mut Ui, n: usize, mut one: impl FnMut(&mut Ui, usize) -> bool) -> bool {
    let mut changed = false;
    if n == 1 {
        return one(ui, 0);
    }
    ui.vertical(|ui| {
        for i in 0..n {
            changed |= one(ui, i);
        }
    });
    changed
}

fn color(ui: &mut Ui, value: &mut [f64; 4], n: usize, linear: bool) -> bool {
    let to_u8 = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    let changed = match (linear, n) {
        (false, 3) => {
            let mut c = [to_u8(value[0]), to_u8(value[1]), to_u8(value[2])];
            let changed = ui.color_edit_button_srgb(&mut c).changed();
            if changed {
                for i in 0..3 {
                    value[i] = f64::from(c[i]) / 255.0;
                }
            }
            changed
        }
        (false, _) => {
            let mut c = [
                to_u8(value[0]),
                to_u8(value[1]),
                to_u8(value[2]),
                to_u8(value[3]),
            ];
            let changed = ui.color_edit_button_srgba_unmultiplied(&mut c).changed();
            if changed {
                for i in 0..4 {
                    value[i] = f64::from(c[i]) / 255.0;
                }
            }
            changed
        }
        (true, 3) => {
            let mut c = [value[0] as f32, value[1] as f32, value[2] as f32];
            let changed = ui.color_edit_button_rgb(&mut c).changed();
            if changed {
                for i in 0..3 {
                    value[i] = f64::from(c[i]);
                }
            }
            changed
        }
        (true, _) => {
            let mut c = [
                value[0] as f32,
                value[1] as f32,
                value[2] as f32,
                value[3] as f32,
            ];
            let changed = ui.color_edit_button_rgba_unmultiplied(&mut c).changed();
            if changed {
                for i in 0..4 {
                    value[i] = f64::from(c[i]);
                }
            }
            changed
        }
    };
    if changed {
        ui.ctx().request_repaint();
    }
    changed
}
