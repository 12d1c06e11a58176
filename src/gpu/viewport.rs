//! The tracer drawing into a window surface, with progressive refinement, a
//! resolution scale and the selection outline. Knows nothing of egui: whoever draws on top of the
//! image gets the frame's encoder and view through a callback.

use std::ops::Range;
use std::sync::{Arc, Mutex, PoisonError};

use web_time::{Duration, Instant};

use super::context::{Gpu, GpuWaitError};
use super::id_pass::FirstHit;
use super::interaction::MIN_SCALE;
use super::jobs::{JOB_BUDGET, JobPlanner, JobsSince, SampleTally};
use super::layout::PackedScene;
use super::limits::BufferLimitError;
use super::offscreen::TexelRead;
use super::outline::Outline;
use super::texture::readback_target;
use super::timer::{GpuTimer, Timing};
use super::tracer::{
    Accumulator, FrameTarget, Pipelines, SceneBuffers, encode_display, encode_frame, encode_job,
};
use super::view::ColourBar;
use crate::scene::{Scene, ShapeId};

/// Format of screenshots: 8-bit RGBA with the exact sRGB formula of the rendering model.
pub const EXPORT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// What a frame adds to the image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refine {
    /// Nothing: the image is shown again.
    Show,
    /// One sample of every pixel in one job: a moving view, whose
    /// resolution scale keeps the frame short.
    WholeSample,
    /// The next pixels of the next sample, as many as fit in a short job
    /// ([`super::jobs`]).
    NextJob,
}

/// What the viewport calls once a job's time is back: in the browser the
/// page's event loop then submits the next job between frames (docs/web.md,
/// "Where a sample's time goes").
pub type JobWaker = Arc<dyn Fn() + Send + Sync>;

/// What happened to a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameStatus {
    /// Drawn and presented.
    Presented,
    /// Not drawn: the window is minimised or the surface was busy or had to
    /// be reconfigured; draw again later.
    Skipped,
}

/// A window's surface and everything the tracer needs to draw into it.
pub struct Viewport {
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    pipelines: Pipelines,
    scene: SceneBuffers,
    accum: Accumulator,
    /// Fraction of the window resolution that is traced (MIN_SCALE..=1).
    scale: f32,
    /// GPU time of the last job (see [`Self::timing`]), until it is taken.
    /// Shared with the queue's work-done callback, which writes it without
    /// timestamps: natively during the blocking wait after submission, in
    /// the browser (which cannot block) when the GPU reports the work done.
    job_time: Arc<Mutex<Option<Duration>>>,
    /// Cuts refinement into short jobs ([`super::jobs`]).
    jobs: JobPlanner,
    /// When the last job started, if the last frame ran one.
    last_job_start: Option<Instant>,
    /// In the browser: the last job's time has not come back yet. No job
    /// of refinement is submitted until it has, so that jobs never queue up
    /// in the browser's GPU process, where each would wait for those before
    /// it (its measured time growing with the queue, and input waiting
    /// behind them all). Natively a job is waited for where it is submitted.
    job_in_flight: bool,
    /// Called once a job's time is back ([`Viewport::wake_after_jobs`]).
    job_waker: Option<JobWaker>,
    /// Whether the last sample was traced whole (a moving view), and its time.
    whole_frame: bool,
    whole_frame_time: Option<Duration>,
    timer: Option<GpuTimer>,
    /// Where the time of the sample in progress goes, and of the last one
    /// traced to its end until the viewer takes it.
    tally: SampleTally,
    finished: Option<SampleTally>,
    /// The selected shape's outline, drawn over the image.
    outline: Outline,
    /// Counts the pictures begun: every restart of refinement starts one.
    picture: u64,
}

