//! `raysandbox bench --throughput`: rays per second, counted by the tracer
//! itself, per bundled scene and per mesh size; with the `embree` feature
//! the same primary rays of each mesh traced by Intel Embree in the same
//! run, frame for frame in turn (docs/performance.md, "Rays per second").

use std::fmt::Write as _;
use std::path::Path;
use std::time::Duration;

use super::measure::{median, process_cpu_time};
use super::meshes::{MESHES, project, staged};
use super::{BenchArgs, BenchError, Environment};
use crate::gpu::{Gpu, OffscreenRenderer, ShaderOptions, ShaderSource};
use crate::scene::{Scene, bundled};

/// Rays traced in one frame, by kind, as the tracer's counting variant
/// (`COUNT_RAYS` in `shaders/shade.wgsl`) adds them up.
#[derive(Debug, Default, Clone, Copy, PartialEq)]
pub struct RayCounts {
    pub primary: u64,
    pub shadow: u64,
    pub reflected: u64,
    pub refracted: u64,
}

impl RayCounts {
    pub fn total(&self) -> u64 {
        self.primary + self.shadow + self.reflected + self.refracted
    }
}

/// A renderer of `scene` at `size` with the embedded shaders.
fn renderer(
    gpu: &Gpu,
    scene: &Scene,
    options: &ShaderOptions,
    (width, height): (u32, u32),
) -> Result<OffscreenRenderer, String> {
    OffscreenRenderer::new(
        gpu,
        &ShaderSource::embedded(),
        options,
        scene,
        width,
        height,
    )
    .map_err(|e| e.to_string())
}

/// The rays `scene` traces at `size` and `spp` samples per pixel, counted
/// by the counting variant of its specialised pipeline.
pub fn count_rays(
    gpu: &Gpu,
    scene: &Scene,
    size: (u32, u32),
    spp: u32,
) -> Result<RayCounts, String> {
    let options = ShaderOptions {
        count_rays: true,
        ..ShaderOptions::for_scene(scene)
    };
    let mut renderer = renderer(gpu, scene, &options, size)?;
    renderer.render(gpu, spp).map_err(|e| e.to_string())?;
    let sums = renderer.read_sums(gpu).map_err(|e| e.to_string())?;
    let mut total = [0u64; 4];
    for pixel in sums.chunks_exact(4) {
        for (t, &c) in total.iter_mut().zip(pixel) {
            // Whole numbers far below 2^24 per pixel: exact in f32.
            *t += c as u64;
        }
    }
    Ok(RayCounts {
        primary: total[0],
        shadow: total[1],
        reflected: total[2],
        refracted: total[3],
    })
}

/// Frame times of the drawing pipeline: GPU time (timestamps) and the
/// process's CPU time (on lavapipe the GPU's threads are ours).
struct FrameTime {
    gpu: Duration,
    cpu: Duration,
}

/// Renders one frame at 1 spp and measures it.
fn timed_frame(gpu: &Gpu, renderer: &mut OffscreenRenderer) -> Result<FrameTime, String> {
    let before = process_cpu_time().ok_or("no /proc/self/task/*/schedstat here")?;
    let gpu_time = renderer.render(gpu, 1).map_err(|e| e.to_string())?;
    let after = process_cpu_time().ok_or("no /proc/self/task/*/schedstat here")?;
    Ok(FrameTime {
        gpu: gpu_time,
        cpu: after.saturating_sub(before),
    })
}

/// One bundled scene's row.
pub struct SceneRow {
    pub name: String,
    pub counts: RayCounts,
    pub gpu_ms: f64,
    pub cpu_ms: f64,
}

impl SceneRow {
    /// Millions of rays per second of GPU time.
    fn mrays_per_s(&self) -> f64 {
        self.counts.total() as f64 / self.gpu_ms / 1e3
    }
}

