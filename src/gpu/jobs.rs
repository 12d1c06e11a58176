//! Short GPU jobs: while the viewer refines, each sample of the image is
//! traced in spans of pixels (whole rows, or a part of a row where one row
//! costs more than a job may), one span per submission, each sized from
//! measured times so that a submission keeps the GPU busy for about
//! [`JOB_BUDGET`] (docs/performance.md, "Short GPU jobs"). Between two
//! jobs the window handles input and draws its UI, and neither a browser's
//! GPU watchdog nor a desktop driver's timeout sees a long submission, however slow
//! a whole sample, or a single row, of the scene is.

use std::ops::Range;

use web_time::{Duration, Instant};

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

/// How finely the costs are remembered: a grid of cells over the image,
/// rows of cells along its height and columns across its width (fractions
/// of the image, so that a new resolution keeps what was learnt). Columns
/// too: in a row, a glass object's pixels cost many times the floor's
/// beside them, and a job cut from a row that crosses it must see that
/// (docs/performance.md, "Short GPU jobs").
const CELL_ROWS: usize = 128;
const CELL_COLUMNS: usize = 64;

/// A cell's cost falls at most to this fraction of what it was by one
/// job (0.5 let the object of `a_costly_object_in_a_cheap_row_keeps_jobs_within_the_budget`
/// take 101 ms in the second sample, 0.8 51 ms), while it rises at once: a cell holds several rows, and a job that
/// traced only its cheap ones (the floor under an object's lower edge) must
/// not make the dear ones look cheap to the next sample.
const MAX_FALL: f64 = 0.8;

/// Pixels of the first job on an image whose costs are unknown: few, since
/// on a slow adapter one pixel of a glass scene can take milliseconds
/// (docs/performance.md, "Short GPU jobs", has the times); the jobs double
/// from there, so a cheap scene reaches the budget within a few jobs. Jobs
/// [`JobPlanner::in_whole_rows`] make the first job a row all the same.
const FIRST_PIXELS: u32 = 64;

/// Over pixels whose cost is unknown, a job takes at most this many times
/// the pixels of the last measured one (of those of them that fitted in
/// the budget).
const GROWTH: u32 = 2;

/// Over pixels whose cost is unknown, a job spans at most this many rows
/// of cells (a 32nd of the image's height): during the first sample, the
/// rows traced so far say nothing of an object that starts below them, and
/// a job sized from the sky above the glass bunny took over a second
/// (docs/performance.md, "Short GPU jobs").
const UNKNOWN_CELL_ROWS: usize = 4;

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
    /// Seconds per pixel, by cell (row of cells times [`CELL_COLUMNS`]
    /// plus column); 0: not measured.
    cost: Vec<f64>,
    /// The job planned last and not measured yet.
    pending: Option<Pending>,
    /// The next job is the first drawn with new pipelines
    /// ([`JobPlanner::pipelines_changed`]).
    first_draw: bool,
    /// Pixels of the last measured job (at most those that fitted in the
    /// budget), and its seconds per pixel; none before the first.
    last: Option<(u32, f64)>,
    /// The GPU time of the sample in progress so far, and of the last
    /// whole sample.
    sample_time: Duration,
    last_sample_time: Option<Duration>,
    /// The jobs measured since [`JobPlanner::take_jobs`].
    since: JobsSince,
    /// The GPU time of the last job measured, and the time around a job,
    /// averaged ([`JobPlanner::cycle`]).
    last_time: Duration,
    overhead: Option<Duration>,
    /// A job is at least a row ([`JobPlanner::in_whole_rows`]).
    whole_rows: bool,
}

/// A job planned and not measured yet: its pixels, in an image of that
/// width and height, the seconds it was predicted to take, the budget it
/// was sized for, and whether it is the first drawn with new pipelines.
#[derive(Debug, Clone)]
struct Pending {
    span: Range<u32>,
    size: (u32, u32),
    predicted: f64,
    budget: Duration,
    first_draw: bool,
}

