//! The page's text editors (docs/web.md, "Editing in the page"): the scene's
//! TOML and a sandbox shader, each an HTML `<textarea>` with a line-number
//! gutter, beside the canvas.
//!
//! A plain `<textarea>` rather than egui's text editor: the browser gives it
//! copy, paste, undo, selection, IME input and screen-reader support, which
//! egui's editor lacks in the page (it has no access to the clipboard
//! there). Each document has its own textarea, so switching documents keeps
//! each one's undo history.
//!
//! What the user types reaches the page's event loop [`DEBOUNCE_MS`] after
//! the last key, as an [`EditorEvent`]; the page compiles it and answers
//! with [`Editor::show_result`].

use std::cell::RefCell;
use std::rc::Rc;

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;
use web_sys::{Document, Element, HtmlElement, HtmlSelectElement, HtmlTextAreaElement};

/// How long after the last key the text is compiled: short enough to feel
/// live, as on GLSL Sandbox, long enough not to compile half-typed words.
pub const DEBOUNCE_MS: i32 = 400;

/// The two documents the page edits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Doc {
    Scene,
    Shader,
}

impl Doc {
    const ALL: [Doc; 2] = [Doc::Scene, Doc::Shader];

    /// The prefix of the document's elements' ids in `web/index.html`.
    fn id(self) -> &'static str {
        match self {
            Doc::Scene => "scene",
            Doc::Shader => "shader",
        }
    }

    fn index(self) -> usize {
        self as usize
    }
}

/// What the editor tells the page.
#[derive(Debug, Clone, PartialEq)]
pub enum EditorEvent {
    /// The text of a document, [`DEBOUNCE_MS`] after the user's last key.
    Changed(Doc, String),
    /// The user chose the document the canvas shows: the scene (the ray
    /// tracer) or the shader (the sandbox).
    Show(Doc),
    /// The user chose an example shader from the menu (its file name).
    Example(String),
}

/// An error to show under a document: the message, and the user's line it
/// is at (1-based), if known.
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    pub message: String,
    pub line: Option<usize>,
}

/// One document's elements.
struct DocView {
    text: HtmlTextAreaElement,
    gutter: Element,
    status: Element,
    /// The text that produced what the canvas shows: the text is "clean"
    /// while the textarea holds exactly this.
    applied: String,
    /// The line the last error is at, marked in the gutter.
    error_line: Option<usize>,
    /// Lines numbered in the gutter now.
    lines: usize,
    /// The debounce timer waiting to send the text.
    timer: Option<i32>,
}

struct State {
    docs: [DocView; 2],
    shown: Doc,
    /// Called with no borrow of the state held: the page may answer at once.
    send: Rc<dyn Fn(EditorEvent)>,
    /// The closures the page's elements call, kept alive with the editor.
    listeners: Vec<Closure<dyn FnMut(web_sys::Event)>>,
    debounced: [Option<Closure<dyn FnMut()>>; 2],
}

/// The editor panel of `web/index.html`.
#[derive(Clone)]
pub struct Editor(Rc<RefCell<State>>);

fn document() -> Option<Document> {
    web_sys::window()?.document()
}

fn element(document: &Document, id: &str) -> Result<Element, String> {
    document
        .get_element_by_id(id)
        .ok_or_else(|| format!("the page has no #{id} element (web/index.html)"))
}

