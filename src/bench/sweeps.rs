//! `raysandbox bench --implicit`: the knobs of tori, implicit surfaces and
//! Julia sets that trade time for accuracy (implicit `steps`, Julia
//! `iterations` and `epsilon`, the torus method), each as frame time against
//! error, and what a scene with such a shape costs against the same scene
//! with a sphere in its place (docs/performance.md, "Implicit surfaces").

use std::fmt::Write as _;
use std::path::Path;

use plotters::prelude::*;

use super::measure::{self, ConvergedReference, REFERENCE_FACTOR};
use super::plot::{log_range, register_font};
use super::{BenchError, Environment, fail, ms};
use crate::gpu::{Gpu, ShaderOptions};
use crate::scene::{Instance, NamedOption, Scene, Sphere, TorusMethod, Unplaced, bundled};

/// Samples per pixel of the images whose error is measured: enough that
/// the knob's error, not the sampling's, separates the settings (the quick
/// run takes 4).
const SWEEP_SPP: u32 = 16;

/// One value of one knob, applied to every shape of its kind in a scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Knob {
    /// Samples along the ray of every `[[implicits]]` shape.
    Steps(u32),
    /// Iterations of every `[[julias]]` shape.
    Iterations(u32),
    /// Surface distance of every `[[julias]]` shape (local units).
    Epsilon(f64),
    /// How the GPU solves the tori's quartic.
    Torus(TorusMethod),
    /// Whether every `[[julias]]` shape grows epsilon with the pixel
    /// footprint.
    Footprint(bool),
}

impl Knob {
    /// The knob's name in the scene file (or on the command line).
    pub fn name(self) -> &'static str {
        match self {
            Knob::Steps(_) => "steps",
            Knob::Iterations(_) => "iterations",
            Knob::Epsilon(_) => "epsilon",
            Knob::Torus(_) => "torus method",
            Knob::Footprint(_) => "footprint",
        }
    }

    pub fn value(self) -> String {
        match self {
            Knob::Steps(n) | Knob::Iterations(n) => n.to_string(),
            Knob::Epsilon(e) => format!("{e:e}"),
            Knob::Torus(m) => m.name().to_string(),
            Knob::Footprint(on) => on.to_string(),
        }
    }

    /// `scene` and `options` with this setting.
    fn apply(self, scene: &mut Scene, options: &mut ShaderOptions) {
        match self {
            Knob::Steps(n) => scene.implicits.iter_mut().for_each(|s| s.steps = n),
            Knob::Iterations(n) => scene.julias.iter_mut().for_each(|s| s.iterations = n),
            Knob::Epsilon(e) => scene.julias.iter_mut().for_each(|s| s.epsilon = e),
            Knob::Torus(m) => options.kinds.tori = m,
            Knob::Footprint(on) => scene.julias.iter_mut().for_each(|s| s.footprint = on),
        }
    }
}

/// One knob swept on one bundled scene.
pub struct Sweep {
    pub scene: &'static str,
    /// The camera moved towards its target by this factor (2: half the
    /// distance, 0.25: four times as far).
    pub zoom: f64,
    /// The settings measured, least work first.
    pub settings: Vec<Knob>,
    /// The setting of the converged reference: finer than every measured
    /// one (the reference is the f64 renderer, which bisects the torus
    /// to full precision whatever the method).
    pub reference: Knob,
}

/// The sweeps of a run, the quickest first: `quick` keeps every third
/// setting of each and one zoom.
pub fn sweeps(quick: bool) -> Vec<Sweep> {
    let sweep = |scene, settings: Vec<Knob>, reference| Sweep {
        scene,
        zoom: 1.0,
        settings,
        reference,
    };
    let mut all = vec![
        sweep(
            "torus",
            vec![
                Knob::Torus(TorusMethod::ClosedForm),
                Knob::Torus(TorusMethod::Newton),
                Knob::Torus(TorusMethod::Bisection),
            ],
            Knob::Torus(TorusMethod::Bisection),
        ),
        sweep(
            "julia",
            [3, 4, 6, 8, 10, 12, 16, 24].map(Knob::Iterations).into(),
            Knob::Iterations(48),
        ),
        sweep(
            "julia",
            [3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4]
                .map(Knob::Epsilon)
                .into(),
            Knob::Epsilon(1e-5),
        ),
    ];
    // The footprint at three camera distances, against the fixed epsilon's
    // finest setting.
    all.extend([0.25, 1.0, 4.0].map(|zoom| Sweep {
        zoom,
        ..sweep(
            "julia",
            vec![Knob::Footprint(true), Knob::Footprint(false)],
            Knob::Epsilon(1e-5),
        )
    }));
    all.push(sweep(
        "implicits",
        [8, 16, 32, 64, 128, 256, 512].map(Knob::Steps).into(),
        Knob::Steps(1024),
    ));
    if !quick {
        return all;
    }
    all.into_iter()
        .filter(|s| s.zoom == 1.0)
        .map(|s| Sweep {
            settings: s.settings.iter().step_by(3).copied().collect(),
            ..s
        })
        .collect()
}

