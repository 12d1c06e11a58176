//! The page's canvas and event loop: the viewer's core (`app::viewer`, the
//! same panel, orbit camera, selection and progressive refinement as the
//! window program) on the scene from the address (or the bundled Whitted
//! scene). What happens is told on the browser's console as
//! `raysandbox: EVENT` lines, for people and for tests.
//!
//! In the browser nothing may block: the adapter, the device and the
//! pipelines' validation arrive asynchronously, and the page hands them to
//! the event loop as [`PageEvent`]s once they are there. The editors and
//! the sandbox are the [`Workbench`]'s.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use wasm_bindgen::prelude::*;
use web_time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop, EventLoopProxy};
use winit::platform::web::{EventLoopExtWebSys, WindowAttributesExtWebSys};
use winit::window::{Window, WindowId};

use super::drop::{Dropped, DroppedFile};
use super::editor::{Doc, EditorEvent};
use super::shape_files::{self, PageFiles};
use super::workbench::{Outcome, WorkEvent, Workbench};
use super::{drop, link, page, panel_width, split};
use crate::app::document::Document;
use crate::app::help::{self, Help};
use crate::app::panel;
use crate::app::pipelines::Built;
use crate::app::shell;
use crate::app::ui::{Command, Host, MenuItem};
use crate::app::viewer::{Platform, Viewer};
use crate::gpu::{Gpu, GpuError, Pipelines, Refine, ShaderSource, Viewport};
use crate::scene::{Scene, bundled};
use crate::shader_params::SourceParams;

/// Samples per pixel the page accumulates before it stops drawing, as the
/// native viewer's progressive refinement does; `?samples=N` in the address
/// sets another limit.
const MAX_SAMPLES: u32 = 64;

/// The page's help (F1): no files, no quitting; the editors, links and
/// dropped files instead.
const PAGE_HELP: Help = Help {
    keys: &[
        help::MOUSE,
        &[
            ("H", "show or hide the panel and status line"),
            ("R", "reset the camera to the scene's"),
            (
                "Ctrl+E or Edit",
                "the scene's text and a shader, in the editor beside the picture",
            ),
            (
                "Copy link",
                "a link to what is shown (the scene, camera included, or the shader)",
            ),
            (
                "Ctrl+plus / minus / 0",
                "UI scale of the panel, editor and status line",
            ),
            ("F1", "this help"),
        ],
    ],
    notes: &[
        "Scenes and Shaders (at the top of the panel) open the bundled examples.",
        "The address always holds a link to what is shown; paste a link into the \
         address bar to open it.",
        "Drop a scene (.toml), a model (.obj, .ply) or a shader (.wgsl, .glsl, .frag) \
         on the picture to open it.",
    ],
};

/// How long the scene must stay unchanged before the address follows it
/// (an orbit changes it every frame).
const ADDRESS_DELAY: Duration = Duration::from_millis(500);

/// Where the browser keeps the UI scale (local storage) between visits.
const UI_SCALE_KEY: &str = "raysandbox.ui-scale";

/// What arrives asynchronously, handed to the event loop.
pub enum PageEvent {
    /// The adapter, the device and the first pipelines, or why not.
    Ready(Result<Box<Graphics>, String>),
    /// Pipelines built off the input path (a new feature set, new shader
    /// parameters).
    PipelinesBuilt(Box<Built>),
    /// "Copy link" finished.
    LinkCopied(Result<(), String>),
    /// The page's own "Copy link" button (over the shader) was clicked.
    CopyLink,
    /// The page's "Restart" button (over the shader) was clicked.
    Restart,
    /// The address's fragment changed (a link pasted into the open tab,
    /// the browser's back button): the page shows what it holds.
    AddressChanged,
    /// Ctrl+plus, minus or 0.
    Scale(page::ScaleKey),
    /// An edit in the text editors, or a sandbox pipeline built.
    Work(WorkEvent),
    /// A file dropped on the canvas, read.
    Dropped(Result<DroppedFile, String>),
    /// A file that a bundled scene's shapes read (a mesh scene's model,
    /// `file` as the scene writes it), fetched over http, or why not.
    FileFetched(PathBuf, Result<Vec<u8>, String>),
    /// The GPU has done a job of refinement: the next one goes at once
    /// (`Viewer::refine_between_frames`).
    JobDone,
}

