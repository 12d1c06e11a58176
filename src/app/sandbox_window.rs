//! The sandbox window (`raysandbox shader FILE`): the user's shader fills the
//! window, the panel holds the clock, the render scale and the generated
//! parameter controls, and the file reloads on every save. A file that does
//! not compile keeps the last good shader running under the error overlay.
//!
//! Window, GPU and egui setup, the error overlay and the controls are the
//! viewer's (`shell`, `overlay`, `controls`); the reload logic is
//! [`Session`]'s, which tests and headless renders use too.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::{Duration, Instant};

use egui::{Key, KeyboardShortcut, Modifiers, RichText, Sense};
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop, EventLoopProxy};
use winit::window::{Window, WindowId};

use super::ViewerError;
use super::controls::{self, ClockAction};
use super::layout::{self, Layout, LayoutReport};
use super::shell::{self, EguiLayer, EventLog};
use super::watch;
use super::window::open_gpu_window;
use super::{memory, overlay};
use crate::gpu::{EXPORT_FORMAT, Gpu, GpuTimer, Timing, Viewport};
use crate::sandbox::channels::{self, CHANNELS};
use crate::sandbox::clock::{Clock, Tick};
use crate::sandbox::mouse::Mouse;
use crate::sandbox::render::{
    BuildFailed, Canvas, FRAME_LIMIT, PipelineBuilder, SandboxGpu, ShaderPipeline, build_too_slow,
};
use crate::sandbox::watchdog::Probe;
use crate::sandbox::{self, Compiled, ReloadError, SandboxError, Session, ShaderArgs};

/// The sandbox window's keyboard shortcuts, for the help window.
pub const SHORTCUTS: [(&str, &str); 10] = [
    ("Space", "pause / resume the clock"),
    ("R", "restart: time and frame back to 0"),
    ("Right arrow", "step one frame (1/60 s), paused"),
    (
        "Mouse over the image",
        "iMouse / u.mouse (drag), mouse (hover)",
    ),
    ("Wheel / right drag", "zoom / pan surfacePosition"),
    ("P", "screenshot of the image next to the shader file"),
    ("Ctrl+S", "save the parameters to FILE.params.toml"),
    ("H", "show or hide the panel"),
    ("F11 / Esc", "fullscreen / leave fullscreen"),
    ("F1 / Ctrl+Q", "this help / quit"),
];

/// Things other threads tell the event loop.
enum SandboxEvent {
    FileChanged,
    Built {
        generation: u64,
        compiled: Box<Compiled>,
        result: Result<ShaderPipeline, String>,
        /// Not the first load (see [`SandboxApp::load`]).
        reloaded: bool,
    },
}

/// `raysandbox shader FILE` without `--render`/`--frames`: opens the window
/// and runs until it closes. A missing display or GPU is the machine's
/// failure; a shader that never compiled is the user's.
pub fn run_sandbox(args: &ShaderArgs) -> Result<(), SandboxError> {
    sandbox::require_file(&args.file)?;
    let images = args.channel_images()?;
    open_window(args.clone(), images).map_err(|e| match e {
        ViewerError::Shader(m) | ViewerError::Scene(m) => SandboxError::Input(m),
        e @ ViewerError::Size(_) => SandboxError::Input(e.to_string()),
        ViewerError::NoDisplay(m) => SandboxError::Runtime(format!(
            "cannot open a window: {m}\n\
             The window needs a display (X11 or Wayland: is DISPLAY or WAYLAND_DISPLAY set?).\n\
             Without one, render headless: raysandbox shader {} --render out.png",
            args.file.display()
        )),
        ViewerError::NoGpu(m) => SandboxError::Runtime(m),
    })
}

/// Builds the pipeline of a compiled shader within [`FRAME_LIMIT`] (a
/// driver compiling for ever is reported, not waited for), then lets the
/// watchdog draw a trial frame with it: a shader that would freeze the
/// window at `size` is refused like a compile error.
fn build_checked(
    builder: &PipelineBuilder,
    probe: &Mutex<Probe>,
    compiled: &Compiled,
    size: (u32, u32),
) -> Result<ShaderPipeline, String> {
    let pipeline = match builder.build_within(compiled, FRAME_LIMIT) {
        Ok(pipeline) => pipeline,
        Err(BuildFailed::Refused(m)) => return Err(m),
        Err(BuildFailed::TooSlow) => return Err(build_too_slow(&compiled.file)),
    };
    probe
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .check(compiled, size)?;
    Ok(pipeline)
}

