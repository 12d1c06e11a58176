//! The error view in the viewer (docs/views.md, "The error view"): the f64
//! reference is traced on a worker thread (and the rayon pool), coarse to
//! fine, while the window keeps drawing; each level's errors replace the
//! last on screen. A generation counter cancels a stale reference: an
//! edit, a camera move, a resize or another view starts a new one, and the
//! old one stops within a few thousand pixels. The web page has no threads
//! to spare: there the view says it is not available.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};

use crate::reference::ReferenceOptions;
use crate::scene::Scene;

/// A level of a reference, traced: its errors, ready to show.
struct Level {
    generation: u64,
    /// The level's grid: 1 is every pixel, the last level.
    stride: u32,
    /// Four floats per pixel (`ErrorImage::quantities`).
    quantities: Vec<f32>,
}

/// The reference of the error view being traced, and what came of it.
pub struct ErrorView {
    /// Bumped by every start and cancel; a worker stops when it differs
    /// from its own.
    generation: Arc<AtomicU64>,
    sender: Sender<Level>,
    levels: Receiver<Level>,
    /// The stride of the level on screen, `None` before the first.
    shown: Option<u32>,
    /// A reference of the current generation is being traced.
    running: bool,
    /// The stride of a level handed out by [`Self::poll`] and not yet
    /// reported as drawn.
    handed_out: Option<u32>,
}

impl Default for ErrorView {
    fn default() -> Self {
        let (sender, levels) = channel();
        ErrorView {
            generation: Arc::default(),
            sender,
            levels,
            shown: None,
            running: false,
            handed_out: None,
        }
    }
}

impl ErrorView {
    /// Stops the reference being traced: the picture changed. Its levels
    /// not yet shown are dropped, so that at most the one a worker was
    /// finishing waits in the channel (a few megabytes) until the next poll.
    pub fn cancel(&mut self) {
        self.generation.fetch_add(1, Ordering::Relaxed);
        while self.levels.try_recv().is_ok() {}
        self.running = false;
        self.shown = None;
        self.handed_out = None;
    }

    /// Starts tracing the reference of `scene` at `size` pixels, whose
    /// errors are against `gpu`, the GPU's radiance at the same pixel
    /// centres (four floats per pixel); cancels the last one.
    pub fn start(
        &mut self,
        scene: &Scene,
        options: &ReferenceOptions,
        size: (u32, u32),
        gpu: Vec<f32>,
    ) {
        self.cancel();
        #[cfg(not(target_arch = "wasm32"))]
        self.spawn(scene, options, size, gpu);
        #[cfg(target_arch = "wasm32")]
        let _ = (scene, options, size, gpu);
    }

    /// The worker: one level after the other, each sent when done.
    #[cfg(not(target_arch = "wasm32"))]
    fn spawn(
        &mut self,
        scene: &Scene,
        options: &ReferenceOptions,
        (width, height): (u32, u32),
        gpu: Vec<f32>,
    ) {
        use crate::reference::{ErrorImage, PreparedScene};
        let generation = self.generation.load(Ordering::Relaxed);
        let current = Arc::clone(&self.generation);
        let sender = self.sender.clone();
        let prepared = PreparedScene::with_options(scene, options);
        let work = move || {
            let mut image = ErrorImage::new(&prepared, width, height);
            let cancelled = || current.load(Ordering::Relaxed) != generation;
            while image.refine(&cancelled) {
                let level = Level {
                    generation,
                    stride: image.stride().unwrap_or(1),
                    quantities: image.quantities(&gpu),
                };
                if sender.send(level).is_err() {
                    return;
                }
            }
        };
        match std::thread::Builder::new()
            .name("error view reference".into())
            .spawn(work)
        {
            Ok(_) => self.running = true,
            Err(e) => log::error!("error view: no thread for the reference: {e}"),
        }
    }

    /// The errors of the newest level of the current reference, when one
    /// came since the last call (older generations' are dropped).
    pub fn poll(&mut self) -> Option<Vec<f32>> {
        let generation = self.generation.load(Ordering::Relaxed);
        let mut newest = None;
        while let Ok(level) = self.levels.try_recv() {
            if level.generation != generation {
                continue;
            }
            self.running &= level.stride > 1;
            self.shown = Some(level.stride);
            self.handed_out = Some(level.stride);
            newest = Some(level.quantities);
        }
        newest
    }

    /// The stride of the level the last [`Self::poll`] handed out, once:
    /// called after the next frame, it is on screen then.
    pub fn take_drawn(&mut self) -> Option<u32> {
        self.handed_out.take()
    }

    /// Whether the reference is still being traced: the viewer looks again
    /// soon, though nothing else asks for a frame.
    pub fn busy(&self) -> bool {
        self.running
    }

    /// What the status line adds to the view's legend: how far the
    /// reference has come.
    pub fn progress(&self) -> String {
        if cfg!(target_arch = "wasm32") {
            return "not available in the page: the f64 reference needs worker threads; \
                    use the native viewer or `raysandbox render --view error`"
                .into();
        }
        match (self.shown, self.running) {
            (Some(1), _) => "reference at every pixel".into(),
            (Some(s), _) => format!("reference at every {s}th pixel of every {s}th row, refining"),
            (None, true) => "tracing the f64 reference (the GPU's picture dimmed meanwhile)".into(),
            (None, false) => "waiting for the picture".into(),
        }
    }
}