/// A job measured (the longest of some, in [`JobsSince`]): its GPU time,
/// what the planner predicted for it, the budget it was sized for, and its
/// pixels. A time far over its
/// prediction is a misjudged cost (or a loaded machine); a prediction over
/// the budget, a job that could not be cut smaller.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MeasuredJob {
    pub time: Duration,
    pub predicted: Duration,
    pub budget: Duration,
    pub pixels: u32,
}

impl MeasuredJob {
    /// Keeps the longer of the two.
    fn keep_longer(&mut self, job: MeasuredJob) {
        if job.time > self.time {
            *self = job;
        }
    }
}

/// The jobs measured since the last [`JobPlanner::take_jobs`]: how many,
/// the longest of all, and the longest of those the planner sized. The
/// first job drawn with new pipelines is the one it cannot size: its time
/// is the GPU's first draw (SwiftShader compiles the shader then), whatever
/// its pixels ([`JobPlanner::pipelines_changed`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct JobsSince {
    pub count: u32,
    pub longest: MeasuredJob,
    pub longest_sized: MeasuredJob,
}

impl JobPlanner {
    pub fn new(budget: Duration) -> Self {
        JobPlanner {
            budget,
            cost: vec![0.0; CELL_ROWS * CELL_COLUMNS],
            pending: None,
            first_draw: false,
            last: None,
            sample_time: Duration::ZERO,
            last_sample_time: None,
            since: JobsSince::default(),
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

    /// The seconds per pixel expected in `cell`: its measured cost, else
    /// the costliest measured of the three cells above it (objects are
    /// whole: during the first sample, the rows just traced are the best
    /// guess of the next ones, and the dearest of them the safe one);
    /// `None` where neither is known.
    fn estimate(&self, cell: usize) -> Option<f64> {
        let known = |c: usize| Some(self.cost[c]).filter(|&c| c > 0.0);
        let (row, column) = (cell / CELL_COLUMNS, cell % CELL_COLUMNS);
        known(cell).or_else(|| {
            let above = row.checked_sub(1)? * CELL_COLUMNS;
            let columns = column.saturating_sub(1)..=(column + 1).min(CELL_COLUMNS - 1);
            columns.filter_map(|c| known(above + c)).reduce(f64::max)
        })
    }

    /// The pixels of the next job, from pixel `start` of an image of
    /// `size` pixels: as many as the remembered costs of the cells they
    /// cross say fit in the budget (at least [`Self::min_pixels`], or what
    /// is left); over pixels whose cell was never measured, growing at
    /// most [`GROWTH`] times and spanning at most [`UNKNOWN_CELL_ROWS`]
    /// rows of cells. A job ends inside a row only where the budget ends
    /// there.
    pub fn next(&mut self, start: u32, (width, height): (u32, u32)) -> Range<u32> {
        let width = width.max(1);
        let total = width * height;
        debug_assert!(start < total, "no pixels left from {start} of {total}");
        let budget = self.budget();
        let (last_pixels, last_cost) = self.last.unwrap_or((FIRST_PIXELS / GROWTH, 0.0));
        let mut unknown_limit = start.saturating_add(last_pixels.max(1).saturating_mul(GROWTH));
        let mut unknown_met = false;
        let mut spent = 0.0;
        let mut end = start;
        while end < total {
            let (row, x) = (end / width, end % width);
            let column = cell_column(x, width);
            let cell = row_cells(row, height) + column;
            if self.cost[cell] <= 0.0 && !std::mem::replace(&mut unknown_met, true) {
                let rows_end = first_row(cell_row(row, height) + UNKNOWN_CELL_ROWS, height);
                unknown_limit = unknown_limit.min(rows_end.min(height) * width);
            }
            // The piece of this row in this cell.
            let row_end = row * width + column_start(column + 1, width).min(width);
            let (limit, per_pixel) = match (self.cost[cell] > 0.0, self.estimate(cell)) {
                (true, Some(known)) => (row_end, known),
                _ if end >= unknown_limit => break,
                (_, guess) => (row_end.min(unknown_limit), guess.unwrap_or(last_cost)),
            };
            let fit = if per_pixel > 0.0 {
                ((budget.as_secs_f64() - spent) / per_pixel).max(0.0)
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
        let predicted = self.predict(&span, (width, height), last_cost);
        self.pending = Some(Pending {
            span: span.clone(),
            size: (width, height),
            predicted,
            budget,
            first_draw: std::mem::take(&mut self.first_draw),
        });
        span
    }

    /// The seconds `span` is expected to take: each cell's pixels at its
    /// estimate, `fallback` where there is none.
    fn predict(&self, span: &Range<u32>, size: (u32, u32), fallback: f64) -> f64 {
        pixels_by_cell(span, size)
            .iter()
            .map(|&(cell, n)| f64::from(n) * self.estimate(cell).unwrap_or(fallback))
            .sum()
    }

    /// The GPU time the job last planned took: counted, and learnt from
    /// ([`Self::learn`]) unless it was the first draw with new pipelines.
    /// Returns whether the job ended a sample; `None` for a job of a
    /// sample restarted since.
    pub fn measured(&mut self, time: Duration) -> Option<bool> {
        let Pending {
            span,
            size,
            predicted,
            budget,
            first_draw,
        } = self.pending.take()?;
        let pixels = span.len() as u32;
        let seconds = time.as_secs_f64();
        log::debug!(
            "job start={} pixels={pixels} predicted_ms={:.2} budget_ms={:.2} ms={:.2} \
             first_draw={first_draw}",
            span.start,
            predicted * 1e3,
            budget.as_secs_f64() * 1e3,
            seconds * 1e3
        );
        let job = MeasuredJob {
            time,
            predicted: Duration::from_secs_f64(predicted),
            budget,
            pixels,
        };
        if !first_draw {
            self.learn(&span, size, seconds);
            self.since.longest_sized.keep_longer(job);
        }
        self.last_time = time;
        self.since.longest.keep_longer(job);
        self.since.count += 1;
        self.sample_time += time;
        let ended = span.end >= size.0 * size.1;
        if ended {
            self.last_sample_time = Some(std::mem::take(&mut self.sample_time));
        }
        Some(ended)
    }

    /// The next job is the first drawn with new pipelines: its time holds
    /// what the GPU does at a pipeline's first draw, not the pixels'. On
    /// SwiftShader that is compiling the shader, about a second for 64
    /// pixels that cost a millisecond later; learnt as their cost, it made
    /// every next job of the sample the fewest pixels, hundreds of them
    /// (docs/web.md, "Where a sample's time goes"). It is counted, and not
    /// learnt from.
    pub fn pipelines_changed(&mut self) {
        self.first_draw = true;
    }

    /// What a job of `span` taking `seconds` says of the costs: each cell
    /// it crossed gets its estimate (its cost, or the guess from the cells
    /// above), all scaled together to the measured time, so that what finer
    /// jobs learnt about their differences (the edge of an object inside a
    /// job) is kept; cells with no estimate get the job's average. And how
    /// far the next job may grow.
    fn learn(&mut self, span: &Range<u32>, size: (u32, u32), seconds: f64) {
        let pixels = span.len() as u32;
        let per_pixel = seconds / f64::from(pixels.max(1));
        let cells = pixels_by_cell(span, size);
        let estimates: Vec<Option<f64>> = cells.iter().map(|&(c, _)| self.estimate(c)).collect();
        let guessed: f64 = cells
            .iter()
            .zip(&estimates)
            .map(|(&(_, n), e)| f64::from(n) * e.unwrap_or(0.0))
            .sum();
        let unguessed: u32 = cells
            .iter()
            .zip(&estimates)
            .filter(|(_, e)| e.is_none())
            .map(|(&(_, n), _)| n)
            .sum();
        // The cells without an estimate take what the others leave of the
        // time, at least the job's average if they leave nothing.
        let rest = if unguessed > 0 {
            ((seconds - guessed) / f64::from(unguessed)).max(per_pixel)
        } else {
            0.0
        };
        let total = guessed + rest * f64::from(unguessed);
        let factor = if total > 0.0 { seconds / total } else { 0.0 };
        for (&(cell, _), estimate) in cells.iter().zip(&estimates) {
            let before = self.cost[cell];
            self.cost[cell] = (estimate.unwrap_or(rest) * factor).max(before * MAX_FALL);
        }
        // A job far over the budget (it met a dear object over pixels
        // never measured) lets the next grow only from the pixels that
        // would have fitted.
        let fitted = (self.budget().as_secs_f64() / per_pixel.max(f64::MIN_POSITIVE)) as u32;
        self.last = Some((pixels.min(fitted.max(MIN_PIXELS)), per_pixel));
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

    /// The jobs measured since the last call.
    pub fn take_jobs(&mut self) -> JobsSince {
        std::mem::take(&mut self.since)
    }
}

/// Where a sample's wall time goes (docs/web.md, "Where a sample's time
/// goes"): its jobs, their GPU time together, the frames presented while it
/// was traced, and the wall time from its first job's submission to the
/// moment its last job's time came back. The wall time less the jobs' GPU
/// time is what refining in jobs costs around them.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SampleTally {
    pub jobs: u32,
    pub gpu: Duration,
    pub frames: u32,
    pub wall: Duration,
    /// When its first job was submitted; `None` before.
    started: Option<Instant>,
}

impl SampleTally {
    /// A job of the sample was submitted.
    pub fn job_submitted(&mut self) {
        self.started.get_or_insert_with(Instant::now);
        self.jobs += 1;
    }

    /// A job's GPU time came back.
    pub fn job_measured(&mut self, time: Duration) {
        self.gpu += time;
        self.wall = self.started.map_or(Duration::ZERO, |s| s.elapsed());
    }

    /// A frame was presented while the sample was traced.
    pub fn frame_presented(&mut self) {
        if self.started.is_some() {
            self.frames += 1;
        }
    }

    /// The wall time since the first job, so far.
    pub fn elapsed(&self) -> Duration {
        self.started.map_or(Duration::ZERO, |s| s.elapsed())
    }

    /// As an event line's fields: `jobs=J gpu_ms=G wall_ms=W frames=F`.
    pub fn fields(&self) -> String {
        format!(
            "jobs={} gpu_ms={:.1} wall_ms={:.1} frames={}",
            self.jobs,
            self.gpu.as_secs_f64() * 1e3,
            self.wall.as_secs_f64() * 1e3,
            self.frames
        )
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

/// How many pixels of `span` fall in each cell, each cell once.
fn pixels_by_cell(span: &Range<u32>, (width, height): (u32, u32)) -> Vec<(usize, u32)> {
    let width = width.max(1);
    let mut counts = vec![0u32; CELL_ROWS * CELL_COLUMNS];
    for [x, y, w, h] in span_rects(span, width) {
        for row in y..y + h {
            let first = row_cells(row, height);
            for column in cell_column(x, width)..=cell_column(x + w - 1, width) {
                let from = column_start(column, width).max(x);
                let to = column_start(column + 1, width).min(x + w);
                counts[first + column] += to.saturating_sub(from);
            }
        }
    }
    counts
        .into_iter()
        .enumerate()
        .filter(|&(_, n)| n > 0)
        .collect()
}

/// The index of the first cell of row `row` in an image `height` rows high.
fn row_cells(row: u32, height: u32) -> usize {
    cell_row(row, height) * CELL_COLUMNS
}

/// The row of cells of pixel row `row` in an image `height` rows high.
fn cell_row(row: u32, height: u32) -> usize {
    (row as usize * CELL_ROWS / height.max(1) as usize).min(CELL_ROWS - 1)
}

/// The first pixel row of the row of cells `cells` (the height for the
/// one after the last): the least row whose [`cell_row`] is it.
fn first_row(cells: usize, height: u32) -> u32 {
    (cells * height as usize).div_ceil(CELL_ROWS) as u32
}

/// The column of cells of pixel column `x` in an image `width` wide.
fn cell_column(x: u32, width: u32) -> usize {
    (x as usize * CELL_COLUMNS / width.max(1) as usize).min(CELL_COLUMNS - 1)
}

/// The first pixel column of the column of cells `column` (the width for
/// the one after the last): the least `x` whose [`cell_column`] is it.
fn column_start(column: usize, width: u32) -> u32 {
    (column * width as usize).div_ceil(CELL_COLUMNS) as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    const WIDTH: u32 = 100;

    /// A GPU whose rows cost `cost(row)` milliseconds each at width 100:
    /// every job of one sample, as (pixels, milliseconds).
    fn run(planner: &mut JobPlanner, cost: impl Fn(u32) -> f64, height: u32) -> Vec<(u32, f64)> {
        run_pixels(planner, |_, row| cost(row) / f64::from(WIDTH), height)
    }

    /// A GPU whose pixel (x, y) costs `cost(x, y)` milliseconds: every job
    /// of one sample of an image 100 pixels wide, as (pixels, milliseconds).
    fn run_pixels(
        planner: &mut JobPlanner,
        cost: impl Fn(u32, u32) -> f64,
        height: u32,
    ) -> Vec<(u32, f64)> {
        let total = WIDTH * height;
        let mut jobs = Vec::new();
        let mut start = 0;
        while start < total {
            let span = planner.next(start, (WIDTH, height));
            assert!(span.start == start && span.end > start && span.end <= total);
            let ms: f64 = span.clone().map(|p| cost(p % WIDTH, p / WIDTH)).sum();
            planner.measured(Duration::from_secs_f64(ms / 1000.0));
            jobs.push((span.len() as u32, ms));
            start = span.end;
        }
        jobs
    }

    /// During the first sample a job over unknown pixels spans at most
    /// [`UNKNOWN_CELL_ROWS`] rows of cells (here 18 or 19 rows of 1 ms);
    /// from the second on, the jobs fill the budget.
    #[test]
    fn jobs_grow_from_a_few_pixels_to_the_budget_and_cover_the_image() {
        let mut planner = JobPlanner::new(Duration::from_millis(30));
        let first = run(&mut planner, |_| 1.0, 600);
        assert_eq!(first.iter().map(|j| j.0).sum::<u32>(), 600 * WIDTH);
        assert_eq!(first[0].0, FIRST_PIXELS);
        assert!(first.iter().all(|&(_, ms)| ms <= 30.0 + 1e-9), "{first:?}");
        assert!(first.iter().all(|&(pixels, _)| pixels <= 2000), "{first:?}");
        let sample = planner.last_sample_time().unwrap().as_secs_f64();
        assert!((sample - 0.6).abs() < 1e-6, "{sample}");
        let second = run(&mut planner, |_| 1.0, 600);
        assert!(
            second.iter().all(|&(_, ms)| ms <= 30.0 + 1e-9),
            "{second:?}"
        );
        // 30 rows of 1 ms, but for the rounding of the measured times.
        let mut last = second.iter().rev().skip(1).take(5);
        assert!(
            last.all(|&(pixels, _)| (2990..=3000).contains(&pixels)),
            "{second:?}"
        );
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

    /// A glass object over a cheap floor: in the rows it crosses, its
    /// pixels cost 500 times the floor's, and a row costs more than the
    /// budget, so jobs are pieces of rows. A cost per band of rows averaged
    /// the object with the floor beside it, and a piece lying on the
    /// object took several budgets (the glass bunny in the page); the
    /// cells of the grid tell them apart, and from the second sample on
    /// no job costs more than the dearest one of the fewest pixels and a
    /// cell.
    #[test]
    fn a_costly_object_in_a_cheap_row_keeps_jobs_within_the_budget() {
        let object = |x: u32, y: u32| (45..55).contains(&x) && (100..200).contains(&y);
        let cost = |x, y| if object(x, y) { 5.0 } else { 0.01 };
        let mut planner = JobPlanner::new(Duration::from_millis(30));
        let first = run_pixels(&mut planner, cost, 300);
        let second = run_pixels(&mut planner, cost, 300);
        let third = run_pixels(&mut planner, cost, 300);
        // The dearest job that cannot be cut, the fewest pixels (16) with
        // the object's 10 among them (50.06 ms), and a cell of the object
        // (2 pixels) more.
        let dearest = 12.0 * 5.0 + 4.0 * 0.01;
        let longest = |jobs: &[(u32, f64)]| jobs.iter().map(|j| j.1).fold(0.0, f64::max);
        assert!(longest(&second) <= dearest, "{second:?}");
        assert!(longest(&third) <= dearest, "{third:?}");
        assert!(
            longest(&first) > dearest,
            "the object's first rows are a surprise"
        );
        // The floor is still traced in large jobs.
        assert!(third.iter().any(|&(pixels, _)| pixels >= 2000), "{third:?}");
    }

    /// What the planner predicts of its own jobs: once the costs are
    /// known, never more than the budget, but for a job of the fewest
    /// pixels (one too dear to cut further).
    #[test]
    fn no_planned_job_is_predicted_over_its_budget() {
        let object = |x: u32, y: u32| (20..70).contains(&x) && (40..90).contains(&y);
        let cost = |x, y| if object(x, y) { 1.0 } else { 0.02 };
        let mut planner = JobPlanner::new(Duration::from_millis(30));
        run_pixels(&mut planner, cost, 120);
        let (width, height) = (WIDTH, 120);
        let mut start = 0;
        while start < width * height {
            let span = planner.next(start, (width, height));
            let predicted = planner.pending.clone().unwrap().predicted;
            assert!(
                predicted <= 0.030 + 1e-9 || span.len() as u32 == MIN_PIXELS,
                "{span:?} predicted {predicted} s"
            );
            let ms: f64 = span.clone().map(|p| cost(p % width, p / width)).sum();
            planner.measured(Duration::from_secs_f64(ms / 1000.0));
            start = span.end;
        }
    }

    /// The first job drawn with new pipelines takes a second whatever its
    /// pixels (SwiftShader compiling the shader at its first draw): the
    /// next job is sized as if it had not been measured, not cut to the
    /// fewest pixels as that second learnt as their cost would make it.
    #[test]
    fn the_first_draw_with_new_pipelines_does_not_size_the_next_jobs() {
        let size = (WIDTH, 600);
        let second_job = |first_draw: bool| {
            let mut planner = JobPlanner::new(Duration::from_millis(30));
            if first_draw {
                planner.pipelines_changed();
            }
            let first = planner.next(0, size);
            assert_eq!(first.len() as u32, FIRST_PIXELS);
            planner.measured(Duration::from_secs(1));
            planner.next(first.end, size).len() as u32
        };
        assert_eq!(second_job(true), FIRST_PIXELS);
        assert_eq!(second_job(false), MIN_PIXELS);
    }

    /// The longest job of all counts the first draw with new pipelines,
    /// the longest sized job does not, and it keeps the budget it was sized
    /// for; taking them starts the count again.
    #[test]
    fn the_longest_sized_job_leaves_out_the_first_draw() {
        let mut planner = JobPlanner::new(Duration::from_millis(30));
        planner.pipelines_changed();
        let jobs = run(&mut planner, |_| 1.0, 40);
        planner.pipelines_changed();
        let first = planner.next(0, (WIDTH, 40));
        planner.measured(Duration::from_secs(1));
        let since = planner.take_jobs();
        assert_eq!(since.count as usize, jobs.len() + 1);
        assert_eq!(since.longest.time, Duration::from_secs(1));
        assert_eq!(since.longest.pixels as usize, first.len());
        let sized = jobs[1..].iter().map(|j| j.1).fold(0.0, f64::max);
        assert!((since.longest_sized.time.as_secs_f64() * 1e3 - sized).abs() < 1e-6);
        assert_eq!(since.longest_sized.budget, Duration::from_millis(30));
        assert_eq!(planner.take_jobs(), JobsSince::default());
    }

    /// A grid of cells counts each pixel of a span once, in its cell, at
    /// widths below, at and above the number of columns.
    #[test]
    fn pixels_by_cell_counts_every_pixel_of_a_span_once() {
        for width in [7, 32, 45, 100] {
            let height = 9;
            for (start, end) in [
                (0, width * height),
                (3, width + 5),
                (width - 1, 3 * width + 2),
            ] {
                let cells = pixels_by_cell(&(start..end), (width, height));
                assert_eq!(cells.iter().map(|c| c.1).sum::<u32>(), end - start);
                for p in start..end {
                    let cell = row_cells(p / width, height) + cell_column(p % width, width);
                    assert!(cells.iter().any(|&(c, _)| c == cell), "pixel {p}");
                }
            }
        }
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