fn open_window(
    options: ShaderArgs,
    images: [Option<image::RgbaImage>; CHANNELS],
) -> Result<(), ViewerError> {
    let event_loop = EventLoop::<SandboxEvent>::with_user_event()
        .build()
        .map_err(|e| ViewerError::NoDisplay(e.to_string()))?;
    event_loop.set_control_flow(ControlFlow::Wait);
    let now = Instant::now();
    let paths = options
        .channel_paths()
        .map(|p| p.map(|p| p.display().to_string()).unwrap_or_default());
    let mut app = SandboxApp {
        proxy: event_loop.create_proxy(),
        events: EventLog {
            print: options.print_events,
        },
        session: Session::new(&options.file),
        probe: Arc::default(),
        clock: Clock::new(options.start_paused, now),
        scale: options.scale.clamp(0.25, 1.0),
        options,
        gfx: None,
        watch: None,
        watched_includes: Vec::new(),
        fatal: None,
        panel: PanelState {
            show: true,
            help: false,
            message: None,
        },
        mouse: Mouse::default(),
        generation: 0,
        draw_next: true,
        check_next: true,
        last_check: now,
        warning: None,
        source_warnings: Vec::new(),
        gpu_time: None,
        last_tick: None,
        after_present: Vec::new(),
        ready: false,
        building: false,
        repaint_at: None,
        channels: ChannelPanel { paths, images },
        layout: LayoutReport::default(),
    };
    event_loop
        .run_app(&mut app)
        .map_err(|e| ViewerError::NoDisplay(e.to_string()))?;
    match app.fatal {
        Some(error) => Err(error),
        None => Ok(()),
    }
}

/// The window, its surface and what draws into it.
struct Graphics {
    window: Arc<Window>,
    gpu: Gpu,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    sandbox: SandboxGpu,
    builder: PipelineBuilder,
    canvas: Canvas,
    egui: EguiLayer,
    /// Timestamps around the shader's pass, where the adapter has them.
    timer: Option<GpuTimer>,
}

/// The channel images: a path per channel in the panel, and the images
/// read at start-up, given to the canvas once it exists.
struct ChannelPanel {
    paths: [String; CHANNELS],
    images: [Option<image::RgbaImage>; CHANNELS],
}

struct PanelState {
    show: bool,
    help: bool,
    /// A short message ("screenshot saved to ...").
    message: Option<String>,
}

/// What the UI asks for in one frame.
#[derive(Debug, Default)]
struct Actions {
    clock: Option<ClockAction>,
    scale: Option<f32>,
    params_changed: bool,
    mouse_changed: bool,
    reset_params: bool,
    save_params: bool,
    load_params: bool,
    /// Load the image at the path into a channel, or (None) give it the
    /// noise back.
    channel: Option<(usize, Option<PathBuf>)>,
    screenshot: bool,
    toggle_fullscreen: bool,
    leave_fullscreen: bool,
    quit: bool,
}

struct SandboxApp {
    proxy: EventLoopProxy<SandboxEvent>,
    options: ShaderArgs,
    events: EventLog,
    session: Session,
    /// The watchdog's device for trial frames, shared with build threads.
    probe: Arc<Mutex<Probe>>,
    clock: Clock,
    scale: f32,
    gfx: Option<Graphics>,
    watch: Option<watch::Watch>,
    /// The included files `watch` watches besides the shader file.
    watched_includes: Vec<PathBuf>,
    fatal: Option<ViewerError>,
    panel: PanelState,
    mouse: Mouse,
    /// Counts reloads, so a slow build finishing after a newer one is dropped.
    generation: u64,
    /// The shader must draw the next frame even with the clock paused.
    draw_next: bool,
    /// Check the next drawn frame for NaN and empty output.
    check_next: bool,
    last_check: Instant,
    /// What the last check found.
    warning: Option<String>,
    /// The warnings of the running shader's source, as shown.
    source_warnings: Vec<String>,
    /// GPU time of the last drawn frame, submit to done.
    gpu_time: Option<Duration>,
    last_tick: Option<Tick>,
    /// Event lines to print once the next frame is on screen.
    after_present: Vec<String>,
    ready: bool,
    /// A pipeline build for the current text is running: "ready" waits for
    /// it on the first load, so the first frame shown is the shader's (or
    /// its error).
    building: bool,
    repaint_at: Option<Instant>,
    channels: ChannelPanel,
    /// Tells where the panel and the overlays are when that changes.
    layout: LayoutReport,
}

