//! The error view in the viewer (docs/views.md, "The error view"): the f64
//! reference is traced coarse to fine while the picture stays live; each
//! level's errors replace the last on screen. Natively a worker thread
//! (and the rayon pool) traces it; the web page has no thread to spare, so
//! there it is traced in slices of some milliseconds after each frame.
//! Both run the same [`Refinement`]. A generation counter cancels a stale
//! reference: an edit, a camera move, a resize or another view starts a
//! new one, and the old one stops within a slice. The `error-flip` view
//! shows the levels until the last, and then FLIP per pixel, computed on
//! the worker (FLIP's filters need the whole image); `nv-flip` is C++,
//! built natively only, so the page says it has no FLIP. A reference at
//! every pixel is kept until the picture changes, so that switching
//! between the two metrics shows the other at once instead of tracing it
//! again.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};

use web_time::Duration;

use crate::gpu::TexelRead;
use crate::reference::{ErrorImage, PreparedScene, ReferenceOptions};
use crate::scene::Scene;

/// Pixels the worker traces between two looks at the generation: a few
/// milliseconds of work, so that a camera move stops a stale reference at
/// once.
#[cfg(not(target_arch = "wasm32"))]
const CHUNK: usize = 2048;

/// Pixels the page traces between two looks at the clock: well under a
/// millisecond on the bundled scenes.
#[cfg(target_arch = "wasm32")]
const SLICE_CHUNK: usize = 64;

/// How long the page traces after each frame: as long as the frame took
/// (since the last slice), so that the reference gets half of the page's
/// time however slow its GPU, but within these bounds, so that input and
/// drawing never wait long.
#[cfg(target_arch = "wasm32")]
const SLICE: std::ops::RangeInclusive<Duration> =
    Duration::from_millis(10)..=Duration::from_millis(40);

/// A level of a reference, traced: its errors, ready to show.
struct Level {
    generation: u64,
    /// The level's grid: 1 is every pixel, the last level.
    stride: u32,
    /// Four floats per pixel (`ErrorImage::quantities`).
    quantities: Vec<f32>,
    /// FLIP's mean and largest when the quantities are FLIP per pixel.
    flip: Option<(f64, f32)>,
    /// The colour bar's range, `None` to fit it to the quantities.
    range: Option<[f32; 2]>,
}

/// A reference being traced against the GPU's radiance: what the worker
/// thread and the page's slices share.
struct Refinement {
    generation: u64,
    image: ErrorImage,
    /// The GPU's radiance at the pixel centres, four floats per pixel.
    gpu: Vec<f32>,
}

impl Refinement {
    fn new(generation: u64, scene: &PreparedScene, (w, h): (u32, u32), gpu: Vec<f32>) -> Self {
        Refinement {
            generation,
            image: ErrorImage::new(scene, w, h),
            gpu,
        }
    }

    /// Traces up to `budget` pixels: the level they finished, if any.
    fn step(&mut self, budget: usize) -> Option<Level> {
        self.image
            .refine_some(budget)
            .then(|| self.level(self.generation))
    }

    /// |GPU - reference| in levels at the reference's current level.
    fn level(&self, generation: u64) -> Level {
        Level {
            generation,
            stride: self.image.stride().unwrap_or(1),
            quantities: self.image.quantities(&self.gpu),
            flip: None,
            range: None,
        }
    }

    /// FLIP per pixel of the GPU's picture against the reference's, once
    /// the reference is at every pixel.
    #[cfg(not(target_arch = "wasm32"))]
    fn flip_level(&self, generation: u64) -> Level {
        let reference = self.image.rgba8();
        let gpu = self.image.gpu_rgba8(&self.gpu);
        let (quantities, mean) = crate::stress::metrics::flip_quantities(&reference, &gpu);
        let largest = quantities.iter().step_by(4).copied().fold(0.0, f32::max);
        Level {
            generation,
            stride: 1,
            quantities,
            flip: Some((mean, largest)),
            range: Some(crate::stress::metrics::FLIP_RANGE),
        }
    }
}

/// What the reference's tracer sends the view.
enum Sent {
    /// A level of the reference traced, or FLIP at every pixel.
    Level(Level),
    /// The reference at every pixel with the picture it was traced
    /// against, to show as the other metric without tracing it again.
    Whole(Arc<Refinement>),
}

