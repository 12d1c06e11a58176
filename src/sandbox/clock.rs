//! The shader clock: time, frame number and frame interval, with pause,
//! resume, restart and single steps. It lives in the app, not in a shader,
//! so it keeps running across reloads. Every method takes `now`, so tests
//! can drive it without waiting.

// std's Instant panics in the browser; web-time's is std's natively.
use web_time::Instant;

/// How far one step (while paused) moves the clock: one frame at 60 Hz.
pub const STEP: f64 = 1.0 / 60.0;

/// The values of one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tick {
    /// Seconds since the start (or the last restart).
    pub time: f64,
    /// Seconds since the previous frame.
    pub delta: f64,
    /// Frames since the start, from 0.
    pub frame: u32,
    /// Frames per second, smoothed over the last frames.
    pub rate: f64,
}

#[derive(Debug, Clone)]
pub struct Clock {
    /// The time when `since` was taken, or the current time while paused.
    base: f64,
    /// When the clock was last resumed; `None` while paused.
    since: Option<Instant>,
    /// The last frame handed out; `None` before the first (or after a restart).
    last: Option<Tick>,
    rate: f64,
}

impl Clock {
    pub fn new(paused: bool, now: Instant) -> Self {
        Clock {
            base: 0.0,
            since: (!paused).then_some(now),
            last: None,
            rate: 60.0,
        }
    }

    pub fn is_paused(&self) -> bool {
        self.since.is_none()
    }

    /// The clock's time at `now` (between frames it runs on).
    pub fn time(&self, now: Instant) -> f64 {
        self.base
            + self
                .since
                .map_or(0.0, |s| now.saturating_duration_since(s).as_secs_f64())
    }

    /// Stops the clock at the last frame shown, so the image does not jump
    /// when something (a parameter) makes the paused frame draw again.
    pub fn pause(&mut self, now: Instant) {
        if self.since.take().is_some() {
            self.base = self.last.map_or(self.time(now), |t| t.time);
        }
    }

    pub fn resume(&mut self, now: Instant) {
        if self.since.is_none() {
            self.since = Some(now);
        }
    }

    pub fn toggle(&mut self, now: Instant) {
        if self.is_paused() {
            self.resume(now);
        } else {
            self.pause(now);
        }
    }

    /// Back to time 0 and frame 0; running or paused as before.
    pub fn restart(&mut self, now: Instant) {
        self.base = 0.0;
        self.last = None;
        if self.since.is_some() {
            self.since = Some(now);
        }
    }

    /// Pauses and moves on by one frame of [`STEP`] seconds.
    pub fn step(&mut self, now: Instant) {
        self.pause(now);
        let time = match self.last {
            Some(last) => last.time + STEP,
            None => self.base,
        };
        self.base = time;
        self.take(time);
    }

    /// The frame to draw now: while running every call is a new frame, while
    /// paused it is the last frame again.
    pub fn tick(&mut self, now: Instant) -> Tick {
        match (self.since, self.last) {
            (None, Some(last)) => last,
            _ => self.take(self.time(now)),
        }
    }

    fn take(&mut self, time: f64) -> Tick {
        let tick = match self.last {
            Some(last) => {
                let delta = (time - last.time).max(0.0);
                if delta > 0.0 {
                    // An exponential average over about ten frames.
                    self.rate += 0.1 * (1.0 / delta - self.rate);
                }
                Tick {
                    time,
                    delta,
                    frame: last.frame + 1,
                    rate: self.rate,
                }
            }
            None => Tick {
                time,
                delta: STEP,
                frame: 0,
                rate: self.rate,
            },
        };
        self.last = Some(tick);
        tick
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    fn at(start: Instant, seconds: f64) -> Instant {
        start + Duration::from_secs_f64(seconds)
    }

    #[test]
    fn running_clock_counts_frames_and_time() {
        let t0 = Instant::now();
        let mut clock = Clock::new(false, t0);
        let first = clock.tick(t0);
        assert_eq!((first.time, first.frame), (0.0, 0));
        let second = clock.tick(at(t0, 0.5));
        assert_eq!((second.time, second.delta, second.frame), (0.5, 0.5, 1));
    }

    #[test]
    fn pause_holds_the_last_frame_and_resume_continues_from_it() {
        let t0 = Instant::now();
        let mut clock = Clock::new(false, t0);
        clock.tick(t0);
        let shown = clock.tick(at(t0, 1.0));
        clock.pause(at(t0, 1.2));
        assert!(clock.is_paused());
        assert_eq!(clock.tick(at(t0, 5.0)), shown, "paused: the same frame");
        clock.resume(at(t0, 10.0));
        let next = clock.tick(at(t0, 10.25));
        assert_eq!((next.time, next.frame), (1.25, 2));
    }

    #[test]
    fn step_and_restart() {
        let t0 = Instant::now();
        let mut clock = Clock::new(true, t0);
        assert_eq!(clock.tick(at(t0, 3.0)).time, 0.0, "starts paused at 0");
        clock.step(at(t0, 4.0));
        let stepped = clock.tick(at(t0, 9.0));
        assert_eq!((stepped.time, stepped.frame), (STEP, 1));
        clock.restart(at(t0, 9.0));
        assert!(clock.is_paused(), "restart keeps paused");
        assert_eq!(clock.tick(at(t0, 9.5)).frame, 0);
        clock.resume(at(t0, 10.0));
        clock.restart(at(t0, 11.0));
        assert_eq!(clock.tick(at(t0, 11.5)).time, 0.5);
    }
}