impl ApplicationHandler<SandboxEvent> for SandboxApp {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.gfx.is_some() {
            return;
        }
        match self.create_graphics(event_loop) {
            Ok(gfx) => {
                self.gfx = Some(gfx);
                self.load(false);
            }
            Err(e) => {
                self.fatal = Some(e);
                event_loop.exit();
            }
        }
    }

    fn user_event(&mut self, _: &ActiveEventLoop, event: SandboxEvent) {
        match event {
            SandboxEvent::FileChanged => self.load(true),
            SandboxEvent::Built {
                generation,
                compiled,
                result,
                reloaded,
            } => {
                if generation == self.generation {
                    self.building = false;
                    self.built(*compiled, result, reloaded);
                }
            }
        }
        // The shader a reload replaced is dropped by now.
        memory::release_freed();
        self.request_redraw();
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(gfx) = &mut self.gfx else { return };
        let response = gfx.egui.state.on_window_event(&gfx.window, &event);
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                gfx.config.width = size.width;
                gfx.config.height = size.height;
                if size.width > 0 && size.height > 0 {
                    gfx.surface.configure(&gfx.gpu.device, &gfx.config);
                }
                self.resize_canvas();
                self.request_redraw();
            }
            WindowEvent::RedrawRequested => self.redraw(event_loop),
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

