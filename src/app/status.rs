//! The status line under the picture: what was drawn (the samples in the
//! picture, how long a sample takes, and how that was measured), the
//! compiler at work, and the last message, wrapped to the window's width
//! and dropped once it is old (docs/web.md, "The status line").

use web_time::{Duration, Instant};

use crate::gpu::Timing;

/// How long a message stays in the status line after it last changed: a
/// message belongs to what the user just did, not to a scene opened later.
const MESSAGE_TIME: Duration = Duration::from_secs(20);

/// Figures for the status line.
pub struct Status {
    /// GPU time of the last sample traced (of the last whole frame while
    /// the view moves), measured as `timing` says.
    pub frame_time: Option<Duration>,
    pub timing: Timing,
    /// Wall time from one sample completed to the next ([`SampleClock`]).
    pub sample_wall: Option<Duration>,
    pub samples: u32,
    pub resolution: (u32, u32),
    /// The traced fraction of the window resolution (below 1 while moving).
    pub scale: f32,
    pub adapter: String,
    /// Pipelines for a new feature set or shader are being compiled.
    pub compiling: bool,
}

/// The wall time between samples completed: what a user waits for each
/// sample, whatever the GPU's own time (timestamps, where the adapter has
/// them, leave out the queueing between the short jobs of a sample).
#[derive(Default)]
pub struct SampleClock {
    samples: u32,
    since: Option<Instant>,
    every: Option<Duration>,
}

impl SampleClock {
    /// After each frame: `samples` are in the picture now. Fewer than
    /// before is a new refinement, timed from now.
    pub fn update(&mut self, samples: u32, now: Instant) {
        match self.since {
            Some(since) if samples > self.samples => {
                self.every = Some((now - since) / (samples - self.samples));
                self.since = Some(now);
            }
            Some(_) if samples == self.samples => {}
            _ => self.since = Some(now),
        }
        self.samples = samples;
    }

    /// The wall time of the last sample, once one was timed.
    pub fn every(&self) -> Option<Duration> {
        self.every
    }
}

/// When the message in the status line last changed.
#[derive(Default)]
pub struct MessageAge {
    text: Option<String>,
    since: Option<Instant>,
}

impl MessageAge {
    /// Drops `message` once it has stayed unchanged for [`MESSAGE_TIME`],
    /// and asks egui to draw again then.
    pub fn expire(&mut self, ctx: &egui::Context, message: &mut Option<String>) {
        let now = Instant::now();
        if *message != self.text {
            self.text = message.clone();
            self.since = Some(now);
        }
        let (Some(_), Some(since)) = (message.as_ref(), self.since) else {
            return;
        };
        let age = now - since;
        if age >= MESSAGE_TIME {
            *message = None;
            self.text = None;
        } else {
            ctx.request_repaint_after(MESSAGE_TIME - age);
        }
    }
}

/// `1.5 ms`, `230 ms`, `2.3 s`.
fn duration(t: Duration) -> String {
    let ms = t.as_secs_f64() * 1e3;
    if ms < 10.0 {
        format!("{ms:.1} ms")
    } else if ms < 1000.0 {
        format!("{ms:.0} ms")
    } else {
        format!("{:.1} s", ms / 1e3)
    }
}

/// What a sample (or, while the view moves, a whole frame) took, and how
/// it was measured.
fn timing_label(status: &Status) -> (String, &'static str) {
    let gpu = status.frame_time.map_or("-".to_string(), duration);
    let wall = status.sample_wall.map_or("-".to_string(), duration);
    match (status.scale < 1.0, status.timing) {
        (true, Timing::GpuTimestamps) => (
            format!("frame {gpu} GPU"),
            "GPU time of the last frame at the moving scale (timestamp queries)",
        ),
        (true, Timing::SubmitToDone) => (
            format!("frame {gpu} (wall time)"),
            "the last frame at the moving scale, from its submission until the GPU \
             said it was done (this GPU has no timestamp queries)",
        ),
        (false, Timing::GpuTimestamps) => (
            format!("sample {gpu} GPU, {wall} wall"),
            "GPU time of the last sample, all its short jobs (timestamp queries), and \
             the wall time from one sample on screen to the next",
        ),
        (false, Timing::SubmitToDone) => (
            format!("sample {wall} (wall time)"),
            "the wall time from one sample on screen to the next (this GPU has no \
             timestamp queries)",
        ),
    }
}

