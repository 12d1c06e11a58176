//! The sandbox window (`raysandbox shader FILE`): the user's shader fills the
//! window, the panel holds the clock, the render scale and the generated
//! parameter controls, and the file reloads on every save. A file that does
//! not compile keeps the last good shader running under the error overlay.
//!
//! Window, GPU and egui setup, the error overlay and the controls are the
//! viewer's (`shell`, `overlay`, `controls`); the reload logic is
//! [`Session`]'s, which tests and headless renders use too.

mod actions;
mod multipass;
mod recover;
mod reload;
mod ui;

use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop, EventLoopProxy};
use winit::window::{Window, WindowId};

use super::ViewerError;
use super::controls::ClockAction;
use super::layout::LayoutReport;
use super::memory;
use super::shell::{self, EguiLayer, EventLog};
use super::watch;
use super::window::{lose_device, open_gpu_window, run_until_closed};
use crate::gpu::{EXPORT_FORMAT, Gpu, GpuTimer, Viewport};
use crate::sandbox::channels::CHANNELS;
use crate::sandbox::clock::{Clock, Tick};
use crate::sandbox::mouse::Mouse;
use crate::sandbox::render::{Canvas, PipelineBuilder, SandboxGpu, ShaderPipeline};
use crate::sandbox::watchdog::Probe;
use crate::sandbox::{self, Compiled, SandboxError, Session, ShaderArgs};

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
    /// The changed passes of a multipass shader, built.
    MultiBuilt {
        generation: u64,
        built: Box<multipass::MultiBuilt>,
        reloaded: bool,
    },
    /// SIGUSR1: drop the GPU device, as a driver reset would, to test the
    /// recovery.
    LoseDevice,
    /// The running shader's pipelines, built again on the device that
    /// replaced a lost one (the `device`-th).
    Rebuilt {
        device: u64,
        rebuilt: Box<recover::Rebuilt>,
    },
}