impl SandboxApp {
    fn create_graphics(&mut self, event_loop: &ActiveEventLoop) -> Result<Graphics, ViewerError> {
        let title = format!("raysandbox: {}", self.options.file.display());
        let (window, gpu, surface) =
            open_gpu_window(event_loop, &title, self.options.size, (1280.0, 720.0))?;
        let format = Viewport::output_formats(&gpu, &surface)[0];
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            color_space: wgpu::SurfaceColorSpace::Auto,
            width: size.width,
            height: size.height,
            present_mode: wgpu::PresentMode::Fifo,
            desired_maximum_frame_latency: 2,
            alpha_mode: wgpu::CompositeAlphaMode::Auto,
            view_formats: vec![],
        };
        if size.width > 0 && size.height > 0 {
            surface.configure(&gpu.device, &config);
        }
        let sandbox = SandboxGpu::new(&gpu, &[format, EXPORT_FORMAT], self.options.nan_color);
        let builder = sandbox.builder(&gpu.device);
        let mut canvas = Canvas::new(
            &gpu,
            &sandbox,
            scaled((size.width, size.height), self.scale),
        );
        for (k, image) in self.channels.images.iter_mut().enumerate() {
            if let Some(image) = image.take() {
                canvas.set_channel(&gpu, &sandbox, k, Some(&image));
            }
        }
        let egui = EguiLayer::new(&window, &gpu, format);
        let timer = GpuTimer::new(&gpu);
        Ok(Graphics {
            timer,
            window,
            gpu,
            surface,
            config,
            sandbox,
            builder,
            canvas,
            egui,
        })
    }

    fn request_redraw(&self) {
        if let Some(gfx) = &self.gfx {
            gfx.window.request_redraw();
        }
    }

    /// The first load and every change of the file: compile now (naga,
    /// quick), build the pipeline on another thread while the window keeps
    /// drawing (the last good shader, if any). The first load takes the same
    /// path, so that a driver stuck on the first shader never freezes the
    /// window either.
    fn load(&mut self, reloaded: bool) {
        if self.gfx.is_none() {
            return;
        }
        let compiled = self.session.compile();
        self.watch_files();
        let compiled = match compiled {
            Ok(Some(c)) => c,
            Ok(None) => return,
            Err(e) => {
                // A build still running is for older text: drop its result.
                self.generation += 1;
                self.building = false;
                return self.failed(&e);
            }
        };
        self.generation += 1;
        let Some(gfx) = &self.gfx else { return };
        let builder = gfx.builder.clone();
        let size = gfx.canvas.size();
        let probe = Arc::clone(&self.probe);
        let proxy = self.proxy.clone();
        let generation = self.generation;
        self.building = true;
        std::thread::spawn(move || {
            let result = build_checked(&builder, &probe, &compiled, size);
            let _ = proxy.send_event(SandboxEvent::Built {
                generation,
                compiled: Box::new(compiled),
                result,
                reloaded,
            });
        });
    }

    /// The warnings of the shader's source (uniforms nothing sets,
    /// docs/sandbox.md): logged and announced once, when they change, and
    /// shown at the top of the window while the shader runs.
    fn note_source_warnings(&mut self) {
        let warnings: Vec<String> = self
            .session
            .compiled()
            .map(|c| c.warnings.iter().map(ToString::to_string).collect())
            .unwrap_or_default();
        if warnings == self.source_warnings {
            return;
        }
        for w in &warnings {
            log::warn!("{w}");
        }
        if !warnings.is_empty() {
            self.after_present
                .push(format!("shader-warning {}", warnings.len()));
        }
        self.source_warnings = warnings;
    }

    /// Watches the shader file and the files it includes (docs/sandbox.md,
    /// "Includes"): after a compile that changed the includes, the watch is
    /// made again for the new set.
    fn watch_files(&mut self) {
        let includes = self.session.includes();
        if self.watch.is_some() && self.watched_includes == includes {
            return;
        }
        self.watched_includes = includes.to_vec();
        let proxy = self.proxy.clone();
        let notify = move |_| {
            let _ = proxy.send_event(SandboxEvent::FileChanged);
        };
        match watch::watch(None, Some(&self.options.file), includes, notify) {
            Ok(w) => self.watch = Some(w),
            Err(e) => self.panel.message = Some(e),
        }
    }

    fn built(
        &mut self,
        compiled: Compiled,
        result: Result<ShaderPipeline, String>,
        reloaded: bool,
    ) {
        match result {
            Ok(pipeline) => {
                let warnings = self.session.install(compiled, pipeline);
                self.loaded(warnings, reloaded);
            }
            Err(e) => {
                let e = ReloadError::Gpu(e);
                self.session.fail(e.clone());
                self.failed(&e);
            }
        }
    }

    fn loaded(&mut self, warnings: Vec<String>, reloaded: bool) {
        for w in &warnings {
            log::warn!("{w}");
        }
        self.note_source_warnings();
        self.panel.message = warnings.into_iter().next();
        self.draw_next = true;
        self.check_next = true;
        self.warning = None;
        if reloaded {
            self.after_present.push("shader-reloaded".into());
        }
    }

    fn failed(&mut self, error: &ReloadError) {
        log::error!("{error}");
        self.after_present
            .push(format!("shader-error {}", error.location()));
    }

    fn resize_canvas(&mut self) {
        let Some(gfx) = &mut self.gfx else { return };
        let size = scaled((gfx.config.width, gfx.config.height), self.scale);
        if size != gfx.canvas.size() {
            gfx.canvas.resize(&gfx.gpu, &gfx.sandbox, size);
            self.draw_next = true;
            self.check_next = true;
        }
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let (actions, output) = self.run_ui();
        self.apply(&actions, event_loop);
        self.paint(output);
    }

    /// Runs the egui frame.
    fn run_ui(&mut self) -> (Actions, egui::FullOutput) {
        let gfx = self.gfx.as_mut().expect("drawing needs graphics");
        let mut actions = Actions::default();
        let window_size = (gfx.config.width, gfx.config.height);
        let canvas_size = gfx.canvas.size();
        let now = Instant::now();
        let tick = self.last_tick.unwrap_or(Tick {
            time: self.clock.time(now),
            delta: 0.0,
            frame: 0,
            rate: 0.0,
        });
        let timing = match gfx.timer {
            Some(_) => Timing::GpuTimestamps,
            None => Timing::SubmitToDone,
        };
        let status = format!(
            "{} x {}   {}   {}",
            canvas_size.0,
            canvas_size.1,
            self.gpu_time.map_or("-".to_string(), |t| format!(
                "{:.1} ms GPU",
                t.as_secs_f64() * 1e3
            )),
            if self.clock.is_paused() {
                String::new()
            } else {
                format!("{:.0} fps", tick.rate)
            },
        );
        let adapter = gfx.gpu.adapter.get_info().name;
        let paused = self.clock.is_paused();
        let session = &mut self.session;
        let panel = &mut self.panel;
        let mouse = &mut self.mouse;
        let scale = self.scale;
        let warning = shown_warning(self.warning.as_deref(), &self.source_warnings);
        let channel_paths = &mut self.channels.paths;
        let file = self.options.file.file_name().map_or_else(
            || self.options.file.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        let mut drawn = Layout::default();
        let output = gfx.egui.run(&gfx.window, |ui| {
            shortcuts(ui, panel, &mut actions);
            if panel.show {
                let shown = egui::Window::new(format!("raysandbox: {file}"))
                    .id(egui::Id::unique("sandbox panel"))
                    .default_pos([10.0, 10.0])
                    .default_width(280.0)
                    .resizable(true)
                    .show(ui.ctx(), |ui| {
                        let style = session.style().map_or("not compiled yet", |s| s.describe());
                        ui.weak(style);
                        ui.separator();
                        if let Some(a) = controls::clock_controls(ui, paused, &tick) {
                            actions.clock = Some(a);
                        }
                        ui.horizontal(|ui| {
                            let mut s = scale;
                            ui.label("render scale");
                            if ui
                                .add(egui::Slider::new(&mut s, 0.25..=1.0).step_by(0.05))
                                .on_hover_text(
                                    "fraction of the window resolution the shader renders at",
                                )
                                .changed()
                            {
                                actions.scale = Some(s);
                            }
                        });
                        ui.label(RichText::new(&status).monospace())
                            .on_hover_text(format!(
                                "time of the shader's pass, {}\nadapter: {adapter}",
                                timing.describe()
                            ));
                        if !session.params.is_empty() {
                            ui.separator();
                            ui.strong("Parameters");
                            egui::ScrollArea::vertical()
                                .max_height(ui.ctx().content_rect().height() * 0.6)
                                .show(ui, |ui| {
                                    actions.params_changed |=
                                        controls::params_ui(ui, &mut session.params);
                                });
                            ui.horizontal(|ui| {
                                let sidecar = session.sidecar().display().to_string();
                                if ui
                                    .button("Reset")
                                    .on_hover_text("the defaults of the source")
                                    .clicked()
                                {
                                    actions.reset_params = true;
                                }
                                if ui
                                    .button("Save")
                                    .on_hover_text(format!("to {sidecar} (Ctrl+S)"))
                                    .clicked()
                                {
                                    actions.save_params = true;
                                }
                                if ui
                                    .button("Load")
                                    .on_hover_text(format!("from {sidecar}"))
                                    .clicked()
                                {
                                    actions.load_params = true;
                                }
                            });
                        }
                        ui.separator();
                        egui::CollapsingHeader::new("Channels")
                            .default_open(false)
                            .show(ui, |ui| {
                                if let Some(a) = channels_ui(ui, channel_paths) {
                                    actions.channel = Some(a);
                                }
                            });
                        if let Some(message) = &panel.message {
                            ui.separator();
                            ui.label(message);
                        }
                        ui.weak("F1: help   H: hide this panel");
                        ui.is_sizing_pass()
                    });
                layout::note_window(ui.ctx(), "panel", shown);
            }
            egui::CentralPanel::no_frame().show(ui, |ui| {
                actions.mouse_changed = view_input(ui, mouse, window_size, canvas_size);
            });
            if let Some(error) = &session.error {
                overlay::error_window(
                    ui.ctx(),
                    "Shader error: the last good shader keeps running",
                    &error.to_string(),
                    egui::Align2::CENTER_BOTTOM,
                );
            }
            if let Some(warning) = &warning {
                overlay::warning(ui.ctx(), warning, egui::Align2::CENTER_TOP);
            }
            if panel.help {
                help_window(ui.ctx(), &mut panel.help);
            }
            drawn = layout::take(ui.ctx());
        });
        if let Some(line) = self.layout.changed(drawn) {
            self.events.event(&line);
        }
        (actions, output)
    }

    fn apply(&mut self, actions: &Actions, event_loop: &ActiveEventLoop) {
        let now = Instant::now();
        match actions.clock {
            Some(ClockAction::Toggle) => self.clock.toggle(now),
            Some(ClockAction::Restart) => {
                self.clock.restart(now);
                self.draw_next = true;
            }
            Some(ClockAction::Step) => {
                self.clock.step(now);
                self.draw_next = true;
            }
            None => {}
        }
        if let Some(scale) = actions.scale {
            self.scale = scale.clamp(0.25, 1.0);
            self.resize_canvas();
        }
        if actions.params_changed || actions.mouse_changed {
            self.draw_next = true;
        }
        if actions.reset_params {
            self.session.params.reset();
            self.draw_next = true;
        }
        if actions.save_params {
            self.panel.message = Some(match self.session.save_params() {
                Ok(path) => {
                    self.events
                        .event(&format!("params-saved {}", path.display()));
                    format!("parameters saved to {}", path.display())
                }
                Err(e) => format!("not saved: {e}"),
            });
        }
        if actions.load_params {
            self.panel.message = Some(match self.session.load_params() {
                Ok(warnings) if warnings.is_empty() => "parameters loaded".to_string(),
                Ok(warnings) => warnings.join("\n"),
                Err(e) => e,
            });
            self.draw_next = true;
        }
        if let Some((k, path)) = &actions.channel {
            self.set_channel(*k, path.as_deref());
        }
        if actions.screenshot {
            self.screenshot();
        }
        if let Some(gfx) = &self.gfx {
            if actions.toggle_fullscreen {
                shell::toggle_fullscreen(&gfx.window);
            }
            if actions.leave_fullscreen {
                gfx.window.set_fullscreen(None);
            }
        }
        if actions.quit {
            event_loop.exit();
        }
    }

    /// Gives channel `k` the image at `path` (None: the noise). An image
    /// that cannot be read leaves the channel as it was, with the error in
    /// the panel.
    fn set_channel(&mut self, k: usize, path: Option<&Path>) {
        let Some(gfx) = &mut self.gfx else { return };
        let image = match path.map(channels::load).transpose() {
            Ok(image) => image,
            Err(e) => {
                self.panel.message = Some(e);
                return;
            }
        };
        gfx.canvas
            .set_channel(&gfx.gpu, &gfx.sandbox, k, image.as_ref());
        self.panel.message = Some(match path {
            Some(path) => format!("iChannel{k}: {}", path.display()),
            None => format!("iChannel{k}: the built-in noise"),
        });
        self.events.event(&format!("channel-set {k}"));
        self.draw_next = true;
    }

    fn screenshot(&mut self) {
        let Some(gfx) = &self.gfx else { return };
        let path = screenshot_path(&self.options.file);
        self.panel.message = Some(match gfx.canvas.capture(&gfx.gpu, &gfx.sandbox) {
            Err(e) => format!("no screenshot: {e}"),
            Ok(image) => match image.save(&path) {
                Ok(()) => {
                    self.events.event(&format!("screenshot {}", path.display()));
                    format!("screenshot saved to {}", path.display())
                }
                Err(e) => format!("{}: {e}", path.display()),
            },
        });
    }

    /// Draws the shader (when the clock runs or something changed), shows
    /// the canvas, paints the UI over it and presents.
    fn paint(&mut self, output: egui::FullOutput) {
        let Some(gfx) = &mut self.gfx else { return };
        let painting = gfx.egui.prepare(&gfx.gpu, &gfx.window, output);
        let now = Instant::now();
        let draw = self.session.pipeline().is_some() && (!self.clock.is_paused() || self.draw_next);
        let frame = if gfx.config.width == 0 || gfx.config.height == 0 {
            None
        } else {
            match gfx.surface.get_current_texture() {
                wgpu::CurrentSurfaceTexture::Success(frame) => Some(frame),
                wgpu::CurrentSurfaceTexture::Suboptimal(frame) => {
                    gfx.surface.configure(&gfx.gpu.device, &gfx.config);
                    Some(frame)
                }
                wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                    gfx.surface.configure(&gfx.gpu.device, &gfx.config);
                    None
                }
                other => {
                    log::debug!("surface not ready: {other:?}");
                    None
                }
            }
        };
        let Some(frame) = frame else {
            let delay = gfx.egui.finish(painting);
            self.schedule(delay, true);
            return;
        };
        let view = frame
            .texture
            .create_view(&wgpu::TextureViewDescriptor::default());
        let mut encoder = gfx.gpu.device.create_command_encoder(&Default::default());
        if draw {
            let tick = self.clock.tick(now);
            self.last_tick = Some(tick);
            let uniforms = self.mouse.frame_uniforms(&tick, gfx.canvas.size());
            let pipeline = self.session.pipeline().expect("checked above");
            let timer = gfx.timer.as_ref();
            if let Some(timer) = timer {
                timer.begin(&mut encoder);
            }
            gfx.canvas.draw(
                &gfx.gpu,
                &gfx.sandbox,
                &mut encoder,
                pipeline,
                &uniforms,
                &self.session.params,
            );
            if let Some(timer) = timer {
                timer.end(&mut encoder);
            }
            self.mouse.just_clicked = false;
            self.draw_next = false;
        }
        gfx.canvas
            .show(&gfx.sandbox, &mut encoder, &view, gfx.config.format);
        let mut buffers = gfx.egui.paint(&gfx.gpu, &mut encoder, &view, &painting);
        buffers.push(encoder.finish());
        let start = Instant::now();
        gfx.gpu.queue.submit(buffers);
        // Waiting keeps the frame time honest and the input latency low.
        let _ = gfx.gpu.device.poll(wgpu::PollType::wait_indefinitely());
        if draw {
            self.gpu_time = match &gfx.timer {
                Some(timer) => timer.read(&gfx.gpu),
                None => Some(start.elapsed()),
            };
        }
        gfx.window.pre_present_notify();
        gfx.gpu.queue.present(frame);
        let delay = gfx.egui.finish(painting);

        // The output checks: after a reload or resize, and about once a
        // second while the clock runs.
        if draw && (self.check_next || self.last_check.elapsed() > Duration::from_secs(1)) {
            let warning = match gfx.canvas.stats(&gfx.gpu) {
                Ok(stats) => stats.warning(),
                Err(e) => Some(e.to_string()),
            };
            if warning.is_some() && warning != self.warning {
                self.events.event("output-warning");
            }
            if warning != self.warning {
                gfx.window.request_redraw();
            }
            self.warning = warning;
            self.check_next = false;
            self.last_check = Instant::now();
        }
        if !self.ready && !self.building {
            self.ready = true;
            self.events.event("ready");
        }
        for line in self.after_present.drain(..) {
            self.events.event(&line);
        }
        let running = !self.clock.is_paused() && self.session.pipeline().is_some();
        self.schedule(delay, running || self.draw_next);
    }

    fn schedule(&mut self, egui_delay: Duration, again: bool) {
        if again {
            self.request_redraw();
        } else if egui_delay < Duration::from_secs(5) {
            self.repaint_at = Some(Instant::now() + egui_delay);
        }
    }
}

