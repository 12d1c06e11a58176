//! The page's canvas and event loop: the scene from the address (or the
//! bundled Whitted scene), drawn with progressive refinement. What happens is
//! told on the browser's console as `raysandbox: EVENT` lines, for people and
//! for tests.
//!
//! In the browser nothing may block: the adapter, the device and the
//! pipelines' validation arrive asynchronously, and the page hands them to
//! the event loop as a [`PageEvent`] once they are there. The editors and
//! the sandbox are the [`Workbench`]'s.

use std::path::Path;
use std::sync::Arc;

use wasm_bindgen::prelude::*;
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop, EventLoopProxy};
use winit::platform::web::{EventLoopExtWebSys, WindowAttributesExtWebSys};
use winit::window::{Window, WindowId};

use super::drop::{Dropped, DroppedFile};
use super::editor::Doc;
use super::workbench::{Outcome, WorkEvent, Workbench};
use super::{drop, link, page};
use crate::gpu::{FrameStatus, Gpu, GpuError, Pipelines, ShaderOptions, ShaderSource, Viewport};
use crate::scene::{Scene, bundled};

/// Samples per pixel the page accumulates before it stops drawing, as the
/// native viewer's progressive refinement does; `?samples=N` in the address
/// sets another limit.
const MAX_SAMPLES: u32 = 64;

/// Starts the page: called by the JavaScript glue once the module is loaded.
#[wasm_bindgen(start)]
pub fn start() {
    std::panic::set_hook(Box::new(|info| page::show_error(&info.to_string())));
    page::timing("start");
    let (scene_text, scene) = match initial_scene() {
        Ok(scene) => scene,
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
    let max_samples = page::query("samples")
        .and_then(|n| n.parse::<u32>().ok())
        .map_or(MAX_SAMPLES, |n| n.max(1));
    let proxy = event_loop.create_proxy();
    let to_page = proxy.clone();
    let work = Workbench::new(&scene_text, &scene, move |e| {
        let _ = to_page.send_event(PageEvent::Work(e));
    });
    if let Some(canvas) = page::canvas() {
        let to_page = proxy.clone();
        let listening = drop::listen(&canvas, move |file| {
            let _ = to_page.send_event(PageEvent::Dropped(file));
        });
        if let Err(e) = listening {
            page::show_error(&e);
        }
    }
    let app = Page {
        proxy,
        work,
        scene,
        max_samples,
        window: None,
        gfx: None,
        input_seen: false,
    };
    event_loop.spawn_app(app);
}

/// The scene the page opens with: the one in the address's `#scene=` link,
/// else the bundled Whitted scene, with its text. A broken link is reported
/// over the canvas and the Whitted scene shown.
fn initial_scene() -> Result<(String, Scene), String> {
    if let Some(text) = page::hash().as_deref().and_then(link::scene_in_hash) {
        let parsed = text.and_then(|text| {
            let scene = Scene::from_toml_str(&text, None).map_err(|e| e.to_string())?;
            Ok((text, scene))
        });
        match parsed {
            Ok(scene) => {
                page::event("scene from-link");
                return Ok(scene);
            }
            Err(e) => page::show_error(&format!("the link's scene cannot be shown: {e}")),
        }
    }
    let name = bundled::names()[0];
    let text = bundled::text(name).expect("a bundled scene has its text");
    page::event(&format!("scene {name}"));
    let scene = Scene::from_toml_str(text, None).map_err(|e| e.to_string())?;
    Ok((text.to_string(), scene))
}

/// What arrives asynchronously at the page's event loop.
pub enum PageEvent {
    /// The GPU objects, made once.
    Ready(Result<Box<Graphics>, String>),
    /// An edit, or a sandbox pipeline built.
    Work(WorkEvent),
    /// The tracer's pipelines built for a scene with other features.
    Pipelines(ShaderOptions, Result<Pipelines, String>),
    /// A file dropped on the canvas, read.
    Dropped(Result<DroppedFile, String>),
}

/// Everything that draws into the canvas.
pub struct Graphics {
    gpu: Gpu,
    viewport: Viewport,
    /// What the viewport's pipelines were built for.
    options: ShaderOptions,
    formats: [wgpu::TextureFormat; 2],
}

struct Page {
    proxy: EventLoopProxy<PageEvent>,
    work: Workbench,
    scene: Scene,
    max_samples: u32,
    window: Option<Arc<Window>>,
    gfx: Option<Box<Graphics>>,
    /// Whether the page handled the user's input yet (for start-up timing).
    input_seen: bool,
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
        self.window = Some(window.clone());
        let proxy = self.proxy.clone();
        let scene = self.scene.clone();
        wasm_bindgen_futures::spawn_local(async move {
            let gfx = create_graphics(window, &scene).await.map(Box::new);
            let _ = proxy.send_event(PageEvent::Ready(gfx));
        });
    }

    fn user_event(&mut self, _: &ActiveEventLoop, event: PageEvent) {
        match event {
            PageEvent::Ready(Ok(mut gfx)) => {
                page::event(&format!("adapter {}", gfx.gpu.describe()));
                page::timing("gpu");
                // The canvas may have been laid out while the device was
                // being made: draw at its size now.
                let size = self
                    .window
                    .as_ref()
                    .map(|w| (w.inner_size().width, w.inner_size().height))
                    .unwrap_or((1, 1));
                gfx.viewport.resize(&gfx.gpu, size);
                let format = gfx.viewport.surface_format();
                self.work.gpu_ready(&gfx.gpu, format, size);
                self.gfx = Some(gfx);
                self.request_redraw();
            }
            PageEvent::Ready(Err(e)) => page::show_error(&e),
            PageEvent::Work(event) => {
                let outcome = self.work.handle(event);
                self.follow(outcome);
            }
            PageEvent::Pipelines(options, built) => self.pipelines_built(options, built),
            PageEvent::Dropped(file) => self.dropped(file),
        }
    }

    fn window_event(&mut self, _: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::Resized(size) => {
                if let Some(gfx) = &mut self.gfx {
                    gfx.viewport.resize(&gfx.gpu, (size.width, size.height));
                    self.work.resize(&gfx.gpu, (size.width, size.height));
                }
                self.request_redraw();
            }
            WindowEvent::RedrawRequested => self.redraw(),
            event => {
                if !self.input_seen && self.gfx.is_some() && is_input(&event) {
                    self.input_seen = true;
                    page::timing("first-input");
                }
                self.work.pointer(&event);
            }
        }
    }
}