impl Viewport {
    /// Configures `surface` for a window of `size` physical pixels, with
    /// the camera, lights and materials of `scene` but none of its shapes:
    /// [`Viewport::set_scene`] brings them, or says why they do not fit.
    pub fn new(
        gpu: &Gpu,
        surface: wgpu::Surface<'static>,
        size: (u32, u32),
        pipelines: Pipelines,
        scene: &Scene,
    ) -> Self {
        let config = surface_config(gpu, &surface, size);
        if size.0 > 0 && size.1 > 0 {
            surface.configure(&gpu.device, &config);
        }
        let empty = PackedScene::new(&scene.without_shapes(), size.0.max(1), size.1.max(1));
        let scene = SceneBuffers::new((&gpu.device, &gpu.queue), &pipelines, empty)
            .expect("a scene without shapes fits any GPU's buffers");
        let accum = Accumulator::new(&gpu.device, &pipelines, size.0.max(1), size.1.max(1));
        let timer = GpuTimer::for_passes(gpu);
        let mut jobs = JobPlanner::new(JOB_BUDGET);
        jobs.pipelines_changed();
        // Natively a job is waited for alone; in the browser only its
        // timestamps leave out the frames queued before it.
        let jobs = if cfg!(target_arch = "wasm32") && timer.is_none() {
            jobs.in_whole_rows()
        } else {
            jobs
        };
        Viewport {
            surface,
            config,
            pipelines,
            scene,
            accum,
            scale: 1.0,
            job_time: Arc::default(),
            jobs,
            last_job_start: None,
            job_in_flight: false,
            job_waker: None,
            whole_frame: false,
            whole_frame_time: None,
            timer,
            tally: SampleTally::default(),
            finished: None,
            outline: Outline::new(&gpu.device),
            picture: 0,
        }
    }

    /// The surface format: pipelines must have a display pass for it.
    pub fn surface_format(&self) -> wgpu::TextureFormat {
        self.config.format
    }

    /// The formats a [`Pipelines`] for this viewport must support.
    pub fn output_formats(gpu: &Gpu, surface: &wgpu::Surface) -> [wgpu::TextureFormat; 2] {
        [surface_config(gpu, surface, (1, 1)).format, EXPORT_FORMAT]
    }

    /// Follows a window resize; a zero size (minimised) just stops drawing.
    pub fn resize(&mut self, gpu: &Gpu, size: (u32, u32)) {
        self.config.width = size.0;
        self.config.height = size.1;
        if size.0 > 0 && size.1 > 0 {
            self.surface.configure(&gpu.device, &self.config);
            self.resize_accumulator(gpu);
        }
    }

    /// Sets the traced fraction of the window resolution; restarts refinement
    /// when the traced size changes.
    pub fn set_scale(&mut self, gpu: &Gpu, scale: f32) {
        let scale = scale.clamp(MIN_SCALE, 1.0);
        if scale != self.scale {
            self.scale = scale;
            self.resize_accumulator(gpu);
        }
    }

    fn traced_size(&self) -> (u32, u32) {
        let scaled = |n: u32| ((n as f32 * self.scale).round() as u32).clamp(1, n.max(1));
        (scaled(self.config.width), scaled(self.config.height))
    }

    fn resize_accumulator(&mut self, gpu: &Gpu) {
        let (w, h) = self.traced_size();
        if self.accum.size() != (w, h) {
            self.accum = Accumulator::new(&gpu.device, &self.pipelines, w, h);
        }
        self.restart_refinement();
    }

    /// Uploads a changed scene and restarts refinement. A scene too large
    /// for the device's buffers is refused and the last one stays.
    pub fn set_scene(&mut self, gpu: &Gpu, scene: &Scene) -> Result<(), BufferLimitError> {
        self.scene = self.scene.changed_to(
            (&gpu.device, &gpu.queue),
            &self.pipelines,
            scene,
            self.traced_size(),
        )?;
        self.restart_refinement();
        Ok(())
    }

    /// Takes a scene whose shapes, materials and lights are unchanged (only
    /// camera or render settings differ): no buffers are rebuilt.
    pub fn set_view(&mut self, scene: &Scene) {
        self.scene.set_view(scene);
        self.restart_refinement();
    }

    /// Swaps in new pipelines (after a shader reload) and restarts refinement.
    /// The scene buffers and accumulator are rebuilt against their layouts.
    pub fn set_pipelines(&mut self, gpu: &Gpu, pipelines: Pipelines) {
        self.pipelines = pipelines;
        let packed = self.scene.packed().clone();
        self.scene = SceneBuffers::reusing(
            (&gpu.device, &gpu.queue),
            &self.pipelines,
            packed,
            &self.scene,
        )
        .expect("the scene on the GPU fitted this device's buffers already");
        let (w, h) = self.accum.size();
        self.accum = Accumulator::new(&gpu.device, &self.pipelines, w, h);
        self.picture += 1;
        self.outline.forget_layouts();
        self.jobs.pipelines_changed();
    }

