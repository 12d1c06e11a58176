//! The page's two documents and what the canvas shows (docs/web.md,
//! "Editing in the page"): the scene's TOML, drawn by the ray tracer, and a
//! sandbox shader, drawn by the sandbox. Edits arrive from the [`Editor`]
//! debounced; a scene text that parses and validates replaces the page's
//! scene, a shader text that compiles replaces the running shader once its
//! pipeline is built. A text that fails leaves the picture as it was and
//! shows the error at the user's line.

use std::rc::Rc;

use web_time::Instant;
use wgpu::TextureFormat;
use winit::event::WindowEvent;

use super::editor::{Doc, Editor, EditorEvent, Problem};
use super::sandbox_page::{Built, ShaderView};
use super::{link, page};
use crate::gpu::Gpu;
use crate::sandbox::bundled as shaders;
use crate::scene::{Scene, SceneFiles};

/// The example shader in the shader document when no link brings one.
const FIRST_SHADER: &str = "blobs.glsl";

/// What the workbench hands to the page's event loop, and gets back.
pub enum WorkEvent {
    Editor(EditorEvent),
    Built(Box<Built>),
}

/// What the page must do after an event.
pub enum Outcome {
    Nothing,
    /// Replace the page's scene with this one (parsed from the editor).
    Scene(Box<Scene>),
    /// The canvas shows another document: draw again.
    Redraw,
}

pub struct Workbench {
    editor: Option<Editor>,
    send: Rc<dyn Fn(WorkEvent)>,
    shown: Doc,
    shader: Option<ShaderView>,
    /// The shader text to compile once the GPU is there.
    pending_shader: Option<String>,
    /// The scene the scene document's text stands for.
    scene: Scene,
}

impl Workbench {
    /// The page's documents: the scene text (already parsed into `scene`),
    /// and the shader of the address's `#shader=` link (then the canvas
    /// shows it) or an example. `send` posts to the page's event loop.
    pub fn new(scene_text: &str, scene: &Scene, send: impl Fn(WorkEvent) + 'static) -> Self {
        let send: Rc<dyn Fn(WorkEvent)> = Rc::new(send);
        let (shader_text, shown) = match initial_shader() {
            Some(text) => (text, Doc::Shader),
            None => (
                shaders::text(FIRST_SHADER).unwrap_or_default().to_string(),
                Doc::Scene,
            ),
        };
        let examples: Vec<&str> = shaders::SHADERS.iter().map(|(name, _)| *name).collect();
        let to_page = send.clone();
        let editor = Editor::attach(scene_text, &shader_text, shown, &examples, move |e| {
            to_page(WorkEvent::Editor(e))
        });
        let editor = match editor {
            Ok(editor) => Some(editor),
            Err(e) => {
                page::show_error(&format!("the editor cannot start: {e}"));
                None
            }
        };
        if page::query("editor").is_some() {
            super::editor::open_panel();
        }
        if page::bare() {
            page::hide_controls();
        }
        page::set_body_class("showing-shader", shown == Doc::Shader);
        Workbench {
            editor,
            send,
            shown,
            shader: None,
            pending_shader: Some(shader_text),
            scene: scene.clone(),
        }
    }

    /// Whether the canvas shows the shader (the sandbox) rather than the
    /// scene (the ray tracer).
    pub fn shows_shader(&self) -> bool {
        self.shown == Doc::Shader
    }

    /// The GPU is there: the sandbox's passes are made for the canvas's
    /// surface, and the shader compiled if it is shown.
    pub fn gpu_ready(&mut self, gpu: &Gpu, format: TextureFormat, size: (u32, u32)) {
        self.shader = Some(ShaderView::new(gpu, format, size));
        if self.shows_shader() {
            self.compile_pending_shader();
        }
    }

    /// The GPU device was lost: the sandbox's passes go with it, and the
    /// shader is compiled again on the next device (see
    /// [`Workbench::gpu_ready`]): the last good text, unless newer text
    /// waits.
    pub fn gpu_lost(&mut self) {
        if self.shader.take().is_some() && self.pending_shader.is_none() {
            self.pending_shader = self.editor.as_ref().map(|e| e.applied(Doc::Shader));
        }
    }

    /// Follows the canvas's size.
    pub fn resize(&mut self, gpu: &Gpu, size: (u32, u32)) {
        if let Some(shader) = &mut self.shader {
            shader.resize(gpu, size);
        }
    }

