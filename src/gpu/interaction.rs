//! The viewer's resolution scale while the view moves (the camera dragged,
//! or a slider of the panel held, such as a Julia set's c): fewer traced
//! pixels, one sample each, so that frames keep coming. With a frame budget
//! the scale follows the measured frame time (docs/performance.md, "Julia
//! sets: dragging c"); the full image refines once the movement stops.

use web_time::Duration;

/// The frame budget while the view moves, by default: 100 ms, ten frames
/// a second, where a dragged slider still feels live (docs/performance.md,
/// "Julia sets: dragging c").
pub const DEFAULT_FRAME_BUDGET_MS: f32 = 100.0;

/// The smallest traced fraction of the window resolution (1280 x 720 traces
/// 160 x 90).
pub const MIN_SCALE: f32 = 0.125;

/// The largest step of the scale from one frame to the next, up or down (a
/// factor): one slow frame (another program took the CPU) must not drop the
/// image to its coarsest at once.
const MAX_STEP: f32 = 1.5;

/// Changes smaller than this fraction of the scale are not made: each change
/// reallocates the image, and frame times jitter by this much anyway.
const DEAD_BAND: f32 = 0.1;

/// The scale for the next moving frame, from the scale and the measured
/// trace time of the last one. Tracing time grows with the number of pixels,
/// the square of the scale, so the scale that fits the budget is
/// `scale * sqrt(budget / time)`; the step is limited to [`MAX_STEP`] and
/// changes within [`DEAD_BAND`] are skipped, except a step up to full
/// resolution: the band would otherwise hold a scale just below 1 for good
/// though the budget allows 1. The result lies in `MIN_SCALE..=1`.
pub fn next_scale(scale: f32, frame: Duration, budget: Duration) -> f32 {
    let time = frame.as_secs_f32().max(1e-6);
    let ideal = scale * (budget.as_secs_f32() / time).sqrt();
    let stepped = ideal.clamp(scale / MAX_STEP, scale * MAX_STEP);
    let next = stepped.clamp(MIN_SCALE, 1.0);
    if next < 1.0 && (next - scale).abs() < DEAD_BAND * scale {
        scale.clamp(MIN_SCALE, 1.0)
    } else {
        next
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ms(x: u64) -> Duration {
        Duration::from_millis(x)
    }

    /// A frame four times over budget halves the scale (a quarter of the
    /// pixels), within the step limit.
    #[test]
    fn a_slow_frame_lowers_the_scale_by_the_root_of_the_overrun() {
        assert_eq!(next_scale(0.5, ms(400), ms(100)), 0.5 / MAX_STEP);
        assert!((next_scale(0.5, ms(160), ms(100)) - 0.5 * (100.0f32 / 160.0).sqrt()).abs() < 1e-6);
    }

    #[test]
    fn a_fast_frame_raises_it_up_to_full_resolution() {
        assert!((next_scale(0.25, ms(50), ms(100)) - 0.25 * 2f32.sqrt()).abs() < 1e-6);
        assert_eq!(next_scale(0.9, ms(10), ms(100)), 1.0);
    }

    /// Within the dead band the scale stays, so the image is not
    /// reallocated for jitter.
    #[test]
    fn a_frame_near_the_budget_keeps_the_scale() {
        assert_eq!(next_scale(0.4, ms(95), ms(100)), 0.4);
        assert_eq!(next_scale(0.4, ms(110), ms(100)), 0.4);
    }

    /// Just below full resolution, a frame that would fit at 1 steps up
    /// to 1 even by less than the dead band; one that would not stays.
    #[test]
    fn full_resolution_is_reached_from_just_below_it() {
        assert_eq!(next_scale(0.96, ms(90), ms(100)), 1.0);
        assert_eq!(next_scale(0.96, ms(95), ms(100)), 0.96);
        assert_eq!(next_scale(1.0, ms(105), ms(100)), 1.0);
    }

    #[test]
    fn the_scale_never_leaves_its_range() {
        assert_eq!(next_scale(MIN_SCALE, ms(10_000), ms(100)), MIN_SCALE);
        assert_eq!(next_scale(1.0, ms(1), ms(100)), 1.0);
        assert_eq!(next_scale(0.5, Duration::ZERO, ms(100)), 0.75);
    }
}
