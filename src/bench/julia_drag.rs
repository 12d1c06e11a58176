//! `raysandbox bench --julia-drag`: the bundled Julia scene while its `c`
//! is dragged in the viewer, traced at the viewer's full resolution
//! (docs/performance.md, "Julia sets: dragging c"). One pipeline is made
//! once; for each value of `c (i)` the scene is uploaded again and frames
//! of one sample per pixel are timed, as the viewer's moving frames are.
//! The report says which values fit the viewer's default frame budget at
//! full resolution, and for the others the resolution scale that would.

use std::fmt::Write as _;

use super::measure::median;
use super::{BenchArgs, BenchError, Environment, ms};
use crate::gpu::{DEFAULT_FRAME_BUDGET_MS, Gpu, OffscreenRenderer, ShaderOptions, ShaderSource};
use crate::scene::{Scene, bundled};

/// What the viewer traces at full resolution in a window of
/// `raysandbox view --size 1280x720`: the whole window, whose left part
/// the panel covers (the status line shows this size).
const FULL_SIZE: (u32, u32) = (1280, 720);

/// The quick run's size: a quarter of the pixels.
const QUICK_SIZE: (u32, u32) = (640, 360);

/// The columns of `julia_drag.csv`.
pub const JULIA_DRAG_COLUMNS: &str = "c_i,median_ms,fastest_ms,slowest_ms,scale";

/// The values of `c (i)` a drag passes through, from 0.4 to 0.8: the
/// range measured in the viewer, over which a frame's cost grows by a
/// quarter to a third (the scene's own value is 0.6).
fn c_values(quick: bool) -> Vec<f64> {
    let steps = if quick { 2 } else { 8 };
    (0..=steps)
        .map(|k| 0.4 + 0.4 * f64::from(k) / f64::from(steps))
        .collect()
}

/// One value of `c (i)`: its frames' GPU times.
struct Row {
    c_i: f64,
    median_ms: f64,
    fastest_ms: f64,
    slowest_ms: f64,
}

impl Row {
    /// The resolution scale whose frame fits `budget_ms`: a frame's time
    /// grows with its pixels, the square of the scale, so
    /// `sqrt(budget / time)`, at most 1 (what the viewer steers to,
    /// `gpu::interaction::next_scale`).
    fn scale(&self, budget_ms: f64) -> f64 {
        (budget_ms / self.median_ms).sqrt().min(1.0)
    }
}

/// Times `frames` frames of `scene` after a warm-up.
fn row(
    gpu: &Gpu,
    renderer: &mut OffscreenRenderer,
    scene: &Scene,
    frames: u32,
) -> Result<Row, String> {
    renderer.set_scene(gpu, scene).map_err(|e| e.to_string())?;
    renderer.render(gpu, 1).map_err(|e| e.to_string())?;
    let times: Vec<f64> = (0..frames)
        .map(|_| renderer.render(gpu, 1).map(ms))
        .collect::<Result<_, _>>()
        .map_err(|e| e.to_string())?;
    Ok(Row {
        c_i: scene.julias[0].c[1],
        median_ms: median(times.iter().copied()),
        fastest_ms: times.iter().copied().fold(f64::INFINITY, f64::min),
        slowest_ms: times.iter().copied().fold(0.0, f64::max),
    })
}

pub fn run(gpu: &Gpu, env: &Environment, args: &BenchArgs) -> Result<(), BenchError> {
    let failed = BenchError::Failed;
    let size = if args.quick { QUICK_SIZE } else { FULL_SIZE };
    let mut scene = Scene::from_toml_str(bundled::text("julia").expect("a bundled scene"), None)
        .map_err(|e| failed(e.to_string()))?;
    let mut renderer = OffscreenRenderer::new(
        gpu,
        &ShaderSource::embedded(),
        &ShaderOptions::for_scene(&scene),
        &scene,
        size.0,
        size.1,
    )
    .map_err(|e| failed(e.to_string()))?;
    let budget = f64::from(DEFAULT_FRAME_BUDGET_MS);
    let mut rows = Vec::new();
    for c_i in c_values(args.quick) {
        scene.julias[0].c[1] = c_i;
        let r = row(gpu, &mut renderer, &scene, args.frames).map_err(failed)?;
        println!(
            "c (i) = {c_i:.2}: {:.1} ms a frame (fastest {:.1}, slowest {:.1}); the budget allows scale {:.3}",
            r.median_ms,
            r.fastest_ms,
            r.slowest_ms,
            r.scale(budget)
        );
        rows.push(r);
    }
    let csv: String = std::iter::once(JULIA_DRAG_COLUMNS.to_string())
        .chain(rows.iter().map(|r| {
            format!(
                "{:.2},{:.2},{:.2},{:.2},{:.3}",
                r.c_i,
                r.median_ms,
                r.fastest_ms,
                r.slowest_ms,
                r.scale(budget)
            )
        }))
        .map(|line| line + "\n")
        .collect();
    let out = args.out.join("julia_drag.csv");
    std::fs::write(&out, csv).map_err(|e| super::fail(&out, e))?;
    let out = args.out.join("julia_drag.md");
    let report = markdown(env, size, args.frames, budget, &rows);
    std::fs::write(&out, report).map_err(|e| super::fail(&out, e))?;
    println!("wrote {}", out.display());
    Ok(())
}

fn markdown(
    env: &Environment,
    (w, h): (u32, u32),
    frames: u32,
    budget: f64,
    rows: &[Row],
) -> String {
    let mut md = env.report_header("The Julia set's c dragged");
    let _ = write!(
        md,
        "The bundled Julia scene at {w} x {h}, 1 sample per pixel, one pipeline, the scene \
         uploaded again for each value of `c (i)`; median of {frames} frames after a warm-up. \
         Budget: the viewer's default, {budget:.0} ms a frame.\n\n\
         | `c (i)` | median ms | fastest ms | slowest ms | within the budget | scale the budget allows |\n\
         | ---: | ---: | ---: | ---: | --- | ---: |\n"
    );
    for r in rows {
        let _ = writeln!(
            md,
            "| {:.2} | {:.1} | {:.1} | {:.1} | {} | {:.3} |",
            r.c_i,
            r.median_ms,
            r.fastest_ms,
            r.slowest_ms,
            if r.median_ms <= budget { "yes" } else { "no" },
            r.scale(budget)
        );
    }
    let within = rows.iter().filter(|r| r.median_ms <= budget).count();
    let _ = writeln!(
        md,
        "\nWithin the budget at this size: {within} of {} values.",
        rows.len()
    );
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_drag_runs_from_0_4_to_0_8() {
        for quick in [true, false] {
            let c = c_values(quick);
            assert!((c[0] - 0.4).abs() < 1e-12 && (c[c.len() - 1] - 0.8).abs() < 1e-12);
            assert!(c.iter().any(|&v| (v - 0.6).abs() < 1e-12), "{c:?}");
        }
        assert_eq!(c_values(false).len(), 9);
    }

    #[test]
    fn the_scale_fits_the_budget() {
        let row = |median_ms| Row {
            c_i: 0.6,
            median_ms,
            fastest_ms: median_ms,
            slowest_ms: median_ms,
        };
        assert_eq!(row(50.0).scale(100.0), 1.0);
        assert!((row(400.0).scale(100.0) - 0.5).abs() < 1e-12);
    }
}
