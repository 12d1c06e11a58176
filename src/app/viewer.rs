//! The scene viewer's core, the same in the window program and in the web
//! page (docs/web.md): the open [`Document`], the panel's [`Editor`], the
//! orbit camera and selection, progressive refinement, and the pipeline
//! cache. What differs between the two (opening the window or canvas, how a
//! pipeline build runs off the input path, files, the address) is left to
//! the program around it, which owns the event loop.

use std::sync::Arc;

use web_time::{Duration, Instant};
use winit::window::Window;

use super::document::Document;
use super::error_view::{ErrorView, Metric};
use super::layout::{self, Layout, LayoutReport};
use super::pipelines::{self, PipelineCache};
use super::ray_tree::{GpuAnswer, PixelTree};
use super::shell::EguiLayer;
use super::status::SampleClock;
use super::ui::{self, Command, Editor, Host, Status, ViewInput};
use super::{camera_model, orbit, panel};
use crate::gpu::{
    ColourBar, FrameStatus, Gpu, JobWaker, LineOverlay, Pipelines, Refine, ShaderOptions,
    ShaderSource, TexelRead, View, Viewport,
};
use crate::reference;
use crate::scene::{Camera, NamedOption, Scene, SceneError};
use crate::shader_params::SourceParams;

/// Width of the selection outline in logical pixels (scaled by the window's
/// DPI factor).
const OUTLINE_WIDTH: f64 = 2.0;

/// Width of the ray tree's lines over the picture in logical pixels.
const RAY_WIDTH: f64 = 2.0;

/// How often a sample still being traced tells where its time went so far
/// (`refining ...`): a heavy scene's first sample can take minutes.
const PROGRESS_EVERY: Duration = Duration::from_secs(10);

/// While the page refines between frames, the picture and the status line
/// are presented again at least this often (the rows traced so far, during
/// a first sample), besides once per sample and whenever input or the UI
/// ask: a frame of the page at 1280 x 900 costs SwiftShader more than a
/// job (docs/web.md, "Where a sample's time goes").
const REPAINT_EVERY: Duration = Duration::from_secs(1);

/// Pipelines to build for `options` from `source`, handed to the program's
/// worker: a thread natively, a future in the browser. The worker reports
/// the [`pipelines::Built`] result through its event loop to
/// [`Viewer::pipelines_built`].
pub struct BuildRequest {
    pub device: wgpu::Device,
    pub source: ShaderSource,
    pub formats: [wgpu::TextureFormat; 2],
    pub options: ShaderOptions,
    pub generation: u64,
}

impl BuildRequest {
    /// Builds the pipelines; natively this future is ready at once (the
    /// worker blocks on it), in the browser it waits for wgpu's validation.
    pub async fn build(self) -> pipelines::Built {
        let result =
            Pipelines::with_outline_async(&self.device, &self.source, &self.formats, &self.options)
                .await
                .map_err(|e| e.to_string());
        pipelines::Built {
            generation: self.generation,
            options: self.options,
            result,
        }
    }
}

/// The window (or canvas) and everything that draws into it.
pub struct Graphics {
    pub window: Arc<Window>,
    pub gpu: Gpu,
    pub viewport: Viewport,
    pub pipelines: PipelineCache,
    pub egui: EguiLayer,
    /// A pixel's ray tree drawn over the picture (docs/ray-tree.md).
    pub lines: LineOverlay,
}

/// What the program around the viewer provides.
pub struct Platform {
    /// Tells scripts and tests what happened (`ready samples=N`, ...).
    pub event: Box<dyn Fn(&str)>,
    /// Starts a pipeline build off the input path.
    pub build: Box<dyn Fn(BuildRequest)>,
    /// In the browser, what wakes the page when the GPU has done a job: the
    /// page then calls [`Viewer::refine_between_frames`], which submits the
    /// next job without a frame. Natively `None`: a job is waited for
    /// where it is submitted, one a frame.
    pub job_done: Option<JobWaker>,
}