impl Editor {
    /// Takes over the editor panel with these texts, showing `shown`;
    /// `send` hands the user's edits to the page's event loop.
    pub fn attach(
        scene: &str,
        shader: &str,
        shown: Doc,
        examples: &[&str],
        send: impl Fn(EditorEvent) + 'static,
    ) -> Result<Editor, String> {
        let document = document().ok_or("no document")?;
        let doc_view = |doc: Doc, text: &str| -> Result<DocView, String> {
            let area: HtmlTextAreaElement = element(&document, &format!("{}-text", doc.id()))?
                .dyn_into()
                .map_err(|_| format!("#{}-text is not a textarea", doc.id()))?;
            set_text_at_top(&area, text);
            Ok(DocView {
                text: area,
                gutter: element(&document, &format!("{}-gutter", doc.id()))?,
                status: element(&document, &format!("{}-status", doc.id()))?,
                applied: text.to_string(),
                error_line: None,
                lines: 0,
                timer: None,
            })
        };
        let state = State {
            docs: [doc_view(Doc::Scene, scene)?, doc_view(Doc::Shader, shader)?],
            shown,
            send: Rc::new(send),
            listeners: Vec::new(),
            debounced: [None, None],
        };
        let editor = Editor(Rc::new(RefCell::new(state)));
        for doc in Doc::ALL {
            editor.number_lines(doc);
            editor.listen_to_document(doc)?;
        }
        editor.listen_to_controls(&document, examples)?;
        editor.show_doc(shown);
        Ok(editor)
    }

    /// The text that produced what the canvas shows of `doc`.
    pub fn applied(&self, doc: Doc) -> String {
        self.0.borrow().docs[doc.index()].applied.clone()
    }

    /// Shows whether the text compiled: a success clears the error and
    /// records the text as applied; a problem is shown under the text and
    /// its line marked in the gutter, while the canvas keeps the last good
    /// picture.
    pub fn show_result(&self, doc: Doc, text: &str, result: Result<String, Problem>) {
        let mut state = self.0.borrow_mut();
        let view = &mut state.docs[doc.index()];
        match result {
            Ok(summary) => {
                view.applied = text.to_string();
                view.error_line = None;
                view.status.set_text_content(Some(&summary));
                let _ = view.status.set_attribute("class", "status");
            }
            Err(problem) => {
                view.error_line = problem.line;
                view.status.set_text_content(Some(&problem.message));
                let _ = view.status.set_attribute("class", "status error");
            }
        }
        view.lines = 0;
        drop(state);
        self.number_lines(doc);
    }

    /// Whether the user holds text of their own in `doc`: typed and not yet
    /// compiled, or not compiling.
    pub fn holds_own_text(&self, doc: Doc) -> bool {
        let state = self.0.borrow();
        let view = &state.docs[doc.index()];
        view.timer.is_some() || view.error_line.is_some() || view.text.value() != view.applied
    }

    /// Replaces a document's text with one made elsewhere (the scene panel,
    /// the orbit, an example shader) unless the user holds text of their
    /// own there: typed and not yet compiled, or not compiling. Returns
    /// whether the text was replaced (docs/web.md, "Editing in the page",
    /// its paragraph "Edits from the panel").
    pub fn offer_text(&self, doc: Doc, text: &str) -> bool {
        if self.holds_own_text(doc) {
            return false;
        }
        let mut state = self.0.borrow_mut();
        let view = &mut state.docs[doc.index()];
        set_text_in_place(&view.text, text);
        view.applied = text.to_string();
        view.lines = 0;
        drop(state);
        self.number_lines(doc);
        true
    }

    /// Puts a text in a document as if the user had chosen it (an example
    /// shader): it replaces the text and is compiled at once.
    pub fn load_text(&self, doc: Doc, text: &str) {
        {
            let state = self.0.borrow();
            set_text_at_top(&state.docs[doc.index()].text, text);
        }
        self.number_lines(doc);
        self.send_now(doc);
    }

    /// Shows `doc`'s textarea (and its tab as chosen).
    pub fn show_doc(&self, doc: Doc) {
        let mut state = self.0.borrow_mut();
        state.shown = doc;
        for other in Doc::ALL {
            if let Some(pane) = document().and_then(|d| d.get_element_by_id(other.id())) {
                let class = if other == doc { "doc shown" } else { "doc" };
                let _ = pane.set_attribute("class", class);
            }
            if let Some(tab) =
                document().and_then(|d| d.get_element_by_id(&format!("{}-tab", other.id())))
            {
                let class = if other == doc { "tab shown" } else { "tab" };
                let _ = tab.set_attribute("class", class);
            }
        }
    }