/// A scene the page opens once the mesh files it names are fetched
/// (docs/web.md, "Scenes with mesh files"), and where it comes from.
enum Opening {
    /// Chosen in the panel's Scenes menu.
    Bundled(&'static str),
    /// The address's `#scene=` link.
    Link(String),
    /// Typed in the scene editor.
    Typed(String),
    /// A scene file dropped on the canvas: its name and text.
    Dropped(String, String),
}

impl Opening {
    fn text(&self) -> &str {
        match self {
            Opening::Bundled(name) => bundled::text(name).unwrap_or_default(),
            Opening::Link(text) | Opening::Typed(text) | Opening::Dropped(_, text) => text,
        }
    }
}

/// An [`Opening`] waiting for `files`.
struct Waiting {
    files: Vec<PathBuf>,
    opening: Opening,
}

/// The GPU objects made asynchronously for the canvas.
pub struct Graphics {
    gpu: Gpu,
    surface: wgpu::Surface<'static>,
    pipelines: Pipelines,
}

/// Starts the page: called by the JavaScript glue once the module is loaded.
#[wasm_bindgen(start)]
pub fn start() {
    std::panic::set_hook(Box::new(|info| page::show_error(&info.to_string())));
    page::timing("start");
    let models = PageFiles::default();
    let (text, doc, link_waits) = match initial_document(&models) {
        Ok(doc) => doc,
        Err(e) => {
            page::show_error(&e);
            return;
        }
    };
    let event_loop = match EventLoop::<PageEvent>::with_user_event().build() {
        Ok(event_loop) => event_loop,
        Err(e) => {
            page::show_error(&format!("cannot start the page's event loop: {e}"));
            return;
        }
    };
    event_loop.set_control_flow(ControlFlow::Wait);
    let proxy = event_loop.create_proxy();
    let shaders = ShaderSource::embedded();
    let params = match SourceParams::read(&shaders) {
        Ok(params) => params,
        Err(e) => {
            page::show_error(&e.to_string());
            return;
        }
    };
    let to_page = proxy.clone();
    let work = Workbench::new(&text, &doc.scene, move |e| {
        let _ = to_page.send_event(PageEvent::Work(e));
    });
    let targets: Vec<web_sys::EventTarget> = [page::canvas().map(Into::into), page::message_box()]
        .into_iter()
        .flatten()
        .map(Into::into)
        .collect();
    let to_page = proxy.clone();
    let listening = drop::listen(&targets, move |file| {
        let _ = to_page.send_event(PageEvent::Dropped(file));
    });
    if let Err(e) = listening {
        page::show_error(&e);
    }
    if let Err(e) = split::attach() {
        page::show_error(&e);
    }
    let to_page = proxy.clone();
    page::listen(None, "hashchange", move || {
        let _ = to_page.send_event(PageEvent::AddressChanged);
    });
    let to_page = proxy.clone();
    page::listen(Some("copy-link"), "click", move || {
        let _ = to_page.send_event(PageEvent::CopyLink);
    });
    let to_page = proxy.clone();
    page::listen(Some("restart"), "click", move || {
        let _ = to_page.send_event(PageEvent::Restart);
    });
    let to_page = proxy.clone();
    page::listen_scale_keys(move |key| {
        let _ = to_page.send_event(PageEvent::Scale(key));
    });
    let mut viewer = Viewer::new(doc, shaders, params, platform(proxy.clone()));
    viewer.editor.view.max_samples = page::query("samples")
        .and_then(|n| n.parse::<u32>().ok())
        .map_or(MAX_SAMPLES, |n| n.max(1));
    // `?ui=0`: the picture alone, as the H key leaves it.
    viewer.editor.show_panel = !page::bare();
    if let Some(width) = panel_width::stored() {
        viewer.editor.panel_width = width;
    }
    let panel_width = viewer.editor.panel_width;
    let mut page = Page {
        proxy,
        viewer,
        work,
        input_seen: false,
        window: None,
        menu: [MenuItem::bundled_scenes(), MenuItem::example_shaders()].concat(),
        address_due: None,
        shape_files: models,
        waiting: None,
        graphics_started: false,
        recovering: None,
        ui_scale: stored_ui_scale(),
        panel_width,
        editor_open: false,
        panel_before_editor: None,
    };
    page::set_ui_scale(page.ui_scale);
    if let Some(text) = link_waits {
        page.open(Opening::Link(text));
    }
    event_loop.spawn_app(page);
}

/// How the viewer's core reaches the page: events on the console, pipeline
/// builds as futures whose results come back through the event loop.
fn platform(proxy: EventLoopProxy<PageEvent>) -> Platform {
    Platform {
        event: Box::new(|line| {
            page::event(line);
            if line.starts_with("first-frame") {
                page::timing("first-frame");
            }
        }),
        // Asked for at once, samples pile up in the browser's GPU process
        // faster than SwiftShader draws them, and the page gets no input
        // until the refinement ends (docs/web.md, "Start-up time"); asked
        // for at the next animation frame, after a display pass and the
        // panel, the GPU waits for the page between jobs (docs/web.md,
        // "Where a sample's time goes"). The next job goes when the GPU
        // has done the last.
        job_done: Some({
            let proxy = proxy.clone();
            Arc::new(move || {
                let _ = proxy.send_event(PageEvent::JobDone);
            })
        }),
        build: Box::new(move |request| {
            let proxy = proxy.clone();
            wasm_bindgen_futures::spawn_local(async move {
                let built = request.build().await;
                let _ = proxy.send_event(PageEvent::PipelinesBuilt(Box::new(built)));
            });
        }),
    }
}

/// The document the page opens with, and its text: the scene in the
/// address's `#scene=` link, else the bundled Whitted scene. A broken link
/// is reported over the canvas and the Whitted scene shown. A link whose
/// scene names mesh files the page must fetch first comes back third: the
/// canvas stays empty until they are there, so that the first pipelines and
/// the first picture are that scene's own.
fn initial_document(files: &PageFiles) -> Result<(String, Document, Option<String>), String> {
    let mut waits = None;
    match page::hash().as_deref().and_then(link::scene_in_hash) {
        Some(Ok(text)) if !files.missing(&text).is_empty() => waits = Some(text),
        Some(Ok(text)) => match Scene::from_toml_with_files(&text, None, files.files()) {
            Ok(scene) => {
                page::event("scene from-link");
                return Ok((text, Document::untitled(scene), None));
            }
            Err(e) => link_error(&e),
        },
        Some(Err(e)) => page::show_error(&e),
        None => {}
    }
    let name = bundled::names()[0];
    let text = bundled::text(name).unwrap_or_default().to_string();
    if waits.is_none() {
        page::event(&format!("scene {name}"));
    }
    let doc = Document::bundled(name).map_err(|e| e.to_string())?;
    Ok((text, doc, waits))
}

struct Page {
    proxy: EventLoopProxy<PageEvent>,
    viewer: Viewer,
    /// The text editors and the sandbox shader.
    work: Workbench,
    /// Whether the page handled the user's input yet (for start-up timing).
    input_seen: bool,
    /// The canvas's window, from `resumed` on (the viewer gets it once the
    /// GPU is there).
    window: Option<Arc<Window>>,
    /// The panel's menu.
    menu: Vec<MenuItem>,
    /// When the address must take the scene as it is (see [`ADDRESS_DELAY`]).
    address_due: Option<Instant>,
    /// The bundled mesh scenes' models fetched so far.
    shape_files: PageFiles,
    /// The last scene opened, while its mesh files are fetched (the last
    /// picture stays meanwhile).
    waiting: Option<Waiting>,
    /// Whether the GPU objects are being made (or made).
    graphics_started: bool,
    /// The device was lost and a new one is being made.
    recovering: Option<Recovering>,
    /// The UI scale: egui's zoom factor, and the page's controls' size.
    ui_scale: f32,
    /// The scene panel's width the browser keeps ([`panel_width`]).
    panel_width: f32,
    /// Whether the editor was open at the last frame.
    editor_open: bool,
    /// Whether the panel was shown before the editor opened (it is hidden
    /// while the editor is open, so that the picture keeps a usable width).
    panel_before_editor: Option<bool>,
}

/// A lost device being replaced (docs/web.md, "A lost GPU device").
struct Recovering {
    /// Why it was lost, as the browser said.
    reason: String,
    /// The lost pipeline cache's generation: builds of it that finish
    /// later are dropped.
    generation: u64,
}

impl ApplicationHandler<PageEvent> for Page {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_some() {
            return;
        }
        let attributes = Window::default_attributes()
            .with_title("raysandbox")
            .with_canvas(page::canvas());
        let window = match event_loop.create_window(attributes) {
            Ok(window) => Arc::new(window),
            Err(e) => {
                page::show_error(&format!("cannot use the page's canvas: {e}"));
                return;
            }
        };
        self.window = Some(window);
        self.start_graphics();
    }

