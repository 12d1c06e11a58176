//! The error view's yardstick (docs/views.md, "The error view"): the f64
//! radiance at pixel centres, traced coarse to fine so that a viewer can
//! show a rough answer at once, and how far the GPU's radiance is from it,
//! per pixel, in 8-bit sRGB levels.

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::PreparedScene;
use super::camera::camera_ray;
use super::output::encode_srgb8;
use super::shade::trace;

/// The grids traced one after the other: every 8th pixel of every 8th row
/// (1/64 of the work), then every 4th, every 2nd, every pixel. Each grid
/// holds the coarser ones, so each level traces only the pixels it adds.
pub const STRIDES: [u32; 4] = [8, 4, 2, 1];

/// The reference's radiance at the pixel centres of a `width x height`
/// image, through the lens centre (the ray of the views), level by level.
/// One refinement serves the viewer's worker thread and the page's slices
/// between frames: both call [`Self::refine_some`], a few pixels at a
/// time, and look between calls whether the picture moved on.
pub struct ErrorImage {
    scene: PreparedScene,
    width: u32,
    height: u32,
    /// Row-major, top row first; set at the pixels of the levels done (and
    /// at some of the level being traced, which nothing reads yet).
    radiance: Vec<DVec3>,
    /// Levels of [`STRIDES`] traced so far.
    levels: usize,
    /// The pixels of the level being traced that are not traced yet, the
    /// next one last.
    pending: Vec<usize>,
    /// Pixels traced so far, of all levels.
    done: usize,
}

impl ErrorImage {
    /// Nothing traced yet.
    pub fn new(scene: &PreparedScene, width: u32, height: u32) -> Self {
        let mut image = ErrorImage {
            scene: scene.sized(height).into_owned(),
            width,
            height,
            radiance: vec![DVec3::ZERO; width as usize * height as usize],
            levels: 0,
            pending: Vec::new(),
            done: 0,
        };
        image.pending = image.level_pixels(STRIDES[0]);
        image
    }

    /// The image traced whole, every pixel (the headless renderer's).
    pub fn traced(scene: &PreparedScene, width: u32, height: u32) -> Self {
        let mut image = Self::new(scene, width, height);
        while !image.finished() {
            image.refine_some(usize::MAX);
        }
        image
    }

    /// The stride of the finest level traced (1: every pixel), `None`
    /// before the first.
    pub fn stride(&self) -> Option<u32> {
        self.levels.checked_sub(1).map(|l| STRIDES[l])
    }

    /// Whether every level is traced.
    pub fn finished(&self) -> bool {
        self.levels == STRIDES.len()
    }

    /// The share of the image's pixels traced so far, 0 to 1: what the
    /// status line says while a level is being traced.
    pub fn fraction(&self) -> f64 {
        self.done as f64 / self.radiance.len().max(1) as f64
    }

    /// Traces up to `budget` pixels of the level being traced, on the
    /// rayon pool (on wasm32, without threads, rayon runs them on the
    /// calling thread). Returns whether that finished the level: a new
    /// [`Self::stride`] to show. Once all are done it does nothing.
    pub fn refine_some(&mut self, budget: usize) -> bool {
        if self.finished() {
            return false;
        }
        let start = self.pending.len().saturating_sub(budget);
        let batch = self.pending.split_off(start);
        let traced: Vec<(usize, DVec3)> = batch
            .par_iter()
            .map(|&p| (p, self.centre_radiance(p)))
            .collect();
        self.done += traced.len();
        for (p, radiance) in traced {
            self.radiance[p] = radiance;
        }
        if !self.pending.is_empty() {
            return false;
        }
        self.levels += 1;
        if let Some(&stride) = STRIDES.get(self.levels) {
            self.pending = self.level_pixels(stride);
        }
        true
    }

    /// The pixels (row-major indices) on the grid of `stride` and not on
    /// the coarser grid of twice the stride, or all of the coarsest grid.
    fn level_pixels(&self, stride: u32) -> Vec<usize> {
        let coarser = (stride < STRIDES[0]).then_some(2 * stride);
        let on = |k: u32, s: u32| k.is_multiple_of(s);
        (0..self.height)
            .step_by(stride as usize)
            .flat_map(|j| {
                (0..self.width)
                    .step_by(stride as usize)
                    .map(move |i| (i, j))
            })
            .filter(|&(i, j)| coarser.is_none_or(|c| !(on(i, c) && on(j, c))))
            .map(|(i, j)| j as usize * self.width as usize + i as usize)
            .collect()
    }

    /// The radiance (before exposure) of the ray through the centre of
    /// pixel `p` and the lens centre.
    fn centre_radiance(&self, p: usize) -> DVec3 {
        let w = self.width as usize;
        let (x, y) = ((p % w) as f64 + 0.5, (p / w) as f64 + 0.5);
        let ray = camera_ray(
            &self.scene.camera,
            self.width,
            self.height,
            x,
            y,
            DVec2::ZERO,
        );
        trace(&self.scene, &ray, 0, 1.0)
    }

    /// The reference's picture, as `render --reference` encodes it (at
    /// the pixel centres; black where no level has traced yet).
    pub fn rgba8(&self) -> image::RgbaImage {
        super::output::to_rgba8(&self.radiance, self.width, self.height, self.scene.exposure)
    }

