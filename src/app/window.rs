//! The window program: the `view` subcommand's winit window around the
//! viewer's core ([`Viewer`]), with what only makes sense natively (docs/web.md,
//! "Differences from the native program"): the scene, shader and mesh files
//! watched and reloaded, saving, file dialogs and the worker threads that
//! build pipelines and read meshes.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop, EventLoopProxy};
use winit::window::{Window, WindowId};

use super::document::Document;
use super::panel::{self, PanelAction};
use super::shell::{self, EventLog};
use super::ui::{Command, Host};
use super::viewer::{Platform, Viewer};
use super::{memory, pipelines, shape_files, watch};
use crate::gpu::{Gpu, Pipelines, ShaderSource, Viewport};
use crate::scene::{NewShape, Scene, ShapeKind, bundled};
use crate::shader_params::SourceParams;

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
    /// What the picture shows at first (docs/views.md).
    pub view: crate::gpu::View,
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
    /// A file that a shape is made from, chosen in the file dialog.
    ShapeFilePicked(PathBuf),
    /// A shape read from a file (and made ready to trace) on another
    /// thread.
    ShapeRead(PathBuf, Box<Result<NewShape, String>>),
    /// SIGUSR1: drop the GPU device, as a driver reset would, to test the
    /// recovery.
    LoseDevice,
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
    let proxy = event_loop.create_proxy();
    let log = EventLog {
        print: options.print_events,
    };
    let worker = proxy.clone();
    let platform = Platform {
        event: Box::new(move |line| log.event(line)),
        // A worker thread per build: the window keeps drawing meanwhile.
        build: Box::new(move |request| {
            let proxy = worker.clone();
            std::thread::spawn(move || {
                let built = pollster::block_on(request.build());
                let _ = proxy.send_event(UserEvent::PipelinesBuilt(Box::new(built)));
            });
        }),
        job_done: None,
    };
    #[cfg(unix)]
    lose_device_on_sigusr1(proxy.clone(), || UserEvent::LoseDevice);
    let mut viewer = Viewer::new(doc, shaders, shader_params, platform);
    if let Some(n) = options.max_samples {
        viewer.editor.view.max_samples = n.max(1);
    }
    viewer.editor.view.shown = options.view;
    let mut app = App {
        proxy,
        log,
        options,
        viewer,
        shader_dir,
        watch: None,
        watched_files: Vec::new(),
        fatal: None,
        title: String::new(),
    };
    run_until_closed(event_loop, &mut app)?;
    app.fatal.map_or(Ok(()), Err)
}

/// Runs `app` until its window closes. The app keeps the error that closed
/// it (`fatal`) itself; this is the error of a display that could not run.
pub(super) fn run_until_closed<T: 'static>(
    event_loop: EventLoop<T>,
    app: &mut impl ApplicationHandler<T>,
) -> Result<(), ViewerError> {
    event_loop
        .run_app(app)
        .map_err(|e| ViewerError::NoDisplay(e.to_string()))
}

/// A thread that sends the event loop `lose` on SIGUSR1, so that the
/// window destroys its own GPU device, as a driver reset would, to try the
/// recovery ([`lose_device`]; docs/reliability.md, "The GPU's limits and
/// a lost device").
#[cfg(unix)]
pub(super) fn lose_device_on_sigusr1<T: Send + 'static>(proxy: EventLoopProxy<T>, lose: fn() -> T) {
    let mut signals = match signal_hook::iterator::Signals::new([signal_hook::consts::SIGUSR1]) {
        Ok(signals) => signals,
        Err(e) => {
            log::warn!("SIGUSR1 not handled: {e}");
            return;
        }
    };
    std::thread::spawn(move || {
        for _ in signals.forever() {
            if proxy.send_event(lose()).is_err() {
                break;
            }
        }
    });
}

/// What SIGUSR1 asks for: the device destroyed; the next frame finds it
/// lost and [`replace_lost_device`] makes a new one.
pub(super) fn lose_device(gpu: &Gpu) {
    log::warn!("SIGUSR1: destroying the GPU device");
    gpu.device.destroy();
}

