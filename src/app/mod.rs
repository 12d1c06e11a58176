//! The interactive viewer: a winit window showing the ray-traced scene, the
//! egui scene editor on top, the orbit camera, and hot reload of shaders and
//! scene file. The app owns the [`Document`] and tells the GPU viewport what
//! changed; drawing is done by `gpu` (the image) and egui-wgpu (the UI).

mod controls;
mod document;
mod mesh_files;
mod orbit;
mod overlay;
mod panel;
mod pipelines;
mod sandbox_window;
mod shell;
mod ui;
mod watch;

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop, EventLoopProxy};
use winit::window::WindowId;

use crate::gpu::{FrameStatus, Gpu, Pipelines, ShaderOptions, ShaderSource, Viewport};
use crate::reference;
use crate::sandbox::SourceParams;
use crate::scene::{Mesh, Scene, bundled};
use document::Document;
use panel::PanelAction;
use shell::{EguiLayer, EventLog};
use ui::{Command, Editor, Status, ViewInput};

pub use sandbox_window::run_sandbox;

/// Width of the selection outline in logical pixels (scaled by the window's
/// DPI factor).
const OUTLINE_WIDTH: f64 = 2.0;

/// How the viewer was started (the `view` subcommand's options).
#[derive(Debug, Clone, Default)]
pub struct ViewerOptions {
    /// Scene file to open; `None` opens the built-in Whitted scene.
    pub scene: Option<PathBuf>,
    /// Shader folder to use and watch; `None`: `./shaders` if it exists, else
    /// the shaders embedded in the binary (not watched).
    pub shaders: Option<PathBuf>,
    /// Initial inner size of the window in physical pixels.
    pub size: Option<(u32, u32)>,
    /// Progressive refinement limit (samples per pixel).
    pub max_samples: Option<u32>,
    /// Print one line per event on stdout (ready, saved, shader error, ...),
    /// for scripts and tests that drive the window.
    pub print_events: bool,
}

#[derive(Debug, thiserror::Error)]
pub enum ViewerError {
    #[error(
        "cannot open a window: {0}\n\
         The viewer needs a display (X11 or Wayland: is DISPLAY or WAYLAND_DISPLAY set?).\n\
         Without one, render headless: raysandbox render SCENE.toml -o image.png"
    )]
    NoDisplay(String),
    #[error(
        "{0}\nWithout a GPU you can still render with the CPU: raysandbox render SCENE.toml -o image.png --reference"
    )]
    NoGpu(String),
    #[error("{0}")]
    Scene(String),
    #[error("{0}")]
    Shader(String),
    /// `--size` beyond what the GPU can draw.
    #[error("--size: {0}")]
    Size(String),
}

/// Things other threads tell the event loop.
pub enum UserEvent {
    FileChanged(watch::Change),
    /// Pipelines built in the background: for a new scene feature set, from
    /// reloaded shaders or for changed shader parameters.
    PipelinesBuilt(Box<pipelines::Built>),
    /// A mesh file chosen in the file dialog.
    MeshFilePicked(PathBuf),
    /// A mesh file read (and its BVH built) on another thread.
    MeshRead(PathBuf, Box<Result<Mesh, String>>),
}

/// Opens the viewer and runs until the window closes.
pub fn run(options: ViewerOptions) -> Result<(), ViewerError> {
    let doc = match &options.scene {
        Some(path) => Document::open(path),
        None => Document::bundled(bundled::names()[0]),
    }
    .map_err(|e| ViewerError::Scene(e.to_string()))?;
    let shader_dir = options.shaders.clone().or_else(|| {
        let default = PathBuf::from("shaders");
        default.join("main.wgsl").is_file().then_some(default)
    });
    let shaders = match &shader_dir {
        Some(dir) => ShaderSource::from_dir(dir),
        None => Ok(ShaderSource::embedded()),
    }
    .and_then(|s| s.validate().map(|_| s))
    .map_err(|e| ViewerError::Shader(e.to_string()))?;
    let shader_params =
        SourceParams::read(&shaders).map_err(|e| ViewerError::Shader(e.to_string()))?;

    let event_loop = EventLoop::<UserEvent>::with_user_event()
        .build()
        .map_err(|e| ViewerError::NoDisplay(e.to_string()))?;
    event_loop.set_control_flow(ControlFlow::Wait);
    let mut app = App {
        proxy: event_loop.create_proxy(),
        options,
        doc,
        editor: Editor::default(),
        shader_dir,
        shaders,
        shader_params,
        reload_pending: false,
        gfx: None,
        watch: None,
        watched_meshes: Vec::new(),
        fatal: None,
        drag_start_distance: None,
        repaint_at: None,
        title: String::new(),
    };
    if let Some(n) = app.options.max_samples {
        app.editor.view.max_samples = n.max(1);
    }
    event_loop
        .run_app(&mut app)
        .map_err(|e| ViewerError::NoDisplay(e.to_string()))?;
    match app.fatal {
        Some(error) => Err(error),
        None => Ok(()),
    }
}