    /// Handles an event of the editor or of a pipeline build.
    /// The files a scene's shapes read come from `files` (the page fetched
    /// them).
    pub fn handle(&mut self, event: WorkEvent, files: &dyn SceneFiles) -> Outcome {
        match event {
            WorkEvent::Editor(EditorEvent::Changed(Doc::Scene, text)) => {
                self.scene_text(&text, files)
            }
            WorkEvent::Editor(EditorEvent::Changed(Doc::Shader, text)) => {
                self.pending_shader = Some(text);
                if self.shader.is_some() {
                    self.compile_pending_shader();
                }
                Outcome::Nothing
            }
            WorkEvent::Editor(EditorEvent::Show(doc)) => self.show(doc),
            WorkEvent::Editor(EditorEvent::Example(name)) => self.open_example(&name),
            WorkEvent::Built(built) => {
                let Some(shader) = &mut self.shader else {
                    return Outcome::Nothing;
                };
                let (text, times) = (built.text().to_string(), built.times());
                if let Some(result) = shader.built(*built) {
                    match &result {
                        Ok(_) => page::event(&format!("shader ok {times}")),
                        Err(problem) => report("shader", problem),
                    }
                    let good = result.is_ok();
                    if let Some(editor) = &self.editor {
                        editor.show_result(Doc::Shader, &text, result);
                    }
                    // After show_result, which records the text as applied:
                    // the address holds the shader now drawn.
                    if good && self.shows_shader() {
                        self.write_link();
                    }
                }
                Outcome::Redraw
            }
        }
    }

    /// Opens a text chosen by the user (an example shader, a dropped file)
    /// in `doc` as if typed there: the document shown, on the canvas too,
    /// and the text compiled at once.
    pub fn open(&mut self, doc: Doc, text: &str) -> Outcome {
        let Some(editor) = self.editor.clone() else {
            return Outcome::Nothing;
        };
        editor.show_doc(doc);
        let outcome = self.show(doc);
        editor.load_text(doc, text);
        outcome
    }

    /// Makes the canvas show `doc`.
    fn show(&mut self, doc: Doc) -> Outcome {
        self.shown = doc;
        page::set_body_class("showing-shader", doc == Doc::Shader);
        page::event(&format!("showing {}", doc_name(doc)));
        if doc == Doc::Shader && self.shader.is_some() {
            self.compile_pending_shader();
        }
        self.write_link();
        Outcome::Redraw
    }

    /// A scene text from the editor: parsed and validated; a good one
    /// replaces the page's scene.
    fn scene_text(&mut self, text: &str, files: &dyn SceneFiles) -> Outcome {
        let start = Instant::now();
        let result = Scene::from_toml_with_files(text, None, files).map_err(|e| Problem {
            message: e.to_string(),
            line: e.line,
        });
        let parse_ms = start.elapsed().as_secs_f64() * 1e3;
        let (summary, outcome) = match result {
            Ok(scene) => {
                page::event(&format!("scene ok parse={parse_ms:.0}ms"));
                self.scene = scene.clone();
                (
                    Ok("scene: valid".to_string()),
                    Outcome::Scene(Box::new(scene)),
                )
            }
            Err(problem) => {
                report("scene", &problem);
                (Err(problem), Outcome::Nothing)
            }
        };
        if let Some(editor) = &self.editor {
            editor.show_result(Doc::Scene, text, summary);
        }
        if matches!(outcome, Outcome::Scene(_)) && !self.shows_shader() {
            self.write_link();
        }
        outcome
    }

    /// Opens the bundled example shader `name` in the shader document (the
    /// editor's Examples menu and the panel's Shaders menu).
    pub fn open_example(&mut self, name: &str) -> Outcome {
        let Some(text) = shaders::text(name) else {
            return Outcome::Nothing;
        };
        page::event(&format!("example {name}"));
        self.open(Doc::Shader, text)
    }

    /// A scene opened other than by the editors (a link whose mesh files
    /// had to be fetched first): the scene document takes its text, unless
    /// the user holds text of their own there.
    pub fn scene_opened(&mut self, text: &str, scene: &Scene) {
        if self
            .editor
            .as_ref()
            .is_some_and(|editor| editor.offer_text(Doc::Scene, text))
        {
            self.scene = scene.clone();
        }
    }

    /// The page's scene changed elsewhere (the panel, the orbit, the menu):
    /// the scene document follows unless the user holds text of their own
    /// there (docs/web.md, "Editing in the page", its paragraph "Edits from
    /// the panel").
    pub fn follow_scene(&mut self, scene: &Scene) {
        if *scene == self.scene {
            return;
        }
        let Some(editor) = &self.editor else { return };
        // Checked before the scene is written out: while the user's text
        // stays, this runs every frame (redraw) and would serialise the
        // scene each time for nothing.
        if editor.holds_own_text(Doc::Scene) {
            return;
        }
        if editor.offer_text(Doc::Scene, &scene.to_toml_string()) {
            self.scene = scene.clone();
        }
    }

