//! `raysandbox bench`: run time against error, specialised against generic
//! pipelines, and scaling with the number of shapes, with and without the
//! BVH. Writes CSV files, a Markdown report and PNG plots to `--out`.

#[cfg(feature = "embree")]
mod embree;
mod julia_drag;
mod measure;
mod meshes;
mod plot;
pub mod storage;
mod sweeps;
mod throughput;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Duration;

use indicatif::{ProgressBar, ProgressStyle};

use crate::gpu::{DEFAULT_MAX_SAMPLES, DEFAULT_MIN_WEIGHT, Gpu, ShaderOptions, Timing};
use crate::scene::{Scene, bundled};
use crate::stress::table::table;
use measure::{ConvergedReference, REFERENCE_FACTOR};

pub use julia_drag::JULIA_DRAG_COLUMNS;
pub use measure::{median, process_cpu_time, sphere_field};
pub use sweeps::spheres_in_place;
pub use throughput::{RayCounts, count_rays};

#[derive(clap::Args, Debug, Clone)]
pub struct BenchArgs {
    /// Folder for the CSV files, results.md and the plots.
    #[arg(long, default_value = "bench-results")]
    pub out: PathBuf,
    /// A small sweep (two scenes, few points, small sizes) that finishes in
    /// a minute or two.
    #[arg(long)]
    pub quick: bool,
    /// Frames timed per point (median), after one warm-up frame.
    #[arg(long, default_value_t = 10, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub frames: u32,
    /// Only the triangle-mesh benchmark (docs/performance.md, "Triangle
    /// meshes"): per mesh size and ray-triangle test, frame time and error,
    /// load and BVH build time, GPU bytes per triangle. The two largest
    /// dragons come from scripts/fetch-meshes.
    #[arg(long)]
    pub meshes: bool,
    /// Only the sweeps of tori, implicit surfaces and Julia sets (implicit
    /// steps, Julia iterations and epsilon, the torus method) and their
    /// cost against spheres in their place: `implicit.md`,
    /// `implicit_knobs.csv`, `implicit_costs.csv` and plots.
    #[arg(long)]
    pub implicit: bool,
    /// Only rays per second (docs/performance.md, "Rays per second"): per
    /// bundled scene, rays by kind as the tracer counts them; per mesh, its
    /// primary rays alone, against Intel Embree on the same rays where
    /// built with the `embree` feature. `throughput.md`.
    #[arg(long)]
    pub throughput: bool,
    /// Only the Julia set's `c (i)` dragged from 0.4 to 0.8 at the
    /// viewer's full resolution (docs/performance.md, "Julia sets:
    /// dragging c"): GPU time per frame against the viewer's default
    /// frame budget. `julia_drag.md`, `julia_drag.csv`.
    #[arg(long)]
    pub julia_drag: bool,
}

/// What one run sweeps.
struct Plan {
    quick: bool,
    scenes: Vec<&'static str>,
    size: (u32, u32),
    spp: Vec<u32>,
    depths: Vec<u32>,
    min_weights: Vec<f64>,
    scales: Vec<f64>,
    sphere_counts: Vec<usize>,
    scaling_size: (u32, u32),
}

impl Plan {
    fn new(quick: bool) -> Plan {
        if quick {
            return Plan {
                quick,
                scenes: vec!["whitted", "mirror_cube"],
                size: (96, 54),
                spp: vec![1, 8, 16],
                depths: vec![1, 4],
                min_weights: vec![0.0, 1e-2],
                scales: vec![0.5, 1.0],
                sphere_counts: vec![1, 16, 256],
                scaling_size: (96, 54),
            };
        }
        Plan {
            quick,
            scenes: bundled::names(),
            // Small enough that the full sweep (with 5 timed frames per
            // point, up to 64 samples, the reference at 512) finishes in
            // about a quarter of an hour on two CPU cores with lavapipe.
            size: (160, 90),
            // 1..16, what a class demo uses, then 32 and 64.
            spp: vec![1, 2, 4, 8, 16, 32, 64],
            // Depth doubling: where more bounces stop paying shows between
            // neighbours, at half the renders of every depth.
            depths: vec![1, 2, 4, 8],
            min_weights: vec![0.0, 1e-3, 1e-2, 5e-2],
            scales: vec![0.5, 1.0],
            sphere_counts: (0..=7).map(|k| 4usize.pow(k)).collect(),
            scaling_size: (160, 90),
        }
    }