pub struct Viewer {
    pub doc: Document,
    pub editor: Editor,
    /// The shader source of the pipelines in use (the last good one).
    pub shaders: ShaderSource,
    /// Its annotated constants: the "Shader parameters" of the panel, whose
    /// values are written into the source the pipelines are built from.
    pub shader_params: SourceParams,
    /// New shaders or parameter values validated; their pipelines are being built.
    reload_pending: bool,
    pub gfx: Option<Graphics>,
    platform: Platform,
    /// Eye-target distance when the current drag or zoom started.
    drag_start_distance: Option<f64>,
    /// A frame has been presented (the `first-frame` event is told once).
    presented: bool,
    /// The `ready` event was told for the picture on screen; a traced sample
    /// (moving or refining) makes it new again.
    settled: bool,
    /// When egui asked to be drawn again (animations, tooltips).
    pub repaint_at: Option<Instant>,
    /// Tells where the panel and its parts are when that changes.
    layout: LayoutReport,
    /// The wall time of a sample, for the status line.
    sample_clock: SampleClock,
    /// When the sample in progress last told where its time went.
    progress_told: Option<Instant>,
    /// While a resting picture refines in the page: the samples it
    /// refines to, job after job between frames.
    between_frames: Option<u32>,
    /// The samples in the picture last presented, and when.
    shown_samples: u32,
    shown_at: Option<Instant>,
    /// A scene whose pipelines are being built: it reaches the GPU with
    /// them, and the last picture stays meanwhile (not the new scene drawn
    /// by pipelines that lack its shape kinds).
    deferred: Option<Scene>,
    /// The feature set of the pipelines drawing now (a shader reload keeps
    /// it: the old shader draws the scene until the new one is built).
    drawing: Option<ShaderOptions>,
    /// The error view's f64 reference, traced beside the window.
    error_view: ErrorView,
    /// A scalar view's quantities on their way back, to fit its colour bar
    /// to: mapped at once natively, a frame or more later in the page.
    bar_quantities: Option<TexelRead>,
    /// The viewport's picture ([`Viewport::picture`]) that a scalar view's
    /// colour bar was last fitted to (or the error view started on): any
    /// other picture waits for the first frame presenting a sample of it,
    /// whether that frame traced it or the page's jobs between frames did.
    fitted_picture: Option<u64>,
    /// Ray trees asked for so far (numbers the trees).
    trees_asked: u64,
    /// What the line overlay holds ([`Lines`]); `None`: nothing.
    lines_for: Option<Lines>,
    /// The selected pixels' camera rays in the camera model.
    pixel_rays: camera_model::PixelRays,
    /// The GPU's answer for the tree shown came in this frame: told once
    /// the frame is on screen.
    tree_answered: bool,
    /// Traces the GPU's trees off the input path.
    #[cfg(not(target_arch = "wasm32"))]
    tree_worker: super::ray_tree::worker::Worker,
}

/// What the line overlay draws: the ray tree `tree` and, from an
/// observer's view, the camera model of `model` with the camera rays of
/// `pixels`, projected with `picture` (the camera the picture is traced
/// from) for a window of `size`.
#[derive(Clone, PartialEq)]
struct Lines {
    tree: Option<u64>,
    model: Option<Camera>,
    pixels: Vec<(u32, u32)>,
    picture: Camera,
    size: (u32, u32),
}

/// The state a frame starts from, to tell what the frame's UI changed.
pub struct FrameStart {
    scene: Scene,
    observer: Option<Camera>,
    min_weight: f64,
    shown: View,
    /// When the frame began, for a moving frame's time in all.
    at: Instant,
}

/// What a frame's UI produced, before the program runs its commands.
pub struct FrameUi {
    pub commands: Vec<Command>,
    input: ViewInput,
    output: egui::FullOutput,
}

impl Viewer {
    pub fn new(
        doc: Document,
        shaders: ShaderSource,
        shader_params: SourceParams,
        platform: Platform,
    ) -> Self {
        Viewer {
            doc,
            editor: Editor::default(),
            shaders,
            shader_params,
            reload_pending: false,
            gfx: None,
            platform,
            drag_start_distance: None,
            presented: false,
            settled: false,
            repaint_at: None,
            layout: LayoutReport::default(),
            sample_clock: SampleClock::default(),
            progress_told: None,
            between_frames: None,
            shown_samples: 0,
            shown_at: None,
            deferred: None,
            drawing: None,
            error_view: ErrorView::default(),
            bar_quantities: None,
            fitted_picture: None,
            trees_asked: 0,
            lines_for: None,
            pixel_rays: camera_model::PixelRays::default(),
            tree_answered: false,
            #[cfg(not(target_arch = "wasm32"))]
            tree_worker: Default::default(),
        }
    }

    pub fn event(&self, line: &str) {
        (self.platform.event)(line);
    }

    /// The source the first pipelines are built from, and their options.
    pub fn first_build(&self) -> (ShaderSource, ShaderOptions) {
        (
            self.shader_params.apply(&self.shaders),
            self.wanted_options(),
        )
    }

    /// The pipelines the scene and the view need: the scene's specialised
    /// ones, for the view shown (docs/views.md).
    fn wanted_options(&self) -> ShaderOptions {
        ShaderOptions {
            view: self.editor.view.shown.traced(),
            ..ShaderOptions::for_scene(&self.doc.scene)
        }
    }