    /// Outlines `shape` (or nothing) with a band `radius` pixels wide; only
    /// with pipelines made [`Pipelines::with_outline`].
    pub fn set_selection(&mut self, gpu: &Gpu, shape: Option<ShapeId>, radius: u32) {
        self.outline
            .select(&gpu.queue, FirstHit::id_of(shape), radius);
    }

    /// Forgets the accumulated samples (e.g. the camera moved).
    pub fn restart(&mut self) {
        self.restart_refinement();
    }

    /// Which picture the samples belong to: a number that changes whenever
    /// refinement starts over (scene, view, size or pipelines changed), so
    /// that what was made of one picture (a colour bar) is known to be stale.
    pub fn picture(&self) -> u64 {
        self.picture
    }

    /// Samples per pixel accumulated so far.
    pub fn samples(&self) -> u32 {
        self.accum.samples()
    }

    /// The traced fraction of the window resolution.
    pub fn scale(&self) -> f32 {
        self.scale
    }

    /// Size of the traced image in pixels.
    pub fn traced_resolution(&self) -> (u32, u32) {
        self.accum.size()
    }

    /// How frame times are measured: timestamps where the adapter has them.
    pub fn timing(&self) -> Timing {
        match self.timer {
            Some(_) => Timing::GpuTimestamps,
            None => Timing::SubmitToDone,
        }
    }

    /// GPU time of the last sample traced: a whole frame while the view
    /// moves, else the sum of the last sample's jobs.
    pub fn last_frame_time(&self) -> Option<Duration> {
        if self.whole_frame {
            self.whole_frame_time
        } else {
            self.jobs.last_sample_time()
        }
    }

    /// Draws a frame: `refine` says what it adds to the image, then
    /// `overlay` draws on top into the same view; the command buffers it
    /// returns are submitted before the frame's own.
    pub fn frame(
        &mut self,
        gpu: &Gpu,
        refine: Refine,
        overlay: impl FnOnce(&mut wgpu::CommandEncoder, &wgpu::TextureView) -> Vec<wgpu::CommandBuffer>,
    ) -> FrameStatus {
        if self.config.width == 0 || self.config.height == 0 {
            return FrameStatus::Skipped;
        }
        // The browser reports the last job's time only once it is done.
        self.record_job_time();
        let Some(frame) = self.current_texture(gpu) else {
            return FrameStatus::Skipped;
        };
        let view = frame
            .texture
            .create_view(&wgpu::TextureViewDescriptor::default());
        if self.accum.samples() == 0 {
            // Refinement starts over: what the image shows changed.
            self.outline.invalidate();
        }
        match refine {
            Refine::Show => self.last_job_start = None,
            Refine::WholeSample => {
                self.last_job_start = None;
                // Any sample in progress is traced over, whole.
                self.jobs.restart();
                self.tally = SampleTally::default();
                let mut encoder = gpu.device.create_command_encoder(&Default::default());
                let (width, height) = self.accum.size();
                let timed = self.trace_job(gpu, &mut encoder, 0..width * height);
                self.submit_timed(gpu, encoder, timed);
                self.whole_frame = true;
            }
            // Shows what is done while the last job runs (the browser only).
            Refine::NextJob if self.job_in_flight => {}
            Refine::NextJob => self.next_job(gpu),
        }
        self.record_job_time();
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        let target = FrameTarget {
            view: &view,
            format: self.config.format,
            size: (self.config.width, self.config.height),
        };
        encode_display(
            &gpu.queue,
            &mut encoder,
            (&self.pipelines, &self.scene),
            &self.accum,
            &target,
        );
        if let Some(outline) = self.pipelines.outline() {
            self.outline.encode(
                &gpu.device,
                &mut encoder,
                outline,
                &self.scene.bind_group,
                self.accum.size(),
                (&view, self.config.format),
            );
        }
        let mut buffers = overlay(&mut encoder, &view);
        buffers.push(encoder.finish());
        gpu.queue.submit(buffers);
        gpu.queue.present(frame);
        self.tally.frame_presented();
        FrameStatus::Presented
    }

