//! Short GPU jobs: while the viewer refines, each sample of the image is
//! traced in spans of pixels (whole rows, or a part of a row where one row
//! costs more than a job may), one span per submission, each sized from
//! measured times so that a submission keeps the GPU busy for about
//! [`JOB_BUDGET`] (docs/performance.md, "Short GPU jobs"). Between two
//! jobs the window handles input and draws its UI, and neither a browser's
//! GPU watchdog nor a desktop driver's timeout sees a long submission, however slow
//! a whole sample, or a single row, of the scene is.

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

/// Pixels of the first job on an image whose costs are unknown: few, since
/// on a slow adapter one pixel of a glass scene can take milliseconds
/// (docs/performance.md, "Short GPU jobs", has the times); the jobs double
/// from there, so a cheap scene reaches the budget within a few jobs. Jobs
/// [`JobPlanner::in_whole_rows`] make the first job a row all the same.
const FIRST_PIXELS: u32 = 64;

/// Over pixels whose cost is unknown, a job takes at most this many times
/// the pixels of the last measured one.
const GROWTH: u32 = 2;

/// The fewest pixels of a job: a CPU rasteriser shades pixels in groups
/// (llvmpipe: 4 x 4 blocks, 8 lanes at once), so a thinner piece of a row
/// would cost nearly as much as this many pixels.
const MIN_PIXELS: u32 = 16;

/// Plans the pixels of each job from the times the last ones took. A job
/// is a range of pixel indices in row-major order (`y * width + x`) of the
/// sample in progress; [`span_rects`] turns it into scissor rectangles.
#[derive(Debug, Clone)]
pub struct JobPlanner {
    budget: Duration,
    /// Seconds per pixel, by band of the image's height (fractions of it,
    /// so that a new resolution keeps what was learnt); 0: not measured.
    cost: [f64; BINS],
    /// The job planned last and not measured yet: its pixels, in an image
    /// of that width and height.
    pending: Option<(Range<u32>, (u32, u32))>,
    /// Pixels of the last measured job, and its seconds per pixel; none
    /// before the first.
    last: Option<(u32, f64)>,
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
    /// A job is at least a row ([`JobPlanner::in_whole_rows`]).
    whole_rows: bool,
}

impl JobPlanner {
    pub fn new(budget: Duration) -> Self {
        JobPlanner {
            budget,
            cost: [0.0; BINS],
            pending: None,
            last: None,
            sample_time: Duration::ZERO,
            last_sample_time: None,
            longest: Duration::ZERO,
            jobs: 0,
            last_time: Duration::ZERO,
            overhead: None,
            whole_rows: false,
        }
    }

    /// Jobs of a row at least, never a piece of one: for job times that
    /// include more than the job. In the browser without timestamp queries
    /// a job is timed from its submission to the GPU's "work done", which
    /// includes the display and UI passes of the frames queued before it
    /// (hundreds of milliseconds on SwiftShader with the panel shown):
    /// pieces of 16 pixels each measured at that queue's length made the
    /// page's first sample take over 20 minutes (docs/performance.md,
    /// "Short GPU jobs").
    pub fn in_whole_rows(mut self) -> Self {
        self.whole_rows = true;
        self
    }