impl Page {
    fn request_redraw(&self) {
        if let Some(window) = &self.window {
            window.request_redraw();
        }
    }

    /// Replaces the scene (edited as text). A scene with the same features
    /// goes to the GPU buffers at once; one that needs other pipelines has
    /// them built without blocking, the last picture kept meanwhile.
    fn replace_scene(&mut self, scene: Scene) {
        self.scene = scene;
        let Some(gfx) = &mut self.gfx else { return };
        let options = ShaderOptions::for_scene(&self.scene);
        if options == gfx.options {
            gfx.viewport.set_scene(&gfx.gpu, &self.scene);
            self.request_redraw();
            return;
        }
        let (device, formats, proxy) = (gfx.gpu.device.clone(), gfx.formats, self.proxy.clone());
        wasm_bindgen_futures::spawn_local(async move {
            let source = ShaderSource::embedded();
            let built = Pipelines::with_outline_async(&device, &source, &formats, &options)
                .await
                .map_err(|e| e.to_string());
            let _ = proxy.send_event(PageEvent::Pipelines(options, built));
        });
    }

    /// Does what the workbench asks after an edit.
    fn follow(&mut self, outcome: Outcome) {
        match outcome {
            Outcome::Scene(scene) => self.replace_scene(*scene),
            Outcome::Redraw => self.request_redraw(),
            Outcome::Nothing => {}
        }
    }

    /// A file dropped on the canvas (docs/web.md, "Dropping files"): a scene
    /// or a shader opens in its editor as if typed there, so the canvas shows
    /// it; a model is added in front of the camera, as on the native window. A file that cannot be used is reported with its name (and line),
    /// and the picture kept.
    fn dropped(&mut self, file: Result<DroppedFile, String>) {
        let dropped = file.and_then(|file| {
            page::event(&format!("dropped {}", file.name));
            Ok((Dropped::of(&file)?, file.name))
        });
        match dropped {
            Ok((Dropped::Scene(text), name)) => {
                match Scene::from_toml_str(&text, Some(Path::new(&name))) {
                    Ok(_) => {
                        let outcome = self.work.open(Doc::Scene, &text);
                        self.follow(outcome);
                    }
                    Err(e) => page::show_error(&e.to_string()),
                }
            }
            Ok((Dropped::Mesh(mesh), name)) => {
                let mut scene = self.scene.clone();
                scene.add_mesh_in_view(*mesh);
                self.replace_scene(scene);
                page::event(&format!("mesh-added {name}"));
            }
            Ok((Dropped::Shader(text), _)) => {
                let outcome = self.work.open(Doc::Shader, &text);
                self.follow(outcome);
            }
            Err(e) => page::show_error(&e),
        }
    }