    /// The scenes timed only specialised against generic: the stress scenes
    /// (`assets/scenes/stress/`) in the full sweep, none in the quick one.
    fn pipeline_only_scenes(&self) -> Vec<&'static str> {
        if self.quick {
            Vec::new()
        } else {
            crate::stress::scenes::SCENES
                .iter()
                .map(|(name, _)| *name)
                .collect()
        }
    }

    /// Samples per pixel of the converged reference: [`REFERENCE_FACTOR`]
    /// times the largest count measured.
    fn reference_spp(&self) -> u32 {
        REFERENCE_FACTOR * self.spp.iter().max().copied().unwrap_or(1)
    }

    /// The two largest sample counts measured: their errors' ratio shows
    /// whether the error falls as averaging predicts.
    fn convergence_pair(&self) -> (u32, u32) {
        let mut spp = self.spp.clone();
        spp.sort_unstable();
        match spp.as_slice() {
            [.., lo, hi] => (*lo, *hi),
            _ => (1, 1),
        }
    }

    /// The (spp, max_depth, min_weight, scale) points of the time/error
    /// sweep: max_depth x min_weight at 1 sample and full resolution, and
    /// samples x resolution scale x min_weight at the scene's own depth (at
    /// most 8). Together they hold the cheap and the converged ends of the
    /// trade-off without the full product of all four axes. Beyond 16
    /// samples (up to the viewer's refinement limit) only full resolution
    /// with min_weight 0 and the viewer's default is measured: those renders
    /// are long, and only they can show where the error becomes invisible.
    fn points(&self, scene: &Scene) -> Vec<Point> {
        let own_depth = scene.render.max_depth.clamp(1, 8);
        let mut points = Vec::new();
        for &depth in &self.depths {
            for &min_weight in &self.min_weights {
                points.push(Point {
                    spp: 1,
                    depth,
                    min_weight,
                    scale: 1.0,
                });
            }
        }
        for &spp in &self.spp {
            for &scale in &self.scales {
                for &min_weight in &self.min_weights {
                    let converging =
                        scale == 1.0 && (min_weight == 0.0 || min_weight == DEFAULT_MIN_WEIGHT);
                    if spp <= 16 || converging {
                        points.push(Point {
                            spp,
                            depth: own_depth,
                            min_weight,
                            scale,
                        });
                    }
                }
            }
        }
        points.sort_by(|a, b| a.key().partial_cmp(&b.key()).expect("finite"));
        points.dedup();
        points
    }
}

/// One setting of the renderer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    pub spp: u32,
    pub depth: u32,
    pub min_weight: f64,
    pub scale: f64,
}

impl Point {
    fn key(&self) -> (u32, u32, f64, f64) {
        (self.spp, self.depth, self.min_weight, self.scale)
    }
}

/// A measured point of the time/error sweep.
#[derive(Debug, Clone)]
pub struct ErrorRow {
    pub scene: String,
    pub point: Point,
    pub time_ms: f64,
    pub rmse: f64,
    pub psnr: f64,
}

/// The converged reference of one scene and its noise floor.
#[derive(Debug, Clone)]
pub struct ReferenceRow {
    pub scene: String,
    pub spp: u32,
    /// RMSE between its two independent halves.
    pub halves_rmse: f64,
    /// Its own RMSE as estimated from the halves (`ConvergedReference::noise_floor`).
    pub noise_floor: f64,
}

#[derive(Debug, Clone)]
pub struct PipelineRow {
    pub scene: String,
    pub specialized_ms: f64,
    pub generic_ms: f64,
    /// The median over frame pairs of generic / specialised time.
    pub ratio: f64,
}

#[derive(Debug, Clone)]
pub struct ScalingRow {
    pub spheres: usize,
    pub bvh_ms: f64,
    pub loop_ms: f64,
    pub build_ms: f64,
}

/// Where and how the numbers were taken.
pub struct Environment {
    pub adapter: String,
    pub timing: Timing,
    pub cpu: String,
}

