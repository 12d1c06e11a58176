//! The window's watchdog: a shader that never finishes a frame (an endless
//! loop) would freeze the window, so each newly compiled shader first draws
//! one small frame on a GPU device of its own, timed. A shader that does not
//! finish it, or whose frames at the window's size would take longer than
//! [`WINDOW_FRAME_LIMIT`] by that measure, is refused like a compile error:
//! the last good shader keeps running (docs/sandbox.md, "The window").
//! Headless renders wait for each frame at most [`super::render::FRAME_LIMIT`].

use std::time::{Duration, Instant};

use super::compose::Compiled;
use super::render::Offscreen;
use super::uniforms::FrameUniforms;
use crate::gpu::Gpu;

/// The size of the trial frame: small, so that it is quick even on the CPU.
pub const PROBE_SIZE: (u32, u32) = (64, 36);

/// The longest a frame at the window's size may take, as estimated from the
/// trial frame, for the window to stay usable.
pub const WINDOW_FRAME_LIMIT: Duration = Duration::from_secs(10);

/// A device for the trial frames, kept between reloads.
#[derive(Default)]
pub struct Probe {
    gpu: Option<Gpu>,
}

impl Probe {
    /// Draws one trial frame of `compiled` (its default parameters, time 0)
    /// and says whether the window may run it at `window` pixels.
    pub fn check(&mut self, compiled: &Compiled, window: (u32, u32)) -> Result<(), String> {
        if self.gpu.is_none() {
            self.gpu = Some(Gpu::headless().map_err(|e| e.to_string())?);
        }
        let gpu = self.gpu.as_ref().expect("created above");
        let mut offscreen = Offscreen::new(gpu);
        let pipeline = offscreen.builder(gpu).build(compiled)?;
        let frame = FrameUniforms::at(0.0, 0, PROBE_SIZE);
        let draw = |offscreen: &mut Offscreen| {
            let start = Instant::now();
            offscreen
                .draw(gpu, &pipeline, &compiled.params, &frame)
                .map(|()| start.elapsed())
        };
        let mut took = draw(&mut offscreen);
        if let Ok(first) = took
            && scaled_time(first, PROBE_SIZE, window) > WINDOW_FRAME_LIMIT
        {
            // A pipeline's first draw can include the driver's own
            // compilation (llvmpipe builds the fragment shader's code for
            // the render state at the first draw), which a heavy shader's
            // trial frame may be mostly made of: time a second frame
            // before refusing. An endless loop never finishes the first.
            took = draw(&mut offscreen).map(|second| first.min(second));
        }
        let took = match took {
            Ok(took) => took,
            Err(stopped) => {
                // The device is still busy with the frame: never wait on it again.
                std::mem::forget((offscreen, pipeline, self.gpu.take()));
                return Err(format!(
                    "{}: {stopped}; the last good shader keeps running",
                    compiled.file
                ));
            }
        };
        let estimate = scaled_time(took, PROBE_SIZE, window);
        if estimate > WINDOW_FRAME_LIMIT {
            return Err(format!(
                "{}: a frame would take about {:.0} s at {}x{} (a {}x{} frame took {:.0} ms): \
                 too slow for the window, so it was not started; an endless loop? \
                 (--scale lowers the resolution) The last good shader keeps running.",
                compiled.file,
                estimate.as_secs_f64(),
                window.0,
                window.1,
                PROBE_SIZE.0,
                PROBE_SIZE.1,
                took.as_secs_f64() * 1e3,
            ));
        }
        Ok(())
    }
}

/// The time of a frame of `to` pixels, from the time of one of `from`
/// pixels: fragment work grows with the pixel count.
fn scaled_time(time: Duration, from: (u32, u32), to: (u32, u32)) -> Duration {
    let ratio = f64::from(to.0 * to.1) / f64::from(from.0 * from.1);
    time.mul_f64(ratio.max(1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_time_scales_with_the_pixel_count_never_below_the_trial() {
        let ms = Duration::from_millis;
        assert_eq!(scaled_time(ms(10), (64, 36), (128, 72)), ms(40));
        assert_eq!(scaled_time(ms(10), (64, 36), (32, 18)), ms(10));
    }
}