/// Makes a new GPU device for `window`, whose device was lost for
/// `reason`, once the window's program has dropped everything made from
/// the old one, and hands it to `attach`, which makes those things again.
/// Prints `device-lost REASON` and, once attached, `device-recovered`.
/// Returns the status line's message, which says what was `kept`, or the
/// error to exit with.
pub(super) fn replace_lost_device(
    window: Arc<Window>,
    (reason, kept): (&str, &str),
    log: EventLog,
    attach: impl FnOnce(Arc<Window>, Gpu, wgpu::Surface<'static>) -> Result<(), ViewerError>,
) -> Result<String, ViewerError> {
    log.event(&format!("device-lost {reason}"));
    let made =
        gpu_for_window(&window, None).and_then(|(gpu, surface)| attach(window, gpu, surface));
    match made {
        Ok(()) => {
            log.event("device-recovered");
            Ok(format!(
                "the GPU device was lost ({reason}); a new one was made, {kept} kept"
            ))
        }
        Err(e) => Err(ViewerError::NoGpu(format!(
            "the GPU device was lost ({reason}) and no new one could be made: {e}"
        ))),
    }
}

/// Opens a window of `size` physical pixels (or `default` logical ones) and
/// a GPU device that can present to it.
pub fn open_gpu_window(
    event_loop: &ActiveEventLoop,
    title: &str,
    size: Option<(u32, u32)>,
    default: (f64, f64),
) -> Result<(Arc<Window>, Gpu, wgpu::Surface<'static>), ViewerError> {
    let mut attributes = Window::default_attributes().with_title(title);
    attributes = match size {
        Some((w, h)) => attributes.with_inner_size(winit::dpi::PhysicalSize::new(w, h)),
        None => attributes.with_inner_size(winit::dpi::LogicalSize::new(default.0, default.1)),
    };
    let window = Arc::new(
        event_loop
            .create_window(attributes)
            .map_err(|e| ViewerError::NoDisplay(e.to_string()))?,
    );
    let (gpu, surface) = gpu_for_window(&window, size)?;
    Ok((window, gpu, surface))
}

/// A GPU device and a surface that presents to `window` (of `size`
/// physical pixels, if the user chose one).
fn gpu_for_window(
    window: &Arc<Window>,
    size: Option<(u32, u32)>,
) -> Result<(Gpu, wgpu::Surface<'static>), ViewerError> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let surface = instance
        .create_surface(window.clone())
        .map_err(|e| ViewerError::NoGpu(format!("cannot draw into the window: {e}")))?;
    let gpu = Gpu::with_adapter(
        instance,
        &wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: Some(&surface),
            apply_limit_buckets: false,
        },
    )
    .map_err(|e| ViewerError::NoGpu(e.to_string()))?;
    log::info!("adapter: {}", gpu.describe());
    if let Some(size) = size {
        gpu.check_size(size)
            .map_err(|e| ViewerError::Size(e.to_string()))?;
    }
    Ok((gpu, surface))
}

struct App {
    proxy: EventLoopProxy<UserEvent>,
    /// Where the viewer's event lines go (also [`Platform::event`]).
    log: EventLog,
    options: ViewerOptions,
    viewer: Viewer,
    shader_dir: Option<PathBuf>,
    watch: Option<watch::Watch>,
    /// The files the shapes read that are being watched (the scene's, when
    /// the watch started).
    watched_files: Vec<PathBuf>,
    /// Why the viewer had to stop, reported after the loop ends.
    fatal: Option<ViewerError>,
    title: String,
}