    /// Starts drawing into `window` with the pipelines of
    /// [`Viewer::first_build`].
    pub fn attach(
        &mut self,
        window: Arc<Window>,
        gpu: Gpu,
        surface: wgpu::Surface<'static>,
        first: Pipelines,
    ) {
        let (source, options) = self.first_build();
        let cache = PipelineCache::new(source, options.clone(), first.clone());
        let size = window.inner_size();
        let shown = self.shown_scene();
        let mut viewport = Viewport::new(&gpu, surface, (size.width, size.height), first, &shown);
        viewport.wake_after_jobs(self.platform.job_done.clone());
        let egui = EguiLayer::new(&window, &gpu, viewport.surface_format());
        let lines = LineOverlay::new(&gpu.device, viewport.surface_format());
        self.gfx = Some(Graphics {
            window,
            gpu,
            viewport,
            pipelines: cache,
            egui,
            lines,
        });
        self.lines_for = None;
        #[cfg(not(target_arch = "wasm32"))]
        self.tree_worker.forget();
        self.deferred = None;
        // A new viewport numbers its pictures from the start again.
        self.fitted_picture = None;
        self.error_view.cancel();
        self.drawing = Some(options);
        self.upload_scene(&shown);
    }

    /// Gives the viewport a scene with new shapes; one the GPU's buffers
    /// cannot hold is reported and the last one that fitted stays.
    fn upload_scene(&mut self, shown: &Scene) {
        let Some(gfx) = &mut self.gfx else { return };
        match gfx.viewport.set_scene(&gfx.gpu, shown) {
            Ok(()) => self.editor.gpu_error = None,
            Err(e) => {
                log::error!("{e}");
                self.editor.gpu_error = Some(e.to_string());
                self.event(&format!("gpu-error {}", e.limit));
            }
        }
    }

    /// After [`Viewer::attach`] on a new device: builds of the pipeline
    /// cache of `generation` (the lost device's) are dropped when they
    /// finish; the first build already holds the current shaders.
    pub fn follow_generation(&mut self, generation: u64) {
        if let Some(gfx) = &mut self.gfx {
            gfx.pipelines.follow(generation);
        }
        self.reload_pending = false;
        self.ensure_pipelines();
    }

    pub fn request_redraw(&self) {
        if let Some(gfx) = &self.gfx {
            gfx.window.request_redraw();
        }
    }

    pub fn resize(&mut self, size: winit::dpi::PhysicalSize<u32>) {
        if let Some(gfx) = &mut self.gfx {
            gfx.viewport.resize(&gfx.gpu, (size.width, size.height));
            gfx.window.request_redraw();
        }
    }

    /// Builds pipelines from the current source and parameter values off
    /// the input path; the pipelines in use keep drawing until they are ready.
    pub fn build_pipelines(&mut self) {
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
        let wanted = self.wanted_options();
        let Some(gfx) = &mut self.gfx else { return };
        if gfx.pipelines.current.as_ref() == Some(&wanted) {
            return;
        }
        let device = gfx.gpu.device.clone();
        let formats = [gfx.viewport.surface_format(), crate::gpu::EXPORT_FORMAT];
        let build = &self.platform.build;
        let spawn = |source, generation| {
            build(BuildRequest {
                device,
                source,
                formats,
                options: wanted.clone(),
                generation,
            });
        };
        if let Some(pipelines) = gfx.pipelines.get_or_build(wanted.clone(), spawn) {
            // The scene that waited for them first, with the pipelines it
            // was drawn with so far, as for any new scene.
            if let Some(scene) = self.deferred.take() {
                self.upload_scene(&scene);
            }
            let Some(gfx) = &mut self.gfx else { return };
            gfx.viewport.set_pipelines(&gfx.gpu, pipelines);
            gfx.pipelines.current = Some(wanted.clone());
            self.drawing = Some(wanted);
            if std::mem::take(&mut self.reload_pending) {
                self.editor.shader_error = None;
                self.event("shaders-reloaded");
            }
        }
    }

    /// Whether pipelines for the scene's feature set are drawing (after
    /// asking for them: they may be built already).
    fn pipelines_ready(&mut self) -> bool {
        self.ensure_pipelines();
        self.drawing == Some(self.wanted_options())
    }

    /// A build started by the worker has finished.
    pub fn pipelines_built(&mut self, built: pipelines::Built) {
        let Some(gfx) = &mut self.gfx else { return };
        let options = built.options.clone();
        if let Err(e) = gfx.pipelines.finished(built) {
            log::error!("{e}");
            self.editor.shader_error = Some(e);
            self.reload_pending = false;
            self.event("shader-error");
            // The scene may have moved on to another feature set meanwhile
            // (one build runs at a time): build that one, never the failed
            // one again. A scene whose own build failed is drawn as the
            // pipelines drawing can (the error says why it looks wrong).
            if self.wanted_options() != options {
                self.ensure_pipelines();
            } else if let Some(scene) = self.deferred.take() {
                self.upload_scene(&scene);
            }
            return;
        }
        self.ensure_pipelines();
        self.request_redraw();
    }

