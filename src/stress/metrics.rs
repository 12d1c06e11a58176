//! How far a GPU render is from the reference: pixel statistics, NVIDIA's
//! FLIP, first-hit agreement outside silhouettes, and false shadows.

use image::{RgbImage, RgbaImage};

use crate::compare::{diff_images, nan_pixels};
use crate::gpu::FirstHit;
use crate::reference::ShapeId;

/// The reference's answers for one scene at one size.
pub struct ReferenceRender {
    /// The f64 image.
    pub image: RgbaImage,
    /// The same scene without its lights: what a pixel in full shadow shows.
    pub unlit: RgbaImage,
    /// The first hit through every pixel centre (id/depth pass).
    pub first_hits: Vec<Option<(ShapeId, f64)>>,
}

/// One GPU render against the reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Comparison {
    /// Root mean square difference, channels in [0, 1].
    pub rmse: f64,
    /// Peak signal-to-noise ratio in dB (infinite for equal images).
    pub psnr: f64,
    /// Mean of NVIDIA's FLIP error map (0 = identical, 1 = as different as
    /// can be), at the default 67 pixels per degree.
    pub flip_mean: f64,
    /// Fraction of pixels with a channel off by more than 8 of 255.
    pub frac_over_8: f64,
    /// Fraction of all pixels whose first-hit shape differs from the
    /// reference's, not counting the one-pixel band around silhouettes.
    pub id_mismatch: f64,
    /// Pixels the shader marked as non-finite (magenta).
    pub nan_pixels: usize,
    /// Of the pixels that a light visibly brightens in the reference, the
    /// fraction that the GPU shows nearer to unlit than to lit: false
    /// shadows (acne). `lit_pixels` is the denominator.
    pub false_shadow: f64,
    pub lit_pixels: usize,
}

/// The thresholds for a render that "passes": a FLIP mean far below what
/// an observer notices, and first hits that are almost all the same shape.
pub const MAX_FLIP: f64 = 0.01;
pub const MAX_ID_MISMATCH: f64 = 0.001;

impl Comparison {
    /// FLIP mean <= 0.01, first-hit mismatch <= 0.1 % outside silhouette
    /// bands, no NaN pixel.
    pub fn passes(&self) -> bool {
        self.flip_mean <= MAX_FLIP && self.id_mismatch <= MAX_ID_MISMATCH && self.nan_pixels == 0
    }
}

/// Compares a GPU image and id pass with the reference. Also returns the
/// FLIP error map, coloured with the magma scale (black = no error).
pub fn compare(
    reference: &ReferenceRender,
    image: &RgbaImage,
    first_hits: &[FirstHit],
) -> (Comparison, RgbImage) {
    let (w, h) = reference.image.dimensions();
    let d = diff_images(image, &reference.image);
    let (flip_mean, flip_map) = flip(&reference.image, image);
    let (false_shadow, lit_pixels) = false_shadows(reference, image);
    let comparison = Comparison {
        rmse: d.rmse,
        psnr: d.psnr(),
        flip_mean,
        frac_over_8: d.frac_over_8,
        id_mismatch: id_mismatch(&reference.first_hits, first_hits, w, h),
        nan_pixels: nan_pixels(image, &reference.image),
        false_shadow,
        lit_pixels,
    };
    (comparison, flip_map)
}

/// FLIP (Andersson et al. 2020, the `nv-flip` crate): the mean of the error
/// map of `test` against `reference`, and the map coloured with magma.
pub fn flip(reference: &RgbaImage, test: &RgbaImage) -> (f64, RgbImage) {
    let (w, h) = reference.dimensions();
    let (map, mean) = flip_map(reference, test);
    let colours = map.apply_color_lut(&nv_flip::magma_lut());
    let image = RgbImage::from_raw(w, h, colours.to_vec()).expect("FLIP map of the image size");
    (mean, image)
}

