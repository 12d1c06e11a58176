//! Short GPU jobs: while the viewer refines, each sample of the image is
//! traced in bands of rows, one band per submission, each band sized from
//! measured times so that a submission keeps the GPU busy for about
//! [`JOB_BUDGET`] (docs/performance.md, "Short GPU jobs"). Between two
//! jobs the window handles input and draws its UI, and neither a browser's
//! GPU watchdog nor a desktop driver's timeout sees a long submission, however slow
//! a whole sample of the scene is.

use std::ops::Range;

use web_time::Duration;

/// What one submission should cost: short enough that input is answered
/// within a frame at 30 fps, long enough that the cost of a submission
/// (display pass, UI, present) stays a small part.
pub const JOB_BUDGET: Duration = Duration::from_millis(30);

/// A job's GPU time is at least this many times the time spent around it
/// (the display pass, the UI, presenting, waiting for the GPU): refining in
/// jobs then takes at most a quarter longer than in whole samples.
const OVERHEAD_SHARE: f64 = 4.0;

/// The budget never grows past this for the overhead's sake: input is
/// still answered within a fifth of a second, and a browser's GPU
/// watchdog (seconds) is far.
const MAX_BUDGET: Duration = Duration::from_millis(200);

/// How finely the costs along the image's height are remembered.
const BINS: usize = 64;

/// Rows of the first job on an image whose costs are unknown.
const FIRST_ROWS: u32 = 8;

/// Over rows whose cost is unknown, a job takes at most this many times
/// the rows of the last measured one.
const GROWTH: u32 = 2;

/// Plans the rows of each job from the times the last ones took.
#[derive(Debug, Clone)]
pub struct JobPlanner {
    budget: Duration,
    /// Seconds per pixel, by band of the image's height (fractions of it,
    /// so that a new resolution keeps what was learnt); 0: not measured.
    cost: [f64; BINS],
    /// The job planned last and not measured yet: its rows, in an image
    /// of that width and height.
    pending: Option<(Range<u32>, (u32, u32))>,
    /// Rows of the last measured job, and its seconds per pixel.
    last: (u32, f64),
    /// The GPU time of the sample in progress so far, and of the last
    /// whole sample.
    sample_time: Duration,
    last_sample_time: Option<Duration>,
    /// The longest job measured since [`JobPlanner::take_longest`].
    longest: Duration,
    jobs: u32,
    /// The GPU time of the last job measured, and the time around a job,
    /// averaged ([`JobPlanner::cycle`]).
    last_time: Duration,
    overhead: Option<Duration>,
}

impl JobPlanner {
    pub fn new(budget: Duration) -> Self {
        JobPlanner {
            budget,
            cost: [0.0; BINS],
            pending: None,
            last: (FIRST_ROWS / GROWTH, 0.0),
            sample_time: Duration::ZERO,
            last_sample_time: None,
            longest: Duration::ZERO,
            jobs: 0,
            last_time: Duration::ZERO,
            overhead: None,
        }
    }

    /// The wall time from the start of one job to the start of the next:
    /// what it holds beyond the job's GPU time is the overhead of a job.
    pub fn cycle(&mut self, wall: Duration) {
        let around = wall.saturating_sub(self.last_time);
        self.overhead = Some(match self.overhead {
            Some(before) => (before * 3 + around) / 4,
            None => around,
        });
    }

    /// What a job may cost: the budget, or more where the overhead of a
    /// job would otherwise be a large part of the time (a busy machine).
    pub fn budget(&self) -> Duration {
        let overhead = self.overhead.unwrap_or_default().mul_f64(OVERHEAD_SHARE);
        self.budget.max(overhead.min(MAX_BUDGET))
    }

    /// The rows of the next job, from row `start` of an image of `size`
    /// pixels: as many as the remembered costs say fit in the budget (at
    /// least one), growing at most [`GROWTH`] times over rows never
    /// measured.
    pub fn next(&mut self, start: u32, (width, height): (u32, u32)) -> Range<u32> {
        let budget = self.budget().as_secs_f64();
        let unknown_limit = start.saturating_add(self.last.0.max(1) * GROWTH);
        let mut spent = 0.0;
        let mut end = start;
        while end < height {
            let known = self.cost[bin(end, height)];
            if known == 0.0 && end >= unknown_limit {
                break;
            }
            let row = f64::from(width) * if known > 0.0 { known } else { self.last.1 };
            if end > start && spent + row > budget {
                break;
            }
            spent += row;
            end += 1;
        }
        debug_assert!(start < height, "no rows left from {start} of {height}");
        let rows = start..end.max(start + 1);
        self.pending = Some((rows.clone(), (width, height)));
        rows
    }

