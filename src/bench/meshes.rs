//! `raysandbox bench --meshes`: triangle meshes from 1k to 871k triangles
//! (docs/performance.md, "Triangle meshes"). Per mesh: the time to load the
//! file, to build its BVH, and the bytes its GPU buffer takes per triangle;
//! per mesh and ray-triangle test: the frame time of the same view (the
//! mesh scaled to the same size on a floor, with its shadow) and the error
//! against the f64 reference. Then the targets: the largest mesh's frame
//! time over the teapot's (timed in turn), and the load time of a 10 MB OBJ
//! file written for the occasion and deleted after. Last, the two storage
//! layouts of `storage` timed against each other on every mesh.

use std::fmt::Write as _;
use std::path::Path;

use glam::DVec3;

use super::measure::{self, median_time};
use super::storage::{self, StorageRow};
use super::{BenchArgs, BenchError, cpu_model, fail, ms, timing_of};
use crate::bvh::build_triangle_bvh;
use crate::compare;
use crate::gpu::layout::PackedScene;
use crate::gpu::{Gpu, ShaderOptions};
use crate::scene::{AxisScale, Geometry, NamedOption, Scene, ShapeId, TriangleTest, load_file};
use crate::stress::table::table;

/// The meshes, smallest first: name and file relative to the project. The
/// last two are not in the repository: scripts/fetch-meshes writes them.
pub(super) const MESHES: [(&str, &str); 6] = [
    ("teapot", "assets/meshes/teapot.obj"),
    ("bunny", "assets/meshes/bunny.obj"),
    ("dragon_res4", "assets/meshes/dragon_res4.ply"),
    ("dragon_res3", "assets/meshes/dragon_res3.ply"),
    ("dragon_res2", "target/meshes/dragon_res2.ply"),
    ("dragon", "target/meshes/dragon.ply"),
];

/// The stage every mesh is shown on: a checker floor, one light casting
/// the mesh's shadow, the camera framing a unit box on the floor. The mesh
/// is scaled so that its largest extent is 1 and set on the floor.
const STAGE: &str = include_str!("stage.toml");

/// The project folder: the meshes are read from there.
pub(super) fn project() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The stage with the mesh of `path` (flat shading) on it.
pub(super) fn staged(path: &Path) -> Result<Scene, String> {
    let text = format!(
        "{STAGE}\n[[meshes]]\nfile = {:?}\nmaterial = \"clay\"\n",
        path.display().to_string()
    );
    let mut scene = Scene::from_toml_str(&text, None).map_err(|e| e.to_string())?;
    let mesh = &mut scene.meshes[0];
    let g = &mesh.geometry.0;
    let lo = g.positions.iter().fold(DVec3::INFINITY, |a, &p| a.min(p));
    let hi = g
        .positions
        .iter()
        .fold(DVec3::NEG_INFINITY, |a, &p| a.max(p));
    let s = 1.0 / (hi - lo).max_element();
    let centre = 0.5 * (lo + hi);
    mesh.placement.scale = AxisScale::Uniform(s);
    mesh.placement.translate = DVec3::new(-centre.x * s, -lo.y * s, -centre.z * s);
    Ok(scene)
}

/// Bytes of the scene's shape buffers on the GPU.
fn shape_bytes(scene: &Scene) -> usize {
    PackedScene::new(scene, 1, 1)
        .shapes
        .iter()
        .map(|words| 4 * words.len())
        .sum()
}

/// One mesh, what does not depend on the ray-triangle test.
pub struct MeshRow {
    pub name: &'static str,
    pub triangles: usize,
    pub file_bytes: u64,
    pub load_ms: f64,
    pub bvh_ms: f64,
    pub bvh_depth: usize,
    /// Bytes the mesh adds to the GPU's shape buffers (BVH nodes and
    /// triangles), per triangle.
    pub gpu_bytes_per_triangle: f64,
    /// The error floor: FLIP and RMSE of the reference of the scene as
    /// given against the reference of its f32-rounded copy (what rounding
    /// the input alone changes).
    pub floor_flip: f64,
    pub floor_rmse: f64,
    /// Pixels of the error image whose first hit is the mesh.
    pub mesh_pixels: usize,
    pub tests: Vec<TestRow>,
}

/// One mesh with one ray-triangle test.
pub struct TestRow {
    pub test: TriangleTest,
    pub frame_ms: f64,
    pub rmse: f64,
    pub psnr: f64,
    pub flip: f64,
    /// RMSE over the pixels whose first hit (in the reference) is the mesh.
    pub mesh_rmse: f64,
    /// The fraction of those pixels off by more than 8 of 255 in a channel.
    pub mesh_over_8: f64,
}