/// A measured setting.
#[derive(Debug, Clone)]
pub struct KnobRow {
    pub scene: String,
    pub knob: Knob,
    /// Median frame time of this setting.
    pub time_ms: f64,
    /// Median over paired frames of this setting's time / the scene's own
    /// setting's time.
    pub relative_time: f64,
    pub rmse: f64,
    pub psnr: f64,
    /// Whether this is the scene file's own setting.
    pub is_default: bool,
}

/// One scene with tori, implicit surfaces or Julia sets against the same
/// scene with a sphere in the place of each.
#[derive(Debug, Clone)]
pub struct CostRow {
    pub scene: String,
    pub with_ms: f64,
    pub spheres_ms: f64,
    /// Median over paired frames of with / spheres.
    pub ratio: f64,
    /// The same from the CPU time of each frame (`measure::paired_renders`),
    /// where the system reports it: with, spheres, ratio.
    pub cpu: Option<(f64, f64, f64)>,
}

pub const KNOB_COLUMNS: &str = "scene,zoom,knob,value,spp,time_ms,time_vs_default,rmse,psnr_db,reference_noise_floor_rmse,default";
pub const COST_COLUMNS: &str = "scene,with_shapes_ms,spheres_instead_ms,ratio,with_shapes_cpu_ms,spheres_instead_cpu_ms,cpu_ratio";

/// The size of the comparison against spheres in the full run: the size
/// the targets of docs/performance.md are stated at.
const COST_SIZE: (u32, u32) = (1280, 720);

fn load(name: &str) -> Scene {
    Scene::from_toml_str(bundled::text(name).expect("a bundled scene"), None)
        .expect("bundled scenes are valid")
}

/// `scene` with a sphere in the place of every torus, implicit surface and
/// Julia set, of the same material, at its centre: radius `(R + r) scale`
/// for a torus (its bounding sphere), half the smallest side of `bounds`
/// times `scale` for an implicit surface, `scale` for a Julia set (about
/// the extent of the sets the sliders reach inside their bounding radius 2).
pub fn spheres_in_place(scene: &Scene) -> Scene {
    let mut out = scene.clone();
    let sphere = |center, radius, material: &Option<String>| Instance {
        shape: Sphere { center, radius },
        placement: Unplaced,
        material: material.clone(),
    };
    for t in out.tori.drain(..) {
        let radius = (t.major_radius + t.minor_radius) * t.placement.scale;
        out.spheres
            .push(sphere(t.placement.translate, radius, &t.material));
    }
    for i in out.implicits.drain(..) {
        let side = (i.bounds[1] - i.bounds[0]).min_element();
        out.spheres.push(sphere(
            i.placement.translate,
            0.5 * side * i.placement.scale,
            &i.material,
        ));
    }
    for j in out.julias.drain(..) {
        out.spheres.push(sphere(
            j.placement.translate,
            j.placement.scale,
            &j.material,
        ));
    }
    out
}