    /// Tells the viewport what changed: only the view (camera, render
    /// settings: the globals) or the shapes too (buffers and BVH rebuilt).
    /// A new feature set gets its own pipelines, and the scene waits for
    /// them (the last picture stays, the status line says "compiling").
    pub fn scene_changed(&mut self, before: Option<&Scene>) {
        self.error_view.cancel();
        let shown = self.shown_scene();
        if self.gfx.is_some() && !self.pipelines_ready() {
            self.deferred = Some(shown);
            return;
        }
        let waited = self.deferred.take().is_some();
        match before {
            Some(old) if !waited && same_shapes(old, &self.doc.scene) => {
                if let Some(gfx) = &mut self.gfx {
                    gfx.viewport.set_view(&shown);
                }
            }
            _ => self.upload_scene(&shown),
        }
    }

    /// The scene as the viewer draws it: [`Viewer::floored_scene`], seen
    /// by the observer while the camera model is shown.
    fn shown_scene(&self) -> Scene {
        let mut scene = self.floored_scene();
        if let Some(observer) = &self.editor.observer {
            scene.camera = observer.clone();
        }
        scene
    }

    /// The file's scene with `min_weight` raised to the viewer's floor (the
    /// panel's "min weight").
    fn floored_scene(&self) -> Scene {
        let mut scene = self.doc.scene.clone();
        let floor = self.editor.view.min_weight;
        scene.render.min_weight = scene.render.min_weight.max(floor);
        scene
    }

    /// Replaces the document (unless it has unsaved edits); returns whether
    /// it did.
    pub fn open(&mut self, doc: Result<Document, SceneError>) -> bool {
        if self.doc.is_dirty() {
            self.editor.message =
                Some("unsaved edits: save them (Ctrl+S) before opening another scene".into());
            return false;
        }
        match doc {
            Ok(doc) => {
                self.replace(doc);
                true
            }
            Err(e) => {
                self.editor.message = Some(e.to_string());
                false
            }
        }
    }

    /// The part of a frame before the program runs the UI's commands.
    pub fn begin_frame(&mut self, host: &Host) -> (FrameStart, FrameUi) {
        let start = FrameStart {
            scene: self.doc.scene.clone(),
            observer: self.editor.observer.clone(),
            min_weight: self.editor.view.min_weight,
            shown: self.editor.view.shown,
            at: Instant::now(),
        };
        self.take_tree_answer();
        let gfx = self.gfx.as_mut().expect("drawing needs graphics");
        let status = Status {
            frame_time: gfx.viewport.last_frame_time(),
            timing: gfx.viewport.timing(),
            sample_wall: self.sample_clock.every(),
            samples: gfx.viewport.samples(),
            resolution: gfx.viewport.traced_resolution(),
            scale: gfx.viewport.scale(),
            adapter: gfx.gpu.adapter.get_info().name,
            compiling: gfx.pipelines.building(),
        };
        let mut result = (Vec::new(), ViewInput::default());
        let mut drawn = Layout::default();
        let output = gfx.egui.run(&gfx.window, |ui| {
            result = ui::draw(
                ui,
                &mut self.doc,
                &mut self.editor,
                &mut self.shader_params.params,
                &status,
                host,
            );
            drawn = layout::take(ui.ctx());
        });
        if let Some(line) = self.layout.changed(drawn) {
            (self.platform.event)(&line);
        }
        let (commands, input) = result;
        (
            start,
            FrameUi {
                commands,
                input,
                output,
            },
        )
    }

    /// The part of a frame after the commands: the mouse over the image,
    /// the changes to the GPU, painting. Returns whether the scene changed
    /// (its camera included).
    pub fn end_frame(&mut self, start: FrameStart, ui: FrameUi) -> bool {
        let picked = self.apply_view_input(&ui.input);
        let changed = self.doc.scene != start.scene;
        let observed = self.editor.observer != start.observer;
        if changed || observed || self.editor.view.min_weight != start.min_weight {
            self.scene_changed(Some(&start.scene));
        }
        let shown = self.editor.view.shown;
        let between_metrics = shown != start.shown && start.shown.is_error() && shown.is_error();
        let picture = self.gfx.as_ref().map(|gfx| gfx.viewport.picture());
        if between_metrics && self.error_view.show_as(error_metric(shown), picture) {
            // The same reference, shown the other way.
            self.event(&format!("view-shown {}", shown.name()));
            if let Some(gfx) = &self.gfx {
                gfx.window.request_redraw();
            }
        } else if shown != start.shown {
            self.editor.view.colour_bar = None;
            self.bar_quantities = None;
            self.editor.view.progress = None;
            self.error_view.cancel();
            // A view that traces as the last one did (the error view's two
            // metrics, its reference not yet at every pixel) builds no
            // pipelines, which would start the picture again: the last
            // one's heat map took the radiance's place.
            let traced = self.editor.view.shown.traced();
            if let Some(gfx) = &mut self.gfx
                && self.drawing.as_ref().is_some_and(|d| d.view == traced)
            {
                gfx.viewport.restart();
            }
            self.event(&format!("view-shown {}", self.editor.view.shown.name()));
            self.ensure_pipelines();
        }
        let moving = ui.input.dragging || ui.input.widget_dragging;
        let had_tree = self.lines_for.as_ref().and_then(|l| l.tree).is_some();
        self.project_lines();
        self.paint(ui.output, moving, start.at);
        if picked {
            // Once the frame with its outline is on screen.
            self.event(&format!("selected {:?}", self.editor.panel.selection));
        }
        if let Some(tree) = &self.editor.ray_tree
            && std::mem::take(&mut self.tree_answered)
        {
            self.event(&tree.event());
        }
        if had_tree && self.lines_for.as_ref().and_then(|l| l.tree).is_none() {
            self.event("ray-tree-cleared");
        }
        if self.editor.observer.is_some() != start.observer.is_some() {
            self.observer_toggled();
        }
        changed
    }