/// The render resolution for a window size and scale.
fn scaled(size: (u32, u32), scale: f32) -> (u32, u32) {
    let s = |n: u32| ((n as f32 * scale).round() as u32).clamp(1, n.max(1));
    (s(size.0), s(size.1))
}

/// A screenshot path next to the shader that does not overwrite an earlier one.
fn screenshot_path(shader: &Path) -> PathBuf {
    let dir = shader.parent().map(Path::to_path_buf).unwrap_or_default();
    let stem = shader
        .file_stem()
        .map_or("shader".into(), |s| s.to_string_lossy().into_owned());
    (1..)
        .map(|n| dir.join(format!("{stem}-screenshot-{n}.png")))
        .find(|p| !p.exists())
        .expect("some screenshot number is free")
}

/// Keys work only while no text field has the keyboard.
fn shortcuts(ui: &mut egui::Ui, panel: &mut PanelState, actions: &mut Actions) {
    if ui.ctx().egui_wants_keyboard_input() {
        return;
    }
    ui.input_mut(|i| {
        if i.consume_shortcut(&KeyboardShortcut::new(Modifiers::COMMAND, Key::S)) {
            actions.save_params = true;
        }
        if i.consume_shortcut(&KeyboardShortcut::new(Modifiers::COMMAND, Key::Q)) {
            actions.quit = true;
        }
        let mut plain = |key| i.consume_key(Modifiers::NONE, key);
        if plain(Key::Space) {
            actions.clock = Some(ClockAction::Toggle);
        }
        if plain(Key::R) {
            actions.clock = Some(ClockAction::Restart);
        }
        if plain(Key::ArrowRight) {
            actions.clock = Some(ClockAction::Step);
        }
        if plain(Key::P) {
            actions.screenshot = true;
        }
        if plain(Key::H) {
            panel.show = !panel.show;
        }
        if plain(Key::F1) {
            panel.help = !panel.help;
        }
        if plain(Key::F11) {
            actions.toggle_fullscreen = true;
        }
        if plain(Key::Escape) {
            actions.leave_fullscreen = true;
        }
    });
}

