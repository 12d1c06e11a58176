//! The measurements: GPU frame times (median after a warm-up frame) and
//! errors against the converged f64 reference.

use std::time::{Duration, Instant};

use glam::DVec3;
use image::RgbaImage;

use crate::bvh::Bvh;
use crate::compare::diff_images;
use crate::gpu::{Gpu, OffscreenRenderer, ShaderOptions, ShaderSource};
use crate::reference;
use crate::scene::{Instance, Scene, Unplaced};

/// Median GPU time of `frames` renders after one warm-up render, and the
/// last image. The warm-up absorbs shader compilation and first-use costs.
pub fn frame_time(
    gpu: &Gpu,
    options: &ShaderOptions,
    scene: &Scene,
    size: (u32, u32),
    spp: u32,
    frames: u32,
) -> Result<(Duration, RgbaImage), String> {
    let source = ShaderSource::embedded();
    let mut renderer = OffscreenRenderer::new(gpu, &source, options, scene, size.0, size.1)
        .map_err(|e| e.to_string())?;
    let wait = |e: crate::gpu::GpuWaitError| e.to_string();
    renderer.render(gpu, spp).map_err(wait)?;
    let times: Vec<Duration> = (0..frames.max(1))
        .map(|_| renderer.render(gpu, spp))
        .collect::<Result<_, _>>()
        .map_err(wait)?;
    Ok((median(times), renderer.read_image(gpu).map_err(wait)?))
}

/// Two pipelines timed on the same scene, frame for frame in turn: see
/// [`paired_scene_times`].
pub fn paired_frame_times(
    gpu: &Gpu,
    options: [&ShaderOptions; 2],
    scene: &Scene,
    size: (u32, u32),
    frames: u32,
) -> Result<([Duration; 2], f64), String> {
    paired_scene_times(gpu, options.map(|o| (o, scene)), size, frames)
}

/// Two renders (a pipeline and a scene each) timed frame for frame in turn
/// (A, B, A, B, ...) after a warm-up render of each: the median time of
/// each, and the median of the per-pair ratios B / A. Taking turns exposes
/// both to the same load of a shared machine, and the pair's ratio cancels
/// what drifts between pairs, so the ratio is steadier than the ratio of
/// the medians.
pub fn paired_scene_times(
    gpu: &Gpu,
    renders: [(&ShaderOptions, &Scene); 2],
    size: (u32, u32),
    frames: u32,
) -> Result<([Duration; 2], f64), String> {
    let paired = paired_renders(gpu, renders, size, frames)?;
    Ok((paired.gpu.times, paired.gpu.ratio))
}

/// One measure of a paired run: the median per render and the median of
/// the per-pair ratios B / A.
#[derive(Debug, Clone, Copy)]
pub struct PairedTimes {
    pub times: [Duration; 2],
    pub ratio: f64,
}

impl PairedTimes {
    fn of(pairs: &[[Duration; 2]]) -> PairedTimes {
        let ratios = pairs
            .iter()
            .map(|[a, b]| b.as_secs_f64() / a.as_secs_f64().max(1e-9));
        PairedTimes {
            times: [0, 1].map(|i| median(pairs.iter().map(|p| p[i]))),
            ratio: median(ratios),
        }
    }
}

/// A paired run measured two ways: GPU time, and the CPU time this process
/// spent per frame where the system reports it (`process_cpu_time`).
pub struct Paired {
    pub gpu: PairedTimes,
    pub cpu: Option<PairedTimes>,
}

/// As [`paired_scene_times`], with the CPU time of each frame too. On
/// lavapipe the GPU is this process's own threads, so their CPU time is the
/// work of the frame, which other programs on a loaded machine do not
/// stretch as they stretch its wall-clock (and timestamp) time.
pub fn paired_renders(
    gpu: &Gpu,
    renders: [(&ShaderOptions, &Scene); 2],
    size: (u32, u32),
    frames: u32,
) -> Result<Paired, String> {
    let source = ShaderSource::embedded();
    let wait = |e: crate::gpu::GpuWaitError| e.to_string();
    let mut renderers = Vec::new();
    for (o, scene) in renders {
        let mut r = OffscreenRenderer::new(gpu, &source, o, scene, size.0, size.1)
            .map_err(|e| e.to_string())?;
        r.render(gpu, 1).map_err(wait)?;
        renderers.push(r);
    }
    let mut gpu_pairs = Vec::new();
    let mut cpu_pairs = Vec::new();
    for _ in 0..frames.max(1) {
        let c0 = process_cpu_time();
        let a = renderers[0].render(gpu, 1).map_err(wait)?;
        let c1 = process_cpu_time();
        let b = renderers[1].render(gpu, 1).map_err(wait)?;
        let c2 = process_cpu_time();
        gpu_pairs.push([a, b]);
        if let (Some(c0), Some(c1), Some(c2)) = (c0, c1, c2) {
            cpu_pairs.push([c1.saturating_sub(c0), c2.saturating_sub(c1)]);
        }
    }
    Ok(Paired {
        gpu: PairedTimes::of(&gpu_pairs),
        cpu: (cpu_pairs.len() == gpu_pairs.len()).then(|| PairedTimes::of(&cpu_pairs)),
    })
}