/// `raysandbox shader FILE` without `--render`/`--frames`: opens the window
/// and runs until it closes. A missing display or GPU is the machine's
/// failure; a shader that never compiled is the user's.
pub fn run_sandbox(args: &ShaderArgs) -> Result<(), SandboxError> {
    sandbox::require_file(&args.file)?;
    let images = args.channel_images()?;
    if sandbox::multipass::is_multipass(&args.file) {
        // Before a window opens: a folder or JSON file that is not one is
        // the user's error.
        sandbox::multipass::Project::load(&args.file).map_err(SandboxError::Input)?;
    }
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
    #[cfg(unix)]
    super::window::lose_device_on_sigusr1(event_loop.create_proxy(), || SandboxEvent::LoseDevice);
    let mut session = Session::new(&options.file);
    session.kinds = options.channel_kinds();
    let mut app = SandboxApp {
        proxy: event_loop.create_proxy(),
        events: EventLog {
            print: options.print_events,
        },
        session,
        multi: sandbox::multipass::is_multipass(&options.file)
            .then(|| multipass::Multi::new(&options.file)),
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
        devices: 0,
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
    run_until_closed(event_loop, &mut app)?;
    app.fatal.map_or(Ok(()), Err)
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
/// shown, kept on the CPU to give to every canvas made (the first, and
/// one on the device that replaces a lost one).
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
    /// A multipass shader (docs/sandbox.md, "Multipass"): its passes run
    /// instead of `session`'s, which only carries the error shown.
    multi: Option<multipass::Multi>,
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
    /// Counts the devices that replaced a lost one, so that pipelines
    /// built for one lost since are dropped.
    devices: u64,
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
            SandboxEvent::MultiBuilt {
                generation,
                built,
                reloaded,
            } => {
                if generation == self.generation {
                    self.building = false;
                    self.multipass_built(*built, reloaded);
                }
            }
            SandboxEvent::LoseDevice => {
                if let Some(gfx) = &self.gfx {
                    lose_device(&gfx.gpu);
                }
            }
            SandboxEvent::Rebuilt { device, rebuilt } => {
                if device == self.devices {
                    self.building = false;
                    self.rebuilt(*rebuilt);
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
            WindowEvent::KeyboardInput { event, .. }
                if !response.consumed && self.multi.is_some() =>
            {
                if let Some(multi) = &mut self.multi {
                    multi.key(&event);
                }
                gfx.window.request_redraw();
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

impl SandboxApp {
    fn create_graphics(&mut self, event_loop: &ActiveEventLoop) -> Result<Graphics, ViewerError> {
        let title = format!("raysandbox: {}", self.options.file.display());
        let (window, gpu, surface) =
            open_gpu_window(event_loop, &title, self.options.size, (1280.0, 720.0))?;
        Ok(self.graphics(window, gpu, surface))
    }

    /// What draws into `window` with `gpu`: at start-up, and again on a
    /// new device after a loss.
    fn graphics(&self, window: Arc<Window>, gpu: Gpu, surface: wgpu::Surface<'static>) -> Graphics {
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
        for (k, image) in self.channels.images.iter().enumerate() {
            if let Some(image) = image {
                canvas.set_channel(&gpu, &sandbox, k, Some(image));
            }
        }
        let egui = EguiLayer::new(&window, &gpu, format);
        let timer = GpuTimer::new(&gpu);
        Graphics {
            timer,
            window,
            gpu,
            surface,
            config,
            sandbox,
            builder,
            canvas,
            egui,
        }
    }

    fn request_redraw(&self) {
        if let Some(gfx) = &self.gfx {
            gfx.window.request_redraw();
        }
    }

    fn resize_canvas(&mut self) {
        let Some(gfx) = &mut self.gfx else { return };
        let size = scaled((gfx.config.width, gfx.config.height), self.scale);
        if size != gfx.canvas.size() {
            gfx.canvas.resize(&gfx.gpu, &gfx.sandbox, size);
            if let Some(multi) = &mut self.multi {
                multi.resize(&gfx.gpu, size);
            }
            self.draw_next = true;
            self.check_next = true;
        }
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(reason) = self.gfx.as_ref().and_then(|gfx| gfx.gpu.lost()) {
            self.recover_lost_device(event_loop, &reason);
            return;
        }
        let (actions, output) = self.run_ui();
        self.apply(&actions, event_loop);
        self.paint(output);
        // A device lost during the frame is replaced at the next one.
        if self
            .gfx
            .as_ref()
            .is_some_and(|gfx| gfx.gpu.lost().is_some())
        {
            self.request_redraw();
        }
    }

    /// Draws the shader (when the clock runs or something changed), shows
    /// the canvas, paints the UI over it and presents.
    fn paint(&mut self, output: egui::FullOutput) {
        let runs = self.runs();
        let Some(gfx) = &mut self.gfx else { return };
        let painting = gfx.egui.prepare(&gfx.gpu, &gfx.window, output);
        let now = Instant::now();
        let draw = runs && (!self.clock.is_paused() || self.draw_next);
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
            let pipeline = self.session.pipeline();
            let timer = gfx.timer.as_ref();
            if let Some(timer) = timer {
                timer.begin(&mut encoder);
            }
            match (&mut self.multi, pipeline) {
                (Some(multi), _) => {
                    multi.draw(
                        &gfx.gpu,
                        &gfx.sandbox,
                        &mut encoder,
                        &uniforms,
                        &mut gfx.canvas,
                    );
                }
                (None, Some(pipeline)) => gfx.canvas.draw(
                    &gfx.gpu,
                    &gfx.sandbox,
                    &mut encoder,
                    pipeline,
                    &uniforms,
                    &self.session.params,
                ),
                (None, None) => {}
            }
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
        let running = !self.clock.is_paused() && self.runs();
        self.schedule(delay, running || self.draw_next);
    }

    /// Whether a shader runs: a pipeline, or a multipass shader's Image
    /// pass.
    fn runs(&self) -> bool {
        match &self.multi {
            Some(multi) => multi.session.runs(),
            None => self.session.pipeline().is_some(),
        }
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
