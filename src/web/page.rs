//! What the Rust side touches of the HTML page (`web/index.html`): the
//! canvas, the message box, and the console.

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

/// Id of the canvas the tracer draws into.
const CANVAS_ID: &str = "raysandbox";
/// Id of the box that shows errors over the canvas.
const MESSAGE_ID: &str = "message";

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

/// Shows `message` where the user looks (over the canvas) and logs it.
pub fn show_error(message: &str) {
    web_sys::console::error_1(&format!("raysandbox: error {message}").into());
    if let Some(element) = document().and_then(|d| d.get_element_by_id(MESSAGE_ID)) {
        element.set_text_content(Some(message));
        let _ = element.set_attribute("class", "shown");
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