/// The pointer over the image (not over the panel or an overlay), as
/// Shadertoy's and GLSL Sandbox's mouse uniforms. True when they changed.
fn view_input(
    ui: &mut egui::Ui,
    mouse: &mut Mouse,
    window: (u32, u32),
    canvas: (u32, u32),
) -> bool {
    let before = *mouse;
    let response = ui.allocate_rect(ui.max_rect(), Sense::click_and_drag());
    let ppp = ui.ctx().pixels_per_point();
    let to_canvas = |p: egui::Pos2| {
        let x = p.x * ppp * canvas.0 as f32 / window.0.max(1) as f32;
        let y = (window.1 as f32 - p.y * ppp) * canvas.1 as f32 / window.1.max(1) as f32;
        [x, y]
    };
    if let Some(p) = response.hover_pos() {
        let [x, y] = to_canvas(p);
        let uv = [x / canvas.0.max(1) as f32, y / canvas.1.max(1) as f32];
        mouse.uv = uv;
    }
    let down = response.is_pointer_button_down_on();
    if let Some(p) = response.interact_pointer_pos().filter(|_| down) {
        let position = to_canvas(p);
        if !mouse.down {
            mouse.click = position;
            mouse.just_clicked = true;
        }
        mouse.position = position;
    }
    mouse.down = down;
    let aspect = canvas.0.max(1) as f32 / canvas.1.max(1) as f32;
    if response.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if scroll != 0.0 {
            mouse.surface.zoom(0.998_f32.powf(scroll), mouse.uv, aspect);
        }
    }
    if response.dragged_by(egui::PointerButton::Secondary) {
        let delta = response.drag_delta() * ppp;
        let delta_uv = [
            delta.x / window.0.max(1) as f32,
            -delta.y / window.1.max(1) as f32,
        ];
        mouse.surface.pan(delta_uv, aspect);
    }
    *mouse != before
}