/// FLIP asked for a reference at every pixel, of generation `generation`.
#[cfg(not(target_arch = "wasm32"))]
struct FlipRequest {
    generation: u64,
    whole: Arc<Refinement>,
}

/// The GPU's radiance on its way back, and the reference to trace
/// against it once it is here.
struct Awaited {
    sums: TexelRead,
    scene: PreparedScene,
    size: (u32, u32),
}

/// What the view shows once the reference is at every pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Metric {
    /// |GPU - reference| in 8-bit levels, as every level before.
    Levels,
    /// FLIP per pixel (natively; the page keeps the levels and says so).
    Flip,
}

/// The page's reference, traced in slices after the frames.
#[cfg(target_arch = "wasm32")]
#[derive(Default)]
struct Slices {
    refinement: Option<Refinement>,
    /// When the last slice ended.
    last_end: Option<web_time::Instant>,
    /// The share of the pixels traced, as the last slice left it.
    fraction: f64,
    /// Slices traced, and their time, for the status line.
    count: u32,
    tracing: Duration,
}

/// The reference of the error view being traced, and what came of it.
pub struct ErrorView {
    /// Bumped by every start and cancel; a refinement stops when it
    /// differs from its own.
    generation: Arc<AtomicU64>,
    sender: Sender<Sent>,
    levels: Receiver<Sent>,
    /// The stride of the level on screen, `None` before the first.
    shown: Option<u32>,
    /// What the view asked for.
    metric: Metric,
    /// FLIP's mean and largest, when FLIP is on screen.
    flip: Option<(f64, f32)>,
    /// The picture's radiance being read back, before its reference.
    awaited: Option<Awaited>,
    /// A reference of the current generation is being traced (or its
    /// radiance read back).
    running: bool,
    #[cfg(target_arch = "wasm32")]
    slices: Slices,
    /// The level handed out by [`Self::poll`] and not yet reported as
    /// drawn ([`Self::take_drawn`]).
    handed_out: Option<String>,
    /// The current picture's reference at every pixel, once traced.
    whole: Option<Arc<Refinement>>,
    /// The viewport's picture the reference is traced against
    /// (`Viewport::picture`).
    picture: Option<u64>,
    /// The FLIP worker's inbox ([`Self::request_flip`]), once started.
    #[cfg(not(target_arch = "wasm32"))]
    flip_requests: Option<Sender<FlipRequest>>,
}

impl Default for ErrorView {
    fn default() -> Self {
        let (sender, levels) = channel();
        ErrorView {
            generation: Arc::default(),
            sender,
            levels,
            shown: None,
            metric: Metric::Levels,
            flip: None,
            awaited: None,
            running: false,
            #[cfg(target_arch = "wasm32")]
            slices: Slices::default(),
            handed_out: None,
            whole: None,
            picture: None,
            #[cfg(not(target_arch = "wasm32"))]
            flip_requests: None,
        }
    }
}

impl ErrorView {
    /// Stops the reference being traced: the picture changed. Its levels
    /// not yet shown and the reference kept are dropped, so that at most
    /// what a worker was finishing (a level of a few megabytes, or the
    /// reference at every pixel, some tens) waits in the channel until the
    /// next poll or start.
    pub fn cancel(&mut self) {
        self.generation.fetch_add(1, Ordering::Relaxed);
        while self.levels.try_recv().is_ok() {}
        self.awaited = None;
        self.running = false;
        self.shown = None;
        self.flip = None;
        self.handed_out = None;
        self.whole = None;
        self.picture = None;
        #[cfg(target_arch = "wasm32")]
        {
            self.slices = Slices::default();
        }
    }

    /// Starts the reference of `scene` at `size` pixels for the viewport's
    /// `picture` (`Viewport::picture`), whose errors are against `sums`,
    /// the GPU's radiance at the same pixel centres (four floats per pixel)
    /// on its way back; cancels the last one. It is traced once the
    /// radiance is here ([`Self::poll`]), and then shown as `metric`.
    pub fn start(
        &mut self,
        scene: &Scene,
        options: &ReferenceOptions,
        size: (u32, u32),
        picture: u64,
        sums: TexelRead,
        metric: Metric,
    ) {
        self.cancel();
        self.picture = Some(picture);
        self.metric = metric;
        self.awaited = Some(Awaited {
            sums,
            scene: PreparedScene::with_options(scene, options),
            size,
        });
        self.running = true;
    }