/// Sizes and repetitions of one run.
struct Plan {
    frame_size: (u32, u32),
    error_size: (u32, u32),
    meshes: usize,
    /// Rays per dispatch of the storage comparison, and dispatches timed.
    storage_rays: usize,
    storage_runs: usize,
}

/// Triangles each ray of the storage comparison is tested against: a few
/// BVH leaves' worth, enough for the loop to dominate the dispatch.
const STORAGE_BLOCK: usize = 64;

impl Plan {
    fn new(quick: bool) -> Plan {
        if quick {
            Plan {
                frame_size: (320, 180),
                error_size: (96, 54),
                meshes: 3,
                storage_rays: 16_384,
                storage_runs: 3,
            }
        } else {
            Plan {
                frame_size: (1280, 720),
                error_size: (320, 180),
                meshes: MESHES.len(),
                storage_rays: 65_536,
                storage_runs: 9,
            }
        }
    }
}

/// Builds needed per timing: fewer for the big meshes, whose single
/// build or load takes long enough to time on its own.
fn runs_for(triangles: usize) -> usize {
    if triangles > 100_000 { 3 } else { 7 }
}

fn measure_mesh(
    gpu: &Gpu,
    name: &'static str,
    path: &Path,
    plan: &Plan,
    frames: u32,
    out: &Path,
) -> Result<MeshRow, BenchError> {
    let load = |p: &Path| load_file(p, false).map_err(BenchError::Failed);
    let geometry: Geometry = load(path)?;
    let triangles = geometry.triangles.len();
    let runs = runs_for(triangles);
    let load_ms = ms(median_time(runs, || {
        std::hint::black_box(load_file(path, false).ok());
    }));
    let bvh_ms = ms(median_time(runs, || {
        std::hint::black_box(build_triangle_bvh(&geometry));
    }));
    let bvh_depth = build_triangle_bvh(&geometry).depth();
    let scene = staged(path).map_err(BenchError::Failed)?;
    let mut empty = scene.clone();
    empty.meshes.clear();
    let mut mesh_only = scene.clone();
    mesh_only.planes.clear();
    empty.planes.clear();
    let gpu_bytes = shape_bytes(&mesh_only) - shape_bytes(&empty);

    let (w, h) = plan.error_size;
    let rounded = crate::stress::scenes::round_to_f32(&scene);
    let reference = crate::reference::render_rgba8(&rounded, w, h, 1);
    let prepared = crate::reference::PreparedScene::new(&rounded);
    let on_mesh: Vec<bool> = crate::reference::first_hits(&prepared, w, h)
        .iter()
        .map(|hit| matches!(hit, Some((ShapeId::Mesh(_), _))))
        .collect();
    let unrounded = crate::reference::render_rgba8(&scene, w, h, 1);
    let floor_flip = crate::stress::metrics::flip(&reference, &unrounded).0;
    let floor_rmse = measure::error(&unrounded, &reference).0;
    let mut tests = Vec::new();
    for test in TriangleTest::ALL {
        let mut options = ShaderOptions::for_scene(&scene);
        options.kinds.meshes = test;
        let (time, _) = measure::frame_time(gpu, &options, &scene, plan.frame_size, 1, frames)
            .map_err(BenchError::Failed)?;
        let (_, image) = measure::frame_time(gpu, &options, &rounded, (w, h), 1, 1)
            .map_err(BenchError::Failed)?;
        let (rmse, psnr) = measure::error(&image, &reference);
        if test == TriangleTest::default() {
            let shown = out.join(format!("mesh_{name}.png"));
            image.save(&shown).map_err(|e| fail(&shown, e))?;
        }
        let on = compare::diff_images_where(&image, &reference, |i| on_mesh[i]);
        let (mesh_rmse, mesh_over_8) = (on.rmse, on.frac_over_8);
        tests.push(TestRow {
            test,
            frame_ms: ms(time),
            rmse,
            psnr,
            mesh_rmse,
            mesh_over_8,
            flip: crate::stress::metrics::flip(&reference, &image).0,
        });
    }
    Ok(MeshRow {
        name,
        triangles,
        file_bytes: std::fs::metadata(path).map_or(0, |m| m.len()),
        load_ms,
        bvh_ms,
        bvh_depth,
        gpu_bytes_per_triangle: gpu_bytes as f64 / triangles as f64,
        floor_flip,
        floor_rmse,
        mesh_pixels: on_mesh.iter().filter(|&&m| m).count(),
        tests,
    })
}