    /// The GPU's picture as `render` encodes it, from its radiance at the
    /// pixel centres (four floats per pixel, the view's read-back): what
    /// FLIP compares with [`Self::rgba8`].
    pub fn gpu_rgba8(&self, gpu: &[f32]) -> image::RgbaImage {
        let radiance: Vec<DVec3> = gpu
            .chunks_exact(4)
            .map(|q| DVec3::new(q[0].into(), q[1].into(), q[2].into()))
            .collect();
        super::output::to_rgba8(&radiance, self.width, self.height, self.scene.exposure)
    }

    /// The error view's quantities: four floats per pixel, row by row, the
    /// error of [`pixel_error`] first and 1 last; `gpu` holds the GPU's
    /// radiance at the same pixel centres, four floats per pixel (the
    /// view's read-back). A pixel not traced yet shows the error of the
    /// traced pixel at the corner of its block (a coarse level's picture).
    /// Empty before the first level, or when `gpu` is of another size.
    pub fn quantities(&self, gpu: &[f32]) -> Vec<f32> {
        let (w, h) = (self.width as usize, self.height as usize);
        let Some(stride) = self.stride() else {
            return Vec::new();
        };
        if gpu.len() != 4 * w * h {
            return Vec::new();
        }
        let s = stride as usize;
        let mut out = Vec::with_capacity(4 * w * h);
        for j in 0..h {
            for i in 0..w {
                let p = (j - j % s) * w + (i - i % s);
                let g = [gpu[4 * p], gpu[4 * p + 1], gpu[4 * p + 2]];
                let e = pixel_error(g, self.radiance[p], self.scene.exposure);
                out.extend([e, 0.0, 0.0, 1.0]);
            }
        }
        out
    }
}

/// How far the GPU's radiance `gpu` is from the reference's: both through
/// the exposure and the 8-bit sRGB encoding of the output
/// ([`encode_srgb8`]), the largest difference of the three channels, in
/// levels (0..=255). What a student sees: a difference that the 8 bits
/// round away is no error, one in the highlights that clamping hides
/// neither. A radiance that is not finite (the shader's magenta) is 255.
pub fn pixel_error(gpu: [f32; 3], reference: DVec3, exposure: f64) -> f32 {
    if gpu.iter().any(|c| !c.is_finite()) {
        return 255.0;
    }
    (0..3)
        .map(|c| {
            let g = encode_srgb8(exposure * f64::from(gpu[c]));
            let r = encode_srgb8(exposure * reference[c]);
            g.abs_diff(r)
        })
        .max()
        .map_or(0.0, f32::from)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    fn whitted() -> PreparedScene {
        let text = crate::scene::bundled::text("whitted").expect("bundled");
        PreparedScene::new(&Scene::from_toml_str(text, None).expect("the Whitted scene"))
    }

    #[test]
    fn levels_cover_every_pixel_once() {
        let image = ErrorImage::new(&whitted(), 19, 11);
        let mut seen = vec![0; 19 * 11];
        for s in STRIDES {
            for p in image.level_pixels(s) {
                seen[p] += 1;
            }
        }
        assert!(seen.iter().all(|&n| n == 1), "{seen:?}");
    }

    #[test]
    fn refining_a_few_pixels_at_a_time_ends_at_the_full_image() {
        let scene = whitted();
        let mut image = ErrorImage::new(&scene, 16, 9);
        assert_eq!(image.stride(), None);
        assert!(image.quantities(&[0.0; 4 * 16 * 9]).is_empty());
        // The coarsest grid of 16 x 9 is 2 x 2 pixels.
        assert!(!image.refine_some(3));
        assert_eq!((image.stride(), image.fraction()), (None, 3.0 / 144.0));
        assert!(image.refine_some(3));
        assert_eq!(image.stride(), Some(8));
        let mut shown = vec![8];
        while !image.finished() {
            if image.refine_some(5) {
                shown.extend(image.stride());
            }
        }
        assert_eq!(shown, STRIDES);
        assert_eq!(image.fraction(), 1.0);
        assert!(!image.refine_some(5));
        let full = ErrorImage::traced(&scene, 16, 9);
        assert_eq!(image.radiance, full.radiance);
        // The GPU's radiance equal to the reference's: no error anywhere.
        let gpu: Vec<f32> = full
            .radiance
            .iter()
            .flat_map(|r| [r.x as f32, r.y as f32, r.z as f32, 2.0])
            .collect();
        let q = full.quantities(&gpu);
        assert_eq!(q.len(), gpu.len());
        assert!(q.chunks(4).all(|q| q == [0.0, 0.0, 0.0, 1.0]), "{q:?}");
    }

    #[test]
    fn the_error_is_in_output_levels() {
        let grey = DVec3::splat(0.5);
        assert_eq!(pixel_error([0.5; 3], grey, 1.0), 0.0);
        // 188 against 255 in the red channel only.
        assert_eq!(pixel_error([1.0, 0.5, 0.5], grey, 1.0), 67.0);
        // Above 1 both clamp: no difference shows.
        assert_eq!(pixel_error([3.0; 3], DVec3::splat(2.0), 1.0), 0.0);
        assert_eq!(pixel_error([f32::NAN, 0.5, 0.5], grey, 1.0), 255.0);
    }
}