    /// Shows the reference at every pixel as `metric` instead (the view
    /// switched between the error view's two metrics) without tracing it
    /// again; FLIP is computed on a worker. False, and nothing changed,
    /// when the reference of `picture` (the viewport's, `None` without
    /// one) is not at every pixel yet: the caller starts over.
    pub fn show_as(&mut self, metric: Metric, picture: Option<u64>) -> bool {
        // The reference may have come after the last level was polled.
        let current = self.generation.load(Ordering::Relaxed);
        while let Ok(sent) = self.levels.try_recv() {
            if let Sent::Whole(whole) = sent
                && whole.generation == current
            {
                self.whole = Some(whole);
            }
        }
        let whole = match &self.whole {
            Some(whole) if picture.is_some() && picture == self.picture => Arc::clone(whole),
            _ => return false,
        };
        let generation = self.generation.fetch_add(1, Ordering::Relaxed) + 1;
        self.metric = metric;
        self.shown = Some(1);
        self.flip = None;
        self.handed_out = None;
        let flip = metric == Metric::Flip && cfg!(not(target_arch = "wasm32"));
        self.running = flip;
        if !flip {
            let _ = self.sender.send(Sent::Level(whole.level(generation)));
            return true;
        }
        #[cfg(not(target_arch = "wasm32"))]
        self.request_flip(generation, whole);
        true
    }

    /// Hands FLIP of the reference `whole` for `generation` to the FLIP
    /// worker ([`Self::flip_inbox`]). False, and the view no longer
    /// running, when no thread could be started.
    #[cfg(not(target_arch = "wasm32"))]
    fn request_flip(&mut self, generation: u64, whole: Arc<Refinement>) -> bool {
        let request = FlipRequest { generation, whole };
        let sent = match self.flip_inbox() {
            None => false,
            Some(inbox) => match inbox.send(request) {
                Ok(()) => true,
                // The worker has gone (FLIP panicked): a new one takes it.
                Err(unsent) => {
                    self.flip_requests = None;
                    self.flip_inbox()
                        .is_some_and(|inbox| inbox.send(unsent.0).is_ok())
                }
            },
        };
        if !sent {
            self.running = false;
        }
        sent
    }

    /// The FLIP worker's inbox, the worker started at the first call. It
    /// computes the newest request it holds and drops the older ones, which
    /// belong to pictures or metrics switched away from: however fast the
    /// metrics are toggled, one FLIP at most is computed at a time, and the
    /// requests that came meanwhile cost one more, the newest's. `None`
    /// when no thread could be started.
    #[cfg(not(target_arch = "wasm32"))]
    fn flip_inbox(&mut self) -> Option<Sender<FlipRequest>> {
        if let Some(inbox) = &self.flip_requests {
            return Some(inbox.clone());
        }
        let (requests, inbox) = channel::<FlipRequest>();
        let current = Arc::clone(&self.generation);
        let sender = self.sender.clone();
        let worker = move || {
            while let Ok(mut request) = inbox.recv() {
                while let Ok(newer) = inbox.try_recv() {
                    request = newer;
                }
                if current.load(Ordering::Relaxed) != request.generation {
                    continue;
                }
                let level = request.whole.flip_level(request.generation);
                let _ = sender.send(Sent::Level(level));
            }
        };
        match std::thread::Builder::new()
            .name("error view FLIP".into())
            .spawn(worker)
        {
            Ok(_) => {
                self.flip_requests = Some(requests.clone());
                Some(requests)
            }
            Err(e) => {
                log::error!("error view: no thread for FLIP: {e}");
                None
            }
        }
    }

    /// Starts tracing the awaited reference once the GPU's radiance is
    /// back: on the worker natively, in slices in the page.
    fn take_sums(&mut self) {
        let Some(result) = self.awaited.as_ref().and_then(|a| a.sums.try_take()) else {
            return;
        };
        let Some(awaited) = self.awaited.take() else {
            return;
        };
        let gpu: Vec<f32> = match result {
            Ok(texels) => bytemuck::pod_collect_to_vec(&texels),
            Err(e) => {
                log::error!("error view: reading the picture back: {e}");
                self.running = false;
                return;
            }
        };
        let generation = self.generation.load(Ordering::Relaxed);
        let refinement = Refinement::new(generation, &awaited.scene, awaited.size, gpu);
        #[cfg(not(target_arch = "wasm32"))]
        self.spawn(refinement);
        #[cfg(target_arch = "wasm32")]
        {
            self.slices.refinement = Some(refinement);
        }
    }