/// The window and everything that draws into it.
struct Graphics {
    window: Arc<winit::window::Window>,
    gpu: Gpu,
    viewport: Viewport,
    pipelines: pipelines::PipelineCache,
    egui: EguiLayer,
}

struct App {
    proxy: EventLoopProxy<UserEvent>,
    options: ViewerOptions,
    doc: Document,
    editor: Editor,
    shader_dir: Option<PathBuf>,
    /// The shader source of the pipelines in use (the last good one), as
    /// read from the files.
    shaders: ShaderSource,
    /// Its annotated constants: the "Shader parameters" of the panel, whose
    /// values are written into the source the pipelines are built from.
    shader_params: SourceParams,
    /// New shaders or parameter values validated; their pipelines are being built.
    reload_pending: bool,
    gfx: Option<Graphics>,
    watch: Option<watch::Watch>,
    /// The mesh files being watched (the scene's, when the watch started).
    watched_meshes: Vec<PathBuf>,
    /// Why the viewer had to stop, reported after the loop ends.
    fatal: Option<ViewerError>,
    /// Eye-target distance when the current drag or zoom started.
    drag_start_distance: Option<f64>,
    /// When egui asked to be drawn again (animations, tooltips).
    repaint_at: Option<Instant>,
    title: String,
}

impl ApplicationHandler<UserEvent> for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.gfx.is_some() {
            return;
        }
        match self.create_graphics(event_loop) {
            Ok(gfx) => {
                self.gfx = Some(gfx);
                self.restart_watch();
            }
            Err(e) => {
                self.fatal = Some(e);
                event_loop.exit();
            }
        }
    }

    fn user_event(&mut self, _: &ActiveEventLoop, event: UserEvent) {
        match event {
            UserEvent::FileChanged(watch::Change::Shaders) => self.reload_shaders(),
            UserEvent::FileChanged(watch::Change::SceneFile) => self.reload_scene_file(),
            UserEvent::FileChanged(watch::Change::MeshFile(path)) => self.reload_mesh_file(&path),
            UserEvent::PipelinesBuilt(built) => self.pipelines_built(*built),
            UserEvent::MeshFilePicked(path) => self.add_mesh_file(&path),
            UserEvent::MeshRead(path, mesh) => self.mesh_read(&path, *mesh),
        }
        self.request_redraw();
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(gfx) = &mut self.gfx else { return };
        let response = gfx.egui.state.on_window_event(&gfx.window, &event);
        match event {
            WindowEvent::CloseRequested => self.quit(event_loop, false),
            WindowEvent::Resized(size) => {
                gfx.viewport.resize(&gfx.gpu, (size.width, size.height));
                gfx.window.request_redraw();
            }
            WindowEvent::RedrawRequested => self.redraw(event_loop),
            WindowEvent::DroppedFile(path) => {
                // A mesh file dropped on the window is added to the scene;
                // any other file opens as the panel's "Open" does.
                let action = if mesh_files::is_mesh_file(&path) {
                    PanelAction::AddMeshFile(path)
                } else {
                    PanelAction::Open(path)
                };
                self.panel_action(action);
                self.request_redraw();
            }
            _ => {
                if response.repaint {
                    gfx.window.request_redraw();
                }
            }
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if shell::wait_for_repaint(&mut self.repaint_at, event_loop) {
            self.request_redraw();
        }
    }
}