    /// The fewest pixels of a job in an image `width` pixels wide.
    fn min_pixels(&self, width: u32) -> u32 {
        if self.whole_rows { width } else { MIN_PIXELS }
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

    /// The pixels of the next job, from pixel `start` of an image of
    /// `size` pixels: as many as the remembered costs say fit in the budget
    /// (at least [`Self::min_pixels`], or what is left), growing at most
    /// [`GROWTH`] times over pixels never measured. A job ends inside a
    /// row only where the budget ends there.
    pub fn next(&mut self, start: u32, (width, height): (u32, u32)) -> Range<u32> {
        let width = width.max(1);
        let total = width * height;
        debug_assert!(start < total, "no pixels left from {start} of {total}");
        let budget = self.budget().as_secs_f64();
        let (last_pixels, last_cost) = self.last.unwrap_or((FIRST_PIXELS / GROWTH, 0.0));
        let unknown_limit = start.saturating_add(last_pixels.max(1).saturating_mul(GROWTH));
        let mut spent = 0.0;
        let mut end = start;
        while end < total {
            let row = end / width;
            let known = self.cost[bin(row, height)];
            let (limit, per_pixel) = if known > 0.0 {
                ((row + 1) * width, known)
            } else if end < unknown_limit {
                (((row + 1) * width).min(unknown_limit), last_cost)
            } else {
                break;
            };
            let fit = if per_pixel > 0.0 {
                ((budget - spent) / per_pixel).max(0.0)
            } else {
                f64::INFINITY
            };
            let take = fit.min(f64::from(limit - end)) as u32;
            spent += f64::from(take) * per_pixel;
            end += take;
            if end < limit {
                break;
            }
        }
        let span = start..end.max(start + self.min_pixels(width)).min(total);
        self.pending = Some((span.clone(), (width, height)));
        span
    }

    /// The GPU time the job last planned took. Where the costs of its bands
    /// were known, they are scaled together to the measured time, which
    /// keeps what finer jobs learnt about their differences (the edge of an
    /// object inside a job); where not, each band gets the job's average.
    pub fn measured(&mut self, time: Duration) {
        let Some((span, (width, height))) = self.pending.take() else {
            return;
        };
        let pixels = span.len() as u32;
        let per_pixel = time.as_secs_f64() / f64::from(pixels.max(1));
        let bands = pixels_by_band(&span, (width, height));
        let known = bands.iter().all(|&(b, _)| self.cost[b] > 0.0);
        let predicted: f64 = bands
            .iter()
            .map(|&(b, n)| f64::from(n) * self.cost[b])
            .sum();
        if known && predicted > 0.0 {
            let factor = time.as_secs_f64() / predicted;
            for (b, _) in bands {
                self.cost[b] *= factor;
            }
        } else {
            for (b, _) in bands {
                self.cost[b] = per_pixel;
            }
        }
        self.last = Some((pixels, per_pixel));
        self.last_time = time;
        self.longest = self.longest.max(time);
        self.jobs += 1;
        self.sample_time += time;
        if span.end >= width * height {
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

/// The scissor rectangles `[x, y, width, height]` that cover exactly the
/// pixels `span` (row-major indices) of an image `width` pixels wide: the
/// rest of a first row begun, the whole rows, the start of a last row.
pub fn span_rects(span: &Range<u32>, width: u32) -> Vec<[u32; 4]> {
    let width = width.max(1);
    let (first_row, first_x) = (span.start / width, span.start % width);
    let (last_row, last_x) = (span.end / width, span.end % width);
    if span.is_empty() {
        return Vec::new();
    }
    if first_row == last_row {
        return vec![[first_x, first_row, last_x - first_x, 1]];
    }
    let mut rects = Vec::with_capacity(3);
    let mut whole_from = first_row;
    if first_x > 0 {
        rects.push([first_x, first_row, width - first_x, 1]);
        whole_from += 1;
    }
    if last_row > whole_from {
        rects.push([0, whole_from, width, last_row - whole_from]);
    }
    if last_x > 0 {
        rects.push([0, last_row, last_x, 1]);
    }
    rects
}

/// How many pixels of `span` fall in each band of the image's height.
fn pixels_by_band(span: &Range<u32>, (width, height): (u32, u32)) -> Vec<(usize, u32)> {
    let width = width.max(1);
    let mut bands: Vec<(usize, u32)> = Vec::new();
    for [_, y, w, h] in span_rects(span, width) {
        for row in y..y + h {
            let b = bin(row, height);
            match bands.last_mut() {
                Some((last, n)) if *last == b => *n += w,
                _ => bands.push((b, w)),
            }
        }
    }
    bands
}

/// The band of row `row` in an image `height` rows high.
fn bin(row: u32, height: u32) -> usize {
    (row as usize * BINS / height.max(1) as usize).min(BINS - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    const WIDTH: u32 = 100;

    /// A GPU whose rows cost `cost(row)` milliseconds each at width 100:
    /// every job of one sample, as (pixels, milliseconds).
    fn run(planner: &mut JobPlanner, cost: impl Fn(u32) -> f64, height: u32) -> Vec<(u32, f64)> {
        let total = WIDTH * height;
        let mut jobs = Vec::new();
        let mut start = 0;
        while start < total {
            let span = planner.next(start, (WIDTH, height));
            assert!(span.start == start && span.end > start && span.end <= total);
            let ms: f64 = span
                .clone()
                .map(|p| cost(p / WIDTH) / f64::from(WIDTH))
                .sum();
            planner.measured(Duration::from_secs_f64(ms / 1000.0));
            jobs.push((span.len() as u32, ms));
            start = span.end;
        }
        jobs
    }

    #[test]
    fn jobs_grow_from_a_few_pixels_to_the_budget_and_cover_the_image() {
        let mut planner = JobPlanner::new(Duration::from_millis(30));
        let jobs = run(&mut planner, |_| 1.0, 600);
        assert_eq!(jobs.iter().map(|j| j.0).sum::<u32>(), 600 * WIDTH);
        assert_eq!(jobs[0].0, FIRST_PIXELS);
        assert!(jobs.iter().all(|&(_, ms)| ms <= 30.0 + 1e-9), "{jobs:?}");
        // 30 rows of 1 ms, but for the rounding of the measured times.
        let mut last = jobs.iter().rev().skip(1).take(5);
        assert!(
            last.all(|&(pixels, _)| (2990..=3000).contains(&pixels)),
            "{jobs:?}"
        );
        let sample = planner.last_sample_time().unwrap().as_secs_f64();
        assert!((sample - 0.6).abs() < 1e-6, "{sample}");
    }

    /// Later samples know the costs of each band: a band ten times dearer
    /// (a glass object) gets jobs of a tenth of the pixels. A job that
    /// mixed cheap and dear rows smears their costs over its bands, so the
    /// edges of the band are learnt over a few samples; by the third, no job
    /// passes the budget by more than one dear row.
    #[test]
    fn a_known_costly_band_gets_shorter_jobs() {
        let cost = |row: u32| if (200..300).contains(&row) { 10.0 } else { 1.0 };
        let mut planner = JobPlanner::new(Duration::from_millis(30));
        run(&mut planner, cost, 640);
        run(&mut planner, cost, 640);
        let third = run(&mut planner, cost, 640);
        let longest = third.iter().map(|j| j.1).fold(0.0, f64::max);
        assert!(longest <= 30.0 + 10.0, "{third:?}");
        assert!(
            third.iter().any(|&(pixels, _)| pixels <= 3 * WIDTH),
            "{third:?}"
        );
    }

    /// A row that alone costs more than the budget (the glass bunny in a
    /// browser on a CPU rasteriser) is cut into pieces of a row: once the
    /// first job has measured the cost, no job passes the budget by more
    /// than a pixel's cost, and none but the image's last is thinner than
    /// [`MIN_PIXELS`].
    #[test]
    fn a_row_over_the_budget_is_cut_into_pieces_within_the_budget() {
        let mut planner = JobPlanner::new(Duration::from_millis(30));
        let jobs = run(&mut planner, |_| 100.0, 20);
        assert_eq!(jobs.iter().map(|j| j.0).sum::<u32>(), 20 * WIDTH);
        assert!(
            jobs[1..].iter().all(|&(_, ms)| ms <= 30.0 + 1.0),
            "{jobs:?}"
        );
        let (_, all_but_last) = jobs.split_last().unwrap();
        assert!(
            all_but_last.iter().all(|&(pixels, _)| pixels >= MIN_PIXELS),
            "{jobs:?}"
        );
        assert!(
            jobs[1..].iter().all(|&(pixels, _)| pixels < WIDTH),
            "{jobs:?}"
        );
    }

    /// Where job times include the queue before them, the same costly rows
    /// are never cut: each job is whole rows, from the first one on.
    #[test]
    fn in_whole_rows_a_costly_row_is_one_job() {
        let mut planner = JobPlanner::new(Duration::from_millis(30)).in_whole_rows();
        let jobs = run(&mut planner, |_| 100.0, 20);
        assert_eq!(jobs.len(), 20, "{jobs:?}");
        assert!(jobs.iter().all(|&(pixels, _)| pixels == WIDTH), "{jobs:?}");
    }

    /// However a span starts and ends, its rectangles cover each of its
    /// pixels once and nothing else.
    #[test]
    fn span_rects_cover_exactly_the_span() {
        let (width, height) = (7, 5);
        for start in 0..width * height {
            for end in start..=width * height {
                let mut covered = vec![0; (width * height) as usize];
                for [x, y, w, h] in span_rects(&(start..end), width) {
                    assert!(w > 0 && h > 0 && x + w <= width && y + h <= height);
                    for row in y..y + h {
                        for col in x..x + w {
                            covered[(row * width + col) as usize] += 1;
                        }
                    }
                }
                for (p, &n) in covered.iter().enumerate() {
                    let inside = (start..end).contains(&(p as u32));
                    assert_eq!(n, u32::from(inside), "pixel {p} of {start}..{end}");
                }
            }
        }
    }
}