    /// The worker: one level after the other, each sent when done.
    #[cfg(not(target_arch = "wasm32"))]
    fn spawn(&mut self, mut refinement: Refinement) {
        let current = Arc::clone(&self.generation);
        let sender = self.sender.clone();
        let work = move || {
            let generation = refinement.generation;
            let cancelled = || current.load(Ordering::Relaxed) != generation;
            while !refinement.image.finished() && !cancelled() {
                if let Some(level) = refinement.step(CHUNK)
                    && sender.send(Sent::Level(level)).is_err()
                {
                    return;
                }
            }
            if cancelled() {
                return;
            }
            let _ = sender.send(Sent::Whole(Arc::new(refinement)));
        };
        match std::thread::Builder::new()
            .name("error view reference".into())
            .spawn(work)
        {
            Ok(_) => {}
            Err(e) => {
                log::error!("error view: no thread for the reference: {e}");
                self.running = false;
            }
        }
    }

    /// The page's share of the work: traces the reference for a slice of
    /// time ([`SLICE`]) after a frame, and sends the levels finished as
    /// the worker does.
    #[cfg(target_arch = "wasm32")]
    fn trace_slice(&mut self) {
        let slices = &mut self.slices;
        let Some(refinement) = &mut slices.refinement else {
            return;
        };
        let start = web_time::Instant::now();
        let slice = slices
            .last_end
            .map_or(*SLICE.start(), |end| start - end)
            .clamp(*SLICE.start(), *SLICE.end());
        while !refinement.image.finished() && start.elapsed() < slice {
            if let Some(level) = refinement.step(SLICE_CHUNK) {
                // The receiver is ours: sending cannot fail.
                let _ = self.sender.send(Sent::Level(level));
            }
        }
        let end = web_time::Instant::now();
        slices.last_end = Some(end);
        slices.count += 1;
        slices.tracing += end - start;
        slices.fraction = refinement.image.fraction();
        if refinement.image.finished()
            && let Some(whole) = slices.refinement.take()
        {
            let _ = self.sender.send(Sent::Whole(Arc::new(whole)));
        }
    }

    /// The errors of the newest level of the current reference, when one
    /// came since the last call (older generations' are dropped), and the
    /// range of their colour bar (`None`: fitted to them). In the page,
    /// traces the next slice first.
    pub fn poll(&mut self) -> Option<(Vec<f32>, Option<[f32; 2]>)> {
        self.take_sums();
        #[cfg(target_arch = "wasm32")]
        self.trace_slice();
        let generation = self.generation.load(Ordering::Relaxed);
        let mut newest = None;
        while let Ok(sent) = self.levels.try_recv() {
            let level = match sent {
                Sent::Level(level) if level.generation == generation => level,
                Sent::Whole(whole) if whole.generation == generation => {
                    self.keep_whole(whole);
                    continue;
                }
                _ => continue,
            };
            self.shown = Some(level.stride);
            self.flip = level.flip;
            self.running &= !self.complete();
            self.handed_out = Some(match level.flip {
                Some(_) => "flip".into(),
                None => format!("stride={}", level.stride),
            });
            newest = Some((level.quantities, level.range));
        }
        newest
    }

    /// Keeps the current picture's reference at every pixel and, when
    /// FLIP is shown, hands its FLIP to the FLIP worker
    /// ([`Self::request_flip`]), as a switch of metric does.
    fn keep_whole(&mut self, whole: Arc<Refinement>) {
        #[cfg(not(target_arch = "wasm32"))]
        if self.metric == Metric::Flip {
            self.request_flip(whole.generation, Arc::clone(&whole));
        }
        self.whole = Some(whole);
    }

    /// Whether what is on screen is the last that comes: every pixel, as
    /// FLIP when FLIP was asked for and can be computed.
    fn complete(&self) -> bool {
        let flip_due = self.metric == Metric::Flip && cfg!(not(target_arch = "wasm32"));
        self.shown == Some(1) && (!flip_due || self.flip.is_some())
    }