    /// Numbers the gutter's lines (and marks the error's), when the number
    /// of lines changed.
    fn number_lines(&self, doc: Doc) {
        let mut state = self.0.borrow_mut();
        let view = &mut state.docs[doc.index()];
        let lines = view.text.value().split('\n').count();
        if lines == view.lines {
            return;
        }
        view.lines = lines;
        let document = view.gutter.owner_document();
        view.gutter.set_text_content(None);
        let Some(document) = document else { return };
        for n in 1..=lines.max(view.error_line.unwrap_or(0)) {
            if let Ok(line) = document.create_element("div") {
                line.set_text_content(Some(&n.to_string()));
                if Some(n) == view.error_line {
                    let _ = line.set_attribute("class", "error");
                }
                let _ = view.gutter.append_child(&line);
            }
        }
        view.gutter.set_scroll_top(view.text.scroll_top());
    }

    /// Sends the document's text now, cancelling a pending send.
    fn send_now(&self, doc: Doc) {
        let text = {
            let mut state = self.0.borrow_mut();
            let view = &mut state.docs[doc.index()];
            if let Some(timer) = view.timer.take()
                && let Some(window) = web_sys::window()
            {
                window.clear_timeout_with_handle(timer);
            }
            view.text.value()
        };
        self.emit(EditorEvent::Changed(doc, text));
    }

    /// Hands an event to the page, which may answer through `self` at once.
    fn emit(&self, event: EditorEvent) {
        let send = self.0.borrow().send.clone();
        send(event);
    }

    /// Restarts the debounce timer of `doc`.
    fn debounce(&self, doc: Doc) {
        let Some(window) = web_sys::window() else {
            return;
        };
        let mut state = self.0.borrow_mut();
        let state = &mut *state;
        if let Some(timer) = state.docs[doc.index()].timer.take() {
            window.clear_timeout_with_handle(timer);
        }
        let callback = state.debounced[doc.index()].get_or_insert_with(|| {
            let editor = Rc::downgrade(&self.0);
            Closure::new(move || {
                if let Some(editor) = editor.upgrade() {
                    let editor = Editor(editor);
                    editor.0.borrow_mut().docs[doc.index()].timer = None;
                    editor.send_now(doc);
                }
            })
        });
        state.docs[doc.index()].timer = window
            .set_timeout_with_callback_and_timeout_and_arguments_0(
                callback.as_ref().unchecked_ref(),
                DEBOUNCE_MS,
            )
            .ok();
    }

    /// Adds a listener that holds the editor weakly (it is kept in the
    /// editor itself).
    fn listen(
        &self,
        target: &web_sys::EventTarget,
        event: &str,
        mut handler: impl FnMut(&Editor, web_sys::Event) + 'static,
    ) -> Result<(), String> {
        let editor = Rc::downgrade(&self.0);
        let closure = Closure::<dyn FnMut(web_sys::Event)>::new(move |e| {
            if let Some(editor) = editor.upgrade() {
                handler(&Editor(editor), e);
            }
        });
        target
            .add_event_listener_with_callback(event, closure.as_ref().unchecked_ref())
            .map_err(|e| format!("cannot listen to {event}: {e:?}"))?;
        self.0.borrow_mut().listeners.push(closure);
        Ok(())
    }

    fn listen_to_document(&self, doc: Doc) -> Result<(), String> {
        let (text, gutter) = {
            let state = self.0.borrow();
            let view = &state.docs[doc.index()];
            (view.text.clone(), view.gutter.clone())
        };
        self.listen(&text, "input", move |editor, _| {
            editor.number_lines(doc);
            editor.debounce(doc);
        })?;
        let scrolled = text.clone();
        self.listen(&text, "scroll", move |_, _| {
            gutter.set_scroll_top(scrolled.scroll_top());
        })?;
        // Tab indents (four spaces) instead of leaving the editor; through
        // the browser's insertText command, so undo takes it back.
        self.listen(&text, "keydown", move |_, e| {
            if let Some(key) = e.dyn_ref::<web_sys::KeyboardEvent>()
                && key.key() == "Tab"
                && !key.shift_key()
                && let Some(html) =
                    document().and_then(|d| d.dyn_into::<web_sys::HtmlDocument>().ok())
                && html
                    .exec_command_with_show_ui_and_value("insertText", false, "    ")
                    .unwrap_or(false)
            {
                e.prevent_default();
            }
        })
    }