    fn user_event(&mut self, _: &ActiveEventLoop, event: PageEvent) {
        match event {
            PageEvent::Ready(Ok(gfx)) => {
                let Some(window) = self.window.clone() else {
                    return;
                };
                page::event(&format!("adapter {}", gfx.gpu.describe()));
                page::timing("gpu");
                let size = window.inner_size();
                // At rest the page draws nothing, so nothing would notice
                // a loss: the device's own callback wakes the loop.
                let waking = window.clone();
                gfx.gpu.wake_on_loss(move || waking.request_redraw());
                self.viewer
                    .attach(window, gfx.gpu, gfx.surface, gfx.pipelines);
                if let Some(gfx) = &self.viewer.gfx {
                    let format = gfx.viewport.surface_format();
                    self.work
                        .gpu_ready(&gfx.gpu, format, (size.width, size.height));
                }
                if let Some(gfx) = &self.viewer.gfx {
                    // The page's own keys scale it (see `Page::scale`).
                    gfx.egui.ctx.options_mut(|o| o.zoom_with_keyboard = false);
                    gfx.egui.ctx.set_zoom_factor(self.ui_scale);
                }
                self.recovered();
                self.open_when_fetched();
            }
            PageEvent::Ready(Err(e)) => match self.recovering.take() {
                Some(lost) => page::show_error(&format!(
                    "the GPU was lost ({}) and no new one could be made: {e}. \
                     Reload the page (F5) to start again; the address holds the scene or shader.",
                    lost.reason
                )),
                None => page::show_error(&e),
            },
            PageEvent::PipelinesBuilt(built) => self.viewer.pipelines_built(*built),
            PageEvent::LinkCopied(result) => {
                let message = match result {
                    Ok(()) => "link copied".to_string(),
                    Err(e) => format!("the link was not copied: {e}"),
                };
                page::event(&message);
                self.viewer.editor.message = Some(message);
            }
            PageEvent::CopyLink => self.copy_link(),
            PageEvent::Restart => {
                if let Some(gfx) = &self.viewer.gfx {
                    self.work.restart_shader(&gfx.gpu);
                }
            }
            PageEvent::AddressChanged => self.address_changed(),
            PageEvent::Scale(key) => self.scale(key),
            PageEvent::Work(WorkEvent::Editor(EditorEvent::Changed(Doc::Scene, text))) => {
                self.open(Opening::Typed(text));
            }
            PageEvent::Work(event) => {
                let outcome = self.work.handle(event, self.shape_files.files());
                self.follow(outcome);
            }
            PageEvent::Dropped(file) => self.dropped(file),
            PageEvent::FileFetched(file, bytes) => self.file_fetched(&file, bytes),
            // No frame: the viewer asks for one when the picture is due.
            PageEvent::JobDone => {
                if !self.work.shows_shader() {
                    self.viewer.refine_between_frames();
                }
                return;
            }
        }
        self.viewer.request_redraw();
    }