    /// What the last [`Self::poll`] handed out (`stride=N`, or `flip`),
    /// once: called after the next frame, it is on screen then.
    pub fn take_drawn(&mut self) -> Option<String> {
        self.handed_out.take()
    }

    /// When the viewer should look again while the reference is still
    /// being traced (though nothing else asks for a frame): `None` once it
    /// is done. The worker's levels are looked for every tenth of a
    /// second; the page traces its next slice after the next frame.
    pub fn look_again(&self) -> Option<Duration> {
        let wait = if cfg!(target_arch = "wasm32") {
            Duration::ZERO
        } else {
            Duration::from_millis(100)
        };
        self.running.then_some(wait)
    }

    /// What the status line adds to the view's legend: how far the
    /// reference has come.
    pub fn progress(&self) -> String {
        let note = self.page_note();
        if let Some((mean, largest)) = self.flip {
            return format!("FLIP at every pixel: mean {mean:.4}, largest {largest:.3}");
        }
        let levels = match (self.shown, self.running) {
            (Some(1), _) => format!("reference at every pixel{note}"),
            (Some(s), _) => {
                format!("reference at every {s}th pixel of every {s}th row, refining{note}")
            }
            (None, true) => {
                format!("tracing the f64 reference{note} (the GPU's picture dimmed meanwhile)")
            }
            (None, false) => "waiting for the picture".into(),
        };
        match self.metric {
            Metric::Levels => levels,
            Metric::Flip if cfg!(target_arch = "wasm32") => format!(
                "{levels}; FLIP is not available in the page (nv-flip is C++, built natively \
                 only): |difference| in levels shown, FLIP in the native viewer"
            ),
            Metric::Flip => format!("{levels}; |difference| in levels until FLIP at every pixel"),
        }
    }

    /// What the page adds to the status line: the share of the pixels
    /// traced, and once all are, how long the slices took. The worker's
    /// levels say how far it has come.
    fn page_note(&self) -> String {
        #[cfg(target_arch = "wasm32")]
        {
            let slices = &self.slices;
            if self.shown == Some(1) {
                return format!(
                    " (traced in {} slices after the frames, {:.1} s in all)",
                    slices.count,
                    slices.tracing.as_secs_f64()
                );
            }
            if self.running {
                return format!(" ({:.0} % of the pixels traced)", 100.0 * slices.fraction);
            }
        }
        String::new()
    }
}

#[cfg(all(test, not(target_arch = "wasm32")))]
mod tests {
    use super::*;

    /// The Whitted scene's reference at every pixel of a small picture,
    /// against a black GPU picture.
    fn whole() -> Arc<Refinement> {
        let text = crate::scene::bundled::text("whitted").expect("bundled");
        let scene = Scene::from_toml_str(text, None).expect("the Whitted scene");
        let size = (32, 18);
        let gpu = vec![0.0; 4 * 32 * 18];
        let mut refinement = Refinement::new(0, &PreparedScene::new(&scene), size, gpu);
        while !refinement.image.finished() {
            refinement.step(CHUNK);
        }
        Arc::new(refinement)
    }

    #[test]
    fn rapid_flip_requests_compute_the_newest_only() {
        let whole = whole();
        let mut view = ErrorView::default();
        // Fifty toggles, each a generation: by the time the worker looks,
        // all but the last are stale.
        let toggles = 50;
        let newest = view.generation.fetch_add(toggles, Ordering::Relaxed) + toggles;
        for generation in 1..=newest {
            assert!(view.request_flip(generation, Arc::clone(&whole)));
        }
        let wait = std::time::Duration::from_secs(60);
        match view.levels.recv_timeout(wait) {
            Ok(Sent::Level(level)) => {
                assert_eq!(level.generation, newest, "FLIP of a stale request");
                assert!(level.flip.is_some(), "a FLIP level");
            }
            Ok(Sent::Whole(_)) => panic!("the FLIP worker sends levels only"),
            Err(e) => panic!("no FLIP of the newest request: {e}"),
        }
        // A request after the first is served by the same worker.
        let generation = view.generation.fetch_add(1, Ordering::Relaxed) + 1;
        assert!(view.request_flip(generation, whole));
        match view.levels.recv_timeout(wait) {
            Ok(Sent::Level(level)) => assert_eq!(level.generation, generation),
            _ => panic!("no FLIP of the request after the first"),
        }
        assert!(view.levels.try_recv().is_err(), "one FLIP per request kept");
    }
}