impl App {
    fn create_graphics(&mut self, event_loop: &ActiveEventLoop) -> Result<Graphics, ViewerError> {
        let (window, gpu, surface) =
            shell::open_window(event_loop, "raysandbox", self.options.size, (1280.0, 760.0))?;
        let formats = Viewport::output_formats(&gpu, &surface);
        let source = self.shader_params.apply(&self.shaders);
        let options = ShaderOptions::for_scene(&self.doc.scene);
        let pipelines = Pipelines::with_outline(&gpu.device, &source, &formats, &options)
            .map_err(|e| ViewerError::Shader(e.to_string()))?;
        let cache = pipelines::PipelineCache::new(source, options, pipelines.clone());
        let size = window.inner_size();
        let viewport = Viewport::new(
            &gpu,
            surface,
            (size.width, size.height),
            pipelines,
            &self.shown_scene(),
        );
        let egui = EguiLayer::new(&window, &gpu, viewport.surface_format());
        Ok(Graphics {
            window,
            gpu,
            viewport,
            pipelines: cache,
            egui,
        })
    }

    fn request_redraw(&self) {
        if let Some(gfx) = &self.gfx {
            gfx.window.request_redraw();
        }
    }

    fn event(&self, line: &str) {
        EventLog {
            print: self.options.print_events,
        }
        .event(line);
    }

    /// (Re)starts watching the shader folder, the scene file and its mesh
    /// files.
    fn restart_watch(&mut self) {
        let proxy = self.proxy.clone();
        self.watch = None;
        self.watched_meshes = self.doc.mesh_files();
        if self.shader_dir.is_none() && self.doc.path().is_none() && self.watched_meshes.is_empty()
        {
            return;
        }
        let notify = move |change| {
            let _ = proxy.send_event(UserEvent::FileChanged(change));
        };
        let (shaders, scene) = (self.shader_dir.as_deref(), self.doc.path());
        match watch::watch(shaders, scene, &self.watched_meshes, notify) {
            Ok(w) => self.watch = Some(w),
            Err(e) => {
                log::warn!("{e}");
                self.editor.message = Some(e);
            }
        }
    }

    /// Reads the shader folder again. naga validates it here, at once; only
    /// a valid source goes on to the (slow) pipeline build, on another thread,
    /// while the last good pipelines keep drawing. Shader parameter values
    /// are kept by name.
    fn reload_shaders(&mut self) {
        let Some(dir) = &self.shader_dir else { return };
        let read = ShaderSource::from_dir(dir).and_then(|source| {
            let mut params = SourceParams::read(&source)?;
            params.params.keep_values_from(&self.shader_params.params);
            params.apply(&source).validate()?;
            Ok((source, params))
        });
        match read {
            Ok((source, params)) => {
                self.shaders = source;
                self.shader_params = params;
                self.build_pipelines();
            }
            Err(e) => {
                self.event(&format!("shader-error {}:{}:{}", e.file, e.line, e.column));
                log::error!("{e}");
                self.editor.shader_error = Some(e.to_string());
            }
        }
    }

    /// Builds pipelines from the current source and parameter values on
    /// another thread; the pipelines in use keep drawing until they are ready.
    fn build_pipelines(&mut self) {
        let Some(gfx) = &mut self.gfx else { return };
        gfx.pipelines
            .set_source(self.shader_params.apply(&self.shaders));
        gfx.pipelines.current = None;
        self.reload_pending = true;
        self.ensure_pipelines();
    }

    /// Draws with the pipelines for the scene's feature set (and the current
    /// shader source) once they are built; starts building them otherwise.
    fn ensure_pipelines(&mut self) {
        let Some(gfx) = &mut self.gfx else { return };
        let wanted = ShaderOptions::for_scene(&self.doc.scene);
        if gfx.pipelines.current.as_ref() == Some(&wanted) {
            return;
        }
        let device = gfx.gpu.device.clone();
        let formats = [gfx.viewport.surface_format(), crate::gpu::EXPORT_FORMAT];
        let proxy = self.proxy.clone();
        let options = wanted.clone();
        let spawn = move |source: ShaderSource, generation| {
            std::thread::spawn(move || {
                let result = Pipelines::with_outline(&device, &source, &formats, &options)
                    .map_err(|e| e.to_string());
                let built = pipelines::Built {
                    generation,
                    options,
                    result,
                };
                let _ = proxy.send_event(UserEvent::PipelinesBuilt(Box::new(built)));
            });
        };
        if let Some(pipelines) = gfx.pipelines.get_or_build(wanted.clone(), spawn) {
            gfx.viewport.set_pipelines(&gfx.gpu, pipelines);
            gfx.pipelines.current = Some(wanted);
            if std::mem::take(&mut self.reload_pending) {
                self.editor.shader_error = None;
                self.event("shaders-reloaded");
            }
        }
    }

