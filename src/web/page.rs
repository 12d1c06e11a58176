//! What the Rust side touches of the HTML page (`web/index.html`): the
//! canvas, the message box, and the console.

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

/// Id of the canvas the tracer draws into.
const CANVAS_ID: &str = "raysandbox";
/// Id of the box that shows errors and notices over the canvas (with its
/// close button, `web/index.html`).
const MESSAGE_ID: &str = "message";
/// Id of the text in that box.
const MESSAGE_TEXT_ID: &str = "message-text";

fn document() -> Option<web_sys::Document> {
    web_sys::window()?.document()
}

/// The page's canvas; without one winit appends its own.
pub fn canvas() -> Option<web_sys::HtmlCanvasElement> {
    document()?
        .get_element_by_id(CANVAS_ID)?
        .dyn_into::<web_sys::HtmlCanvasElement>()
        .ok()
}

/// The box of errors and notices over the canvas: files dropped on it go
/// where files dropped on the canvas go (it may say "drop the image on
/// the canvas" while covering the canvas's middle).
pub fn message_box() -> Option<web_sys::Element> {
    document()?.get_element_by_id(MESSAGE_ID)
}

/// The value of `key` in the page address's query (`?samples=1`), the
/// page's options, as the native viewer's command-line options.
pub fn query(key: &str) -> Option<String> {
    let search = web_sys::window()?.location().search().ok()?;
    web_sys::UrlSearchParams::new_with_str(&search)
        .ok()?
        .get(key)
}

/// The page address's fragment (after `#`, without it).
pub fn hash() -> Option<String> {
    let hash = web_sys::window()?.location().hash().ok()?;
    Some(hash.trim_start_matches('#').to_string())
}

/// Whether the address asks for the picture alone (`?ui=0`): no panel and
/// no controls over it (for a projector, an embedded page, or a screenshot
/// compared pixel by pixel).
pub fn bare() -> bool {
    query("ui").as_deref() == Some("0")
}

/// Hides the page's controls over the picture (see [`bare`]).
pub fn hide_controls() {
    if let Some(body) = document().and_then(|d| d.body()) {
        let _ = body.class_list().add_1("bare");
    }
}

/// Calls `handler` at each `event` of the page's element `id`, or of the
/// browser window for `None` (`hashchange`); the listener lives as long as
/// the page.
pub fn listen(id: Option<&str>, event: &str, handler: impl FnMut() + 'static) {
    let window = web_sys::window();
    let target: Option<web_sys::EventTarget> = match id {
        Some(id) => document()
            .and_then(|d| d.get_element_by_id(id))
            .map(Into::into),
        None => window.map(Into::into),
    };
    let Some(target) = target else { return };
    let closure = Closure::<dyn FnMut()>::new(handler);
    let _ = target.add_event_listener_with_callback(event, closure.as_ref().unchecked_ref());
    closure.forget();
}

/// A change of the UI scale asked for with the keyboard.
#[derive(Debug, Clone, Copy)]
pub enum ScaleKey {
    /// Ctrl+plus (or Ctrl+=).
    Larger,
    /// Ctrl+minus.
    Smaller,
    /// Ctrl+0.
    Reset,
}

/// Calls `scale` for Ctrl+plus, minus and 0 anywhere in the page (over the
/// picture or in the editor), instead of the browser's own zoom: the page
/// scales its panel, editor and status line together.
pub fn listen_scale_keys(scale: impl Fn(ScaleKey) + 'static) {
    let Some(document) = document() else { return };
    let closure =
        Closure::<dyn FnMut(web_sys::KeyboardEvent)>::new(move |event: web_sys::KeyboardEvent| {
            if !(event.ctrl_key() || event.meta_key()) {
                return;
            }
            let key = match event.key().as_str() {
                "+" | "=" => ScaleKey::Larger,
                "-" => ScaleKey::Smaller,
                "0" => ScaleKey::Reset,
                _ => return,
            };
            event.prevent_default();
            scale(key);
        });
    let _ = document.add_event_listener_with_callback("keydown", closure.as_ref().unchecked_ref());
    closure.forget();
}

/// Sets or clears the class `name` of the page's body, which the style
/// sheet follows (`showing-shader`: the shader's controls are shown).
pub fn set_body_class(name: &str, on: bool) {
    if let Some(body) = document().and_then(|d| d.body()) {
        let _ = body.class_list().toggle_with_force(name, on);
    }
}

/// The value the browser keeps for this site under `key` (local storage:
/// it outlives the page), if any.
pub fn stored(key: &str) -> Option<String> {
    let storage = web_sys::window()?.local_storage().ok()??;
    storage.get_item(key).ok()?
}

/// Keeps `value` under `key` in the browser's local storage; a browser
/// that refuses (private mode, storage full) only forgets it.
pub fn store(key: &str, value: &str) {
    if let Some(Ok(Some(storage))) = web_sys::window().map(|w| w.local_storage()) {
        let _ = storage.set_item(key, value);
    }
}

/// Scales the page's own controls (the editor, its buttons, the message
/// box: `--ui-scale` in web/editor.css) as egui's zoom scales the panel.
pub fn set_ui_scale(scale: f32) {
    let root = document()
        .and_then(|d| d.document_element())
        .and_then(|e| e.dyn_into::<web_sys::HtmlElement>().ok());
    if let Some(root) = root {
        let _ = root.style().set_property("--ui-scale", &scale.to_string());
    }
}