    fn compile_pending_shader(&mut self) {
        let (Some(shader), Some(text)) = (&mut self.shader, self.pending_shader.take()) else {
            return;
        };
        let send = self.send.clone();
        if let Err(problem) =
            shader.compile(&text, move |built| send(WorkEvent::Built(Box::new(built))))
        {
            report("shader", &problem);
            if let Some(editor) = &self.editor {
                editor.show_result(Doc::Shader, &text, Err(problem));
            }
        }
    }

    /// Draws the shader's next frame onto `target` (the shader is shown).
    pub fn draw(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        format: TextureFormat,
    ) {
        if let Some(shader) = &mut self.shader {
            shader.draw(gpu, encoder, target, format);
        }
    }

    /// The pointer and the keys over the canvas, for the shader's mouse
    /// uniforms and keyboard texture.
    pub fn input(&mut self, event: &WindowEvent) {
        if let (true, Some(shader)) = (self.shows_shader(), &mut self.shader) {
            shader.input(event);
        }
    }

    /// The "Restart" button: the shader shown starts again from time 0
    /// (docs/web.md, "Multipass shaders").
    pub fn restart_shader(&mut self, gpu: &Gpu) {
        if let (true, Some(shader)) = (self.shows_shader(), &mut self.shader) {
            shader.restart(gpu);
        }
    }

    /// An image dropped on the canvas: a texture channel of the multipass
    /// shader shown reads it (docs/web.md, "Multipass shaders"); the line
    /// under the shader's editor says which, unless the user's own text
    /// (an error, an edit not yet compiled) is there.
    pub fn image_dropped(&mut self, name: &str, image: image::RgbaImage) -> Outcome {
        let Some(shader) = &mut self.shader else {
            return Outcome::Nothing;
        };
        let Some(status) = shader.add_image(name, image) else {
            page::event(&format!("image-kept {name}"));
            page::show_notice(&format!(
                "{name}: kept for the texture channels of a multipass Shadertoy shader \
                 (a .json); the shader shown has none"
            ));
            return Outcome::Nothing;
        };
        if let Some(editor) = self
            .editor
            .as_ref()
            .filter(|e| !e.holds_own_text(Doc::Shader))
        {
            editor.show_result(Doc::Shader, &editor.applied(Doc::Shader), Ok(status));
        }
        Outcome::Redraw
    }

    /// Keeps the shown document in the address, so that a copied link
    /// reproduces it (docs/web.md, "Sharing a scene or a shader").
    fn write_link(&self) {
        let Some(editor) = &self.editor else { return };
        let hash = match self.shown {
            Doc::Shader => match self.shader_fragment() {
                Some(hash) => hash,
                None => return,
            },
            Doc::Scene => link::scene_hash(&editor.applied(Doc::Scene)),
        };
        page::replace_hash(&hash);
    }

    /// The fragment of a link to the shader drawn, while the canvas shows
    /// one; `None` while it shows the scene (or no shader compiled yet).
    pub fn shader_fragment(&self) -> Option<String> {
        let drawn = self.shader.as_ref().is_some_and(ShaderView::has_shader);
        let editor = self
            .editor
            .as_ref()
            .filter(|_| self.shows_shader() && drawn)?;
        Some(link::shader_hash(&editor.applied(Doc::Shader)))
    }

    /// Makes the canvas show the scene (a scene link opened over the shader).
    pub fn show_scene(&mut self) {
        if !self.shows_shader() {
            return;
        }
        if let Some(editor) = &self.editor {
            editor.show_doc(Doc::Scene);
        }
        self.show(Doc::Scene);
    }
}

/// The shader text of the address's `#shader=` link; a broken link is
/// reported over the canvas.
fn initial_shader() -> Option<String> {
    match page::hash().as_deref().and_then(link::shader_in_hash)? {
        Ok(text) => {
            page::event("shader from-link");
            Some(text)
        }
        Err(e) => {
            page::show_error(&format!("the link's shader cannot be shown: {e}"));
            None
        }
    }
}

fn doc_name(doc: Doc) -> &'static str {
    match doc {
        Doc::Scene => "scene",
        Doc::Shader => "shader",
    }
}

/// Logs an error of the user's text with its line, for people reading the
/// console and for tests.
fn report(what: &str, problem: &Problem) {
    let line = problem.line.map_or("?".to_string(), |l| l.to_string());
    page::event(&format!("{what}-error line={line}"));
}