    /// The GPU time the job last planned took. Where the costs of its rows
    /// were known, they are scaled together to the measured time, which
    /// keeps what finer jobs learnt about their differences (the edge of an
    /// object inside a job); where not, each row gets the job's average.
    pub fn measured(&mut self, time: Duration) {
        let Some((rows, (width, height))) = self.pending.take() else {
            return;
        };
        let pixels = f64::from(rows.len() as u32 * width.max(1));
        let per_pixel = time.as_secs_f64() / pixels;
        let bins: Vec<usize> = {
            let mut bins: Vec<usize> = rows.clone().map(|row| bin(row, height)).collect();
            bins.dedup();
            bins
        };
        let known = bins.iter().all(|&b| self.cost[b] > 0.0);
        let predicted: f64 = rows.clone().map(|row| self.cost[bin(row, height)]).sum();
        if known && predicted > 0.0 {
            let factor = per_pixel * rows.len() as f64 / predicted;
            for b in bins {
                self.cost[b] *= factor;
            }
        } else {
            for b in bins {
                self.cost[b] = per_pixel;
            }
        }
        self.last = (rows.len() as u32, per_pixel);
        self.last_time = time;
        self.longest = self.longest.max(time);
        self.jobs += 1;
        self.sample_time += time;
        if rows.end >= height {
            self.last_sample_time = Some(std::mem::take(&mut self.sample_time));
        }
    }

    /// Forgets the sample in progress (the view changed): its time so far
    /// no longer counts. What was learnt of the costs stays.
    pub fn restart(&mut self) {
        self.pending = None;
        self.sample_time = Duration::ZERO;
    }

    /// The GPU time of the last sample traced to its end, all its jobs.
    pub fn last_sample_time(&self) -> Option<Duration> {
        self.last_sample_time
    }

    /// The number of jobs measured and the longest of them, since the last
    /// call.
    pub fn take_longest(&mut self) -> (u32, Duration) {
        let taken = (self.jobs, self.longest);
        self.jobs = 0;
        self.longest = Duration::ZERO;
        taken
    }
}

/// The band of row `row` in an image `height` rows high.
fn bin(row: u32, height: u32) -> usize {
    (row as usize * BINS / height.max(1) as usize).min(BINS - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A GPU whose rows cost `cost(row)` milliseconds each at width 100.
    fn run(planner: &mut JobPlanner, cost: impl Fn(u32) -> f64, height: u32) -> Vec<(u32, f64)> {
        let mut jobs = Vec::new();
        let mut start = 0;
        while start < height {
            let rows = planner.next(start, (100, height));
            assert!(rows.start == start && rows.end > start && rows.end <= height);
            let ms: f64 = rows.clone().map(&cost).sum();
            planner.measured(Duration::from_secs_f64(ms / 1000.0));
            jobs.push((rows.len() as u32, ms));
            start = rows.end;
        }
        jobs
    }

    #[test]
    fn jobs_grow_from_a_few_rows_to_the_budget_and_cover_the_image() {
        let mut planner = JobPlanner::new(Duration::from_millis(30));
        let jobs = run(&mut planner, |_| 1.0, 600);
        assert_eq!(jobs.iter().map(|j| j.0).sum::<u32>(), 600);
        assert_eq!(jobs[0].0, FIRST_ROWS);
        assert!(jobs.iter().all(|&(_, ms)| ms <= 30.0 + 1e-9), "{jobs:?}");
        // 30 rows of 1 ms, but for the rounding of the measured times.
        let mut last = jobs.iter().rev().skip(1).take(5);
        assert!(last.all(|&(rows, _)| (29..=30).contains(&rows)), "{jobs:?}");
        let sample = planner.last_sample_time().unwrap().as_secs_f64();
        assert!((sample - 0.6).abs() < 1e-6, "{sample}");
    }

    /// Later samples know the costs of each band: a band ten times dearer
    /// (a glass object) gets jobs of a tenth of the rows. A job that mixed
    /// cheap and dear rows smears their costs over its bands, so the edges
    /// of the band are learnt over a few samples; by the third, no job passes
    /// the budget by more than one dear row.
    #[test]
    fn a_known_costly_band_gets_shorter_jobs() {
        let cost = |row: u32| if (200..300).contains(&row) { 10.0 } else { 1.0 };
        let mut planner = JobPlanner::new(Duration::from_millis(30));
        run(&mut planner, cost, 640);
        run(&mut planner, cost, 640);
        let third = run(&mut planner, cost, 640);
        let longest = third.iter().map(|j| j.1).fold(0.0, f64::max);
        assert!(longest <= 30.0 + 10.0, "{third:?}");
        assert!(third.iter().any(|&(rows, _)| rows <= 3), "{third:?}");
    }

    #[test]
    fn a_job_is_never_empty_even_when_one_row_is_over_the_budget() {
        let mut planner = JobPlanner::new(Duration::from_millis(30));
        let jobs = run(&mut planner, |_| 100.0, 20);
        assert!(jobs.iter().all(|&(rows, _)| rows >= 1));
        assert_eq!(jobs.iter().map(|j| j.0).sum::<u32>(), 20);
    }
}