/// The CPU time all threads of this process have used so far (lavapipe
/// renders on threads of ours), the sum of the first field of
/// `/proc/self/task/*/schedstat` (nanoseconds on the CPU); `None` where
/// the system has no such files.
pub fn process_cpu_time() -> Option<Duration> {
    let mut total = 0u64;
    for task in std::fs::read_dir("/proc/self/task").ok()? {
        let path = task.ok()?.path().join("schedstat");
        // A thread that ended since the listing no longer counts.
        let Ok(text) = std::fs::read_to_string(path) else {
            continue;
        };
        total += text.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(Duration::from_nanos(total))
}

/// How many times the largest sample count measured the converged reference
/// traces: its own error is then well below that of every measured render.
pub const REFERENCE_FACTOR: u32 = 8;

/// The two Cranley-Patterson rotations of the R4 sequence (see
/// `reference::render_linear_rotated`) the reference's halves are traced
/// with: fixed pseudo-random shifts, so runs repeat, and far from zero and
/// from each other, so neither half shares a sample with the unrotated
/// sequence of the GPU renders (checked by a test) or with the other half.
pub const REFERENCE_SHIFTS: [[f64; 4]; 2] = [
    [0.2731, 0.6158, 0.4127, 0.7346],
    [0.8623, 0.1547, 0.5391, 0.3089],
];

/// The converged reference of one scene: the f64 renderer, max_depth 16,
/// min_weight 0, whatever the scene file says, with samples that no GPU
/// render has (both halves rotated), and how far it is from converged.
pub struct ConvergedReference {
    pub image: RgbaImage,
    /// Samples per pixel, both halves together.
    pub spp: u32,
    /// RMSE between the two halves (each `spp / 2` samples, traced with
    /// different rotations): two independent estimates of the same image.
    pub halves_rmse: f64,
}

impl ConvergedReference {
    /// Traces `spp` samples per pixel in two halves with the two
    /// [`REFERENCE_SHIFTS`] and averages them.
    pub fn render(scene: &Scene, size: (u32, u32), spp: u32) -> Self {
        let mut scene = scene.clone();
        scene.render.max_depth = 16;
        scene.render.min_weight = 0.0;
        let prepared = reference::PreparedScene::new(&scene);
        let half = (spp / 2).max(1);
        let [a, b] = REFERENCE_SHIFTS
            .map(|shift| reference::render_linear_rotated(&prepared, size.0, size.1, half, shift));
        let exposure = scene.render.exposure;
        let image_of = |linear: &[DVec3]| reference::to_rgba8(linear, size.0, size.1, exposure);
        let mean: Vec<DVec3> = a.iter().zip(&b).map(|(a, b)| (a + b) / 2.0).collect();
        ConvergedReference {
            image: image_of(&mean),
            spp: 2 * half,
            halves_rmse: error(&image_of(&a), &image_of(&b)).0,
        }
    }

    /// The reference's own RMSE, estimated from its halves: each half's
    /// error is about `halves_rmse / sqrt 2` (two independent errors add in
    /// squares), and averaging two halves divides it by at least `sqrt 2`
    /// (exactly so for independent random samples; quasi-random ones
    /// converge faster), so the mean's error is at most `halves_rmse / 2`.
    pub fn noise_floor(&self) -> f64 {
        self.halves_rmse / 2.0
    }
}

/// RMSE (channels in [0, 1]) and PSNR (dB) of `image`, shown at the size of
/// `reference` (a lower-resolution image is scaled up pixel by pixel, as the
/// viewer shows it), against `reference`.
pub fn error(image: &RgbaImage, reference: &RgbaImage) -> (f64, f64) {
    let shown = if image.dimensions() == reference.dimensions() {
        image.clone()
    } else {
        image::imageops::resize(
            image,
            reference.width(),
            reference.height(),
            image::imageops::FilterType::Nearest,
        )
    };
    let d = diff_images(&shown, reference);
    (d.rmse, d.psnr())
}

/// Median time of building the BVH of `scene`, over `runs` builds.
pub fn bvh_build_time(scene: &Scene, runs: usize) -> Duration {
    median_time(runs, || {
        std::hint::black_box(Bvh::build(std::hint::black_box(scene)));
    })
}

/// Median of `runs` timings of `f`.
pub fn median_time(runs: usize, mut f: impl FnMut()) -> Duration {
    median((0..runs.max(1)).map(|_| {
        let start = Instant::now();
        f();
        start.elapsed()
    }))
}

/// The middle value (the upper one of an even count): a timing that a
/// shared machine's stray slow run does not move. A NaN (a 0/0 ratio)
/// sorts after every number, so the order stays total and the sort cannot
/// panic. Panics when empty (a caller bug: every measure takes at least
/// one run).
pub fn median<T: PartialOrd>(values: impl IntoIterator<Item = T>) -> T {
    let mut values: Vec<T> = values.into_iter().collect();
    // A NaN is the one value not comparable with itself.
    let nan = |x: &T| x.partial_cmp(x).is_none();
    values.sort_by(|a, b| a.partial_cmp(b).unwrap_or_else(|| nan(a).cmp(&nan(b))));
    values.swap_remove(values.len() / 2)
}

/// `n` spheres on a jittered grid over a fixed square of the floor, with
/// radii shrinking as 1 / sqrt(n): the picture covers about the same part
/// of the screen at every n, so only the number of shapes changes.
pub fn sphere_field(n: usize) -> Scene {
    let mut scene = Scene::from_toml_str(include_str!("sphere_field.toml"), None)
        .expect("the field scene is valid");
    let side = (n as f64).sqrt().ceil().max(1.0) as usize;
    let spacing = 10.0 / side as f64;
    let radius = 0.35 * spacing;
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    let mut jitter = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed % 1000) as f64 / 1000.0 - 0.5
    };
    for k in 0..n {
        let (i, j) = ((k % side) as f64, (k / side) as f64);
        let x = -5.0 + (i + 0.5 + 0.3 * jitter()) * spacing;
        let z = -5.0 + (j + 0.5 + 0.3 * jitter()) * spacing;
        let sphere = crate::scene::Sphere {
            center: DVec3::new(x, radius, z),
            radius,
        };
        let sphere = Instance::new(sphere, Unplaced).with_material("ball");
        scene.spheres.push(sphere);
    }
    scene
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_takes_the_middle_and_sorts_nan_last() {
        assert_eq!(median([3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median([f64::NAN, 1.0, 2.0]), 2.0);
        assert!(median([f64::NAN, f64::NAN, 1.0]).is_nan());
        let ms = Duration::from_millis;
        assert_eq!(median([ms(5), ms(1)]), ms(5));
    }

    #[test]
    fn sphere_field_has_n_valid_spheres_on_the_floor() {
        for n in [1, 7, 64] {
            let scene = sphere_field(n);
            assert_eq!(scene.spheres.len(), n);
            let text = scene.to_toml_string();
            let back = Scene::from_toml_str(&text, None).expect("valid");
            assert_eq!(back.spheres.len(), n);
            assert!(
                scene
                    .spheres
                    .iter()
                    .all(|s| (s.center.y - s.radius).abs() < 1e-12)
            );
        }
    }

    /// The reference's samples are no GPU render's: every rotated sample of
    /// both halves (up to 8 x 1024 per pixel) is at least 1e-4 away, in some
    /// component, from every sample the GPU traces up to 1024 per pixel, and
    /// from every sample of the other half.
    #[test]
    fn reference_halves_share_no_sample_with_the_renders_or_each_other() {
        let n = 1024;
        let gpu: Vec<[f64; 4]> = (0..n).map(reference::r4).collect();
        let halves: Vec<Vec<[f64; 4]>> = REFERENCE_SHIFTS
            .iter()
            .map(|&shift| {
                (0..REFERENCE_FACTOR * n / 2)
                    .map(|k| reference::r4_rotated(k, shift))
                    .collect()
            })
            .collect();
        let apart = |a: &[f64; 4], b: &[f64; 4]| {
            a.iter().zip(b).any(|(x, y)| {
                let d = (x - y).rem_euclid(1.0);
                d.min(1.0 - d) > 1e-4
            })
        };
        for half in &halves {
            for s in half {
                assert!(gpu.iter().all(|g| apart(s, g)), "{s:?} is a GPU sample");
            }
        }
        for a in &halves[0] {
            assert!(
                halves[1].iter().all(|b| apart(a, b)),
                "{a:?} in both halves"
            );
        }
    }

    #[test]
    fn error_of_an_upscaled_image_compares_at_full_size() {
        let reference = RgbaImage::from_pixel(4, 2, image::Rgba([100, 100, 100, 255]));
        let small = RgbaImage::from_pixel(2, 1, image::Rgba([100, 100, 100, 255]));
        let (rmse, psnr) = error(&small, &reference);
        assert_eq!(rmse, 0.0);
        assert!(psnr.is_infinite());
    }
}