    /// Traces the next job of the sample in progress (the first of a new
    /// one after the last), sized by the job planner. In a frame, or
    /// between frames in the page ([`Self::job_in_flight`] first).
    pub fn next_job(&mut self, gpu: &Gpu) {
        let now = Instant::now();
        if let Some(last) = self.last_job_start.replace(now) {
            self.jobs.cycle(now - last);
        }
        let span = self.jobs.next(self.accum.pixels_done(), self.accum.size());
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        let timed = self.trace_job(gpu, &mut encoder, span);
        self.submit_timed(gpu, encoder, timed);
        self.tally.job_submitted();
        self.whole_frame = false;
    }

    /// In the browser: whether the last job's time has not come back yet
    /// (after taking it if it has); no other job may be submitted then.
    pub fn job_in_flight(&mut self) -> bool {
        self.record_job_time();
        self.job_in_flight
    }

    /// `waker` is called each time a job's time is back (in the browser,
    /// when the GPU has done the job): the page then submits the next job
    /// at once, between frames, instead of at the next animation frame
    /// after a display pass and the UI.
    pub fn wake_after_jobs(&mut self, waker: Option<JobWaker>) {
        self.job_waker = waker;
    }

    /// The surface's next texture, reconfiguring the surface when it asks.
    fn current_texture(&mut self, gpu: &Gpu) -> Option<wgpu::SurfaceTexture> {
        match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame) => Some(frame),
            wgpu::CurrentSurfaceTexture::Suboptimal(frame) => {
                // Usable this once; reconfigure for the next frame.
                self.surface.configure(&gpu.device, &self.config);
                Some(frame)
            }
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&gpu.device, &self.config);
                None
            }
            other => {
                log::debug!("surface not ready: {other:?}");
                None
            }
        }
    }

    /// Encodes the trace of the pixels `span` of the next sample, its pass
    /// timed where the adapter has timestamps.
    /// Encodes the trace of `span`, its pass timed by the timer unless the
    /// timer still reads the last job's time back (in the page, a moving
    /// frame follows the last before that is known). Returns whether it is
    /// timed.
    fn trace_job(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        span: Range<u32>,
    ) -> bool {
        let timer = self.timer.as_ref().filter(|timer| !timer.reading());
        encode_job(
            &gpu.queue,
            encoder,
            (&self.pipelines, &self.scene),
            &mut self.accum,
            span,
            timer.map(GpuTimer::pass_writes),
        );
        if let Some(timer) = timer {
            timer.resolve(encoder);
        }
        timer.is_some()
    }

    /// Submits a job and measures it: natively by waiting for it (which
    /// also keeps input latency low: frames are only drawn on demand, so
    /// nothing else waits for us), in the browser, which cannot wait, when
    /// the GPU reports the work done ([`Self::record_job_time`] then finds
    /// it at a later frame). With timestamps the time is the job's pass
    /// alone; without, from submission until done, which in the browser
    /// also holds the frames queued before the job (docs/web.md, "The
    /// status line").
    fn submit_timed(&mut self, gpu: &Gpu, encoder: wgpu::CommandEncoder, timed: bool) {
        let start = Instant::now();
        gpu.queue.submit([encoder.finish()]);
        let slot = Arc::clone(&self.job_time);
        let waker = self.job_waker.clone();
        let store = move |time: Option<Duration>| {
            let time = time.unwrap_or_else(|| start.elapsed());
            *slot.lock().unwrap_or_else(PoisonError::into_inner) = Some(time);
            if let Some(wake) = waker {
                wake();
            }
        };
        match self.timer.as_ref().filter(|_| timed) {
            Some(timer) if cfg!(target_arch = "wasm32") => timer.read_later(store),
            Some(timer) => store(timer.read(gpu)),
            None => gpu.queue.on_submitted_work_done(move || store(None)),
        }
        let _ = gpu.device.poll(wgpu::PollType::wait_indefinitely());
        self.job_in_flight = cfg!(target_arch = "wasm32");
    }

    /// Takes the time of the last job, once it is known: the frame time of
    /// a whole sample, or a measurement for the job planner.
    fn record_job_time(&mut self) {
        let time = self
            .job_time
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .take();
        if time.is_some() {
            self.job_in_flight = false;
        }
        match time {
            Some(time) if self.whole_frame => self.whole_frame_time = Some(time),
            Some(time) => {
                if let Some(ended) = self.jobs.measured(time) {
                    self.tally.job_measured(time);
                    if ended {
                        self.finished = Some(std::mem::take(&mut self.tally));
                    }
                }
            }
            None => {}
        }
    }

    /// Forgets the samples and the sample in progress.
    fn restart_refinement(&mut self) {
        self.picture += 1;
        self.accum.reset();
        self.jobs.restart();
        self.tally = SampleTally::default();
    }

    /// Where the time of the sample in progress has gone so far, and the
    /// pixels of it traced.
    pub fn sample_in_progress(&self) -> (SampleTally, u32) {
        (self.tally, self.accum.pixels_done())
    }

    /// Where the time of the last sample traced to its end went, once.
    pub fn take_finished_sample(&mut self) -> Option<SampleTally> {
        self.finished.take()
    }

    /// The jobs measured since the last call, the longest of all and the
    /// longest the planner sized: what the viewer reports once the image is
    /// refined.
    pub fn take_jobs(&mut self) -> JobsSince {
        self.jobs.take_jobs()
    }

    /// For a scalar view: fits the colour bar to `quantities`, the ones
    /// of a traced sample ([`Self::start_read_sums`]); the next frame shows
    /// it (docs/views.md). `None` where no pixel has a quantity.
    pub fn fit_colour_bar(&mut self, quantities: &[f32]) -> Option<ColourBar> {
        super::offscreen::fit_colour_bar_to(&mut self.scene, quantities)
    }

    /// The view's quantities of the image traced, on their way back to
    /// the CPU (four floats per pixel, row by row, once taken): for the
    /// colour bar, and for the error view to compare with the reference.
    /// Not waited for: the page takes them a frame later.
    pub fn start_read_sums(&self, gpu: &Gpu) -> TexelRead {
        TexelRead::start(gpu, self.accum.sum())
    }

    /// Shows `quantities` in place of the view's own (the error view's
    /// errors) with a colour bar over `range` (`None`: fitted to them),
    /// from the next frame on; returns the bar, `None` when nothing was
    /// shown.
    pub fn show_quantities(
        &mut self,
        gpu: &Gpu,
        quantities: &[f32],
        range: Option<[f32; 2]>,
    ) -> Option<ColourBar> {
        super::offscreen::show_quantities(gpu, &mut self.scene, &self.accum, quantities, range)
    }

    /// The current image at the traced resolution, without anything drawn
    /// on top, as 8-bit sRGB (for screenshots and tests).
    pub fn capture(&mut self, gpu: &Gpu) -> Result<image::RgbaImage, GpuWaitError> {
        let size = self.accum.size();
        let texture = readback_target(&gpu.device, "screenshot", size, EXPORT_FORMAT);
        let view = texture.create_view(&Default::default());
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encode_frame(
            &gpu.queue,
            &mut encoder,
            &self.pipelines,
            &self.scene,
            &mut self.accum,
            0,
            &FrameTarget {
                view: &view,
                format: EXPORT_FORMAT,
                size,
            },
        );
        gpu.queue.submit([encoder.finish()]);
        super::offscreen::read_texture(gpu, &texture)
    }
}

/// Surface settings: a plain (non-sRGB) 8-bit format when there is one, so
/// the display pass encodes with the exact formula of the rendering model, as in PNG
/// output, and egui's colours (already sRGB) are written unchanged; FIFO
/// presentation (no tearing, and supported everywhere).
fn surface_config(
    gpu: &Gpu,
    surface: &wgpu::Surface,
    size: (u32, u32),
) -> wgpu::SurfaceConfiguration {
    let caps = surface.get_capabilities(&gpu.adapter);
    let format = caps
        .formats
        .iter()
        .copied()
        .find(|f| {
            matches!(
                f,
                wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm
            )
        })
        .unwrap_or(caps.formats[0]);
    wgpu::SurfaceConfiguration {
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        format,
        color_space: wgpu::SurfaceColorSpace::Auto,
        width: size.0,
        height: size.1,
        present_mode: wgpu::PresentMode::Fifo,
        desired_maximum_frame_latency: 2,
        alpha_mode: wgpu::CompositeAlphaMode::Auto,
        view_formats: vec![],
    }
}