    fn window_event(&mut self, _: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(gfx) = &mut self.viewer.gfx else {
            return;
        };
        if !self.input_seen && is_input(&event) {
            self.input_seen = true;
            page::timing("first-input");
        }
        if self.work.shows_shader() {
            // The sandbox has the canvas: the pointer is the shader's mouse,
            // the keys its keyboard texture.
            self.work.input(&event);
        } else if gfx.egui.state.on_window_event(&gfx.window, &event).repaint
            && !matches!(event, WindowEvent::RedrawRequested)
        {
            // egui asks for a frame at every frame too; asked for here, the
            // page drew one frame after another for as long as it was open
            // (docs/web.md, "Where a sample's time goes").
            gfx.window.request_redraw();
        }
        match event {
            WindowEvent::Resized(size) => {
                self.work.resize(&gfx.gpu, (size.width, size.height));
                self.viewer.resize(size);
            }
            WindowEvent::RedrawRequested => self.redraw(),
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if shell::wait_for_repaint(&mut self.viewer.repaint_at, event_loop) {
            self.viewer.request_redraw();
        }
    }
}

impl Page {
    /// Draws the scene with the panel over it; or, while the shader is
    /// shown, the shader's next frame, frame after frame.
    fn redraw(&mut self) {
        if let Some(reason) = self.viewer.gfx.as_ref().and_then(|gfx| gfx.gpu.lost()) {
            self.recover(reason);
            return;
        }
        if self.work.shows_shader() {
            self.draw_shader();
            return;
        }
        self.follow_editor();
        let host = Host {
            files: None,
            menu: &self.menu,
            copy_link: true,
            help: &PAGE_HELP,
        };
        let (start, mut ui) = self.viewer.begin_frame(&host);
        for command in std::mem::take(&mut ui.commands) {
            self.execute(command);
        }
        if self.viewer.end_frame(start, ui) {
            self.address_due = Some(Instant::now() + ADDRESS_DELAY);
        }
        self.work.follow_scene(&self.viewer.doc.scene);
        self.follow_address();
        self.follow_ui_scale();
        self.follow_panel_width();
    }