/// Runs every sweep and the cost comparison; writes `implicit_knobs.csv`,
/// `implicit_costs.csv`, `implicit.md` and a plot per sweep into `out`.
pub fn run(
    gpu: &Gpu,
    env: &Environment,
    out: &Path,
    quick: bool,
    frames: u32,
) -> Result<(), BenchError> {
    let (size, spp) = if quick {
        ((96, 54), 4)
    } else {
        ((160, 90), SWEEP_SPP)
    };
    let cost_size = if quick { size } else { COST_SIZE };
    let mut md = String::new();
    let _ = writeln!(md, "# raysandbox bench --implicit\n");
    let _ = writeln!(md, "- adapter: {}", env.adapter);
    let _ = writeln!(md, "- frame time: {}", env.timing.describe());
    let _ = writeln!(md, "- CPU: {}", env.cpu);
    let _ = writeln!(
        md,
        "- {}x{}, errors at {spp} samples per pixel, times at 1 (median of {frames} frames \
         after a warm-up, each setting timed in turn with the scene's own setting)\n",
        size.0, size.1
    );
    let mut csv = format!("{KNOB_COLUMNS}\n");
    for sweep in sweeps(quick) {
        let (rows, floor) = run_sweep(gpu, &sweep, (size, spp), frames, &mut csv, &mut md)?;
        let plot_name = plot_name(&sweep);
        plot_sweep(&out.join(&plot_name), &sweep, &rows, floor)
            .map_err(|e| fail(&out.join(&plot_name), e))?;
        let _ = writeln!(md, "![{}]({plot_name})\n", sweep.settings[0].name());
    }
    write(out, "implicit_knobs.csv", csv)?;

    let _ = writeln!(
        md,
        "## With tori, implicit surfaces and Julia sets against spheres in their place\n\n\
         1 sample per pixel, {}x{}, each scene's own settings; the two scenes rendered in \
         turn, each ratio the median over frame pairs of with / spheres: of GPU time, and of \
         the CPU time the process spent on the frame (lavapipe's threads; what a loaded \
         machine does not stretch).\n\n\
         | scene | with the shapes (ms) | spheres instead (ms) | ratio | CPU with (ms) | CPU spheres (ms) | CPU ratio |\n\
         | --- | --- | --- | --- | --- | --- | --- |",
        cost_size.0, cost_size.1
    );
    let mut csv = format!("{COST_COLUMNS}\n");
    for name in ["torus", "julia", "implicits"] {
        let row = cost_row(gpu, name, cost_size, frames)?;
        let (cpu_with, cpu_spheres, cpu_ratio) = row.cpu.unwrap_or((f64::NAN, f64::NAN, f64::NAN));
        println!(
            "{name}: {:.1} ms, spheres instead {:.1} ms, ratio {:.2}, CPU ratio {cpu_ratio:.2}",
            row.with_ms, row.spheres_ms, row.ratio
        );
        let _ = writeln!(
            csv,
            "{},{:.4},{:.4},{:.4},{cpu_with:.4},{cpu_spheres:.4},{cpu_ratio:.4}",
            row.scene, row.with_ms, row.spheres_ms, row.ratio
        );
        let _ = writeln!(
            md,
            "| {} | {:.2} | {:.2} | {:.2} | {cpu_with:.2} | {cpu_spheres:.2} | {cpu_ratio:.2} |",
            row.scene, row.with_ms, row.spheres_ms, row.ratio
        );
    }
    write(out, "implicit_costs.csv", csv)?;
    write(out, "implicit.md", md)?;
    println!("wrote {}", out.join("implicit.md").display());
    Ok(())
}

fn write(out: &Path, name: &str, text: String) -> Result<(), BenchError> {
    let path = out.join(name);
    std::fs::write(&path, text).map_err(|e| fail(&path, e))
}

/// The plot's file name: `knob_SCENE_KNOB[_zoomZ].png`.
fn plot_name(sweep: &Sweep) -> String {
    let knob = match sweep.settings[0] {
        Knob::Torus(_) => "method",
        other => other.name(),
    };
    let zoom = if sweep.zoom == 1.0 {
        String::new()
    } else {
        format!("_zoom{}", sweep.zoom)
    };
    format!("knob_{}_{knob}{zoom}.png", sweep.scene)
}

/// The scene file's own setting of the knob `like` is a value of.
fn own_setting(scene: &Scene, like: Knob) -> Knob {
    match like {
        Knob::Steps(_) => Knob::Steps(scene.implicits[0].steps),
        Knob::Iterations(_) => Knob::Iterations(scene.julias[0].iterations),
        Knob::Epsilon(_) => Knob::Epsilon(scene.julias[0].epsilon),
        Knob::Torus(_) => Knob::Torus(ShaderOptions::for_scene(scene).kinds.tori),
        Knob::Footprint(_) => Knob::Footprint(scene.julias[0].footprint),
    }
}

