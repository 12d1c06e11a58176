//! The scene panel's width, kept by the browser for the next visit as the
//! editor's width (`split.rs`) and the UI scale are (docs/web.md, "Editing
//! in the page"): a teacher who widened the panel for a projector finds it
//! so again.

use super::page;

/// Where the browser keeps the panel's width, in egui points.
const WIDTH_KEY: &str = "raysandbox.panel-width";

/// The narrowest and widest width taken from the browser: a damaged or
/// odd value is ignored, and the panel opens at its default.
const KEPT: std::ops::RangeInclusive<f32> = 120.0..=4000.0;

/// The width the browser kept, if any and sensible.
pub fn stored() -> Option<f32> {
    page::stored(WIDTH_KEY)
        .and_then(|w| w.parse::<f32>().ok())
        .filter(|w| KEPT.contains(w))
}

/// After a frame: keeps the panel's `width` when it differs from the
/// `kept` one and no button is down (a drag of its edge is over). Logs
/// `panel-width W` then (the tests read it).
pub fn follow(kept: &mut f32, width: f32, ctx: &egui::Context) {
    let changed = (*kept - width).abs() >= 0.5;
    if changed && !ctx.input(|i| i.pointer.any_down()) {
        *kept = width;
        page::store(WIDTH_KEY, &width.to_string());
        page::event(&format!("panel-width {width}"));
    }
}
