//! `raysandbox bench` end to end on its smallest configuration: the files it
//! promises exist, with the documented columns and finite numbers. No
//! timing is asserted (timing targets belong to the benchmark itself).

mod common;

use std::path::Path;
use std::process::Command;

use raysandbox::bench::{
    ERROR_COLUMNS, JULIA_DRAG_COLUMNS, PIPELINE_COLUMNS, REFERENCE_COLUMNS, RayCounts,
    SCALING_COLUMNS, count_rays,
};
use raysandbox::gpu::{OffscreenRenderer, ShaderOptions, ShaderSource};
use raysandbox::scene::{Scene, bundled};

fn check_csv(path: &Path, columns: &str, text_columns: usize) -> usize {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some(columns), "{}", path.display());
    let width = columns.split(',').count();
    let mut rows = 0;
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells.len(), width, "{line}");
        for cell in &cells[text_columns..] {
            let value: f64 = cell
                .parse()
                .unwrap_or_else(|_| panic!("not a number: {cell} in {line}"));
            // PSNR is infinite only for an exact match, which the sweep's
            // cheap points cannot have; everything else must be finite.
            assert!(value.is_finite() && value >= 0.0, "{line}");
        }
        rows += 1;
    }
    rows
}

#[test]
fn quick_bench_writes_csv_markdown_and_plots() {
    common::require_gpu();
    let out = std::env::temp_dir().join(format!("raysandbox-bench-{}", std::process::id()));
    let status = Command::new(env!("CARGO_BIN_EXE_raysandbox"))
        .args([
            "bench",
            "--quick",
            "--frames",
            "1",
            "--out",
            out.to_str().unwrap(),
        ])
        .status()
        .expect("run raysandbox bench");
    assert!(status.success());
    assert!(check_csv(&out.join("time_vs_error.csv"), ERROR_COLUMNS, 1) > 4);
    assert_eq!(
        check_csv(&out.join("specialized_vs_generic.csv"), PIPELINE_COLUMNS, 1),
        2
    );
    assert_eq!(check_csv(&out.join("scaling.csv"), SCALING_COLUMNS, 0), 3);
    assert_eq!(
        check_csv(&out.join("reference.csv"), REFERENCE_COLUMNS, 1),
        2
    );
    // The reference shares no sample with the renders: the error falls with
    // the samples as averaging predicts, by 1.2 to 2 times from 8 to 16 (a
    // reference made of the renders' own samples shows 10 times and more).
    let rows = std::fs::read_to_string(out.join("time_vs_error.csv")).unwrap();
    let rmse = |scene: &str, spp: &str| -> f64 {
        rows.lines()
            .map(|l| l.split(',').collect::<Vec<_>>())
            .filter(|c| c[0] == scene && c[1] == spp && c[3] == "0" && c[4] == "1")
            .map(|c| (c[2].parse::<u32>().unwrap(), c[6].parse::<f64>().unwrap()))
            .max_by_key(|(depth, _)| *depth)
            .unwrap_or_else(|| panic!("no {scene} row at {spp} spp"))
            .1
    };
    for scene in ["whitted", "mirror_cube"] {
        let ratio = rmse(scene, "8") / rmse(scene, "16");
        assert!(
            (1.2..=2.1).contains(&ratio),
            "{scene}: 8 -> 16 spp divides the error by {ratio:.2}"
        );
    }
    let report = std::fs::read_to_string(out.join("results.md")).unwrap();
    for needle in [
        "adapter:",
        "CPU:",
        "Pareto",
        "noise floor",
        "Specialised against generic",
        "Scaling",
    ] {
        assert!(report.contains(needle), "results.md lacks {needle}");
    }
    for plot in [
        "pareto_whitted.png",
        "pareto_mirror_cube.png",
        "scaling.png",
    ] {
        let image = image::open(out.join(plot)).expect("a PNG plot").to_rgb8();
        let first = image.get_pixel(0, 0);
        assert!(image.pixels().any(|p| p != first), "{plot} is blank");
    }
    std::fs::remove_dir_all(&out).unwrap();
}