/// Image size and frames timed of one run of the bench.
#[derive(Clone, Copy)]
struct Run {
    size: (u32, u32),
    frames: u32,
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn scene_row(gpu: &Gpu, (name, scene): (&str, &Scene), run: Run) -> Result<SceneRow, String> {
    let Run { size, frames } = run;
    let counts = count_rays(gpu, scene, size, 1)?;
    let mut renderer = renderer(gpu, scene, &ShaderOptions::for_scene(scene), size)?;
    renderer.render(gpu, 1).map_err(|e| e.to_string())?;
    let times: Vec<FrameTime> = (0..frames)
        .map(|_| timed_frame(gpu, &mut renderer))
        .collect::<Result<_, _>>()?;
    Ok(SceneRow {
        name: name.to_string(),
        counts,
        gpu_ms: ms(median(times.iter().map(|t| t.gpu))),
        cpu_ms: ms(median(times.iter().map(|t| t.cpu))),
    })
}

/// The bundled scenes, those with mesh files included, loaded.
fn bundled_scenes() -> Result<Vec<(String, Scene)>, String> {
    let mut scenes = Vec::new();
    for name in bundled::names() {
        let text = bundled::text(name).expect("a bundled scene");
        scenes.push((
            name.to_string(),
            Scene::from_toml_str(text, None).map_err(|e| e.to_string())?,
        ));
    }
    for name in bundled::names_with_files() {
        let path = project()
            .join(bundled::SCENES_WITH_FILES_FOLDER)
            .join(format!("{name}.toml"));
        let scene = Scene::load(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        scenes.push((format!("meshes/{name}"), scene));
    }
    Ok(scenes)
}

/// The mesh alone, placed as `bench --meshes` places it: no floor, no
/// light, `max_depth = 0`, a white mesh under ambient light 1 on black, so
/// a pixel is black exactly where its primary ray hits nothing.
fn mesh_alone(path: &Path) -> Result<Scene, String> {
    let mut scene = staged(path)?;
    scene.planes.clear();
    scene.lights.clear();
    scene.render.max_depth = 0;
    scene.render.background = glam::DVec3::ZERO;
    scene.render.ambient = glam::DVec3::ONE;
    for m in scene.materials.values_mut() {
        m.color = glam::DVec3::ONE;
        m.checker = None;
    }
    Ok(scene)
}

/// The primary ray through each pixel centre (origin, direction; f32, row
/// by row): the reference camera's, which the shader's follows.
#[cfg(feature = "embree")]
fn primary_rays(scene: &Scene, (w, h): (u32, u32)) -> Vec<[f32; 6]> {
    use crate::reference::{Camera, camera_ray};
    let camera = Camera::new(&scene.camera);
    let mut rays = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            let r = camera_ray(
                &camera,
                w,
                h,
                f64::from(x) + 0.5,
                f64::from(y) + 0.5,
                glam::DVec2::ZERO,
            );
            let (o, d) = (r.origin.as_vec3(), r.dir.as_vec3());
            rays.push([o.x, o.y, o.z, d.x, d.y, d.z]);
        }
    }
    rays
}

/// The mesh's triangles in world coordinates: vertices (f32) and indices.
#[cfg(feature = "embree")]
fn world_triangles(scene: &Scene) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let mesh = &scene.meshes[0];
    let g = &mesh.geometry.0;
    let linear = mesh.placement.linear();
    let vertices = g
        .positions
        .iter()
        .map(|&p| (mesh.placement.translate + linear * p).as_vec3().to_array())
        .collect();
    (vertices, g.triangles.clone())
}

/// Pixels where `a` and `b` differ and no pixel within one (the 3 x 3
/// neighbourhood) of the other mask agrees: differences a silhouette
/// rounded to the other side of a pixel centre does not explain.
pub fn mask_mismatches(a: &[bool], b: &[bool], (w, h): (u32, u32)) -> usize {
    let at = |m: &[bool], x: i64, y: i64| {
        (x >= 0 && y >= 0 && x < i64::from(w) && y < i64::from(h))
            .then(|| m[(y * i64::from(w) + x) as usize])
    };
    let explained = |mine: &[bool], other: &[bool], x: i64, y: i64| {
        let want = at(mine, x, y);
        (-1..=1).any(|dy| (-1..=1).any(|dx| at(other, x + dx, y + dy) == want))
    };
    let mut bad = 0;
    for y in 0..i64::from(h) {
        for x in 0..i64::from(w) {
            let i = (y * i64::from(w) + x) as usize;
            if a[i] != b[i] && !(explained(a, b, x, y) && explained(b, a, x, y)) {
                bad += 1;
            }
        }
    }
    bad
}

/// One mesh's row: the GPU's primary rays, and Embree's where built.
pub struct MeshRow {
    pub name: String,
    pub triangles: usize,
    pub gpu_ms: f64,
    pub gpu_cpu_ms: f64,
    pub embree: Option<EmbreeColumns>,
}

/// Embree's times on the same rays, the per-pair ratios and the hit check.
pub struct EmbreeColumns {
    pub wall_ms: f64,
    pub cpu_ms: f64,
    /// Median over the frame pairs of GPU time / Embree wall time.
    pub ratio: f64,
    /// Median over the frame pairs of the two CPU times' ratio.
    pub cpu_ratio: f64,
    /// Pixels whose hit differs beyond one pixel ([`mask_mismatches`]).
    pub mismatches: usize,
    pub differing: usize,
}