    /// Says in the status line what the observer's view shows, once it is
    /// on screen.
    fn observer_toggled(&mut self) {
        let size = self.lines_for.as_ref().map_or((0, 0), |l| l.size);
        if self.editor.observer.is_some() {
            self.editor.message = Some(format!(
                "observer's view (C: back): the scene's camera, its film of {} x {} pixels \
                 (grid every {} pixels) and frustum; orbit to look around it",
                size.0,
                size.1,
                camera_model::grid_step(size)
            ));
            self.event("observer on");
        } else {
            self.editor.message = None;
            self.event("observer off");
        }
    }

    /// The tree of the pixel at `(x, y)` (window pixels): the reference's
    /// at once, the GPU's from the worker (natively; the page has none).
    fn ask_ray_tree(&mut self, (x, y): (f64, f64)) {
        let Some(gfx) = &self.gfx else { return };
        let size = gfx.window.inner_size();
        let size = (size.width, size.height);
        if x < 0.0 || y < 0.0 || size.0 == 0 || size.1 == 0 {
            return;
        }
        let pixel = ((x as u32).min(size.0 - 1), (y as u32).min(size.1 - 1));
        self.trees_asked += 1;
        let scene = self.floored_scene();
        let tree = PixelTree::new(&scene, size, pixel, self.trees_asked);
        #[cfg(not(target_arch = "wasm32"))]
        {
            let window = gfx.window.clone();
            let request = super::ray_tree::worker::Request {
                gpu: gfx.gpu.clone(),
                source: self.shader_params.apply(&self.shaders),
                options: ShaderOptions::for_scene(&scene),
                scene,
                size,
                pixel,
                number: self.trees_asked,
            };
            self.tree_worker
                .trace(request, move || window.request_redraw());
        }
        #[cfg(target_arch = "wasm32")]
        let tree = {
            let mut tree = tree;
            tree.answered(GpuAnswer::Missing(
                "the page cannot wait for the GPU's readback; the window program shows it".into(),
            ));
            tree
        };
        self.editor.message = Some(tree.summary());
        self.event(&format!("ray-tree-asked {},{}", pixel.0, pixel.1));
        self.editor.ray_tree = Some(tree);
        camera_model::select(&mut self.editor.pixels, pixel);
    }

    /// Takes the worker's answer for the tree shown (one for a tree
    /// forgotten or replaced since is dropped).
    fn take_tree_answer(&mut self) {
        #[cfg(not(target_arch = "wasm32"))]
        while let Some((number, answer)) = self.tree_worker.take() {
            let Some(tree) = &mut self.editor.ray_tree else {
                continue;
            };
            if tree.number == number && tree.gpu == GpuAnswer::Tracing {
                if let GpuAnswer::Missing(why) = &answer {
                    log::error!("the GPU's ray tree: {why}");
                }
                tree.answered(answer);
                self.editor.message = Some(tree.summary());
                self.tree_answered = true;
            }
        }
    }