    /// The panel's edge was dragged: the browser keeps its width.
    fn follow_panel_width(&mut self) {
        let Some(gfx) = &self.viewer.gfx else { return };
        if self.viewer.editor.show_panel {
            let width = self.viewer.editor.panel_width;
            panel_width::follow(&mut self.panel_width, width, &gfx.egui.ctx);
        }
    }

    /// The editor opened or closed (Ctrl+E, Edit): the scene panel hides
    /// while it is open and comes back as it was when it closes, so that
    /// the picture between them stays usable on a small screen or a
    /// projector (H shows the panel all the same).
    fn follow_editor(&mut self) {
        let open = page::editing();
        if open == self.editor_open {
            return;
        }
        self.editor_open = open;
        let shown = &mut self.viewer.editor.show_panel;
        if open {
            self.panel_before_editor = Some(std::mem::replace(shown, false));
        } else if let Some(before) = self.panel_before_editor.take() {
            *shown = before;
        }
    }

    /// Ctrl+plus, minus or 0: egui's zoom, in the steps egui's own keys
    /// take, within [`help::SCALES`].
    fn scale(&mut self, key: page::ScaleKey) {
        let Some(gfx) = &self.viewer.gfx else { return };
        let zoom = match key {
            page::ScaleKey::Larger => self.ui_scale * 1.1,
            page::ScaleKey::Smaller => self.ui_scale / 1.1,
            page::ScaleKey::Reset => 1.0,
        };
        let zoom = zoom.clamp(*help::SCALES.start(), *help::SCALES.end());
        gfx.egui.ctx.set_zoom_factor((zoom * 100.0).round() / 100.0);
    }

    /// Egui's zoom changed (Ctrl+plus or minus, the help's slider): the
    /// page's own controls follow, and the browser keeps it for next time.
    fn follow_ui_scale(&mut self) {
        let Some(gfx) = &self.viewer.gfx else { return };
        let zoom = gfx.egui.ctx.zoom_factor();
        if zoom != self.ui_scale {
            self.ui_scale = zoom;
            page::set_ui_scale(zoom);
            page::store(UI_SCALE_KEY, &zoom.to_string());
            page::event(&format!("ui-scale {zoom}"));
        }
    }

    fn draw_shader(&mut self) {
        let Some(gfx) = &mut self.viewer.gfx else {
            return;
        };
        let format = gfx.viewport.surface_format();
        let work = &mut self.work;
        gfx.viewport.frame(&gfx.gpu, Refine::Show, |encoder, view| {
            work.draw(&gfx.gpu, encoder, view, format);
            Vec::new()
        });
        gfx.window.request_redraw();
    }

    /// Does what the workbench asks after an edit: a scene text that
    /// validated replaces the scene (new pipelines, if it needs them, built
    /// without blocking, the last picture kept meanwhile).
    fn follow(&mut self, outcome: Outcome) {
        match outcome {
            Outcome::Scene(scene) => {
                let before = std::mem::replace(&mut self.viewer.doc.scene, *scene);
                self.viewer.scene_changed(Some(&before));
                self.viewer.request_redraw();
            }
            Outcome::Redraw => self.viewer.request_redraw(),
            Outcome::Nothing => {}
        }
    }

    /// A file dropped on the canvas (docs/web.md, "Dropping files"): a scene
    /// or a shader opens in its editor as if typed there, so the canvas shows
    /// it; a model is added in front of the camera, as on the native window;
    /// an image goes to a multipass shader's texture channels.
    /// A file that cannot be used is reported with its name (and line), and
    /// the picture kept.
    fn dropped(&mut self, file: Result<DroppedFile, String>) {
        let dropped = file.and_then(|file| {
            page::event(&format!("dropped {}", file.name));
            Ok((Dropped::of(&file.name, file.bytes)?, file.name))
        });
        match dropped {
            Ok((Dropped::Scene(text), name)) => self.open(Opening::Dropped(name, text)),
            Ok((Dropped::Shape(shape), name)) => {
                // In front of the camera, as natively (not selected: the
                // picture stays the scene's alone).
                let before = self.viewer.doc.scene.clone();
                self.viewer.doc.scene.add_in_view(shape);
                self.viewer.scene_changed(Some(&before));
                self.viewer.request_redraw();
                self.address_due = Some(Instant::now());
                page::event(&format!("shape-added {name}"));
            }
            Ok((Dropped::Shader(text), _)) => {
                let outcome = self.work.open(Doc::Shader, &text);
                self.follow(outcome);
            }
            Ok((Dropped::Image(image), name)) => {
                let outcome = self.work.image_dropped(&name, *image);
                self.follow(outcome);
            }
            Err(e) => page::show_error(&e),
        }
    }