impl Environment {
    /// A Markdown report's title and where its numbers were taken.
    fn report_header(&self, title: &str) -> String {
        format!(
            "# {title}\n\nadapter: {}\n\ntiming: {}\n\ncpu: {}\n\n",
            self.adapter,
            self.timing.describe(),
            self.cpu
        )
    }
}

#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    #[error("{0}")]
    NoGpu(String),
    #[error("{0}")]
    Failed(String),
}

pub fn run(args: &BenchArgs) -> Result<(), BenchError> {
    let gpu = Gpu::headless().map_err(|e| BenchError::NoGpu(e.to_string()))?;
    if args.meshes {
        return meshes::run(&gpu, args);
    }
    let plan = Plan::new(args.quick);
    let env = Environment {
        adapter: gpu.describe(),
        timing: timing_of(&gpu),
        cpu: cpu_model(),
    };
    println!(
        "adapter: {}\ntiming: {}\ncpu: {}",
        env.adapter,
        env.timing.describe(),
        env.cpu
    );
    std::fs::create_dir_all(&args.out).map_err(|e| fail(&args.out, e))?;
    if args.throughput {
        return throughput::run(&gpu, &env, args);
    }
    if args.julia_drag {
        return julia_drag::run(&gpu, &env, args);
    }
    if args.implicit {
        return sweeps::run(&gpu, &env, &args.out, args.quick, args.frames);
    }

    let scenes: Vec<(String, Scene)> = plan
        .scenes
        .iter()
        .map(|name| {
            let text = bundled::text(name).expect("a bundled scene");
            (
                name.to_string(),
                Scene::from_toml_str(text, None).expect("bundled scenes are valid"),
            )
        })
        .collect();
    let steps: usize = scenes
        .iter()
        .map(|(_, s)| plan.points(s).len() + 3)
        .sum::<usize>()
        + plan.pipeline_only_scenes().len()
        + plan.sphere_counts.len();
    let bar = ProgressBar::new(steps as u64).with_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} {elapsed_precise} {msg}")
            .expect("a valid template"),
    );

    let mut errors = Vec::new();
    let mut pipelines = Vec::new();
    let mut references = Vec::new();
    for (name, scene) in &scenes {
        bar.set_message(format!("{name}: converged reference"));
        let reference = ConvergedReference::render(scene, plan.size, plan.reference_spp());
        bar.suspend(|| {
            println!(
                "{name}: reference {} spp, its halves differ by RMSE {:.5}: noise floor {:.5}",
                reference.spp,
                reference.halves_rmse,
                reference.noise_floor()
            )
        });
        references.push(ReferenceRow {
            scene: name.clone(),
            spp: reference.spp,
            halves_rmse: reference.halves_rmse,
            noise_floor: reference.noise_floor(),
        });
        let reference = reference.image;
        bar.inc(1);
        for point in plan.points(scene) {
            bar.set_message(format!("{name}: {point:?}"));
            errors.push(error_row(
                &gpu,
                name,
                scene,
                &plan,
                point,
                &reference,
                args.frames,
            )?);
            bar.inc(1);
        }
        bar.set_message(format!("{name}: specialised and generic"));
        pipelines.push(pipeline_row(&gpu, name, scene, plan.size, args.frames)?);
        bar.inc(2);
    }
    for name in plan.pipeline_only_scenes() {
        bar.set_message(format!("{name}: specialised and generic"));
        let scene = crate::stress::scenes::load(name);
        pipelines.push(pipeline_row(&gpu, name, &scene, plan.size, args.frames)?);
        bar.inc(1);
    }
    let mut scaling = Vec::new();
    for &n in &plan.sphere_counts {
        bar.set_message(format!("{n} spheres"));
        scaling.push(scaling_row(&gpu, n, plan.scaling_size, args.frames)?);
        bar.inc(1);
    }
    bar.finish_with_message("done");
    let (lo, hi) = plan.convergence_pair();
    for name in &plan.scenes {
        let rows: Vec<&ErrorRow> = errors.iter().filter(|r| r.scene == *name).collect();
        if let Some(ratio) = convergence_ratio(&rows, lo, hi) {
            println!("{name}: RMSE at {lo} spp / RMSE at {hi} spp = {ratio:.2}");
        }
    }

    let results = Results {
        references,
        errors,
        pipelines,
        scaling,
    };
    write_outputs(&args.out, &env, &plan, &results)?;
    println!("wrote {}", args.out.join("results.md").display());
    Ok(())
}