    /// The tabs, the example menu and the button that hides the panel.
    fn listen_to_controls(&self, document: &Document, examples: &[&str]) -> Result<(), String> {
        for doc in Doc::ALL {
            let tab = element(document, &format!("{}-tab", doc.id()))?;
            self.listen(&tab, "click", move |editor, _| {
                editor.show_doc(doc);
                editor.emit(EditorEvent::Show(doc));
            })?;
        }
        let menu: HtmlSelectElement = element(document, "shader-examples")?
            .dyn_into()
            .map_err(|_| "#shader-examples is not a select element".to_string())?;
        for name in examples {
            let option = web_sys::HtmlOptionElement::new_with_text_and_value(name, name)
                .map_err(|e| format!("{e:?}"))?;
            menu.add_with_html_option_element(&option)
                .map_err(|e| format!("{e:?}"))?;
        }
        let chosen = menu.clone();
        self.listen(&menu, "change", move |editor, _| {
            let name = chosen.value();
            chosen.set_selected_index(0);
            if !name.is_empty() {
                editor.emit(EditorEvent::Example(name));
            }
        })?;
        let toggle = element(document, "editor-toggle")?;
        self.listen(&toggle, "click", |_, _| toggle_panel())?;
        // Ctrl+E opens and closes the panel from anywhere on the page.
        let window = web_sys::window().ok_or("no window")?;
        self.listen(&window, "keydown", |_, e| {
            if let Some(key) = e.dyn_ref::<web_sys::KeyboardEvent>()
                && key.ctrl_key()
                && key.key().eq_ignore_ascii_case("e")
            {
                e.prevent_default();
                toggle_panel();
            }
        })
    }
}

/// Replaces a textarea's text, the caret and the view at its start: a new
/// text is read from its top (the browser would put the caret at its end,
/// and focusing the textarea would scroll there).
fn set_text_at_top(area: &HtmlTextAreaElement, text: &str) {
    area.set_value(text);
    let _ = area.set_selection_range(0, 0);
    area.set_scroll_top(0);
}

/// Replaces a textarea's text (rewritten from the scene) where the user was
/// reading it: the caret and the scroll position stay.
fn set_text_in_place(area: &HtmlTextAreaElement, text: &str) {
    let top = area.scroll_top();
    let caret = area.selection_start().ok().flatten().unwrap_or(0);
    area.set_value(text);
    let caret = caret.min(text.encode_utf16().count() as u32);
    let _ = area.set_selection_range(caret, caret);
    area.set_scroll_top(top);
}

/// Opens or closes the editor panel: the page's `editing` class lays the
/// canvas out beside it (web/index.html).
pub fn toggle_panel() {
    if let Some(body) = document().and_then(|d| d.body()) {
        let _ = body.class_list().toggle("editing");
        if body.class_list().contains("editing") {
            focus_shown_text();
        }
    }
}

/// Opens the editor panel (`?editor` in the address).
pub fn open_panel() {
    if let Some(body) = document().and_then(|d| d.body()) {
        let _ = body.class_list().add_1("editing");
    }
}

fn focus_shown_text() {
    let Some(document) = document() else { return };
    for doc in Doc::ALL {
        let shown = document
            .get_element_by_id(doc.id())
            .is_some_and(|pane| pane.class_list().contains("shown"));
        if shown
            && let Some(area) = document
                .get_element_by_id(&format!("{}-text", doc.id()))
                .and_then(|e| e.dyn_into::<HtmlElement>().ok())
        {
            let _ = area.focus();
        }
    }
}