/// The largest mesh's frame time over the teapot's, the two rendered in
/// turn with the default test.
pub struct FrameRatio {
    pub small: &'static str,
    pub large: &'static str,
    pub small_ms: f64,
    pub large_ms: f64,
    pub ratio: f64,
}

fn frame_ratio(
    gpu: &Gpu,
    small: (&'static str, &Path),
    large: (&'static str, &Path),
    size: (u32, u32),
    frames: u32,
) -> Result<FrameRatio, BenchError> {
    let a = staged(small.1).map_err(BenchError::Failed)?;
    let b = staged(large.1).map_err(BenchError::Failed)?;
    let (oa, ob) = (ShaderOptions::for_scene(&a), ShaderOptions::for_scene(&b));
    let ([ta, tb], ratio) = measure::paired_scene_times(gpu, [(&oa, &a), (&ob, &b)], size, frames)
        .map_err(BenchError::Failed)?;
    Ok(FrameRatio {
        small: small.0,
        large: large.0,
        small_ms: ms(ta),
        large_ms: ms(tb),
        ratio,
    })
}

/// An OBJ file of at least `min_bytes`: copies of `geometry` side by side,
/// as `v` and `f` records.
fn write_obj(path: &Path, geometry: &Geometry, min_bytes: usize) -> std::io::Result<usize> {
    let mut text = String::new();
    let mut base = 1;
    let mut copy = 0.0;
    while text.len() < min_bytes {
        for p in &geometry.positions {
            let _ = writeln!(text, "v {:.6} {:.6} {:.6}", p.x + copy, p.y, p.z);
        }
        for t in &geometry.triangles {
            let _ = writeln!(
                text,
                "f {} {} {}",
                t[0] as usize + base,
                t[1] as usize + base,
                t[2] as usize + base
            );
        }
        base += geometry.positions.len();
        copy += 1.0;
    }
    std::fs::write(path, &text)?;
    Ok(text.len())
}

/// The 10 MB OBJ: written, loaded (median of 3), deleted.
pub struct ObjLoad {
    pub bytes: usize,
    pub triangles: usize,
    pub load_ms: f64,
}

fn obj_load(out: &Path) -> Result<ObjLoad, BenchError> {
    let source = project().join(MESHES[3].1);
    let geometry = load_file(&source, false).map_err(BenchError::Failed)?;
    let path = out.join("generated-10MB.obj");
    let bytes = write_obj(&path, &geometry, 10_000_000).map_err(|e| fail(&path, e))?;
    let loaded = load_file(&path, false).map_err(BenchError::Failed);
    let load_ms = ms(median_time(3, || {
        std::hint::black_box(load_file(&path, false).ok());
    }));
    std::fs::remove_file(&path).map_err(|e| fail(&path, e))?;
    Ok(ObjLoad {
        bytes,
        triangles: loaded?.triangles.len(),
        load_ms,
    })
}

pub fn run(gpu: &Gpu, args: &BenchArgs) -> Result<(), BenchError> {
    let plan = Plan::new(args.quick);
    let threads = std::thread::available_parallelism().map_or(0, |n| n.get());
    let machine = format!(
        "{}; {}; frame time: {}",
        gpu.describe(),
        cpu_model(),
        timing_of(gpu).describe()
    );
    println!("{machine}");
    std::fs::create_dir_all(&args.out).map_err(|e| fail(&args.out, e))?;
    let mut rows = Vec::new();
    let mut missing = Vec::new();
    for (name, file) in MESHES.iter().take(plan.meshes) {
        let path = project().join(file);
        if !path.exists() {
            println!(
                "{name}: {} is missing: run scripts/fetch-meshes",
                path.display()
            );
            missing.push(*file);
            continue;
        }
        let row = measure_mesh(gpu, name, &path, &plan, args.frames, &args.out)?;
        println!("{}", console_line(&row));
        rows.push(row);
    }
    let largest = rows.last().map(|r| r.name).unwrap_or(MESHES[0].0);
    let large_path = project().join(MESHES.iter().find(|m| m.0 == largest).map_or("", |m| m.1));
    let ratio = frame_ratio(
        gpu,
        (MESHES[0].0, &project().join(MESHES[0].1)),
        (largest, &large_path),
        plan.frame_size,
        args.frames,
    )?;
    println!(
        "frame time {} / {} at {}x{}, in turn: {:.2} ms / {:.2} ms, median ratio {:.2}",
        ratio.large,
        ratio.small,
        plan.frame_size.0,
        plan.frame_size.1,
        ratio.large_ms,
        ratio.small_ms,
        ratio.ratio
    );
    let obj = obj_load(&args.out)?;
    println!(
        "OBJ of {:.1} MB ({} triangles) loaded in {:.0} ms",
        obj.bytes as f64 / 1e6,
        obj.triangles,
        obj.load_ms
    );
    let storage_rows = storage_rows(gpu, &plan)?;
    let plot = args.out.join("meshes.png");
    frame_time_plot(&plot, &rows).map_err(|e| fail(&plot, e))?;
    let write = |name: &str, text: String| {
        let path = args.out.join(name);
        std::fs::write(&path, text).map_err(|e| fail(&path, e))
    };
    write("meshes.csv", csv(&rows))?;
    write("storage.csv", storage::csv(&storage_rows))?;
    write(
        "meshes.md",
        markdown(&machine, threads, &plan, &rows, &ratio, &obj, &missing)
            + &storage::markdown(&storage_rows),
    )?;
    println!("wrote {}", args.out.join("meshes.md").display());
    Ok(())
}

/// The storage comparison on every mesh of the plan that is present.
fn storage_rows(gpu: &Gpu, plan: &Plan) -> Result<Vec<StorageRow>, BenchError> {
    let mut rows = Vec::new();
    for (name, file) in MESHES.iter().take(plan.meshes) {
        let path = project().join(file);
        if !path.exists() {
            continue;
        }
        let geometry = load_file(&path, false).map_err(BenchError::Failed)?;
        let row = storage::measure(
            gpu,
            name,
            &geometry,
            plan.storage_rays,
            STORAGE_BLOCK,
            plan.storage_runs,
        )
        .map_err(BenchError::Failed)?;
        println!("{}", storage::console_line(&row));
        rows.push(row);
    }
    Ok(rows)
}

fn console_line(r: &MeshRow) -> String {
    let tests: Vec<String> = r
        .tests
        .iter()
        .map(|t| format!("{} {:.1} ms FLIP {:.4}", t.test.name(), t.frame_ms, t.flip))
        .collect();
    format!(
        "{}: {} triangles, load {:.0} ms, BVH {:.0} ms (depth {}), {:.1} B/triangle; {}",
        r.name,
        r.triangles,
        r.load_ms,
        r.bvh_ms,
        r.bvh_depth,
        r.gpu_bytes_per_triangle,
        tests.join(", ")
    )
}

/// The CSV columns of `meshes.csv`.
pub const MESH_COLUMNS: &str = "mesh,triangles,file_bytes,load_ms,bvh_build_ms,bvh_depth,gpu_bytes_per_triangle,floor_flip,floor_rmse,test,frame_ms,rmse,psnr_db,flip,mesh_rmse,mesh_over_8";

fn csv(rows: &[MeshRow]) -> String {
    table(MESH_COLUMNS, tests_of(rows), |(r, t)| {
        format!(
            "{},{},{},{:.3},{:.3},{},{:.2},{:.6},{:.6},{},{:.3},{:.6},{:.3},{:.6},{:.6},{:.6}",
            r.name,
            r.triangles,
            r.file_bytes,
            r.load_ms,
            r.bvh_ms,
            r.bvh_depth,
            r.gpu_bytes_per_triangle,
            r.floor_flip,
            r.floor_rmse,
            t.test.name(),
            t.frame_ms,
            t.rmse,
            t.psnr,
            t.flip,
            t.mesh_rmse,
            t.mesh_over_8
        )
    })
}

/// Every test of every mesh, with its mesh.
fn tests_of(rows: &[MeshRow]) -> impl Iterator<Item = (&MeshRow, &TestRow)> {
    rows.iter()
        .flat_map(|r| r.tests.iter().map(move |t| (r, t)))
}

fn markdown(
    machine: &str,
    threads: usize,
    plan: &Plan,
    rows: &[MeshRow],
    ratio: &FrameRatio,
    obj: &ObjLoad,
    missing: &[&str],
) -> String {
    let mut md = String::from("# raysandbox bench --meshes\n\n");
    let _ = writeln!(md, "- machine: {machine}");
    let _ = writeln!(md, "- rayon threads: {threads}");
    let _ = writeln!(
        md,
        "- frames at {}x{}, 1 sample per pixel, median after a warm-up frame; errors at {}x{} \
         against the f64 reference (watertight test) of the f32-rounded scene, same sample",
        plan.frame_size.0, plan.frame_size.1, plan.error_size.0, plan.error_size.1
    );
    for file in missing {
        let _ = writeln!(
            md,
            "- left out, missing: `{file}` (run `scripts/fetch-meshes`)"
        );
    }
    let _ = writeln!(
        md,
        "\n| mesh | triangles | file (MB) | load (ms) | BVH build (ms) | BVH depth | GPU bytes / triangle | error floor FLIP | mesh pixels |\n\
         | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    );
    for r in rows {
        let _ = writeln!(
            md,
            "| {} | {} | {:.2} | {:.1} | {:.1} | {} | {:.1} | {:.5} | {} |",
            r.name,
            r.triangles,
            r.file_bytes as f64 / 1e6,
            r.load_ms,
            r.bvh_ms,
            r.bvh_depth,
            r.gpu_bytes_per_triangle,
            r.floor_flip,
            r.mesh_pixels
        );
    }
    md += "\n![frame time against triangles](meshes.png)\n\n";
    md += &table(
        "| mesh | test | frame (ms) | RMSE | PSNR (dB) | FLIP | RMSE on the mesh | mesh pixels > 8/255 |\n\
         | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |",
        tests_of(rows),
        |(r, t)| {
            format!(
                "| {} | {} | {:.2} | {:.5} | {:.1} | {:.5} | {:.5} | {:.3}% |",
                r.name,
                t.test.name(),
                t.frame_ms,
                t.rmse,
                t.psnr,
                t.flip,
                t.mesh_rmse,
                t.mesh_over_8 * 100.0
            )
        },
    );
    let _ = writeln!(
        md,
        "\n## Targets\n\n- {} over {} frame time (rendered in turn, median of the per-pair ratios): \
         {:.2} ({:.1} ms / {:.1} ms)",
        ratio.large, ratio.small, ratio.ratio, ratio.large_ms, ratio.small_ms
    );
    if let Some(r) = rows.last() {
        let _ = writeln!(
            md,
            "- BVH build of {} ({} triangles): {:.0} ms",
            r.name, r.triangles, r.bvh_ms
        );
    }
    let _ = writeln!(
        md,
        "- OBJ load: {:.1} MB ({} triangles) in {:.0} ms",
        obj.bytes as f64 / 1e6,
        obj.triangles,
        obj.load_ms
    );
    md
}

/// Frame time against the number of triangles, one line per test.
fn frame_time_plot(path: &Path, rows: &[MeshRow]) -> Result<(), Box<dyn std::error::Error>> {
    let series: Vec<(String, Vec<(f64, f64)>)> = TriangleTest::ALL
        .iter()
        .map(|&test| {
            let points = rows
                .iter()
                .filter_map(|r| {
                    let t = r.tests.iter().find(|t| t.test == test)?;
                    Some((r.triangles as f64, t.frame_ms))
                })
                .collect();
            (test.name().to_string(), points)
        })
        .collect();
    super::plot::log_log_lines(
        path,
        "Frame time against the number of triangles",
        ("triangles", "GPU frame time (ms)"),
        &series,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_staged_mesh_stands_on_the_floor_with_extent_one() {
        for (_, file) in MESHES.iter().take(3) {
            let scene = staged(&project().join(file)).unwrap();
            let m = &scene.meshes[0];
            let g = &m.geometry.0;
            let (translate, linear) = (m.placement.translate, m.placement.linear());
            let world: Vec<DVec3> = g
                .positions
                .iter()
                .map(|&p| translate + linear * p)
                .collect();
            let lo = world.iter().fold(DVec3::INFINITY, |a, &p| a.min(p));
            let hi = world.iter().fold(DVec3::NEG_INFINITY, |a, &p| a.max(p));
            assert!(lo.y.abs() < 1e-12, "{file}: {lo}");
            assert!(((hi - lo).max_element() - 1.0).abs() < 1e-12, "{file}");
        }
    }

    #[test]
    fn the_generated_obj_is_large_enough_and_loads_whole() {
        let geometry = load_file(&project().join(MESHES[0].1), false).unwrap();
        let dir = std::env::temp_dir().join(format!("raysandbox-obj-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("big.obj");
        let bytes = write_obj(&path, &geometry, 100_000).unwrap();
        assert!(bytes >= 100_000);
        let loaded = load_file(&path, false).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(loaded.triangles.len() % geometry.triangles.len(), 0);
        assert!(loaded.triangles.len() >= 2 * geometry.triangles.len());
    }
}
