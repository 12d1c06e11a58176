//! Image comparison: how far a GPU image is from the reference, in 8-bit units.

use image::RgbaImage;

/// Differences between two images of the same size, over the RGB channels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImageDiff {
    /// Mean of |a - b| over all pixels and RGB channels, in 8-bit units.
    pub mean_abs: f64,
    /// Fraction of pixels with some channel differing by more than 8.
    pub frac_over_8: f64,
    /// Largest channel difference.
    pub max_abs: u8,
    /// Root mean square difference, with channels scaled to [0, 1].
    pub rmse: f64,
}

impl ImageDiff {
    /// Peak signal-to-noise ratio in dB (peak 1); infinite for equal images.
    pub fn psnr(&self) -> f64 {
        -20.0 * self.rmse.log10()
    }
}

/// Compares `a` with `b`. Panics if their sizes differ (a caller bug).
pub fn diff_images(a: &RgbaImage, b: &RgbaImage) -> ImageDiff {
    diff_images_where(a, b, |_| true)
}

/// Compares `a` with `b` over the pixels (in row order) for which `keep` is
/// true, e.g. those a mesh covers. Panics if their sizes differ.
pub fn diff_images_where(
    a: &RgbaImage,
    b: &RgbaImage,
    mut keep: impl FnMut(usize) -> bool,
) -> ImageDiff {
    assert_eq!(a.dimensions(), b.dimensions(), "images of different sizes");
    let mut sum = 0u64;
    let mut sum_sq = 0u64;
    let mut over = 0usize;
    let mut max_abs = 0u8;
    let mut pixels = 0usize;
    for (_, (pa, pb)) in (a.pixels().zip(b.pixels()))
        .enumerate()
        .filter(|(i, _)| keep(*i))
    {
        let mut pixel_max = 0u8;
        for c in 0..3 {
            let d = pa[c].abs_diff(pb[c]);
            sum += u64::from(d);
            sum_sq += u64::from(d) * u64::from(d);
            pixel_max = pixel_max.max(d);
        }
        if pixel_max > 8 {
            over += 1;
        }
        max_abs = max_abs.max(pixel_max);
        pixels += 1;
    }
    let pixels = pixels.max(1);
    let samples = (pixels * 3) as f64;
    ImageDiff {
        mean_abs: sum as f64 / samples,
        frac_over_8: over as f64 / pixels as f64,
        max_abs,
        rmse: (sum_sq as f64 / samples).sqrt() / 255.0,
    }
}

/// The colour the shader shows where a pixel's radiance is not finite.
pub const NAN_MAGENTA: [u8; 3] = [255, 0, 255];

/// Number of pixels that are magenta in `gpu` but not in `reference`: the
/// shader's non-finite marker, where the reference has a real colour.
pub fn nan_pixels(gpu: &RgbaImage, reference: &RgbaImage) -> usize {
    gpu.pixels()
        .zip(reference.pixels())
        .filter(|(g, r)| g.0[..3] == NAN_MAGENTA && r.0[..3] != NAN_MAGENTA)
        .count()
}

/// Number of distinct RGB colours, up to `limit` (to tell a picture from a
/// blank image cheaply).
pub fn distinct_colors(image: &RgbaImage, limit: usize) -> usize {
    let mut seen = std::collections::HashSet::new();
    for p in image.pixels() {
        seen.insert([p[0], p[1], p[2]]);
        if seen.len() >= limit {
            break;
        }
    }
    seen.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diff_of_known_images() {
        let a = RgbaImage::from_pixel(2, 1, image::Rgba([10, 20, 30, 255]));
        let mut b = a.clone();
        b.put_pixel(1, 0, image::Rgba([10, 20, 42, 255]));
        let d = diff_images(&a, &b);
        assert_eq!(d.max_abs, 12);
        assert!((d.mean_abs - 12.0 / 6.0).abs() < 1e-12);
        assert_eq!(d.frac_over_8, 0.5);
        assert!((d.rmse - (144.0f64 / 6.0).sqrt() / 255.0).abs() < 1e-12);
        assert!(diff_images(&a, &a).psnr().is_infinite());
    }

    #[test]
    fn masked_diff_counts_only_the_kept_pixels() {
        let a = RgbaImage::from_pixel(3, 1, image::Rgba([10, 20, 30, 255]));
        let mut b = a.clone();
        b.put_pixel(1, 0, image::Rgba([10, 20, 42, 255]));
        let only_changed = diff_images_where(&a, &b, |i| i == 1);
        assert_eq!(only_changed.max_abs, 12);
        assert_eq!(only_changed.frac_over_8, 1.0);
        assert!((only_changed.mean_abs - 4.0).abs() < 1e-12);
        let without_it = diff_images_where(&a, &b, |i| i != 1);
        assert_eq!(without_it.max_abs, 0);
        assert_eq!(without_it.rmse, 0.0);
    }

    #[test]
    fn magenta_counts_only_where_the_reference_differs() {
        let reference = RgbaImage::from_pixel(3, 1, image::Rgba([0, 0, 0, 255]));
        let mut gpu = reference.clone();
        gpu.put_pixel(0, 0, image::Rgba([255, 0, 255, 255]));
        assert_eq!(nan_pixels(&gpu, &reference), 1);
        assert_eq!(distinct_colors(&gpu, 10), 2);
    }
}
