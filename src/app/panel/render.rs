//! The panel's Render section: the scene's render settings and the
//! viewer's own (sample limit, frame budget).

use super::widgets::{MIN_POSITIVE, VALUE_LIMIT, color_row, named_row, slider};
use super::{ViewSettings, field};
use crate::gpu::MIN_SCALE;
use crate::scene::{Intersections, Render};
use egui::{Grid, Slider, Ui};

pub(super) fn render_section(ui: &mut Ui, render: &mut Render, view: &mut ViewSettings) {
    Grid::new("render").num_columns(2).show(ui, |ui| {
        super::view_menu::lecture_switches(ui, render);
        intersections_row(ui, &mut render.intersections);
        super::shapes::settings_rows(ui, render);
        field(
            ui,
            "max depth",
            "Deepest secondary ray: 0 = primary rays only (no reflections, no refraction)",
        );
        ui.add(Slider::new(&mut render.max_depth, 0..=16));
        ui.end_row();

        field(
            ui,
            "min weight",
            "Secondary rays whose weight falls below this are not traced (0 = all up to max depth)",
        );
        slider(ui, &mut render.min_weight, 0.0..=1.0, 0.0..=1.0, true);
        ui.end_row();

        field(ui, "background", "Radiance of rays that hit nothing");
        color_row(ui, &mut render.background);
        ui.end_row();

        field(
            ui,
            "ambient",
            "Light that reaches everywhere: ambient * albedo * kd",
        );
        color_row(ui, &mut render.ambient);
        ui.end_row();

        field(
            ui,
            "exposure",
            "Multiplies the radiance before clamping to [0, 1]",
        );
        slider(
            ui,
            &mut render.exposure,
            0.01..=100.0,
            MIN_POSITIVE..=VALUE_LIMIT,
            true,
        );
        ui.end_row();
    });
    ui.separator();
    ui.label("Viewer (not saved in the file)");
    Grid::new("view").num_columns(2).show(ui, |ui| {
        super::view_menu::view_row(ui, &mut view.shown);
        field(
            ui,
            "samples",
            "Progressive refinement stops after this many samples per pixel",
        );
        ui.add(Slider::new(&mut view.max_samples, 1..=1024).logarithmic(true));
        ui.end_row();

        field(
            ui,
            "moving scale",
            "Resolution while the camera moves or a slider is dragged: lower keeps it \
             smooth. With a frame budget, where the first moving frame starts",
        );
        ui.add(Slider::new(&mut view.interaction_scale, MIN_SCALE..=1.0));
        ui.end_row();

        field(
            ui,
            "frame budget",
            "While moving, pick the scale from the last frame's time so that a frame \
             takes about this long (ms)",
        );
        ui.horizontal(|ui| {
            ui.checkbox(&mut view.adaptive_scale, "");
            ui.add_enabled(
                view.adaptive_scale,
                Slider::new(&mut view.frame_budget_ms, 10.0..=1000.0)
                    .logarithmic(true)
                    .suffix(" ms"),
            );
        });
        ui.end_row();

        field(
            ui,
            "last moving frame",
            "Trace time and resolution scale of the last frame drawn while moving",
        );
        ui.label(view.moving_frame.map_or("-".to_string(), |f| {
            format!(
                "{:.1} ms at scale {:.2}",
                f.time.as_secs_f64() * 1e3,
                f.scale
            )
        }));
        ui.end_row();

        field(
            ui,
            "min weight",
            "While viewing, skip secondary rays weaker than this (the file's min_weight is kept)",
        );
        ui.add(Slider::new(&mut view.min_weight, 0.0..=0.1).logarithmic(true));
        ui.end_row();
    });
}

/// The intersection routines, a lecture switch saved with the scene
/// (docs/rendering-model.md, "Lecture switches"): the textbook ones show
/// their leaks and acne in the error, normals and cost views.
fn intersections_row(ui: &mut Ui, intersections: &mut Intersections) {
    named_row(
        ui,
        "intersections",
        "Robust (camera-relative, stable roots, scaled offsets) or the lecture's \
         textbook routines (naive quadratic, world coordinates, offset 1e-3), saved \
         with the scene: the error, normals and cost views show the leaks and acne \
         of the textbook ones far from the origin or at small scales",
        intersections,
    );
}