/// A row per channel: the image's path, Load, and Clear (back to the
/// noise). Returns what was asked for.
fn channels_ui(
    ui: &mut egui::Ui,
    paths: &mut [String; CHANNELS],
) -> Option<(usize, Option<PathBuf>)> {
    let mut asked = None;
    for (k, path) in paths.iter_mut().enumerate() {
        ui.horizontal(|ui| {
            ui.label(format!("iChannel{k}"));
            let edit = ui.add(
                egui::TextEdit::singleline(path)
                    .hint_text("noise (path to an image)")
                    .desired_width(150.0),
            );
            let entered = edit.lost_focus() && ui.input(|i| i.key_pressed(Key::Enter));
            if (ui.button("Load").clicked() || entered) && !path.trim().is_empty() {
                asked = Some((k, Some(PathBuf::from(path.trim()))));
            }
            if ui
                .button("Clear")
                .on_hover_text("back to the built-in noise")
                .clicked()
            {
                path.clear();
                asked = Some((k, None));
            }
        });
    }
    asked
}

fn help_window(ctx: &egui::Context, open: &mut bool) {
    egui::Window::new("Help")
        .open(open)
        .collapsible(false)
        .show(ctx, |ui| {
            egui::Grid::new("sandbox shortcuts")
                .striped(true)
                .show(ui, |ui| {
                    for (keys, what) in SHORTCUTS {
                        ui.strong(keys);
                        ui.label(what);
                        ui.end_row();
                    }
                });
            ui.separator();
            ui.label("Edit the shader file in any editor: it reloads on every save.");
            ui.label("Annotate parameters in a comment: // @slider(0, 1), @color, @checkbox, @select(a, b), @log(1e-3, 1).");
            ui.label("docs/sandbox.md lists the uniforms and the preludes.");
        });
}

/// The warning at the top of the window: what the output check found, and
/// the warnings of the shader's source.
fn shown_warning(output: Option<&str>, source: &[String]) -> Option<String> {
    let lines: Vec<&str> = output
        .into_iter()
        .chain(source.iter().map(String::as_str))
        .collect();
    (!lines.is_empty()).then(|| lines.join("\n"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn render_size_follows_the_scale() {
        assert_eq!(scaled((800, 450), 0.25), (200, 113));
        assert_eq!(scaled((800, 450), 1.0), (800, 450));
        assert_eq!(scaled((1, 1), 0.25), (1, 1));
    }
}