    fn pipelines_built(&mut self, built: pipelines::Built) {
        let Some(gfx) = &mut self.gfx else { return };
        if let Err(e) = gfx.pipelines.finished(built) {
            log::error!("{e}");
            self.editor.shader_error = Some(e);
            self.reload_pending = false;
            self.event("shader-error");
            return;
        }
        self.ensure_pipelines();
    }

    /// An external edit of the scene file: an invalid file is reported and
    /// the current scene kept; unsaved edits are not replaced without asking.
    fn reload_scene_file(&mut self) {
        match self.doc.read_external_change() {
            Ok(None) => {
                // Back to the text last loaded (an error undone): the scene
                // shown is that file's, the error is gone.
                if self.editor.scene_error.take().is_some() {
                    self.event("scene-error-cleared");
                }
            }
            Ok(Some((scene, text))) => {
                self.editor.scene_error = None;
                if self.doc.is_dirty() {
                    self.editor.pending_reload = Some((scene, text));
                    self.event("scene-changed-on-disk");
                } else {
                    self.doc.accept_external(scene, text);
                    self.scene_changed(None);
                    self.event("scene-reloaded");
                }
            }
            Err(e) => {
                log::error!("{e}");
                let message = e.to_string();
                let first_line = message.lines().next().unwrap_or_default();
                self.event(&format!("scene-error {first_line}"));
                self.editor.scene_error = Some(message);
            }
        }
    }

    /// A mesh file changed on disk: every mesh that shows it takes the new
    /// triangles; a bad file is reported (file and line) in the panel and
    /// the meshes keep their last good triangles.
    fn reload_mesh_file(&mut self, path: &Path) {
        match self.doc.reload_mesh_file(path) {
            Ok(0) => {}
            Ok(_) => {
                self.editor.panel.mesh_error = None;
                self.scene_changed(None);
                self.event(&format!("mesh-reloaded {}", path.display()));
            }
            Err(e) => {
                log::error!("{e}");
                self.event(&format!("mesh-error {e}"));
                self.editor.panel.mesh_error = Some(e);
            }
        }
    }

    /// Reads the mesh in `path` (picked, typed or dropped) and builds its
    /// BVH on another thread, so that the window keeps drawing while a
    /// large model loads; [`App::mesh_read`] adds it.
    fn add_mesh_file(&mut self, path: &Path) {
        let read = self.doc.mesh_reader(path);
        let (proxy, path) = (self.proxy.clone(), path.to_path_buf());
        self.editor.message = Some(format!("reading {}…", path.display()));
        std::thread::spawn(move || {
            let mesh = read().inspect(|mesh| {
                crate::bvh::mesh_bvh(&mesh.geometry.0);
            });
            let _ = proxy.send_event(UserEvent::MeshRead(path, Box::new(mesh)));
        });
    }

    /// Adds a mesh read by [`App::add_mesh_file`] in front of the camera,
    /// selected; a file that could not be read is reported in the panel and
    /// the scene is left as it was.
    fn mesh_read(&mut self, path: &Path, mesh: Result<Mesh, String>) {
        match mesh {
            Ok(mut mesh) => {
                // Named for the scene open now (another may have been
                // opened while the file was read).
                mesh.file = Some(mesh_files::scene_relative(path, self.doc.path()));
                let triangles = mesh.geometry.0.triangles.len();
                let before = self.doc.scene.clone();
                panel::add_mesh(&mut self.doc.scene, &mut self.editor.panel, mesh);
                self.scene_changed(Some(&before));
                self.editor.message =
                    Some(format!("added {} ({triangles} triangles)", path.display()));
                self.event(&format!("mesh-added {}", path.display()));
            }
            Err(e) => {
                log::error!("{e}");
                self.event(&format!("mesh-error {e}"));
                self.editor.message = None;
                self.editor.panel.mesh_error = Some(e);
            }
        }
    }