impl ApplicationHandler<UserEvent> for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.viewer.gfx.is_some() {
            return;
        }
        match self.create_graphics(event_loop) {
            Ok(()) => self.restart_watch(),
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
            UserEvent::FileChanged(watch::Change::ShapeFile(path)) => self.reload_shape_file(&path),
            UserEvent::PipelinesBuilt(built) => self.viewer.pipelines_built(*built),
            UserEvent::ShapeFilePicked(path) => self.add_shape_file(&path),
            UserEvent::ShapeRead(path, shape) => self.shape_read(&path, *shape),
            UserEvent::LoseDevice => {
                if let Some(gfx) = &self.viewer.gfx {
                    lose_device(&gfx.gpu);
                }
            }
        }
        // What a reload replaced is dropped by now.
        memory::release_freed();
        self.request_redraw();
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(gfx) = &mut self.viewer.gfx else {
            return;
        };
        let response = gfx.egui.state.on_window_event(&gfx.window, &event);
        match event {
            WindowEvent::CloseRequested => self.quit(event_loop, false),
            WindowEvent::Resized(size) => self.viewer.resize(size),
            WindowEvent::RedrawRequested => self.redraw(event_loop),
            WindowEvent::DroppedFile(path) => {
                // A file a shape is made from (a mesh's model) dropped on
                // the window is added to the scene; any other file opens
                // as the panel's "Open" does.
                let action = if ShapeKind::for_file(&path).is_some() {
                    PanelAction::AddShapeFile(path)
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
        if shell::wait_for_repaint(&mut self.viewer.repaint_at, event_loop) {
            self.request_redraw();
        }
    }
}

impl App {
    fn create_graphics(&mut self, event_loop: &ActiveEventLoop) -> Result<(), ViewerError> {
        let (window, gpu, surface) =
            open_gpu_window(event_loop, "raysandbox", self.options.size, (1280.0, 760.0))?;
        self.attach(window, gpu, surface)
    }

    /// Builds the first pipelines on `gpu` and starts drawing into `window`.
    fn attach(
        &mut self,
        window: Arc<Window>,
        gpu: Gpu,
        surface: wgpu::Surface<'static>,
    ) -> Result<(), ViewerError> {
        let formats = Viewport::output_formats(&gpu, &surface);
        let (source, options) = self.viewer.first_build();
        let pipelines = Pipelines::with_outline(&gpu.device, &source, &formats, &options)
            .map_err(|e| ViewerError::Shader(e.to_string()))?;
        self.viewer.attach(window, gpu, surface, pipelines);
        Ok(())
    }

    /// The GPU device was lost (a driver reset, SIGUSR1): everything made
    /// from it is dropped and made again on a new device, in the same
    /// window. The document (the scene and its unsaved edits), the panel's
    /// state and the shaders are the viewer's and stay as they were.
    fn recover_lost_device(&mut self, event_loop: &ActiveEventLoop, reason: &str) {
        let Some(lost) = self.viewer.gfx.take() else {
            return;
        };
        let window = lost.window.clone();
        let generation = lost.pipelines.generation();
        drop(lost);
        let log = self.log;
        let lost = (reason, "the scene and its edits are");
        match replace_lost_device(window, lost, log, |window, gpu, surface| {
            self.attach(window, gpu, surface)
        }) {
            Ok(message) => {
                self.viewer.follow_generation(generation);
                self.viewer.editor.message = Some(message);
                self.request_redraw();
            }
            Err(e) => {
                self.fatal = Some(e);
                event_loop.exit();
            }
        }
    }

    fn request_redraw(&self) {
        self.viewer.request_redraw();
    }

    fn event(&self, line: &str) {
        self.viewer.event(line);
    }

    /// (Re)starts watching the shader folder, the scene file and the files
    /// its shapes read.
    fn restart_watch(&mut self) {
        let proxy = self.proxy.clone();
        self.watch = None;
        self.watched_files = self.viewer.doc.files_read();
        if self.shader_dir.is_none()
            && self.viewer.doc.path().is_none()
            && self.watched_files.is_empty()
        {
            return;
        }
        let notify = move |change| {
            let _ = proxy.send_event(UserEvent::FileChanged(change));
        };
        let (shaders, scene) = (self.shader_dir.as_deref(), self.viewer.doc.path());
        match watch::watch(shaders, scene, &self.watched_files, notify) {
            Ok(w) => self.watch = Some(w),
            Err(e) => {
                log::warn!("{e}");
                self.viewer.editor.message = Some(e);
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
            params
                .params
                .keep_values_from(&self.viewer.shader_params.params);
            params.apply(&source).validate()?;
            Ok((source, params))
        });
        match read {
            Ok((source, params)) => {
                self.viewer.shaders = source;
                self.viewer.shader_params = params;
                self.viewer.build_pipelines();
            }
            Err(e) => {
                self.event(&format!("shader-error {}:{}:{}", e.file, e.line, e.column));
                log::error!("{e}");
                self.viewer.editor.shader_error = Some(e.to_string());
            }
        }
    }

    /// An external edit of the scene file: an invalid file is reported and
    /// the current scene kept; unsaved edits are not replaced without asking.
    fn reload_scene_file(&mut self) {
        match self.viewer.doc.read_external_change() {
            Ok(None) => {
                // Back to the text last loaded (an error undone): the scene
                // shown is that file's, the error is gone.
                if self.viewer.editor.scene_error.take().is_some() {
                    self.event("scene-error-cleared");
                }
            }
            Ok(Some((scene, text))) => {
                self.viewer.editor.scene_error = None;
                if self.viewer.doc.is_dirty() {
                    self.viewer.editor.pending_reload = Some((scene, text));
                    self.event("scene-changed-on-disk");
                } else {
                    self.viewer.doc.accept_external(scene, text);
                    self.scene_changed(None);
                    self.event("scene-reloaded");
                }
            }
            Err(e) => {
                log::error!("{e}");
                let message = e.to_string();
                let first_line = message.lines().next().unwrap_or_default();
                self.event(&format!("scene-error {first_line}"));
                self.viewer.editor.scene_error = Some(message);
            }
        }
    }

    /// A file a shape reads changed on disk: every shape that reads it
    /// takes the new contents (a mesh its triangles); a bad file is
    /// reported (file and line) in the panel and the shapes keep their
    /// last good state.
    fn reload_shape_file(&mut self, path: &Path) {
        match self.viewer.doc.reload_file(path) {
            Ok(0) => {}
            Ok(_) => {
                self.viewer.editor.panel.file_error = None;
                self.scene_changed(None);
                self.event(&format!("file-reloaded {}", path.display()));
            }
            Err(e) => {
                log::error!("{e}");
                self.event(&format!("file-error {e}"));
                self.viewer.editor.panel.file_error = Some(e);
            }
        }
    }

    /// Reads the shape in `path` (picked, typed or dropped) and makes it
    /// ready to trace (a mesh's BVH) on another thread, so that the window
    /// keeps drawing while a large model loads; [`App::shape_read`] adds
    /// it.
    fn add_shape_file(&mut self, path: &Path) {
        let Some(kind) = ShapeKind::for_file(path) else {
            return self.shape_read(path, Err(shape_files::not_a_shape_file(path)));
        };
        let read = self.viewer.doc.shape_reader(kind, path);
        let (proxy, path) = (self.proxy.clone(), path.to_path_buf());
        self.viewer.editor.message = Some(format!("reading {}…", path.display()));
        std::thread::spawn(move || {
            let shape = read().inspect(crate::reference::prepare_ahead);
            let _ = proxy.send_event(UserEvent::ShapeRead(path, Box::new(shape)));
        });
    }

    /// Adds a shape read by [`App::add_shape_file`] in front of the camera,
    /// selected; a file that could not be read is reported in the panel and
    /// the scene is left as it was. (The events `shape-added` and
    /// `file-error` are what the viewer's tests wait for.)
    fn shape_read(&mut self, path: &Path, shape: Result<NewShape, String>) {
        match shape {
            Ok(mut shape) => {
                // Named for the scene open now (another may have been
                // opened while the file was read).
                if let Some(file) = shape.file_mut() {
                    *file = shape_files::scene_relative(path, self.viewer.doc.path());
                }
                let summary = shape.summary();
                let before = self.viewer.doc.scene.clone();
                panel::add_in_view(
                    &mut self.viewer.doc.scene,
                    &mut self.viewer.editor.panel,
                    shape,
                );
                self.scene_changed(Some(&before));
                self.viewer.editor.message = Some(format!("added {}{summary}", path.display()));
                self.event(&format!("shape-added {}", path.display()));
            }
            Err(e) => {
                log::error!("{e}");
                self.event(&format!("file-error {e}"));
                self.viewer.editor.message = None;
                self.viewer.editor.panel.file_error = Some(e);
            }
        }
    }

    /// Opens the file dialog for "Add ... from file", in the scene's
    /// folder; the window keeps drawing while it is open.
    fn pick_shape_file(&self) {
        let proxy = self.proxy.clone();
        let start = self
            .viewer
            .doc
            .path()
            .and_then(Path::parent)
            .map(Path::to_path_buf);
        shape_files::pick_shape_file(start, move |path| {
            let _ = proxy.send_event(UserEvent::ShapeFilePicked(path));
        });
    }

    /// The viewer's [`Viewer::scene_changed`], and the watch follows the
    /// scene's mesh files.
    fn scene_changed(&mut self, before: Option<&Scene>) {
        self.viewer.scene_changed(before);
        self.follow_shape_files();
    }

    fn follow_shape_files(&mut self) {
        if self.viewer.doc.files_read() != self.watched_files {
            self.restart_watch();
        }
    }

    fn quit(&mut self, event_loop: &ActiveEventLoop, force: bool) {
        if force || !self.viewer.doc.is_dirty() {
            event_loop.exit();
        } else {
            self.viewer.editor.confirm_quit = true;
            self.request_redraw();
        }
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(reason) = self.viewer.gfx.as_ref().and_then(|gfx| gfx.gpu.lost()) {
            self.recover_lost_device(event_loop, &reason);
            return;
        }
        let names = bundled::names();
        let host = Host {
            files: Some(&names),
            menu: &[],
            copy_link: false,
            help: &super::help::WINDOW,
        };
        let (start, mut ui) = self.viewer.begin_frame(&host);
        for command in std::mem::take(&mut ui.commands) {
            self.execute(command, event_loop);
        }
        self.update_title();
        self.viewer.end_frame(start, ui);
        self.follow_shape_files();
        // A device lost during the frame is replaced at the next one.
        if self
            .viewer
            .gfx
            .as_ref()
            .is_some_and(|gfx| gfx.gpu.lost().is_some())
        {
            self.request_redraw();
        }
    }

    fn execute(&mut self, command: Command, event_loop: &ActiveEventLoop) {
        match command {
            Command::Panel(action) => self.panel_action(action),
            Command::ShaderParamsChanged => self.viewer.build_pipelines(),
            // Not offered natively (no page address to link to).
            Command::CopyLink => {}
            Command::ToggleFullscreen => {
                if let Some(gfx) = &self.viewer.gfx {
                    shell::toggle_fullscreen(&gfx.window);
                }
            }
            Command::LeaveFullscreen => {
                if let Some(gfx) = &self.viewer.gfx {
                    gfx.window.set_fullscreen(None);
                }
            }
            Command::Quit => self.quit(event_loop, false),
            Command::QuitNow => self.quit(event_loop, true),
            Command::SaveAndQuit => {
                self.viewer.editor.confirm_quit = false;
                if self.save(None) {
                    self.quit(event_loop, true);
                }
            }
            Command::KeepEdits => {
                if let Some((_, text)) = self.viewer.editor.pending_reload.take() {
                    self.viewer.doc.ignore_external(text);
                }
            }
            Command::AcceptReload => {
                if let Some((scene, text)) = self.viewer.editor.pending_reload.take() {
                    self.viewer.doc.accept_external(scene, text);
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
            PanelAction::Open(path) => {
                if self.viewer.open(Document::open(&path)) {
                    self.opened();
                }
            }
            PanelAction::OpenBundled(name) => {
                if self.viewer.open(Document::bundled(name)) {
                    self.opened();
                }
            }
            // Not in the window's panel: `raysandbox shader FILE` runs shaders.
            PanelAction::OpenExampleShader(_) => {}
            PanelAction::ResetCamera => self.viewer.reset_camera(),
            PanelAction::Screenshot => self.screenshot(),
            PanelAction::PickShapeFile => self.pick_shape_file(),
            PanelAction::AddShapeFile(path) => self.add_shape_file(&path),
        }
    }

    /// Another scene replaced the document: its files are watched, and the
    /// memory of the one it replaced goes back to the system.
    fn opened(&mut self) {
        self.restart_watch();
        memory::release_freed();
    }

    /// Saves to the document's file, or to `path`. Reports the outcome in the
    /// status line; returns whether it worked.
    fn save(&mut self, path: Option<&Path>) -> bool {
        let had_path = self.viewer.doc.path().map(Path::to_path_buf);
        let result = match path {
            Some(p) => self.viewer.doc.save_as(p),
            None => self.viewer.doc.save(),
        };
        match result {
            Ok(saved) => {
                self.viewer.editor.message = Some(format!("saved {}", saved.display()));
                self.event(&format!("saved {}", saved.display()));
                if had_path.as_deref() != Some(saved.as_path()) {
                    self.restart_watch();
                }
                true
            }
            Err(e) => {
                self.viewer.editor.message = Some(format!("not saved: {e}"));
                log::error!("{e}");
                false
            }
        }
    }

    fn screenshot(&mut self) {
        let Some(gfx) = &mut self.viewer.gfx else {
            return;
        };
        let image = match gfx.viewport.capture(&gfx.gpu) {
            Ok(image) => image,
            Err(e) => {
                self.viewer.editor.message = Some(format!("no screenshot: {e}"));
                return;
            }
        };
        let path = self.viewer.doc.screenshot_path();
        match image.save(&path) {
            Ok(()) => {
                self.viewer.editor.message =
                    Some(format!("screenshot saved to {}", path.display()));
                self.event(&format!("screenshot {}", path.display()));
            }
            Err(e) => self.viewer.editor.message = Some(format!("{}: {e}", path.display())),
        }
    }

    fn update_title(&mut self) {
        let title = format!("raysandbox: {}", self.viewer.doc.label());
        if title != self.title {
            if let Some(gfx) = &self.viewer.gfx {
                gfx.window.set_title(&title);
            }
            self.title = title;
        }
    }
}
