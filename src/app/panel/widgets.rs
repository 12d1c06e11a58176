//! Small widgets over the scene's values. Each writes only values the rendering model
//! accepts: finite and inside the field's range. That needs care with egui:
//! a number field parses what the user types with `str::parse`, which takes
//! "inf" and "nan", so every field here has a finite range (egui clamps typed
//! values into it, NaN included), and sliders that may be typed past their
//! ends check the value themselves.

use std::ops::RangeInclusive;

use egui::{ComboBox, DragValue, Response, Slider, SliderClamping, Ui};
use glam::DVec3;

use super::field;
use crate::scene::NamedOption;

/// Largest coordinate the panel writes: far beyond any teaching scene, and
/// small enough that differences and squared lengths of points stay finite.
pub(super) const COORDINATE_LIMIT: f64 = 1e9;

/// Largest value typed into weights, colours, intensities and sizes.
pub(super) const VALUE_LIMIT: f64 = 1e6;

/// Smallest value the panel writes into a field that must be > 0 (radius,
/// exposure, ior...): the rendering model only asks for > 0, and a drag must not stop at 0.
pub(super) const MIN_POSITIVE: f64 = 1e-6;

/// Range of a position component.
pub(super) const COORDINATES: RangeInclusive<f64> = -COORDINATE_LIMIT..=COORDINATE_LIMIT;

/// Colour pickers write multiples of this: plenty for an 8-bit image, and the
/// saved file reads `0.4824` rather than `0.48235294222831726`.
const PICKER_STEP: f64 = 1e-4;

/// What happened to a row of three number fields this frame.
pub(super) struct RowEdit {
    /// A value changed.
    pub changed: bool,
    /// A field is being dragged or typed into: the edit is not finished.
    pub active: bool,
}

/// Three number fields for x, y, z on one line. Values already outside
/// `range` (from a file) are kept until the user edits them.
pub(super) fn vec3_row(
    ui: &mut Ui,
    v: &mut DVec3,
    speed: f64,
    range: RangeInclusive<f64>,
) -> RowEdit {
    let mut components = v.to_array();
    let mut edit = RowEdit {
        changed: false,
        active: false,
    };
    ui.horizontal(|ui| {
        for x in &mut components {
            let response = ui.add(number(x, speed, range.clone()));
            edit.changed |= response.changed();
            edit.active |= response.dragged() || response.has_focus();
        }
    });
    if edit.changed {
        *v = DVec3::from_array(components);
    }
    edit
}

/// A grid row of a position: its label with `tooltip`, and x, y, z dragged
/// by a two-hundredth of the scene `scale`.
pub(super) fn position_row(ui: &mut Ui, name: &str, tooltip: &str, v: &mut DVec3, scale: f64) {
    super::field(ui, name, tooltip);
    vec3_row(ui, v, 0.005 * scale, COORDINATES);
    ui.end_row();
}

/// A grid row of a colour: its label with `tooltip`, and the colour's row
/// ([`color_row`]).
pub(super) fn colour_field(ui: &mut Ui, name: &str, tooltip: &str, color: &mut DVec3) {
    super::field(ui, name, tooltip);
    color_row(ui, color);
    ui.end_row();
}

/// A grid row of a length (> 0): its label with `tooltip`, and the number
/// dragged by `speed`.
pub(super) fn length_row(ui: &mut Ui, name: &str, tooltip: &str, value: &mut f64, speed: f64) {
    super::field(ui, name, tooltip);
    ui.add(number(value, speed, MIN_POSITIVE..=VALUE_LIMIT));
    ui.end_row();
}

/// A number field with a finite range that does not touch values already
/// outside it (a loaded scene must not count as edited just by being shown).
pub(super) fn number(value: &mut f64, speed: f64, range: RangeInclusive<f64>) -> DragValue<'_> {
    DragValue::new(value)
        .speed(speed)
        .range(range)
        .clamp_existing_to_range(false)
}

/// A slider over `shown`, where the useful values lie, whose number can be
/// typed beyond it anywhere in `valid` (a mirror weight of 1.2 is legal and
/// sometimes instructive). Non-finite input is ignored.
pub(super) fn slider(
    ui: &mut Ui,
    value: &mut f64,
    shown: RangeInclusive<f64>,
    valid: RangeInclusive<f64>,
    logarithmic: bool,
) -> Response {
    let (low, high) = valid.into_inner();
    let get_set = move |new: Option<f64>| {
        if let Some(x) = new
            && x.is_finite()
        {
            *value = x.clamp(low, high);
        }
        *value
    };
    ui.add(
        Slider::from_get_set(shown, get_set)
            .clamping(SliderClamping::Never)
            .logarithmic(logarithmic),
    )
}

/// A linear RGB colour: a picker for 0..=1, then three number fields, the
/// only way to enter channels above 1 (an over-bright light or background).
/// Returns whether the colour changed.
pub(super) fn color_row(ui: &mut Ui, color: &mut DVec3) -> bool {
    ui.horizontal(|ui| {
        let shown = color
            .as_vec3()
            .clamp(glam::Vec3::ZERO, glam::Vec3::ONE)
            .to_array();
        let mut picked = shown;
        let mut changed = false;
        let picker = ui.color_edit_button_rgb(&mut picked);
        if picker.changed() {
            // Only the channels the picker moved: the others keep their
            // exact f64 value (and may stay above 1).
            for (i, (&new, &old)) in picked.iter().zip(&shown).enumerate() {
                if new != old && new.is_finite() {
                    color[i] = ((f64::from(new) / PICKER_STEP).round() * PICKER_STEP).max(0.0);
                    changed = true;
                }
            }
        }
        picker.on_hover_text("Pick a colour (linear RGB). Type a channel to go above 1.");
        let mut channels = color.to_array();
        for x in &mut channels {
            changed |= ui.add(number(x, 0.005, 0.0..=VALUE_LIMIT)).changed();
        }
        if changed {
            *color = DVec3::from_array(channels);
        }
        changed
    })
    .inner
}

/// A grid row choosing one of a named option's values.
pub(super) fn named_row<T: NamedOption + PartialEq>(
    ui: &mut Ui,
    label: &str,
    tooltip: &str,
    value: &mut T,
) {
    field(ui, label, tooltip);
    ComboBox::from_id_salt(label)
        .selected_text(value.name())
        .show_ui(ui, |ui| {
            for &v in T::all() {
                ui.selectable_value(value, v, v.name());
            }
        });
    ui.end_row();
}