fn mesh_row(gpu: &Gpu, (name, path): (&str, &Path), run: Run) -> Result<MeshRow, String> {
    let Run { size, frames } = run;
    let scene = mesh_alone(path)?;
    let mut renderer = renderer(gpu, &scene, &ShaderOptions::for_scene(&scene), size)?;
    renderer.render(gpu, 1).map_err(|e| e.to_string())?;
    let image = renderer.read_image(gpu).map_err(|e| e.to_string())?;
    let gpu_mask: Vec<bool> = image.pixels().map(|p| p.0[..3] != [0, 0, 0]).collect();
    let anchor = Anchor::new(&scene, size)?;
    let mut gpu_times = Vec::new();
    let mut anchor_times = Vec::new();
    for _ in 0..frames {
        gpu_times.push(timed_frame(gpu, &mut renderer)?);
        if let Some(a) = &anchor {
            anchor_times.push(a.timed_trace()?);
        }
    }
    let embree = anchor.map(|a| {
        let differing = a.mask.iter().zip(&gpu_mask).filter(|(a, b)| a != b).count();
        let ratio = |f: fn(&FrameTime) -> Duration| {
            median(
                gpu_times
                    .iter()
                    .zip(&anchor_times)
                    .map(|(g, e)| f(g).as_secs_f64() / f(e).as_secs_f64().max(1e-9)),
            )
        };
        EmbreeColumns {
            wall_ms: ms(median(anchor_times.iter().map(|t| t.gpu))),
            cpu_ms: ms(median(anchor_times.iter().map(|t| t.cpu))),
            ratio: ratio(|t| t.gpu),
            cpu_ratio: ratio(|t| t.cpu),
            mismatches: mask_mismatches(&gpu_mask, &a.mask, size),
            differing,
        }
    });
    Ok(MeshRow {
        name: name.to_string(),
        triangles: scene.meshes[0].geometry.0.triangles.len(),
        gpu_ms: ms(median(gpu_times.iter().map(|t| t.gpu))),
        gpu_cpu_ms: ms(median(gpu_times.iter().map(|t| t.cpu))),
        embree,
    })
}

/// Embree on the mesh's primary rays, with the hits of its first trace.
#[cfg(feature = "embree")]
struct Anchor {
    embree: super::embree::Embree,
    rays: Vec<[f32; 6]>,
    mask: Vec<bool>,
}

#[cfg(feature = "embree")]
impl Anchor {
    fn new(scene: &Scene, size: (u32, u32)) -> Result<Option<Anchor>, String> {
        let (vertices, triangles) = world_triangles(scene);
        let embree = super::embree::Embree::new(&vertices, &triangles)?;
        let rays = primary_rays(scene, size);
        let (mask, _) = embree.trace(&rays);
        Ok(Some(Anchor { embree, rays, mask }))
    }

    /// One trace of all rays on two threads: wall time (in the `gpu`
    /// field) and the CPU time of the two threads (which have ended when
    /// the process's own count could be read, so they measure it
    /// themselves).
    fn timed_trace(&self) -> Result<FrameTime, String> {
        let start = std::time::Instant::now();
        let (mask, cpu) = self.embree.trace(&self.rays);
        let wall = start.elapsed();
        std::hint::black_box(mask);
        Ok(FrameTime { gpu: wall, cpu })
    }
}

/// Without the `embree` feature there is no anchor.
#[cfg(not(feature = "embree"))]
struct Anchor {
    mask: Vec<bool>,
}

#[cfg(not(feature = "embree"))]
impl Anchor {
    fn new(_: &Scene, _: (u32, u32)) -> Result<Option<Anchor>, String> {
        Ok(None)
    }

    fn timed_trace(&self) -> Result<FrameTime, String> {
        unreachable!("no anchor is made without the embree feature")
    }
}

pub fn run(gpu: &Gpu, env: &Environment, args: &BenchArgs) -> Result<(), BenchError> {
    let size = if args.quick { (320, 180) } else { (1280, 720) };
    let run = Run {
        size,
        frames: args.frames,
    };
    let failed = |e: String| BenchError::Failed(e);
    std::fs::create_dir_all(&args.out).map_err(|e| super::fail(&args.out, e))?;
    let mut scenes = Vec::new();
    for (name, scene) in bundled_scenes().map_err(failed)? {
        let row = scene_row(gpu, (&name, &scene), run).map_err(failed)?;
        println!(
            "{name}: {:.2} Mrays/s ({} rays in {:.1} ms GPU, {:.1} ms CPU)",
            row.mrays_per_s(),
            row.counts.total(),
            row.gpu_ms,
            row.cpu_ms
        );
        scenes.push(row);
        if args.quick && scenes.len() == 2 {
            break;
        }
    }
    let mut meshes = Vec::new();
    for (name, file) in MESHES {
        let path = project().join(file);
        if !path.exists() || (args.quick && meshes.len() == 2) {
            continue;
        }
        let row = mesh_row(gpu, (name, &path), run).map_err(failed)?;
        println!("{}", mesh_line(&row, size));
        meshes.push(row);
    }
    let report = markdown(env, size, args.frames, &scenes, &meshes);
    let out = args.out.join("throughput.md");
    std::fs::write(&out, report).map_err(|e| super::fail(&out, e))?;
    println!("wrote {}", out.display());
    if let Some(bad) = meshes
        .iter()
        .find(|m| m.embree.as_ref().is_some_and(|e| e.mismatches > 0))
    {
        return Err(BenchError::Failed(format!(
            "{}: the GPU and Embree disagree on {} pixels beyond one pixel",
            bad.name,
            bad.embree.as_ref().map_or(0, |e| e.mismatches)
        )));
    }
    Ok(())
}