    /// Opens the file dialog for "Add mesh from file", in the scene's folder;
    /// the window keeps drawing while it is open.
    fn pick_mesh_file(&self) {
        let proxy = self.proxy.clone();
        let start = self
            .doc
            .path()
            .and_then(Path::parent)
            .map(Path::to_path_buf);
        mesh_files::pick_mesh_file(start, move |path| {
            let _ = proxy.send_event(UserEvent::MeshFilePicked(path));
        });
    }

    /// Tells the viewport what changed: only the view (camera, render
    /// settings: the globals) or the shapes too (buffers and BVH rebuilt).
    /// A new feature set gets its own pipelines.
    fn scene_changed(&mut self, before: Option<&Scene>) {
        let shown = self.shown_scene();
        if let Some(gfx) = &mut self.gfx {
            match before {
                Some(old) if same_shapes(old, &self.doc.scene) => gfx.viewport.set_view(&shown),
                _ => gfx.viewport.set_scene(&gfx.gpu, &shown),
            }
        }
        self.ensure_pipelines();
        if self.doc.mesh_files() != self.watched_meshes {
            self.restart_watch();
        }
    }

    /// The scene as the viewer draws it: the file's, with `min_weight`
    /// raised to the viewer's floor (the panel's "min weight").
    fn shown_scene(&self) -> Scene {
        let mut scene = self.doc.scene.clone();
        let floor = self.editor.view.min_weight;
        scene.render.min_weight = scene.render.min_weight.max(floor);
        scene
    }

    fn quit(&mut self, event_loop: &ActiveEventLoop, force: bool) {
        if force || !self.doc.is_dirty() {
            event_loop.exit();
        } else {
            self.editor.confirm_quit = true;
            self.request_redraw();
        }
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let start = Instant::now();
        let before = self.doc.scene.clone();
        let view_before = self.editor.view.min_weight;
        let (commands, input, egui_output) = self.run_ui();
        for command in commands {
            self.execute(command, event_loop);
        }
        let picked = self.apply_view_input(&input);
        if self.doc.scene != before || self.editor.view.min_weight != view_before {
            self.scene_changed(Some(&before));
        }
        self.update_title();
        self.paint(egui_output, input.dragging || input.widget_dragging, start);
        if picked {
            // Once the frame with its outline is on screen.
            self.event(&format!("selected {:?}", self.editor.panel.selection));
        }
    }

    /// Runs the egui frame: returns what to do and what to paint.
    fn run_ui(&mut self) -> (Vec<Command>, ViewInput, egui::FullOutput) {
        let gfx = self.gfx.as_mut().expect("drawing needs graphics");
        let status = Status {
            frame_time: gfx.viewport.last_frame_time(),
            timing: gfx.viewport.timing().describe(),
            samples: gfx.viewport.samples(),
            resolution: gfx.viewport.traced_resolution(),
            scale: gfx.viewport.scale(),
            adapter: gfx.gpu.adapter.get_info().name,
            compiling: gfx.pipelines.building(),
        };
        let names = bundled::names();
        let mut result = (Vec::new(), ViewInput::default());
        let output = gfx.egui.run(&gfx.window, |ui| {
            result = ui::draw(
                ui,
                &mut self.doc,
                &mut self.editor,
                &mut self.shader_params.params,
                &status,
                &names,
            );
        });
        (result.0, result.1, output)
    }