/// Primary rays per second: one ray per traced pixel in the sample that
/// `frame_time` timed (a frame while the view moves traces one sample too),
/// over that time. The drawing pipelines count no rays, so this is the part
/// of the rate the viewer knows exactly: shadow, reflected and refracted
/// rays come on top (`raysandbox bench --throughput` counts them,
/// docs/performance.md, "Rays per second").
fn primary_rays_per_second(status: &Status) -> Option<f64> {
    let seconds = status.frame_time?.as_secs_f64();
    let (w, h) = status.resolution;
    (seconds > 0.0).then(|| f64::from(w) * f64::from(h) / seconds)
}

/// `1.25 M primary rays/s`, `310 k primary rays/s`.
fn rays_label(rate: f64) -> String {
    if rate >= 1e6 {
        format!("{:.2} M primary rays/s", rate / 1e6)
    } else {
        format!("{:.0} k primary rays/s", rate / 1e3)
    }
}

/// The status line: "F1: help" first, so that it is never pushed off; the
/// figures wrap, each one whole, then what a view's colours mean (`legend`); the message on
/// a row of its own, wrapped.
pub fn show(
    ui: &mut egui::Ui,
    status: &Status,
    max_samples: u32,
    legend: Option<&str>,
    message: Option<&str>,
) {
    ui.horizontal_wrapped(|ui| {
        // A figure moves to the next row whole: broken inside ("0 / 1" on
        // one row, "spp" on the next) it would make the line's height
        // change with the numbers.
        ui.style_mut().wrap_mode = Some(egui::TextWrapMode::Extend);
        ui.label("F1: help");
        ui.separator();
        let (time, how) = timing_label(status);
        ui.label(time).on_hover_text(how);
        if let Some(rate) = primary_rays_per_second(status) {
            ui.label(rays_label(rate)).on_hover_text(
                "the primary rays of that sample (one per traced pixel) over its time; \
                 shadow, reflected and refracted rays come on top and are not counted \
                 here (raysandbox bench --throughput counts them)",
            );
        }
        ui.separator();
        ui.label(format!("{} / {max_samples} spp", status.samples))
            .on_hover_text("samples per pixel in the picture shown");
        ui.separator();
        let (w, h) = status.resolution;
        if status.scale < 1.0 {
            ui.label(format!("{w} x {h} (scale {:.2})", status.scale));
        } else {
            ui.label(format!("{w} x {h}"));
        }
        ui.separator();
        ui.label(&status.adapter)
            .on_hover_text("the GPU adapter in use");
        if status.compiling {
            ui.separator();
            ui.spinner();
            ui.label("compiling…")
                .on_hover_text("the last picture stays until the new shaders are built");
        }
        if let Some(legend) = legend {
            ui.separator();
            ui.label(legend);
        }
    });
    if let Some(message) = message {
        ui.add(egui::Label::new(message).wrap());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sample_clock_times_samples_from_a_restart_on() {
        let start = Instant::now();
        let at = |ms| start + Duration::from_millis(ms);
        let mut clock = SampleClock::default();
        clock.update(0, at(0));
        assert_eq!(clock.every(), None);
        clock.update(0, at(100));
        clock.update(1, at(2300));
        assert_eq!(clock.every(), Some(Duration::from_millis(2300)));
        clock.update(3, at(3300));
        assert_eq!(clock.every(), Some(Duration::from_millis(500)));
        // A new refinement: timed from the restart, not from the last sample.
        clock.update(0, at(10_000));
        clock.update(1, at(10_400));
        assert_eq!(clock.every(), Some(Duration::from_millis(400)));
    }

    #[test]
    fn primary_rays_per_second_are_the_traced_pixels_over_the_sample_time() {
        let status = Status {
            frame_time: Some(Duration::from_millis(400)),
            timing: Timing::GpuTimestamps,
            sample_wall: None,
            samples: 3,
            resolution: (1280, 720),
            scale: 1.0,
            adapter: String::new(),
            compiling: false,
        };
        let rate = primary_rays_per_second(&status).expect("a sample was timed");
        assert!((rate - 2_304_000.0).abs() < 1e-6, "{rate}");
        assert_eq!(rays_label(rate), "2.30 M primary rays/s");
        assert_eq!(rays_label(310_400.0), "310 k primary rays/s");
        let untimed = Status {
            frame_time: None,
            ..status
        };
        assert_eq!(primary_rays_per_second(&untimed), None);
    }

    #[test]
    fn durations_read_in_their_unit() {
        assert_eq!(duration(Duration::from_micros(1500)), "1.5 ms");
        assert_eq!(duration(Duration::from_millis(230)), "230 ms");
        assert_eq!(duration(Duration::from_millis(2300)), "2.3 s");
    }
}
