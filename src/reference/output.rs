//! From linear radiance to 8-bit sRGB pixels (docs/rendering-model.md, "Output").

use glam::DVec3;
use image::{Rgba, RgbaImage};

/// One channel of linear radiance (already multiplied by the exposure) as an
/// 8-bit sRGB value: clamped to `[0, 1]`, encoded with the sRGB transfer
/// function, rounded to the nearest of the 256 levels.
///
/// The transfer function (IEC 61966-2-1) spends more of the 8 bits on dark
/// values, where the eye is most sensitive: a straight line `12.92 c` near
/// black, `1.055 c^(1/2.4) - 0.055` above `0.0031308`. NaN, which the tracer
/// never produces, would encode as 0.
pub fn encode_srgb8(linear: f64) -> u8 {
    // Written so that NaN falls into the first branch.
    let c = if linear > 0.0 { linear.min(1.0) } else { 0.0 };
    let encoded = if c < 0.0031308 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    // In [0, 1] (up to rounding), so the cast neither wraps nor saturates
    // for anything but the value it should give.
    (encoded * 255.0).round() as u8
}

/// The image of a `width x height` buffer of linear radiance (row-major, top
/// row first): exposure, then [`encode_srgb8`] per channel, alpha 255.
pub fn to_rgba8(linear: &[DVec3], width: u32, height: u32, exposure: f64) -> RgbaImage {
    RgbaImage::from_fn(width, height, |i, j| {
        let c = exposure * linear[j as usize * width as usize + i as usize];
        Rgba([encode_srgb8(c.x), encode_srgb8(c.y), encode_srgb8(c.z), 255])
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encode_ends_and_middle() {
        assert_eq!(encode_srgb8(0.0), 0);
        assert_eq!(encode_srgb8(1.0), 255);
        // 1.055 * 0.5^(1/2.4) - 0.055 = 0.735357..., * 255 = 187.516...
        assert_eq!(encode_srgb8(0.5), 188);
        // 0.2140 is the linear value of sRGB 0.5 (127.5 of 255).
        assert_eq!(encode_srgb8(0.214), 127);
        assert_eq!(encode_srgb8(0.2142), 128);
    }

    #[test]
    fn encode_linear_segment() {
        // 12.92 * 0.001 * 255 = 3.29...; 12.92 * 0.003 * 255 = 9.88...
        assert_eq!(encode_srgb8(0.001), 3);
        assert_eq!(encode_srgb8(0.003), 10);
        // The two pieces meet at 0.0031308: 12.92 * 0.0031308 = 0.04045 (10.31).
        assert_eq!(encode_srgb8(0.0031307), 10);
        assert_eq!(encode_srgb8(0.0031309), 10);
    }

    #[test]
    fn encode_clamps() {
        assert_eq!(encode_srgb8(-1.0), 0);
        assert_eq!(encode_srgb8(7.0), 255);
        assert_eq!(encode_srgb8(f64::INFINITY), 255);
        assert_eq!(encode_srgb8(f64::NAN), 0);
    }

    #[test]
    fn exposure_scales_before_encoding() {
        let img = to_rgba8(&[DVec3::new(0.25, 0.5, 2.0), DVec3::ZERO], 2, 1, 2.0);
        assert_eq!(img.get_pixel(0, 0).0, [188, 255, 255, 255]);
        assert_eq!(img.get_pixel(1, 0).0, [0, 0, 0, 255]);
    }
}