    /// Pipelines built for a scene: used if the scene still needs them.
    fn pipelines_built(&mut self, options: ShaderOptions, built: Result<Pipelines, String>) {
        let Some(gfx) = &mut self.gfx else { return };
        if options != ShaderOptions::for_scene(&self.scene) {
            return;
        }
        match built {
            Ok(pipelines) => {
                gfx.viewport.set_pipelines(&gfx.gpu, pipelines);
                gfx.viewport.set_scene(&gfx.gpu, &self.scene);
                gfx.options = options;
                self.request_redraw();
            }
            Err(e) => page::show_error(&e),
        }
    }

    /// Adds one sample per pixel until the limit, then stops drawing; or,
    /// while the shader is shown, draws its next frame, frame after frame.
    fn redraw(&mut self) {
        let Some(gfx) = &mut self.gfx else { return };
        if self.work.shows_shader() {
            let format = gfx.viewport.surface_format();
            let work = &mut self.work;
            gfx.viewport.frame(&gfx.gpu, 0, |encoder, view| {
                work.draw(&gfx.gpu, encoder, view, format);
                Vec::new()
            });
            self.request_redraw();
            return;
        }
        self.work.follow_scene(&self.scene);
        let before = gfx.viewport.samples();
        let new_samples = u32::from(before < self.max_samples);
        let status = gfx.viewport.frame(&gfx.gpu, new_samples, |_, _| Vec::new());
        let samples = gfx.viewport.samples();
        if status == FrameStatus::Presented && before == 0 && samples > 0 {
            let (w, h) = gfx.viewport.traced_resolution();
            page::event(&format!("first-frame {w}x{h}"));
            page::timing("first-frame");
        }
        if new_samples > 0 && samples >= self.max_samples {
            page::event(&format!("ready samples={samples}"));
        }
        if status == FrameStatus::Skipped {
            self.request_redraw();
        } else if new_samples > 0
            && let Some(window) = self.window.clone()
        {
            // The next sample once the GPU has finished this one: asked for
            // at once, samples pile up in the browser's GPU process faster
            // than SwiftShader draws them, and the page then gets no input
            // until the refinement ends (docs/web.md, "Start-up time").
            gfx.gpu
                .queue
                .on_submitted_work_done(move || window.request_redraw());
        }
    }
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

/// The WebGPU adapter and device, and the tracer's pipelines for `scene`,
/// validated before the first frame.
async fn create_graphics(window: Arc<Window>, scene: &Scene) -> Result<Graphics, String> {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
        backends: wgpu::Backends::BROWSER_WEBGPU,
        ..wgpu::InstanceDescriptor::new_without_display_handle()
    });
    let size = window.inner_size();
    let surface = instance
        .create_surface(window)
        .map_err(|e| format!("cannot draw into the canvas: {e}"))?;
    let options = wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::HighPerformance,
        force_fallback_adapter: false,
        compatible_surface: Some(&surface),
        apply_limit_buckets: false,
    };
    let gpu = Gpu::request(instance, &options)
        .await
        .map_err(|e| match e {
            // The native advice (installing a Vulkan driver) does not apply here.
            GpuError::NoAdapter(reason) => page::no_webgpu_help(&reason),
            other => other.to_string(),
        })?;
    let formats = Viewport::output_formats(&gpu, &surface);
    let source = ShaderSource::embedded();
    let options = ShaderOptions::for_scene(scene);
    let pipelines = Pipelines::with_outline_async(&gpu.device, &source, &formats, &options)
        .await
        .map_err(|e| e.to_string())?;
    let viewport = Viewport::new(&gpu, surface, (size.width, size.height), pipelines, scene);
    Ok(Graphics {
        gpu,
        viewport,
        options,
        formats,
    })
}