    /// Projects the tree's rays (and the camera model, from an observer's
    /// view) with the camera of the picture, when the tree, a camera or
    /// the window changed: they stay where they are in the scene while the
    /// camera orbits.
    fn project_lines(&mut self) {
        let Some(gfx) = &mut self.gfx else { return };
        let size = gfx.window.inner_size();
        let size = (size.width, size.height);
        let tree = self.editor.ray_tree.as_ref();
        let model = self
            .editor
            .observer
            .is_some()
            .then(|| self.doc.scene.camera.clone());
        let picture = self.editor.observer.as_ref();
        let wanted = (tree.is_some() || model.is_some()).then(|| Lines {
            tree: tree.map(|t| t.number),
            model: model.clone(),
            pixels: self.editor.pixels.clone(),
            picture: picture.unwrap_or(&self.doc.scene.camera).clone(),
            size,
        });
        if wanted == self.lines_for {
            return;
        }
        let mut segments = tree.map(|t| t.segments.clone()).unwrap_or_default();
        if let Some(model) = &model {
            segments.extend(camera_model::segments(model, size));
            let scene = &self.doc.scene;
            segments.extend(self.pixel_rays.segments(scene, &self.editor.pixels, size));
        }
        let width = (RAY_WIDTH * gfx.window.scale_factor()).round() as u32;
        let camera = picture.unwrap_or(&self.doc.scene.camera);
        gfx.lines
            .set(&gfx.gpu.device, camera, (size, width), &segments);
        self.lines_for = wanted;
        gfx.window.request_redraw();
    }

    /// Shows `doc` instead of the document open now, unsaved edits or not
    /// (the web page has no files to save them to).
    pub fn replace(&mut self, doc: Document) {
        self.doc = doc;
        self.editor.panel.selection = None;
        self.editor.scene_error = None;
        self.scene_changed(None);
        self.editor.message = Some(format!("opened {}", self.doc.label()));
    }

    /// Puts the camera back where the scene file has it.
    pub fn reset_camera(&mut self) {
        self.doc.scene.camera = self.doc.saved_camera().clone();
    }

    /// Mouse input over the image moves the camera or picks an object;
    /// returns whether it picked.
    fn apply_view_input(&mut self, input: &ViewInput) -> bool {
        let Some(gfx) = &self.gfx else { return false };
        let size = gfx.window.inner_size();
        // From an observer's view the mouse moves the observer; the
        // scene's camera stays as the panel has it.
        let camera = match &mut self.editor.observer {
            Some(observer) => observer,
            None => &mut self.doc.scene.camera,
        };
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
        if let Some(at) = input.ray_tree {
            self.ask_ray_tree(at);
        }
        let click = input.click.or(input.double_click);
        if let Some((x, y)) = click {
            let scene = reference::PreparedScene::new(&self.shown_scene());
            let hit = reference::pick(&scene, size.width, size.height, x, y);
            self.editor.panel.selection = hit.map(|(id, _)| id);
            if let (Some((_, point)), Some(_)) = (hit, input.double_click) {
                let camera = match &mut self.editor.observer {
                    Some(observer) => observer,
                    None => &mut self.doc.scene.camera,
                };
                orbit::recenter(camera, point);
            }
        }
        click.is_some()
    }

    /// Draws the image and the UI; keeps refining while samples are missing.
    /// While the view moves, one sample per pixel at the moving scale
    /// ([`Viewer::moving_scale`]); full resolution once it stops. `start`:
    /// when this redraw began, for the moving frame's time in all.
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
        // A view looks at the ray through each pixel centre: one sample.
        let shown = self.editor.view.shown;
        let max_samples = if dragging || shown != View::Shaded {
            1
        } else {
            self.editor.view.max_samples
        };
        let new_samples = u32::from(gfx.viewport.samples() < max_samples);
        // A moving view is traced whole at its moving scale; a resting one
        // refines in short jobs (docs/performance.md, "Short GPU jobs").
        let refine = match (new_samples, dragging) {
            (0, _) => Refine::Show,
            (_, true) => Refine::WholeSample,
            (_, false) => Refine::NextJob,
        };