    fn execute(&mut self, command: Command, event_loop: &ActiveEventLoop) {
        match command {
            Command::Panel(action) => self.panel_action(action),
            Command::ShaderParamsChanged => self.build_pipelines(),
            Command::ToggleFullscreen => {
                if let Some(gfx) = &self.gfx {
                    shell::toggle_fullscreen(&gfx.window);
                }
            }
            Command::LeaveFullscreen => {
                if let Some(gfx) = &self.gfx {
                    gfx.window.set_fullscreen(None);
                }
            }
            Command::Quit => self.quit(event_loop, false),
            Command::QuitNow => self.quit(event_loop, true),
            Command::SaveAndQuit => {
                self.editor.confirm_quit = false;
                if self.save(None) {
                    self.quit(event_loop, true);
                }
            }
            Command::KeepEdits => {
                if let Some((_, text)) = self.editor.pending_reload.take() {
                    self.doc.ignore_external(text);
                }
            }
            Command::AcceptReload => {
                if let Some((scene, text)) = self.editor.pending_reload.take() {
                    self.doc.accept_external(scene, text);
                    self.scene_changed(None);
                    self.event("scene-reloaded");
                }
            }
        }
    }

    fn panel_action(&mut self, action: PanelAction) {
        match action {
            PanelAction::Save => {
                self.save(None);
            }
            PanelAction::SaveAs(path) => {
                self.save(Some(&path));
            }
            PanelAction::Open(path) => self.open(Document::open(&path)),
            PanelAction::OpenBundled(name) => self.open(Document::bundled(name)),
            PanelAction::ResetCamera => self.doc.scene.camera = self.doc.saved_camera().clone(),
            PanelAction::Screenshot => self.screenshot(),
            PanelAction::PickMeshFile => self.pick_mesh_file(),
            PanelAction::AddMeshFile(path) => self.add_mesh_file(&path),
        }
    }

    /// Saves to the document's file, or to `path`. Reports the outcome in the
    /// status line; returns whether it worked.
    fn save(&mut self, path: Option<&Path>) -> bool {
        let had_path = self.doc.path().map(Path::to_path_buf);
        let result = match path {
            Some(p) => self.doc.save_as(p),
            None => self.doc.save(),
        };
        match result {
            Ok(saved) => {
                self.editor.message = Some(format!("saved {}", saved.display()));
                self.event(&format!("saved {}", saved.display()));
                if had_path.as_deref() != Some(saved.as_path()) {
                    self.restart_watch();
                }
                true
            }
            Err(e) => {
                self.editor.message = Some(format!("not saved: {e}"));
                log::error!("{e}");
                false
            }
        }
    }

    fn open(&mut self, doc: Result<Document, crate::scene::SceneError>) {
        if self.doc.is_dirty() {
            self.editor.message =
                Some("unsaved edits: save them (Ctrl+S) before opening another scene".into());
            return;
        }
        match doc {
            Ok(doc) => {
                self.doc = doc;
                self.editor.panel.selection = None;
                self.editor.scene_error = None;
                self.scene_changed(None);
                self.restart_watch();
                self.editor.message = Some(format!("opened {}", self.doc.label()));
            }
            Err(e) => self.editor.message = Some(e.to_string()),
        }
    }

    fn screenshot(&mut self) {
        let Some(gfx) = &mut self.gfx else { return };
        let image = match gfx.viewport.capture(&gfx.gpu) {
            Ok(image) => image,
            Err(e) => {
                self.editor.message = Some(format!("no screenshot: {e}"));
                return;
            }
        };
        let path = self.doc.screenshot_path();
        match image.save(&path) {
            Ok(()) => {
                self.editor.message = Some(format!("screenshot saved to {}", path.display()));
                self.event(&format!("screenshot {}", path.display()));
            }
            Err(e) => self.editor.message = Some(format!("{}: {e}", path.display())),
        }
    }

    /// Mouse input over the image moves the camera or picks an object;
    /// returns whether it picked.
    fn apply_view_input(&mut self, input: &ViewInput) -> bool {
        let Some(gfx) = &self.gfx else { return false };
        let size = gfx.window.inner_size();
        let camera = &mut self.doc.scene.camera;
        if input.dragging || input.zoom != 0.0 {
            let start = *self
                .drag_start_distance
                .get_or_insert((camera.from - camera.to).length());
            orbit::orbit(camera, input.orbit.0, input.orbit.1);
            orbit::pan(camera, input.pan.0, input.pan.1, f64::from(size.height));
            orbit::zoom(camera, input.zoom, start);
        } else {
            self.drag_start_distance = None;
        }
        let click = input.click.or(input.double_click);
        if let Some((x, y)) = click {
            let scene = reference::PreparedScene::new(&self.doc.scene);
            let hit = reference::pick(&scene, size.width, size.height, x, y);
            self.editor.panel.selection = hit.map(|(id, _)| id);
            if let (Some((_, point)), Some(_)) = (hit, input.double_click) {
                orbit::recenter(&mut self.doc.scene.camera, point);
            }
        }
        click.is_some()
    }