    fn execute(&mut self, command: Command) {
        match command {
            Command::Panel(panel::PanelAction::OpenBundled(name)) => {
                self.open(Opening::Bundled(name));
            }
            Command::Panel(panel::PanelAction::OpenExampleShader(name)) => {
                let outcome = self.work.open_example(name);
                self.follow(outcome);
            }
            Command::Panel(panel::PanelAction::ResetCamera) => self.viewer.reset_camera(),
            Command::ShaderParamsChanged => self.viewer.build_pipelines(),
            Command::CopyLink => self.copy_link(),
            Command::ToggleFullscreen => {
                if let Some(window) = &self.window {
                    shell::toggle_fullscreen(window);
                }
            }
            Command::LeaveFullscreen => {
                if let Some(window) = &self.window {
                    window.set_fullscreen(None);
                }
            }
            // Save, Open, screenshots, reloads and quitting: files and the
            // window belong to the native program.
            _ => {
                self.viewer.editor.message = Some(
                    "The page has no files: \"Copy link\" shares the scene, \
                     dropping a file on the page opens it (docs/web.md)"
                        .to_string(),
                );
            }
        }
    }

    /// Makes the adapter, the device and the first pipelines, for the scene
    /// shown, once the canvas's window is there. A link's scene that waits
    /// for its models goes first: the first pipelines are then its own, and
    /// the first picture its own too (not the Whitted scene, nor the link's
    /// scene drawn without its shape kinds while its pipelines are built).
    fn start_graphics(&mut self) {
        let link_waits = matches!(
            self.waiting,
            Some(Waiting {
                opening: Opening::Link(_),
                ..
            })
        );
        let Some(window) = self.window.clone() else {
            return;
        };
        if self.graphics_started || link_waits {
            return;
        }
        self.graphics_started = true;
        let proxy = self.proxy.clone();
        let (source, options) = self.viewer.first_build();
        wasm_bindgen_futures::spawn_local(async move {
            let gfx = create_graphics(window, &source, &options).await;
            let _ = proxy.send_event(PageEvent::Ready(gfx.map(Box::new)));
        });
    }

    /// The GPU device was lost (the browser's GPU process restarted, a
    /// driver reset, `GPUDevice.destroy()`): everything made from it is
    /// dropped and made again on a new device, for the same canvas. The
    /// scene, the editors' texts and the panel's state are not the GPU's
    /// and stay. The page says so over the canvas meanwhile, never showing a
    /// stale "ready" (docs/web.md, "A lost GPU device").
    fn recover(&mut self, reason: String) {
        let Some(lost) = self.viewer.gfx.take() else {
            return;
        };
        let generation = lost.pipelines.generation();
        drop(lost);
        self.work.gpu_lost();
        page::event(&format!("device-lost {reason}"));
        page::show_notice(&format!("The GPU was lost: {reason}. Recovering…"));
        self.recovering = Some(Recovering { reason, generation });
        self.graphics_started = false;
        self.start_graphics();
    }

    /// A new device replaced a lost one: builds for the lost one are
    /// dropped, and the page says what happened until the user closes the
    /// message (a picture that froze or flickered has its explanation).
    fn recovered(&mut self) {
        let Some(lost) = self.recovering.take() else {
            return;
        };
        self.viewer.follow_generation(lost.generation);
        let message = format!(
            "The GPU was lost ({}). A new one was made: the scene and the edits are kept.",
            lost.reason
        );
        page::show_notice(&message);
        self.viewer.editor.message = Some(message);
        page::event("device-recovered");
    }

    /// Opens a scene (docs/web.md, "Scenes with mesh files"): at once if
    /// the page has every mesh file it names, else once they are fetched,
    /// the status line saying "loading NAME" and the last picture (if any)
    /// staying meanwhile. A newer scene replaces one still waiting, and its
    /// "loading" with it.
    fn open(&mut self, opening: Opening) {
        if self.waiting.take().is_some() {
            self.viewer.editor.message = None;
        }
        let files = self.shape_files.missing(opening.text());
        if files.is_empty() {
            self.opened(opening);
            // It may have replaced a link's scene the GPU waited for.
            self.start_graphics();
            return;
        }
        let names: Vec<String> = files.iter().map(|f| file_name(f)).collect();
        let message = format!("loading {}", names.join(", "));
        page::event(&message);
        self.viewer.editor.message = Some(message);
        for file in self.shape_files.start_fetching(&files) {
            self.fetch(file);
        }
        self.waiting = Some(Waiting { files, opening });
    }