/// Whether the editor beside the picture is open.
pub fn editing() -> bool {
    document()
        .and_then(|d| d.body())
        .is_some_and(|body| body.class_list().contains("editing"))
}

/// Replaces the address's fragment (`#` and `hash`) without adding a step
/// to the browser's history or reloading.
pub fn replace_hash(hash: &str) {
    if let Some(history) = web_sys::window().and_then(|w| w.history().ok()) {
        let _ = history.replace_state_with_url(
            &wasm_bindgen::JsValue::NULL,
            "",
            Some(&format!("#{hash}")),
        );
    }
}

/// Logs one `raysandbox: EVENT` line on the console (tests read them).
pub fn event(line: &str) {
    web_sys::console::log_1(&format!("raysandbox: {line}").into());
}

/// Logs `raysandbox: timing WHAT MS`, the milliseconds since the page's
/// navigation started (`performance.now()`): how long the page takes to
/// become usable, read by scripts/web-startup (docs/web.md, "Start-up time").
pub fn timing(what: &str) {
    let now = web_sys::window()
        .and_then(|w| w.performance())
        .map(|p| p.now());
    event(&format!("timing {what} {:.0}", now.unwrap_or(f64::NAN)));
}

/// Shows `message` where the user looks (over the canvas, beside the
/// panel, until closed) and logs it.
pub fn show_error(message: &str) {
    web_sys::console::error_1(&format!("raysandbox: error {message}").into());
    show_message(message, "shown error");
}

/// Shows `message` over the canvas as news, not as an error (the page
/// recovering from a lost GPU).
pub fn show_notice(message: &str) {
    show_message(message, "shown");
}

fn show_message(message: &str, class: &str) {
    let Some(document) = document() else { return };
    if let Some(text) = document.get_element_by_id(MESSAGE_TEXT_ID) {
        text.set_text_content(Some(message));
    }
    if let Some(element) = document.get_element_by_id(MESSAGE_ID) {
        let _ = element.set_attribute("class", class);
    }
}

/// Hides the message box (its news is over).
pub fn hide_message() {
    if let Some(element) = document().and_then(|d| d.get_element_by_id(MESSAGE_ID)) {
        let _ = element.set_attribute("class", "");
    }
}

/// An adapter or device error, with what enables WebGPU.
pub fn no_webgpu_help(error: &str) -> String {
    format!(
        "WebGPU is not available: {error}.\n\
         raysandbox draws with WebGPU: use a recent Chrome, Edge or Chromium (113 or later), \
         Firefox 141 or later on Windows, or Safari 26; on Linux, start Chromium with \
         --enable-unsafe-webgpu --enable-features=Vulkan, or enable \
         chrome://flags/#enable-unsafe-webgpu."
    )
}

/// The page's address with `fragment` (without `#`) after it.
pub fn address_with(fragment: &str) -> Result<String, String> {
    let location = web_sys::window().ok_or("no browser window")?.location();
    let href = location.href().map_err(|e| describe(&e))?;
    let page = href.split('#').next().unwrap_or_default();
    Ok(format!("{page}#{fragment}"))
}

/// Puts `text` on the clipboard; the browser may refuse (permissions, a
/// page without focus), which the error says.
pub async fn copy_text(text: &str) -> Result<(), String> {
    let promise = write_text(text).map_err(|e| describe(&e))?;
    wasm_bindgen_futures::JsFuture::from(promise)
        .await
        .map(|_| ())
        .map_err(|e| describe(&e))
}

/// The bytes at `address` (relative to the page's), fetched over http; an
/// error says why (the status, as `404 Not Found`, or the network's).
pub async fn fetch_bytes(address: &str) -> Result<Vec<u8>, String> {
    let window = web_sys::window().ok_or("no browser window")?;
    let response = wasm_bindgen_futures::JsFuture::from(window.fetch_with_str(address))
        .await
        .map_err(|e| describe(&e))?;
    let response: web_sys::Response = response
        .dyn_into()
        .map_err(|_| "the browser's answer is not a response".to_string())?;
    if !response.ok() {
        return Err(format!("{} {}", response.status(), response.status_text()));
    }
    let buffer = response.array_buffer().map_err(|e| describe(&e))?;
    let buffer = wasm_bindgen_futures::JsFuture::from(buffer)
        .await
        .map_err(|e| describe(&e))?;
    Ok(js_sys::Uint8Array::new(&buffer).to_vec())
}

#[wasm_bindgen]
extern "C" {
    /// `navigator.clipboard.writeText` (web-sys has it only among its
    /// unstable APIs).
    #[wasm_bindgen(js_namespace = ["navigator", "clipboard"], js_name = writeText, catch)]
    fn write_text(text: &str) -> Result<js_sys::Promise, JsValue>;
}

/// A JavaScript error as text.
fn describe(error: &JsValue) -> String {
    error
        .as_string()
        .or_else(|| {
            error
                .dyn_ref::<js_sys::Error>()
                .map(|e| String::from(e.message()))
        })
        .unwrap_or_else(|| format!("{error:?}"))
}