/// One sweep: its reference, then each setting timed against the scene's
/// own; rows appended to `csv`, the table and the choice to `md`.
fn run_sweep(
    gpu: &Gpu,
    sweep: &Sweep,
    (size, spp): ((u32, u32), u32),
    frames: u32,
    csv: &mut String,
    md: &mut String,
) -> Result<(Vec<KnobRow>, f64), BenchError> {
    let mut base = load(sweep.scene);
    let camera = &mut base.camera;
    camera.from = camera.to + (camera.from - camera.to) / sweep.zoom;
    let own = own_setting(&base, sweep.settings[0]);
    let name = sweep.settings[0].name();
    let reference_name = sweep.reference.name();
    let mut reference_scene = base.clone();
    sweep
        .reference
        .apply(&mut reference_scene, &mut ShaderOptions::for_scene(&base));
    let reference = ConvergedReference::render(&reference_scene, size, REFERENCE_FACTOR * spp);
    let floor = reference.noise_floor();
    println!(
        "{} (zoom {}) {name}: reference at {reference_name} = {}, {} spp, noise floor RMSE {floor:.5}",
        sweep.scene,
        sweep.zoom,
        sweep.reference.value(),
        reference.spp
    );
    let default_options = ShaderOptions::for_scene(&base);
    let mut rows = Vec::new();
    for &knob in &sweep.settings {
        let mut scene = base.clone();
        let mut options = ShaderOptions::for_scene(&base);
        knob.apply(&mut scene, &mut options);
        let ([_, time], relative) = measure::paired_scene_times(
            gpu,
            [(&default_options, &base), (&options, &scene)],
            size,
            frames,
        )
        .map_err(BenchError::Failed)?;
        let (_, image) =
            measure::frame_time(gpu, &options, &scene, size, spp, 1).map_err(BenchError::Failed)?;
        let (rmse, psnr) = measure::error(&image, &reference.image);
        let row = KnobRow {
            scene: sweep.scene.to_string(),
            knob,
            time_ms: ms(time),
            relative_time: relative,
            rmse,
            psnr,
            is_default: knob == own,
        };
        println!(
            "  {name} = {}: {:.1} ms ({:.2}x the scene's own), RMSE {rmse:.5}",
            knob.value(),
            row.time_ms,
            relative
        );
        let _ = writeln!(
            csv,
            "{},{},{},{},{spp},{:.4},{:.4},{rmse:.6},{psnr:.3},{floor:.6},{}",
            row.scene,
            sweep.zoom,
            name,
            knob.value(),
            row.time_ms,
            relative,
            row.is_default
        );
        rows.push(row);
    }
    let _ = writeln!(
        md,
        "## {}{}: {name}\n\nReference: the f64 renderer at {reference_name} = {}, {} samples per pixel in two \
         halves with samples no timed render has; its halves give a noise floor of RMSE \
         {floor:.5}.\n\n| {name} | time (ms) | time / scene's own | RMSE | PSNR (dB) |\n\
         | --- | --- | --- | --- | --- |",
        sweep.scene,
        match sweep.zoom {
            1.0 => String::new(),
            z if z < 1.0 => format!(", camera {}x as far", 1.0 / z),
            z => format!(", camera {z}x closer"),
        },
        sweep.reference.value(),
        reference.spp
    );
    for r in &rows {
        let own = if r.is_default { " (scene's own)" } else { "" };
        let _ = writeln!(
            md,
            "| {}{own} | {:.2} | {:.2} | {:.5} | {:.1} |",
            r.knob.value(),
            r.time_ms,
            r.relative_time,
            r.rmse,
            r.psnr
        );
    }
    let _ = match cheapest_near_best(&rows, floor) {
        Some(r) => writeln!(
            md,
            "\nLeast work within the noise floor of the best error: {name} = {} \
             ({:.2} ms, RMSE {:.5}).\n",
            r.knob.value(),
            r.time_ms,
            r.rmse
        ),
        None => writeln!(md),
    };
    Ok((rows, floor))
}

/// The first row (the settings are listed by the work they do, least
/// first: fewer samples or iterations, a larger epsilon) whose RMSE is
/// within `noise` of the smallest RMSE measured. The work, not the measured
/// time, orders them: on a shared machine neighbouring settings' times
/// differ by less than their noise.
pub fn cheapest_near_best(rows: &[KnobRow], noise: f64) -> Option<&KnobRow> {
    let best = rows.iter().map(|r| r.rmse).min_by(f64::total_cmp)?;
    rows.iter().find(|r| r.rmse <= best + noise)
}

/// Both renders of one cost row, paired at 1 sample per pixel.
fn cost_row(gpu: &Gpu, name: &str, size: (u32, u32), frames: u32) -> Result<CostRow, BenchError> {
    let with = load(name);
    let spheres = spheres_in_place(&with);
    let [a, b] = [&spheres, &with].map(ShaderOptions::for_scene);
    let paired = measure::paired_renders(gpu, [(&a, &spheres), (&b, &with)], size, frames)
        .map_err(BenchError::Failed)?;
    let [s, w] = paired.gpu.times;
    Ok(CostRow {
        scene: name.to_string(),
        with_ms: ms(w),
        spheres_ms: ms(s),
        ratio: paired.gpu.ratio,
        cpu: paired
            .cpu
            .map(|c| (ms(c.times[1]), ms(c.times[0]), c.ratio)),
    })
}