fn mesh_line(r: &MeshRow, (w, h): (u32, u32)) -> String {
    let rays = f64::from(w * h);
    let mut line = format!(
        "{} ({} triangles): {:.2} Mrays/s ({:.1} ms GPU, {:.1} ms CPU)",
        r.name,
        r.triangles,
        rays / r.gpu_ms / 1e3,
        r.gpu_ms,
        r.gpu_cpu_ms
    );
    if let Some(e) = &r.embree {
        let _ = write!(
            line,
            "; Embree {:.2} Mrays/s ({:.1} ms wall, {:.1} ms CPU), ratio {:.1}x (CPU {:.1}x), {} pixels differ, {} beyond a pixel",
            rays / e.wall_ms / 1e3,
            e.wall_ms,
            e.cpu_ms,
            e.ratio,
            e.cpu_ratio,
            e.differing,
            e.mismatches
        );
    }
    line
}

fn markdown(
    env: &Environment,
    (w, h): (u32, u32),
    frames: u32,
    scenes: &[SceneRow],
    meshes: &[MeshRow],
) -> String {
    let mut md = env.report_header("Rays per second");
    let _ = write!(
        md,
        "{w} x {h}, 1 sample per pixel, median of {frames} frames after a warm-up.\n\n"
    );
    md += "## Bundled scenes\n\n| scene | primary | shadow | reflected | refracted | GPU ms | CPU ms | Mrays/s |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for r in scenes {
        let c = r.counts;
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {:.1} | {:.1} | {:.2} |",
            r.name,
            c.primary,
            c.shadow,
            c.reflected,
            c.refracted,
            r.gpu_ms,
            r.cpu_ms,
            r.mrays_per_s()
        );
    }
    md += "\n## Primary rays on a mesh alone, against Embree\n\n";
    if meshes.iter().all(|m| m.embree.is_none()) {
        md += "Embree: not built in (cargo feature `embree`, libembree-dev).\n\n";
    }
    md += "| mesh | triangles | GPU ms | GPU CPU ms | GPU Mrays/s | Embree ms | Embree CPU ms | Embree Mrays/s | GPU / Embree (time) | (CPU time) | pixels differing | beyond 1 px |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    let rays = f64::from(w * h);
    for r in meshes {
        let _ = write!(
            md,
            "| {} | {} | {:.1} | {:.1} | {:.2} |",
            r.name,
            r.triangles,
            r.gpu_ms,
            r.gpu_cpu_ms,
            rays / r.gpu_ms / 1e3
        );
        let _ = match &r.embree {
            Some(e) => writeln!(
                md,
                " {:.1} | {:.1} | {:.2} | {:.1} | {:.1} | {} | {} |",
                e.wall_ms,
                e.cpu_ms,
                rays / e.wall_ms / 1e3,
                e.ratio,
                e.cpu_ratio,
                e.differing,
                e.mismatches
            ),
            None => writeln!(md, " | | | | | | |"),
        };
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn masks_differing_by_a_shifted_edge_match_within_a_pixel() {
        let size = (8, 4);
        let left = |edge: u32| -> Vec<bool> { (0..32).map(|i| i % 8 < edge).collect() };
        assert_eq!(mask_mismatches(&left(3), &left(3), size), 0);
        assert_eq!(mask_mismatches(&left(3), &left(4), size), 0);
        // Two columns off: in both differing columns one mask's pixel has
        // no pixel of its value in the other within one pixel.
        assert_eq!(mask_mismatches(&left(2), &left(4), size), 8);
        assert_eq!(mask_mismatches(&left(2), &left(5), size), 12);
        // A hit that the other mask has nowhere near.
        let mut speck = left(0);
        speck[10] = true;
        assert_eq!(mask_mismatches(&speck, &left(0), size), 1);
    }
}