    /// Fetches a bundled mesh scene's model; the bytes come back through
    /// the event loop.
    fn fetch(&self, file: PathBuf) {
        let proxy = self.proxy.clone();
        let Some(address) = shape_files::address(&file) else {
            // Not reached (only served files are waited for), but a scene
            // must never wait for a file nobody fetches.
            let _ = proxy.send_event(PageEvent::FileFetched(file, Err("not served".into())));
            return;
        };
        wasm_bindgen_futures::spawn_local(async move {
            let bytes = page::fetch_bytes(&address).await;
            let _ = proxy.send_event(PageEvent::FileFetched(file, bytes));
        });
    }

    /// A model arrived (kept for every later scene that names it), or could
    /// not be fetched: the error names the file, and the scene that waited
    /// for it is not opened (the last good one stays). A failure no waiting
    /// scene cares about any more (a newer scene replaced it) is only
    /// logged, not shown over the scene now on screen.
    fn file_fetched(&mut self, file: &Path, bytes: Result<Vec<u8>, String>) {
        match bytes {
            Ok(bytes) => {
                page::event(&format!(
                    "fetched {} {} bytes",
                    file_name(file),
                    bytes.len()
                ));
                self.shape_files.fetched(file, Some(bytes));
                self.open_when_fetched();
                self.start_graphics();
            }
            Err(e) => {
                self.shape_files.fetched(file, None);
                let address = shape_files::address(file).unwrap_or_default();
                let message = format!("cannot load the file {address}: {e}");
                let waited = self
                    .waiting
                    .as_ref()
                    .is_some_and(|w| w.files.iter().any(|f| f == file));
                if !waited {
                    page::event(&message);
                    return;
                }
                self.waiting = None;
                self.viewer.editor.message = Some(message.clone());
                page::show_error(&message);
                self.start_graphics();
            }
        }
    }

    /// Opens the scene that waited, once its files are all there and the
    /// GPU is; a link's scene opens before the GPU (see
    /// [`Page::start_graphics`]).
    fn open_when_fetched(&mut self) {
        let ready = self.waiting.as_ref().is_some_and(|w| {
            let fetched = w.files.iter().all(|f| self.shape_files.files().has(f));
            let link = matches!(w.opening, Opening::Link(_));
            fetched && (self.viewer.gfx.is_some() || link)
        });
        if let Some(waiting) = self.waiting.take_if(|_| ready) {
            // "loading ..." is over ("opened ..." for a bundled scene).
            self.viewer.editor.message = None;
            self.opened(waiting.opening);
        }
    }

    /// Opens a scene whose mesh files the page has (or that names none it
    /// serves: the parse reports those at their line).
    fn opened(&mut self, opening: Opening) {
        let files = self.shape_files.files();
        match opening {
            Opening::Bundled(name) => match Document::bundled_with_files(name, files) {
                Ok(doc) => {
                    self.viewer.replace(doc);
                    page::event(&format!("scene {name}"));
                    self.address_due = Some(Instant::now());
                }
                Err(e) => {
                    self.viewer.editor.message = Some(e.to_string());
                    page::show_error(&e.to_string());
                }
            },
            Opening::Link(text) => match Scene::from_toml_with_files(&text, None, files) {
                Ok(scene) => {
                    self.work.scene_opened(&text, &scene);
                    self.viewer.replace(Document::untitled(scene));
                    page::event("scene from-link");
                }
                Err(e) => link_error(&e),
            },
            Opening::Typed(text) => {
                let typed = WorkEvent::Editor(EditorEvent::Changed(Doc::Scene, text));
                let outcome = self.work.handle(typed, files);
                self.follow(outcome);
            }
            Opening::Dropped(name, text) => {
                match Scene::from_toml_with_files(&text, Some(Path::new(&name)), files) {
                    Ok(_) => {
                        let outcome = self.work.open(Doc::Scene, &text);
                        self.follow(outcome);
                    }
                    Err(e) => page::show_error(&e.to_string()),
                }
            }
        }
    }

    /// The address's `#scene=` link to the scene as it is now.
    fn scene_fragment(&self) -> String {
        link::scene_hash(&self.viewer.doc.scene.to_toml_string())
    }

    /// Puts the scene in the address once it has stayed unchanged for
    /// [`ADDRESS_DELAY`], and wakes the loop then. (While the shader is
    /// shown, the address carries the shader: the workbench writes it.)
    fn follow_address(&mut self) {
        let Some(due) = self.address_due else { return };
        if self.work.shows_shader() {
            return;
        }
        if Instant::now() >= due {
            self.address_due = None;
            let fragment = self.scene_fragment();
            page::replace_hash(&fragment);
            // The tests read the scene shown from this line.
            page::event(&format!("address {fragment}"));
        } else {
            let at = self.viewer.repaint_at.map_or(due, |at| at.min(due));
            self.viewer.repaint_at = Some(at);
        }
    }