/// Time (x, relative to the scene's own setting, log scale) against RMSE
/// (y, from 0), each point labelled with its setting, the scene's own
/// setting as a large mark, the reference's noise floor as a line.
fn plot_sweep(
    path: &Path,
    sweep: &Sweep,
    rows: &[KnobRow],
    noise: f64,
) -> Result<(), Box<dyn std::error::Error>> {
    register_font();
    let root = BitMapBackend::new(path, (800, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let top = rows.iter().map(|r| r.rmse).fold(noise, f64::max) * 1.15;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!(
                "{} (zoom {}): {}, time against error",
                sweep.scene,
                sweep.zoom,
                sweep.settings[0].name()
            ),
            ("sans-serif", 26),
        )
        .margin(12)
        .x_label_area_size(46)
        .y_label_area_size(70)
        .build_cartesian_2d(
            log_range(rows.iter().map(|r| r.relative_time)).log_scale(),
            0.0..top,
        )?;
    chart
        .configure_mesh()
        .x_labels(12)
        .x_label_formatter(&|x| format!("{x:.2}"))
        .x_desc("frame time / frame time at the scene's own setting")
        .y_desc("RMSE against the converged reference")
        .label_style(("sans-serif", 15))
        .draw()?;
    let (left, right) = (chart.x_range().start, chart.x_range().end);
    chart
        .draw_series(LineSeries::new(
            [(left, noise), (right, noise)],
            RED.stroke_width(1),
        ))?
        .label("the reference's noise floor")
        .legend(|(x, y)| PathElement::new(vec![(x - 8, y), (x + 8, y)], RED.stroke_width(1)));
    let at = |r: &KnobRow| (r.relative_time, r.rmse);
    chart.draw_series(LineSeries::new(rows.iter().map(at), BLUE.stroke_width(2)))?;
    chart.draw_series(rows.iter().map(|r| {
        EmptyElement::at(at(r))
            + Circle::new((0, 0), 4, BLUE.filled())
            + Text::new(r.knob.value(), (6, -16), ("sans-serif", 15))
    }))?;
    chart
        .draw_series(
            rows.iter()
                .filter(|r| r.is_default)
                .map(|r| TriangleMarker::new(at(r), 9, BLACK.filled())),
        )?
        .label("the scene's own setting")
        .legend(|(x, y)| TriangleMarker::new((x, y), 6, BLACK.filled()));
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 15))
        .position(SeriesLabelPosition::LowerLeft)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spheres_take_the_place_of_every_implicit_shape() {
        for name in ["torus", "julia", "implicits"] {
            let scene = load(name);
            let spheres = spheres_in_place(&scene);
            let replaced = scene.tori.len() + scene.implicits.len() + scene.julias.len();
            assert!(replaced > 0, "{name} has shapes to replace");
            assert_eq!(spheres.spheres.len(), scene.spheres.len() + replaced);
            assert!(spheres.tori.is_empty() && spheres.implicits.is_empty());
            assert!(spheres.julias.is_empty());
            let text = spheres.to_toml_string();
            Scene::from_toml_str(&text, None).expect("a valid scene");
        }
    }

    #[test]
    fn every_sweep_holds_its_scenes_own_setting() {
        for sweep in sweeps(false) {
            let scene = load(sweep.scene);
            let own = own_setting(&scene, sweep.settings[0]);
            assert!(sweep.settings.contains(&own), "{}", own.value());
        }
    }

    #[test]
    fn the_cheapest_setting_near_the_best_error_is_chosen() {
        let row = |relative_time, rmse| KnobRow {
            scene: "s".into(),
            knob: Knob::Steps(1),
            time_ms: relative_time,
            relative_time,
            rmse,
            psnr: 0.0,
            is_default: false,
        };
        let rows = [row(1.0, 0.2), row(2.0, 0.051), row(4.0, 0.05)];
        assert_eq!(cheapest_near_best(&rows, 0.002).unwrap().relative_time, 2.0);
        assert_eq!(cheapest_near_best(&rows, 0.0).unwrap().relative_time, 4.0);
    }
}