/// FLIP's scale, the error view's colour bar for it: 0 where the two
/// pictures look alike, 1 where they differ most.
pub const FLIP_RANGE: [f32; 2] = [0.0, 1.0];

/// FLIP per pixel as the error view shows it (docs/views.md, "The error
/// view"): four floats per pixel, row by row, the pixel's FLIP (0 to 1)
/// first and 1 last; and the mean.
pub fn flip_quantities(reference: &RgbaImage, test: &RgbaImage) -> (Vec<f32>, f64) {
    let (map, mean) = flip_map(reference, test);
    let quantities = map.to_vec().into_iter().flat_map(|f| [f, 0.0, 0.0, 1.0]);
    (quantities.collect(), mean)
}

/// The FLIP error map of `test` against `reference`, and its mean.
fn flip_map(reference: &RgbaImage, test: &RgbaImage) -> (nv_flip::FlipImageFloat, f64) {
    let (w, h) = reference.dimensions();
    let rgb = |img: &RgbaImage| {
        let data: Vec<u8> = img.pixels().flat_map(|p| [p[0], p[1], p[2]]).collect();
        nv_flip::FlipImageRgb8::with_data(w, h, &data)
    };
    let map = nv_flip::flip(
        rgb(reference),
        rgb(test),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    let mean = nv_flip::FlipPool::from_image(&map).mean();
    (map, f64::from(mean))
}

/// The shader's kind and index of a reference shape.
fn kind_index(hit: Option<(ShapeId, f64)>) -> (u32, u32) {
    FirstHit::id_of(hit.map(|(id, _)| id))
}

/// Whether pixel `(i, j)` lies within one pixel of a silhouette of the
/// reference: some pixel of its 3 x 3 neighbourhood sees another shape.
pub fn near_silhouette(ids: &[(u32, u32)], w: usize, h: usize, i: usize, j: usize) -> bool {
    let me = ids[j * w + i];
    for y in j.saturating_sub(1)..=(j + 1).min(h - 1) {
        for x in i.saturating_sub(1)..=(i + 1).min(w - 1) {
            if ids[y * w + x] != me {
                return true;
            }
        }
    }
    false
}

/// The fraction of all pixels whose first-hit shape (kind and index)
/// differs between GPU and reference, outside the one-pixel silhouette band.
pub fn id_mismatch(reference: &[Option<(ShapeId, f64)>], gpu: &[FirstHit], w: u32, h: u32) -> f64 {
    let (w, h) = (w as usize, h as usize);
    if w == 0 || h == 0 {
        return 0.0;
    }
    let ids: Vec<(u32, u32)> = reference.iter().map(|&r| kind_index(r)).collect();
    let mut wrong = 0usize;
    for j in 0..h {
        for i in 0..w {
            let g = gpu[j * w + i];
            let g = if g.kind == FirstHit::NONE {
                (FirstHit::NONE, 0)
            } else {
                (g.kind, g.index)
            };
            if g != ids[j * w + i] && !near_silhouette(&ids, w, h, i, j) {
                wrong += 1;
            }
        }
    }
    wrong as f64 / (w * h) as f64
}

/// A pixel is lit when the reference's image and its unlit image differ by
/// more than this in some channel (8-bit units).
const LIT_MARGIN: u8 = 16;

/// False shadows: among the pixels that the lights brighten by more than
/// `LIT_MARGIN` in the reference, those whose GPU colour is nearer to the
/// unlit colour than to the lit one. Returns (fraction, number lit).
pub fn false_shadows(reference: &ReferenceRender, image: &RgbaImage) -> (f64, usize) {
    let dist = |a: &image::Rgba<u8>, b: &image::Rgba<u8>| -> u32 {
        (0..3).map(|c| u32::from(a[c].abs_diff(b[c]))).sum()
    };
    let (mut lit, mut dark) = (0usize, 0usize);
    for ((r, u), g) in reference
        .image
        .pixels()
        .zip(reference.unlit.pixels())
        .zip(image.pixels())
    {
        let brightened = (0..3).any(|c| r[c] > u[c].saturating_add(LIT_MARGIN));
        if !brightened {
            continue;
        }
        lit += 1;
        if dist(g, u) < dist(g, r) {
            dark += 1;
        }
    }
    let fraction = if lit == 0 {
        0.0
    } else {
        dark as f64 / lit as f64
    };
    (fraction, lit)
}

/// The absolute difference of two images, scaled by `gain` (to make small
/// errors visible), NaN pixels of `test` kept magenta.
pub fn difference_image(reference: &RgbaImage, test: &RgbaImage, gain: u32) -> RgbImage {
    RgbImage::from_fn(reference.width(), reference.height(), |x, y| {
        let (r, t) = (reference.get_pixel(x, y), test.get_pixel(x, y));
        if t.0[..3] == crate::compare::NAN_MAGENTA && r.0[..3] != crate::compare::NAN_MAGENTA {
            return image::Rgb(crate::compare::NAN_MAGENTA);
        }
        image::Rgb(std::array::from_fn(|c| {
            (u32::from(r[c].abs_diff(t[c])) * gain).min(255) as u8
        }))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::ShapeKind;

    fn hit(kind: u32, index: u32) -> FirstHit {
        FirstHit {
            kind,
            index,
            t: 1.0,
        }
    }

    #[test]
    fn silhouette_band_is_excluded() {
        // 6 x 1: sphere 0 on the left half, nothing on the right.
        let reference: Vec<Option<(ShapeId, f64)>> = (0..6)
            .map(|i| (i < 3).then_some((ShapeId::Sphere(0), 1.0)))
            .collect();
        let mut gpu: Vec<FirstHit> = reference
            .iter()
            .map(|r| match r {
                Some(_) => hit(ShapeKind::Sphere.number(), 0),
                None => hit(FirstHit::NONE, 7),
            })
            .collect();
        assert_eq!(
            id_mismatch(&reference, &gpu, 6, 1),
            0.0,
            "miss ignores index"
        );
        // A wrong pixel at the edge (2 or 3) is in the band.
        gpu[3] = hit(ShapeKind::Sphere.number(), 0);
        assert_eq!(id_mismatch(&reference, &gpu, 6, 1), 0.0);
        // Two away from the edge it counts, as does a wrong index.
        gpu[5] = hit(ShapeKind::Sphere.number(), 0);
        gpu[0] = hit(ShapeKind::Sphere.number(), 1);
        assert_eq!(id_mismatch(&reference, &gpu, 6, 1), 2.0 / 6.0);
    }

    #[test]
    fn false_shadows_counts_dark_lit_pixels() {
        let px = |v: u8| image::Rgba([v, v, v, 255]);
        let mut lit = RgbaImage::from_pixel(4, 1, px(200));
        lit.put_pixel(3, 0, px(50)); // in shadow in the reference too
        let reference = ReferenceRender {
            image: lit.clone(),
            unlit: RgbaImage::from_pixel(4, 1, px(50)),
            first_hits: vec![None; 4],
        };
        let mut gpu = lit.clone();
        gpu.put_pixel(0, 0, px(60));
        gpu.put_pixel(1, 0, px(150));
        let (fraction, lit_pixels) = false_shadows(&reference, &gpu);
        assert_eq!(lit_pixels, 3);
        assert_eq!(fraction, 1.0 / 3.0);
    }

    #[test]
    fn flip_of_equal_images_is_zero() {
        let a = RgbaImage::from_fn(32, 16, |x, y| {
            image::Rgba([x as u8 * 8, y as u8 * 16, 90, 255])
        });
        let (mean, map) = flip(&a, &a);
        assert_eq!(mean, 0.0);
        assert_eq!(map.dimensions(), (32, 16));
        let mut b = a.clone();
        for x in 0..32 {
            b.put_pixel(x, 8, image::Rgba([255, 255, 255, 255]));
        }
        assert!(flip(&a, &b).0 > 0.01);
    }
}