    /// The address's fragment changed other than by the page (which writes
    /// it with `history.replaceState`, which fires no `hashchange`): a
    /// scene or shader link is shown as if the page had been opened with
    /// it, without a reload; a damaged one is reported and what is shown
    /// stays (docs/web.md, "Sharing a scene or a shader").
    fn address_changed(&mut self) {
        let Some(hash) = page::hash() else { return };
        if let Some(scene) = link::scene_in_hash(&hash) {
            match scene {
                Ok(text) => {
                    page::hide_message();
                    self.work.show_scene();
                    self.open(Opening::Link(text));
                    // Showing the scene document wrote its last text.
                    page::replace_hash(&hash);
                }
                Err(e) => page::show_error(&e),
            }
        } else if let Some(shader) = link::shader_in_hash(&hash) {
            match shader {
                Ok(text) => {
                    page::hide_message();
                    page::event("shader from-link");
                    let outcome = self.work.open(Doc::Shader, &text);
                    self.follow(outcome);
                }
                Err(e) => page::show_error(&e),
            }
        }
    }

    /// Puts a link to what is shown (the scene, camera included, or the
    /// shader) on the clipboard, and in the address at once.
    fn copy_link(&mut self) {
        let fragment = match self.work.shader_fragment() {
            Some(shader) => shader,
            None => self.scene_fragment(),
        };
        self.address_due = None;
        page::replace_hash(&fragment);
        let address = match page::address_with(&fragment) {
            Ok(address) => address,
            Err(e) => {
                self.viewer.editor.message = Some(format!("no link: {e}"));
                return;
            }
        };
        let proxy = self.proxy.clone();
        wasm_bindgen_futures::spawn_local(async move {
            let result = page::copy_text(&address).await;
            let _ = proxy.send_event(PageEvent::LinkCopied(result));
        });
    }
}

/// The WebGPU adapter and device, and the tracer's first pipelines,
/// validated before the first frame.
async fn create_graphics(
    window: Arc<Window>,
    source: &ShaderSource,
    options: &crate::gpu::ShaderOptions,
) -> Result<Graphics, String> {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
        backends: wgpu::Backends::BROWSER_WEBGPU,
        ..wgpu::InstanceDescriptor::new_without_display_handle()
    });
    let surface = instance
        .create_surface(window)
        .map_err(|e| format!("cannot draw into the canvas: {e}"))?;
    let adapter_options = wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::HighPerformance,
        force_fallback_adapter: false,
        compatible_surface: Some(&surface),
        apply_limit_buckets: false,
    };
    let gpu = Gpu::request(instance, &adapter_options)
        .await
        .map_err(|e| match e {
            // The native advice (installing a Vulkan driver) does not apply here.
            GpuError::NoAdapter(reason) => page::no_webgpu_help(&reason),
            other => other.to_string(),
        })?;
    let formats = Viewport::output_formats(&gpu, &surface);
    let pipelines = Pipelines::with_outline_async(&gpu.device, source, &formats, options)
        .await
        .map_err(|e| e.to_string())?;
    Ok(Graphics {
        gpu,
        surface,
        pipelines,
    })
}

/// The UI scale the browser kept, within [`help::SCALES`]; 1 without one.
fn stored_ui_scale() -> f32 {
    page::stored(UI_SCALE_KEY)
        .and_then(|v| v.parse::<f32>().ok())
        .filter(|s| help::SCALES.contains(s))
        .unwrap_or(1.0)
}

/// Reports a link whose scene cannot be shown (the picture shown stays).
fn link_error(e: &dyn std::fmt::Display) {
    page::show_error(&format!("the link's scene cannot be shown: {e}"));
}

/// The last part of a mesh file's path (`bunny.obj`), for the status line.
fn file_name(file: &Path) -> String {
    file.file_name()
        .unwrap_or(file.as_os_str())
        .to_string_lossy()
        .into_owned()
}

/// Whether `event` is the user's (the mouse, the keyboard).
fn is_input(event: &WindowEvent) -> bool {
    matches!(
        event,
        WindowEvent::CursorMoved { .. }
            | WindowEvent::MouseInput { .. }
            | WindowEvent::MouseWheel { .. }
            | WindowEvent::KeyboardInput { .. }
    )
}