/// The counting variant of the tracer (`bench --throughput`) counts what
/// the rendering model traces: one primary ray per pixel and sample, no
/// shadow ray without a light, no child ray without a mirror or glass, and
/// in the Whitted scene (two lights, a mirror and a glass sphere) every
/// kind, at most two shadow rays per ray traced.
#[test]
fn the_tracer_counts_its_rays_by_kind() {
    let gpu = common::gpu();
    let plain = Scene::from_toml_str(
        "[camera]\nfrom = [0, 0, 4]\nto = [0, 0, 0]\nfov = 40\n\
         [materials.clay]\ncolor = [0.8, 0.5, 0.4]\n\
         [[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"clay\"\n",
        None,
    )
    .unwrap();
    let only_primary = |primary| RayCounts {
        primary,
        shadow: 0,
        reflected: 0,
        refracted: 0,
    };
    assert_eq!(
        count_rays(&gpu, &plain, (32, 18), 1).unwrap(),
        only_primary(576)
    );
    assert_eq!(
        count_rays(&gpu, &plain, (32, 18), 3).unwrap(),
        only_primary(3 * 576)
    );
    let whitted = Scene::from_toml_str(bundled::text("whitted").unwrap(), None).unwrap();
    let c = count_rays(&gpu, &whitted, (32, 18), 1).unwrap();
    assert_eq!(c.primary, 576);
    assert!(c.shadow > 0 && c.reflected > 0 && c.refracted > 0, "{c:?}");
    assert!(
        c.shadow <= 2 * (c.primary + c.reflected + c.refracted),
        "{c:?}"
    );
}

/// `bench --julia-drag` times the Julia scene for each value of `c (i)`
/// from 0.4 to 0.8 and says which fit the viewer's budget.
#[test]
fn the_julia_drag_bench_times_each_value_of_c() {
    common::require_gpu();
    let out = std::env::temp_dir().join(format!("raysandbox-julia-drag-{}", std::process::id()));
    let status = Command::new(env!("CARGO_BIN_EXE_raysandbox"))
        .args(["bench", "--julia-drag", "--quick", "--frames", "1", "--out"])
        .arg(&out)
        .status()
        .expect("run raysandbox bench --julia-drag");
    assert!(status.success());
    let csv = out.join("julia_drag.csv");
    assert_eq!(check_csv(&csv, JULIA_DRAG_COLUMNS, 0), 3);
    let rows = std::fs::read_to_string(&csv).unwrap();
    let c: Vec<&str> = rows.lines().skip(1).map(|l| &l[..4]).collect();
    assert_eq!(c, ["0.40", "0.60", "0.80"]);
    for line in rows.lines().skip(1) {
        let scale: f64 = line.rsplit(',').next().unwrap().parse().unwrap();
        assert!(scale > 0.0 && scale <= 1.0, "{line}");
    }
    let report = std::fs::read_to_string(out.join("julia_drag.md")).unwrap();
    assert!(
        report.contains("Within the budget at this size:"),
        "{report}"
    );
    std::fs::remove_dir_all(&out).unwrap();
}

/// What the drag bench relies on: a renderer given a changed scene
/// (`set_scene`, its pipelines kept) draws what a renderer made for that
/// scene draws.
#[test]
fn a_scene_set_on_a_renderer_draws_as_a_new_renderer() {
    let gpu = common::gpu();
    let size = (96, 64);
    let mut scene = Scene::from_toml_str(bundled::text("julia").unwrap(), None).unwrap();
    let options = ShaderOptions::for_scene(&scene);
    let draw = |renderer: &mut OffscreenRenderer| {
        renderer.render(&gpu, 1).unwrap();
        renderer.read_image(&gpu).unwrap()
    };
    let new_renderer = |scene: &Scene| {
        OffscreenRenderer::new(
            &gpu,
            &ShaderSource::embedded(),
            &options,
            scene,
            size.0,
            size.1,
        )
        .unwrap()
    };
    let mut kept = new_renderer(&scene);
    let before = draw(&mut kept);
    scene.julias[0].c[1] = 0.8;
    kept.set_scene(&gpu, &scene).unwrap();
    let after = draw(&mut kept);
    assert_ne!(before, after, "the new c changed nothing");
    assert_eq!(after, draw(&mut new_renderer(&scene)));
}