        let painting = gfx.egui.prepare(&gfx.gpu, &gfx.window, output);
        let egui = &mut gfx.egui;
        let lines = &gfx.lines;
        let gpu = &gfx.gpu;
        gfx.window.pre_present_notify();
        // The ray tree over the picture, under the UI.
        let status = gfx.viewport.frame(gpu, refine, |encoder, view| {
            lines.draw(encoder, view);
            egui.paint(gpu, encoder, view, &painting)
        });
        let delay = gfx.egui.finish(painting);
        // After a frame that added samples, draw once more: either the next
        // sample, or (refinement done) only the display pass, so the status
        // line shows the final count. Then nothing is drawn until something
        // changes, and an idle window costs no CPU. In the page a resting
        // picture refines between frames instead, job after job as the GPU
        // reports each done ([`Viewer::refine_between_frames`]), in every
        // view; other frames wait for the GPU too, so that they never queue
        // up there.
        let samples = gfx.viewport.samples();
        let between = refine == Refine::NextJob && self.platform.job_done.is_some();
        self.between_frames = between.then_some(max_samples);
        if status == FrameStatus::Skipped {
            gfx.window.request_redraw();
        } else if self.between_frames.is_some() {
            // The next job goes when the GPU has done the one on its way.
        } else if new_samples > 0 && self.platform.job_done.is_some() {
            let window = gfx.window.clone();
            gfx.gpu
                .queue
                .on_submitted_work_done(move || window.request_redraw());
        } else if new_samples > 0 {
            gfx.window.request_redraw();
        }
        if status == FrameStatus::Presented {
            self.shown_samples = samples;
            self.shown_at = Some(Instant::now());
        }
        let resolution = gfx.viewport.traced_resolution();
        let traced = status == FrameStatus::Presented && new_samples > 0;
        let moving_frame = (dragging && traced)
            .then(|| gfx.viewport.last_frame_time())
            .flatten()
            .map(|time| (time, gfx.viewport.scale()));
        if new_samples > 0 {
            self.settled = false;
        }
        self.tell_sample_times();
        let Some(gfx) = &mut self.gfx else { return };
        self.sample_clock.update(samples, Instant::now());
        // The first frame that presents the view's sample fits its bar, once
        // the view's own pipelines traced it (not the last view's picture,
        // kept while they build).
        let presented = status == FrameStatus::Presented;
        let own = self
            .drawing
            .as_ref()
            .is_some_and(|d| d.view == shown.traced());
        let picture = gfx.viewport.picture();
        let fit_pending = self.fitted_picture != Some(picture);
        let fitted = shown.scalar() && presented && fit_pending && !dragging && samples > 0 && own;
        if fitted {
            self.fitted_picture = Some(picture);
        }
        if fitted && !shown.is_error() {
            self.bar_quantities = Some(gfx.viewport.start_read_sums(&gfx.gpu));
            // Natively this maps the copy at once; in the page a later
            // frame takes the quantities.
            if let Err(e) = gfx.gpu.wait() {
                log::error!("colour bar: {e}");
            }
        }
        let bar_fitted = take_colour_bar(&mut self.bar_quantities, gfx);
        if let Some(bar) = bar_fitted {
            self.editor.view.colour_bar = bar;
        }
        // Not while a scene waits for its pipelines (the picture is the
        // last scene's), nor before the colour bar is fitted and shown.
        let unfitted = shown.scalar() && fit_pending && own;
        // In the page, not before the last job's time is back either (its
        // sample's time is told first).
        let timed = !gfx.viewport.job_in_flight();
        let ready = !self.settled
            && timed
            && samples >= max_samples
            && !dragging
            && !fitted
            && !unfitted
            && bar_fitted.is_none()
            && self.bar_quantities.is_none()
            && self.deferred.is_none();
        let jobs = ready.then(|| (gfx.viewport.take_jobs(), gfx.viewport.timing()));
        if let Some(Some(bar)) = bar_fitted {
            let [lo, hi] = bar.range;
            self.event(&format!("colour-bar {lo} {hi}"));
        }
        if status == FrameStatus::Presented && samples > 0 && !self.presented {
            self.presented = true;
            let (w, h) = resolution;
            self.event(&format!("first-frame {w}x{h}"));
        }
        if let Some((time, scale)) = moving_frame {
            let wall = start.elapsed();
            self.editor.view.moving_frame = Some(panel::MovingFrame { time, wall, scale });
            self.event(&format!(
                "moving-frame ms={:.1} wall_ms={:.1} scale={scale:.3}",
                time.as_secs_f64() * 1e3,
                wall.as_secs_f64() * 1e3
            ));
        }
        // Ready once the view rests with all its samples. A drag whose
        // moving frames were already at full scale leaves nothing to refine
        // with one sample per pixel: the release itself makes it ready.
        if let Some((jobs, timing)) = jobs {
            self.settled = true;
            let ms = |d: Duration| d.as_secs_f64() * 1e3;
            let (longest, sized) = (jobs.longest, jobs.longest_sized);
            self.event(&format!(
                "ready samples={samples} jobs={} longest_job_ms={:.1} \
                 longest_job_predicted_ms={:.1} longest_job_pixels={} \
                 longest_sized_job_ms={:.1} longest_sized_job_budget_ms={:.1} timing={}",
                jobs.count,
                ms(longest.time),
                ms(longest.predicted),
                longest.pixels,
                ms(sized.time),
                ms(sized.budget),
                timing.name()
            ));
        }
        if delay < Duration::from_secs(5) {
            self.repaint_at = Some(Instant::now() + delay);
        }
        if shown.is_error() {
            self.error_view_frame(fitted);
        }
    }

    /// In the page, once the GPU has done a job (the platform's
    /// [`Platform::job_done`]): the next job of a resting picture's sample,
    /// at once and without a frame. A frame of the page (the display pass,
    /// the outline, the panel) at 1280 x 900 costs SwiftShader more than a
    /// job, and waiting for the next animation frame for each job left the
    /// GPU idle; so the picture is presented again only when a sample is
    /// done, every [`REPAINT_EVERY`] meanwhile, and when input or the UI
    /// ask (docs/web.md, "Where a sample's time goes"). Input is handled
    /// between two jobs, as before.
    pub fn refine_between_frames(&mut self) {
        let Some(gfx) = &mut self.gfx else { return };
        if gfx.viewport.job_in_flight() {
            return;
        }
        let Some(max_samples) = self.between_frames else {
            // The time of a job that a frame submitted came back after a
            // later frame had nothing more to refine: its sample's time is
            // told now, and a frame says `ready`, which waits for it.
            gfx.window.request_redraw();
            self.tell_sample_times();
            return;
        };
        let samples = gfx.viewport.samples();
        let stale = self.shown_at.is_none_or(|at| at.elapsed() >= REPAINT_EVERY);
        if samples != self.shown_samples || samples >= max_samples || stale {
            gfx.window.request_redraw();
        }
        if samples < max_samples {
            gfx.viewport.next_job(&gfx.gpu);
            self.settled = false;
        }
        self.tell_sample_times();
    }

    /// Tells where a sample's time went (docs/web.md, "Where a sample's
    /// time goes"): `sample-time` once it is traced to its end, and every
    /// [`PROGRESS_EVERY`] while it is traced, `refining`.
    fn tell_sample_times(&mut self) {
        let Some(gfx) = &mut self.gfx else { return };
        let samples = gfx.viewport.samples();
        let finished = gfx.viewport.take_finished_sample();
        let (tally, pixels) = gfx.viewport.sample_in_progress();
        let (width, height) = gfx.viewport.traced_resolution();
        if let Some(done) = finished {
            self.event(&format!("sample-time n={samples} {}", done.fields()));
            self.progress_told = None;
        }
        let told = *self.progress_told.get_or_insert_with(Instant::now);
        if tally.jobs > 0 && told.elapsed() >= PROGRESS_EVERY {
            self.progress_told = Some(Instant::now());
            self.event(&format!(
                "refining pixels={pixels}/{} elapsed_ms={:.0} {}",
                width * height,
                tally.elapsed().as_secs_f64() * 1e3,
                tally.fields()
            ));
        }
    }

    /// The error view's part of a frame (docs/views.md, "The error view"):
    /// a picture just `traced` at rest starts its reference against the
    /// GPU's radiance, read back; a level of the reference that came in
    /// replaces the last on screen; while one is traced, the viewer looks
    /// again soon (`ErrorView::look_again`).
    fn error_view_frame(&mut self, traced: bool) {
        if let Some(level) = self.error_view.take_drawn() {
            self.event(&format!("error-level {level}"));
            self.event(&format!("error-status {}", self.error_view.progress()));
        }
        let scene = traced.then(|| self.shown_scene());
        let Some(gfx) = &mut self.gfx else { return };
        if let Some(scene) = scene {
            let options = reference::ReferenceOptions {
                kinds: self
                    .drawing
                    .as_ref()
                    .map(|o| o.kinds.clone())
                    .unwrap_or_default(),
                ..reference::ReferenceOptions::of(&scene)
            };
            let size = gfx.viewport.traced_resolution();
            let sums = gfx.viewport.start_read_sums(&gfx.gpu);
            // Natively this maps the copy at once; in the page it does
            // nothing, and a later frame takes the radiance.
            if let Err(e) = gfx.gpu.wait() {
                log::error!("error view: {e}");
            }
            let metric = error_metric(self.editor.view.shown);
            let picture = gfx.viewport.picture();
            self.error_view
                .start(&scene, &options, size, picture, sums, metric);
        }
        if let Some((errors, range)) = self.error_view.poll() {
            self.editor.view.colour_bar = gfx.viewport.show_quantities(&gfx.gpu, &errors, range);
            gfx.window.request_redraw();
        }
        self.editor.view.progress = Some(self.error_view.progress());
        if let Some(wait) = self.error_view.look_again() {
            let soon = Instant::now() + wait;
            self.repaint_at = Some(self.repaint_at.map_or(soon, |at| at.min(soon)));
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

/// Fits the colour bar to a scalar view's quantities once they are back
/// (`read`, then emptied), for the next frame to show; asks for frames
/// until then. `Some` once it did: the bar, `None` where no pixel has a
/// quantity.
fn take_colour_bar(read: &mut Option<TexelRead>, gfx: &mut Graphics) -> Option<Option<ColourBar>> {
    let pending = read.as_ref()?;
    gfx.window.request_redraw();
    let result = pending.try_take()?;
    *read = None;
    Some(match result {
        Ok(texels) => gfx
            .viewport
            .fit_colour_bar(&bytemuck::pod_collect_to_vec(&texels)),
        Err(e) => {
            log::error!("colour bar: reading the view back: {e}");
            None
        }
    })
}

/// What an error view shows once its reference is at every pixel.
fn error_metric(view: View) -> Metric {
    match view {
        View::ErrorFlip => Metric::Flip,
        _ => Metric::Levels,
    }
}