fn fail(path: &Path, e: impl std::fmt::Display) -> BenchError {
    BenchError::Failed(format!("{}: {e}", path.display()))
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn timing_of(gpu: &Gpu) -> Timing {
    if gpu.device.features().contains(crate::gpu::TIMER_FEATURES) {
        Timing::GpuTimestamps
    } else {
        Timing::SubmitToDone
    }
}

/// The CPU's model name from /proc/cpuinfo, and the number of threads.
fn cpu_model() -> String {
    let model = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|text| {
            text.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let threads = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!("{model}, {threads} threads")
}

fn error_row(
    gpu: &Gpu,
    name: &str,
    scene: &Scene,
    plan: &Plan,
    point: Point,
    reference: &image::RgbaImage,
    frames: u32,
) -> Result<ErrorRow, BenchError> {
    let mut scene = scene.clone();
    scene.render.max_depth = point.depth;
    scene.render.min_weight = point.min_weight;
    let size = (
        ((f64::from(plan.size.0) * point.scale).round() as u32).max(1),
        ((f64::from(plan.size.1) * point.scale).round() as u32).max(1),
    );
    let options = ShaderOptions::for_scene(&scene);
    let (time, image) = measure::frame_time(gpu, &options, &scene, size, point.spp, frames)
        .map_err(BenchError::Failed)?;
    let (rmse, psnr) = measure::error(&image, reference);
    Ok(ErrorRow {
        scene: name.to_string(),
        point,
        time_ms: ms(time),
        rmse,
        psnr,
    })
}

/// Specialised against generic on one scene at 1 sample per pixel, frame
/// for frame in turn (`measure::paired_frame_times`).
fn pipeline_row(
    gpu: &Gpu,
    name: &str,
    scene: &Scene,
    size: (u32, u32),
    frames: u32,
) -> Result<PipelineRow, BenchError> {
    let specialised = ShaderOptions::for_scene(scene);
    let generic = ShaderOptions::generic(scene);
    let ([s, g], ratio) =
        measure::paired_frame_times(gpu, [&specialised, &generic], scene, size, frames)
            .map_err(BenchError::Failed)?;
    Ok(PipelineRow {
        scene: name.to_string(),
        specialized_ms: ms(s),
        generic_ms: ms(g),
        ratio,
    })
}

fn scaling_row(
    gpu: &Gpu,
    n: usize,
    size: (u32, u32),
    frames: u32,
) -> Result<ScalingRow, BenchError> {
    let scene = sphere_field(n);
    let mut options = ShaderOptions::for_scene(&scene);
    options.features.bvh = true;
    let time = |options: &ShaderOptions| {
        measure::frame_time(gpu, options, &scene, size, 1, frames)
            .map(|(t, _)| ms(t))
            .map_err(BenchError::Failed)
    };
    let bvh_ms = time(&options)?;
    options.features.bvh = false;
    let loop_ms = time(&options)?;
    Ok(ScalingRow {
        spheres: n,
        bvh_ms,
        loop_ms,
        build_ms: ms(measure::bvh_build_time(&scene, 9)),
    })
}

/// The Pareto front of one scene's points: those no other point beats in
/// both time and error, by increasing time.
pub fn pareto_front(rows: &[&ErrorRow]) -> Vec<ErrorRow> {
    let mut sorted: Vec<&ErrorRow> = rows.to_vec();
    sorted.sort_by(|a, b| {
        a.time_ms
            .total_cmp(&b.time_ms)
            .then(a.rmse.total_cmp(&b.rmse))
    });
    let mut front: Vec<ErrorRow> = Vec::new();
    for row in sorted {
        if front.last().is_none_or(|best| row.rmse < best.rmse) {
            front.push(row.clone());
        }
    }
    front
}

/// The cheapest point whose PSNR reaches `psnr` (the error is invisible).
pub fn cheapest_at(rows: &[&ErrorRow], psnr: f64) -> Option<ErrorRow> {
    rows.iter()
        .filter(|r| r.psnr >= psnr)
        .min_by(|a, b| a.time_ms.total_cmp(&b.time_ms))
        .map(|r| (*r).clone())
}

/// The sweep point that uses the viewer's defaults for `scene`: the
/// refinement limit, the scene's own depth, the default min_weight, full
/// resolution.
fn is_default(row: &ErrorRow, scene: &Scene) -> bool {
    row.point.spp == DEFAULT_MAX_SAMPLES
        && row.point.depth == scene.render.max_depth.clamp(1, 8)
        && row.point.min_weight == DEFAULT_MIN_WEIGHT
        && row.point.scale == 1.0
}

/// PSNR levels the report finds the cheapest point for: from a clearly
/// visible difference (30 dB, about 8 of 255 RMS) to one hard to see at all
/// (40 dB, about 2.5 of 255).
const VISIBILITY_PSNR: [f64; 3] = [30.0, 35.0, 40.0];

/// The CSV columns of `time_vs_error.csv` (tests check them).
pub const ERROR_COLUMNS: &str = "scene,spp,max_depth,min_weight,scale,time_ms,rmse,psnr_db";
pub const REFERENCE_COLUMNS: &str = "scene,spp,halves_rmse,noise_floor_rmse";
pub const PIPELINE_COLUMNS: &str = "scene,specialized_ms,generic_ms,ratio";
pub const SCALING_COLUMNS: &str = "spheres,bvh_ms,loop_ms,bvh_build_ms";

/// Everything one run measured.
pub struct Results {
    pub references: Vec<ReferenceRow>,
    pub errors: Vec<ErrorRow>,
    pub pipelines: Vec<PipelineRow>,
    pub scaling: Vec<ScalingRow>,
}

/// The RMSE at `spp` samples of one scene's convergence series: full
/// resolution, the scene's own depth, min_weight 0.
pub fn series_rmse(rows: &[&ErrorRow], spp: u32) -> Option<f64> {
    rows.iter()
        .filter(|r| r.point.spp == spp && r.point.min_weight == 0.0 && r.point.scale == 1.0)
        .max_by_key(|r| r.point.depth)
        .map(|r| r.rmse)
}

/// The error at `lo` samples over the error at `hi` (`lo < hi`) of the
/// convergence series: Monte Carlo averaging divides the error by
/// sqrt(hi / lo), quasi-random samples by up to hi / lo.
pub fn convergence_ratio(rows: &[&ErrorRow], lo: u32, hi: u32) -> Option<f64> {
    Some(series_rmse(rows, lo)? / series_rmse(rows, hi)?)
}

/// PSNR (dB) of an RMSE in [0, 1] units.
fn psnr_of(rmse: f64) -> f64 {
    -20.0 * rmse.log10()
}

fn write_outputs(
    out: &Path,
    env: &Environment,
    plan: &Plan,
    results: &Results,
) -> Result<(), BenchError> {
    let Results {
        references,
        errors,
        pipelines,
        scaling,
    } = results;
    let write = |name: &str, text: String| {
        let path = out.join(name);
        std::fs::write(&path, text).map_err(|e| fail(&path, e))
    };
    let tables = [
        (
            "time_vs_error.csv",
            table(ERROR_COLUMNS, errors, |r| {
                let p = r.point;
                format!(
                    "{},{},{},{},{},{:.4},{:.6},{:.3}",
                    r.scene, p.spp, p.depth, p.min_weight, p.scale, r.time_ms, r.rmse, r.psnr
                )
            }),
        ),
        (
            "reference.csv",
            table(REFERENCE_COLUMNS, references, |r| {
                format!(
                    "{},{},{:.6},{:.6}",
                    r.scene, r.spp, r.halves_rmse, r.noise_floor
                )
            }),
        ),
        (
            "specialized_vs_generic.csv",
            table(PIPELINE_COLUMNS, pipelines, |r| {
                format!(
                    "{},{:.4},{:.4},{:.4}",
                    r.scene, r.specialized_ms, r.generic_ms, r.ratio
                )
            }),
        ),
        (
            "scaling.csv",
            table(SCALING_COLUMNS, scaling, |r| {
                format!(
                    "{},{:.4},{:.4},{:.4}",
                    r.spheres, r.bvh_ms, r.loop_ms, r.build_ms
                )
            }),
        ),
    ];
    for (name, text) in tables {
        write(name, text)?;
    }

    let mut md = String::new();
    let _ = writeln!(md, "# raysandbox bench\n");
    let _ = writeln!(md, "- adapter: {}", env.adapter);
    let _ = writeln!(
        md,
        "- frame time: {}, median after one warm-up frame",
        env.timing.describe()
    );
    let _ = writeln!(md, "- CPU: {}", env.cpu);
    let _ = writeln!(
        md,
        "- time/error sweep at {}x{} (resolution scale multiplies it), scaling at {}x{}\n",
        plan.size.0, plan.size.1, plan.scaling_size.0, plan.scaling_size.1
    );
    let _ = writeln!(md, "## The converged reference\n");
    let _ = writeln!(
        md,
        "Every error below is measured against the f64 CPU reference at {} samples per \
         pixel ({REFERENCE_FACTOR}x the largest count measured), max_depth 16, min_weight 0, \
         traced in two halves with two Cranley-Patterson rotations of the R4 sequence: it \
         shares no sample with any measured render, which all use the unrotated sequence. \
         The two halves are independent estimates of the same image; their RMSE bounds the \
         reference's own error (noise floor = halves / 2). Errors near the floor are not \
         resolved.\n",
        plan.reference_spp()
    );
    let _ = writeln!(
        md,
        "| scene | reference spp | halves RMSE | noise floor RMSE | floor PSNR (dB) |"
    );
    let _ = writeln!(md, "| --- | --- | --- | --- | --- |");
    for r in references {
        let _ = writeln!(
            md,
            "| {} | {} | {:.5} | {:.5} | {:.1} |",
            r.scene,
            r.spp,
            r.halves_rmse,
            r.noise_floor,
            psnr_of(r.noise_floor)
        );
    }
    let (lo, hi) = plan.convergence_pair();
    let _ = writeln!(
        md,
        "\n### Convergence: error at {lo} against {hi} samples\n\n\
         Full resolution, the scene's own depth, min_weight 0. Averaging independent \
         samples divides the error by sqrt({hi}/{lo}) = {:.2}; quasi-random samples by up \
         to {hi}/{lo} = {:.0}.\n",
        (f64::from(hi) / f64::from(lo)).sqrt(),
        f64::from(hi) / f64::from(lo)
    );
    let _ = writeln!(
        md,
        "| scene | RMSE {lo} spp | RMSE {hi} spp | ratio |\n| --- | --- | --- | --- |"
    );
    for name in &plan.scenes {
        let rows: Vec<&ErrorRow> = errors.iter().filter(|r| r.scene == *name).collect();
        if let (Some(a), Some(b)) = (series_rmse(&rows, lo), series_rmse(&rows, hi)) {
            let _ = writeln!(md, "| {name} | {a:.5} | {b:.5} | {:.2} |", a / b);
        }
    }
    let _ = writeln!(md, "\n## Time against error: Pareto fronts\n");
    for name in &plan.scenes {
        let rows: Vec<&ErrorRow> = errors.iter().filter(|r| r.scene == *name).collect();
        let scene =
            Scene::from_toml_str(bundled::text(name).expect("bundled"), None).expect("valid");
        let front = pareto_front(&rows);
        let default = rows
            .iter()
            .find(|r| is_default(r, &scene))
            .map(|r| (*r).clone());
        let plot_name = format!("pareto_{name}.png");
        plot::pareto(&out.join(&plot_name), name, &rows, &front, default.as_ref())
            .map_err(|e| fail(&out.join(&plot_name), e))?;
        let _ = writeln!(md, "### {name}\n\n![{name}]({plot_name})\n");
        let _ = writeln!(
            md,
            "| spp | max_depth | min_weight | scale | time (ms) | RMSE | PSNR (dB) |"
        );
        let _ = writeln!(md, "| --- | --- | --- | --- | --- | --- | --- |");
        for r in &front {
            let p = r.point;
            let _ = writeln!(
                md,
                "| {} | {} | {} | {} | {:.2} | {:.5} | {:.1} |",
                p.spp, p.depth, p.min_weight, p.scale, r.time_ms, r.rmse, r.psnr
            );
        }
        for psnr in VISIBILITY_PSNR {
            let _ = match cheapest_at(&rows, psnr) {
                Some(r) => writeln!(
                    md,
                    "- cheapest point with PSNR >= {psnr} dB: {:?} at {:.2} ms ({:.1} dB)",
                    r.point, r.time_ms, r.psnr
                ),
                None => writeln!(md, "- no point of the sweep reaches PSNR {psnr} dB"),
            };
        }
        let _ = writeln!(md);
        if let Some(d) = default {
            let _ = writeln!(
                md,
                "Viewer defaults ({:?}): {:.2} ms, {:.1} dB.\n",
                d.point, d.time_ms, d.psnr
            );
        }
    }
    let _ = writeln!(
        md,
        "## Specialised against generic pipeline (1 spp, {}x{})\n",
        plan.size.0, plan.size.1
    );
    let _ = writeln!(
        md,
        "Median frame times of the two pipelines rendered in turn, and the median over \
         those frame pairs of generic / specialised; the bundled scenes, then the stress scenes.\n"
    );
    md += &table(
        "| scene | specialised (ms) | generic (ms) | generic / specialised |\n\
         | --- | --- | --- | --- |",
        pipelines,
        |r| {
            format!(
                "| {} | {:.2} | {:.2} | {:.2} |",
                r.scene, r.specialized_ms, r.generic_ms, r.ratio
            )
        },
    );
    let _ = writeln!(
        md,
        "\n## Scaling with the number of spheres\n\n![scaling](scaling.png)\n"
    );
    md += &table(
        "| spheres | BVH (ms) | loop (ms) | BVH build (ms) |\n| --- | --- | --- | --- |",
        scaling,
        |r| {
            format!(
                "| {} | {:.2} | {:.2} | {:.3} |",
                r.spheres, r.bvh_ms, r.loop_ms, r.build_ms
            )
        },
    );
    plot::scaling(&out.join("scaling.png"), scaling)
        .map_err(|e| fail(&out.join("scaling.png"), e))?;
    write("results.md", md)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(time_ms: f64, rmse: f64) -> ErrorRow {
        ErrorRow {
            scene: "s".into(),
            point: Point {
                spp: 1,
                depth: 1,
                min_weight: 0.0,
                scale: 1.0,
            },
            time_ms,
            rmse,
            psnr: -20.0 * rmse.log10(),
        }
    }

    #[test]
    fn pareto_front_keeps_only_undominated_points() {
        let rows = [
            row(1.0, 0.1),
            row(2.0, 0.2),
            row(3.0, 0.05),
            row(4.0, 0.05),
            row(0.5, 0.3),
        ];
        let refs: Vec<&ErrorRow> = rows.iter().collect();
        let front: Vec<(f64, f64)> = pareto_front(&refs)
            .iter()
            .map(|r| (r.time_ms, r.rmse))
            .collect();
        assert_eq!(front, vec![(0.5, 0.3), (1.0, 0.1), (3.0, 0.05)]);
        assert_eq!(cheapest_at(&refs, 20.0).unwrap().time_ms, 1.0);
        assert!(cheapest_at(&refs, 90.0).is_none());
    }

    #[test]
    fn the_full_plan_sweeps_every_axis() {
        let plan = Plan::new(false);
        let scene = Scene::from_toml_str(bundled::text("whitted").unwrap(), None).unwrap();
        let points = plan.points(&scene);
        for spp in [1, 2, 4, 8, 16] {
            assert!(points.iter().any(|p| p.spp == spp));
        }
        for depth in [1, 2, 4, 8] {
            assert!(points.iter().any(|p| p.depth == depth));
        }
        assert_eq!(plan.reference_spp(), 512);
        assert_eq!(plan.convergence_pair(), (32, 64));
        assert_eq!(
            plan.pipeline_only_scenes().len(),
            crate::stress::scenes::SCENES.len()
        );
        for mw in [0.0, 1e-3, 1e-2, 5e-2] {
            assert!(points.iter().any(|p| p.min_weight == mw));
        }
        assert!(points.iter().any(|p| p.scale == 0.5));
        assert_eq!(plan.sphere_counts.last(), Some(&16384));
        assert!(points.iter().any(|p| is_default(
            &ErrorRow {
                point: *p,
                ..row(1.0, 0.1)
            },
            &scene
        )));
    }
}