    fn update_title(&mut self) {
        let title = format!("raysandbox: {}", self.doc.label());
        if title != self.title {
            if let Some(gfx) = &self.gfx {
                gfx.window.set_title(&title);
            }
            self.title = title;
        }
    }

    /// Draws the image and the UI; keeps refining while samples are missing.
    /// While the view moves, one sample per pixel at the moving scale
    /// ([`App::moving_scale`]); full resolution once it stops. `start`: when
    /// this redraw began, for the moving frame's time in all.
    fn paint(&mut self, output: egui::FullOutput, dragging: bool, start: Instant) {
        let scale = if dragging { self.moving_scale() } else { 1.0 };
        let Some(gfx) = &mut self.gfx else { return };
        gfx.viewport.set_scale(&gfx.gpu, scale);
        // The outline searches (2 width + 3)^2 id texels per window pixel,
        // several times the cost of a moving frame's trace on lavapipe
        // (docs/performance.md, "Julia sets: dragging c"): it is left out
        // while the view moves and drawn again once it rests.
        let outlined = if dragging {
            None
        } else {
            self.editor.panel.selection
        };
        let outline_width = (OUTLINE_WIDTH * gfx.window.scale_factor()).round() as u32;
        gfx.viewport
            .set_selection(&gfx.gpu, outlined, outline_width);
        let max_samples = if dragging {
            1
        } else {
            self.editor.view.max_samples
        };
        let new_samples = u32::from(gfx.viewport.samples() < max_samples);

        let painting = gfx.egui.prepare(&gfx.gpu, &gfx.window, output);
        let egui = &mut gfx.egui;
        let gpu = &gfx.gpu;
        gfx.window.pre_present_notify();
        let status = gfx.viewport.frame(gpu, new_samples, |encoder, view| {
            egui.paint(gpu, encoder, view, &painting)
        });
        let delay = gfx.egui.finish(painting);
        // After a frame that added samples, draw once more: either the next
        // sample, or (refinement done) only the display pass, so the status
        // line shows the final count. Then nothing is drawn until something
        // changes, and an idle window costs no CPU.
        let samples = gfx.viewport.samples();
        if status == FrameStatus::Skipped || new_samples > 0 {
            gfx.window.request_redraw();
        }
        let traced = status == FrameStatus::Presented && new_samples > 0;
        if let (true, true, Some(time)) = (dragging, traced, gfx.viewport.last_frame_time()) {
            let (scale, wall) = (gfx.viewport.scale(), start.elapsed());
            self.editor.view.moving_frame = Some(panel::MovingFrame { time, wall, scale });
            self.event(&format!(
                "moving-frame ms={:.1} wall_ms={:.1} scale={scale:.3}",
                time.as_secs_f64() * 1e3,
                wall.as_secs_f64() * 1e3
            ));
        }
        if new_samples > 0 && samples >= max_samples && !dragging {
            self.event(&format!("ready samples={samples}"));
        }
        if delay < Duration::from_secs(5) {
            self.repaint_at = Some(Instant::now() + delay);
        }
    }

    /// The resolution scale of a frame while the view moves: the panel's
    /// moving scale, or with a frame budget the scale that the last moving
    /// frame's time says fits it (gpu/interaction.rs). A new movement
    /// starts where the last one ended: the scene is mostly the same.
    fn moving_scale(&self) -> f32 {
        let view = &self.editor.view;
        match view.moving_frame {
            Some(last) if view.adaptive_scale => {
                let budget = Duration::from_secs_f32(view.frame_budget_ms / 1e3);
                crate::gpu::interaction::next_scale(last.scale, last.time, budget)
            }
            _ => view.interaction_scale,
        }
    }
}

/// Whether two scenes differ at most in camera and render settings.
fn same_shapes(a: &Scene, b: &Scene) -> bool {
    a.lights == b.lights && a.materials == b.materials && a.same_shapes(b)
}
