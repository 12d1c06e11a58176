//! The divider between the picture and the editor (docs/web.md, "Editing in
//! the page"): dragged, it moves the border between them; the browser keeps
//! the width for the next visit, as it keeps the UI scale.
//!
//! The width the user chose is `--editor-chosen` in `web/editor.css`, which
//! clamps it to the window (`--editor-width`): a width kept from a wide
//! screen still leaves a picture on a projector's.

use std::cell::Cell;
use std::rc::Rc;

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;
use web_sys::{EventTarget, HtmlElement, PointerEvent};

use super::page;

/// Where the browser keeps the editor's width, in CSS pixels.
const WIDTH_KEY: &str = "raysandbox.editor-width";
/// Id of the divider at the editor's left edge (`web/index.html`).
const DIVIDER_ID: &str = "editor-divider";
/// The narrowest editor and picture a drag leaves, in CSS pixels; the same
/// bounds as `--editor-width` in `web/editor.css`.
const MIN_EDITOR: f64 = 240.0;
const MIN_PICTURE: f64 = 320.0;

/// Applies the kept width and lets the user drag the divider. Logs
/// `editor-width W` when a drag ends (the tests read it).
pub fn attach() -> Result<(), String> {
    if let Some(width) = page::stored(WIDTH_KEY).and_then(|w| w.parse::<f64>().ok()) {
        set_width(width);
    }
    let document = web_sys::window()
        .and_then(|w| w.document())
        .ok_or("no document")?;
    let divider: HtmlElement = document
        .get_element_by_id(DIVIDER_ID)
        .ok_or_else(|| format!("the page has no #{DIVIDER_ID} element (web/index.html)"))?
        .dyn_into()
        .map_err(|_| format!("#{DIVIDER_ID} is not an HTML element"))?;
    // The moves are followed on the window, over the canvas and the
    // editor too, which take no pointer events meanwhile (`resizing` in
    // web/editor.css): the canvas's own listeners would see a move with no
    // press.
    let drag = Rc::new(Drag::default());
    let pressed = drag.clone();
    listen(&divider, "pointerdown", move |event| {
        pressed.active.set(true);
        page::set_body_class("resizing", true);
        event.prevent_default();
    })?;
    let window = web_sys::window().ok_or("no window")?;
    let moving = drag.clone();
    listen(&window, "pointermove", move |event| {
        if moving.active.get() {
            let width = width_at(f64::from(event.client_x()));
            set_width(width);
            moving.width.set(Some(width));
        }
    })?;
    let released = drag.clone();
    listen(&window, "pointerup", move |event| {
        if released.active.get() {
            released.end(Some(width_at(f64::from(event.client_x()))));
        }
    })?;
    // A touch taken over by the browser ends the drag where it was.
    listen(&window, "pointercancel", move |_| {
        if drag.active.get() {
            drag.end(drag.width.get());
        }
    })
}

/// A drag of the divider.
#[derive(Default)]
struct Drag {
    /// The button is down on the divider.
    active: Cell<bool>,
    /// The width at the last move.
    width: Cell<Option<f64>>,
}

impl Drag {
    /// Ends the drag at `width` (none: where it started), which the browser
    /// keeps.
    fn end(&self, width: Option<f64>) {
        self.active.set(false);
        self.width.set(None);
        page::set_body_class("resizing", false);
        if let Some(width) = width {
            set_width(width);
            page::store(WIDTH_KEY, &width.to_string());
            page::event(&format!("editor-width {width}"));
        }
    }
}

/// The editor's width with its left edge at `x`, within the bounds.
fn width_at(x: f64) -> f64 {
    let window = web_sys::window()
        .and_then(|w| w.inner_width().ok())
        .and_then(|w| w.as_f64())
        .unwrap_or(0.0);
    (window - x)
        .min(window - MIN_PICTURE)
        .max(MIN_EDITOR)
        .round()
}

/// Sets the width the user chose (the style sheet clamps it to the window).
fn set_width(width: f64) {
    let root = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.document_element())
        .and_then(|e| e.dyn_into::<HtmlElement>().ok());
    if let Some(root) = root {
        let _ = root
            .style()
            .set_property("--editor-chosen", &format!("{width}px"));
    }
}

/// Calls `handler` at each pointer `event` on `target`, for the page's
/// lifetime; before the listeners of the elements inside it (the capture
/// phase), which may stop the event.
fn listen(
    target: &EventTarget,
    event: &str,
    handler: impl Fn(&PointerEvent) + 'static,
) -> Result<(), String> {
    let closure = Closure::<dyn FnMut(PointerEvent)>::new(move |e: PointerEvent| handler(&e));
    target
        .add_event_listener_with_callback_and_bool(event, closure.as_ref().unchecked_ref(), true)
        .map_err(|e| format!("cannot listen to {event}: {e:?}"))?;
    closure.forget();
    Ok(())
}
