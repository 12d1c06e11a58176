//! Where the samples of a pixel go: the R4 quasirandom sequence for the pixel
//! offset and the lens point, and Shirley and Chiu's map from the square to
//! the lens disk (docs/implementation.md, "Sample sequence").

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

use glam::DVec2;

/// The real root of `x^5 = x + 1`, the "generalised golden ratio" for four
/// dimensions (Roberts 2018, "The Unreasonable Effectiveness of Quasirandom
/// Sequences").
pub const R4_ROOT: f64 = 1.1673039782614187;

/// Sample `k` of the 4-D additive recurrence `fract(0.5 + k * alpha)` with
/// `alpha = (1/g, 1/g^2, 1/g^3, 1/g^4)`.
///
/// Why R4: successive samples fill the 4-D unit cube evenly, whatever their
/// number, so progressive refinement (one sample per frame) converges
/// smoothly. The `0.5` start makes sample 0 the pixel centre and the lens
/// centre, which the rendering model requires at 1 sample per pixel. Components 0 and 1
/// are the pixel offset `(sx, sy)`, 2 and 3 the lens sample in the square.
/// The reference computes `k * alpha` in f64 (the shader in f32).
pub fn r4(k: u32) -> [f64; 4] {
    let mut sample = [0.0; 4];
    let mut alpha = 1.0;
    for s in &mut sample {
        alpha /= R4_ROOT;
        // The argument is positive, so `fract` is `x - floor(x)`.
        *s = (0.5 + f64::from(k) * alpha).fract();
    }
    sample
}

/// Sample `k` of the R4 sequence rotated by `shift`: every component moved by
/// the same `shift[i]` modulo 1 (a Cranley-Patterson rotation).
///
/// Why: a rotated sequence spreads its points as evenly as the original, but
/// shares none of them (unless the shift happens to be the difference of two
/// of its points in all four components), and two different random shifts give two independent
/// estimates of the same pixel. The time/error benchmark builds its
/// converged reference this way, so that the renders it measures cannot be
/// compared with copies of their own samples. A zero shift is [`r4`].
pub fn r4_rotated(k: u32, shift: [f64; 4]) -> [f64; 4] {
    let mut sample = r4(k);
    for (s, d) in sample.iter_mut().zip(shift) {
        *s = (*s + d).rem_euclid(1.0);
        // Rounding can land a sum just below 1 on 1 itself.
        if *s >= 1.0 {
            *s = 0.0;
        }
    }
    sample
}

/// Shirley and Chiu's concentric map ("A Low Distortion Map Between Disk and
/// Square", 1997) from `s` in `[0, 1)^2` to the unit disk.
///
/// Why this map and not `(sqrt(s.x), 2 pi s.y)` in polar form: it keeps
/// neighbouring points neighbours and areas proportional, so well spread
/// square samples stay well spread on the lens. The square's centre maps to
/// the disk's centre.
pub fn concentric_disk(s: DVec2) -> DVec2 {
    let a = 2.0 * s.x - 1.0;
    let b = 2.0 * s.y - 1.0;
    if a == 0.0 && b == 0.0 {
        return DVec2::ZERO;
    }
    // Concentric squares become concentric circles; in each of the four
    // wedges the larger coordinate is the radius.
    let (r, phi) = if a.abs() > b.abs() {
        (a, FRAC_PI_4 * (b / a))
    } else {
        (b, FRAC_PI_2 - FRAC_PI_4 * (a / b))
    };
    r * DVec2::new(phi.cos(), phi.sin())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn root_solves_x5_eq_x_plus_1() {
        let g = R4_ROOT;
        assert!((g.powi(5) - g - 1.0).abs() < 1e-15);
    }

    #[test]
    fn sample_zero_is_the_centre() {
        assert_eq!(r4(0), [0.5; 4]);
    }

    #[test]
    fn sample_one_by_hand_and_all_in_unit_cube() {
        let s = r4(1);
        for (i, si) in s.iter().enumerate() {
            let expected = (0.5 + R4_ROOT.powi(-(i as i32 + 1))).fract();
            assert!((si - expected).abs() < 1e-15, "component {i}");
        }
        // 1/g = 0.8567.., so 0.5 + 1/g wraps around.
        assert!((s[0] - (0.5 + 1.0 / R4_ROOT - 1.0)).abs() < 1e-15);
        for k in [2, 17, 1000, 123_456, u32::MAX] {
            assert!(r4(k).iter().all(|&x| (0.0..1.0).contains(&x)), "k = {k}");
        }
    }

    #[test]
    fn rotation_by_zero_is_r4_and_others_share_no_sample() {
        for k in [0, 1, 17, 4096] {
            assert_eq!(r4_rotated(k, [0.0; 4]), r4(k));
        }
        let shift = [0.31, 0.77, 0.05, 0.52];
        let rotated: Vec<[f64; 4]> = (0..512).map(|k| r4_rotated(k, shift)).collect();
        assert!(rotated.iter().flatten().all(|x| (0.0..1.0).contains(x)));
        for k in 0..512 {
            let s = r4(k);
            assert!(rotated.iter().all(|r| r != &s), "sample {k} is shared");
            let r = r4_rotated(k, shift);
            for i in 0..4 {
                let moved = (r[i] - s[i]).rem_euclid(1.0);
                assert!((moved - shift[i]).abs() < 1e-12, "k {k}, component {i}");
            }
        }
    }

    #[test]
    fn concentric_map_centre_edges_and_disk() {
        assert_eq!(concentric_disk(DVec2::splat(0.5)), DVec2::ZERO);
        let right = concentric_disk(DVec2::new(1.0, 0.5));
        assert!((right - DVec2::X).length() < 1e-15);
        let top = concentric_disk(DVec2::new(0.5, 1.0));
        assert!((top - DVec2::Y).length() < 1e-15);
        // A square corner goes to the circle at 45 degrees.
        let corner = concentric_disk(DVec2::ZERO);
        let expected = -DVec2::splat(std::f64::consts::FRAC_1_SQRT_2);
        assert!((corner - expected).length() < 1e-15);
        for k in 0..1000 {
            let s = r4(k);
            assert!(concentric_disk(DVec2::new(s[2], s[3])).length() <= 1.0 + 1e-15);
        }
    }

    #[test]
    fn concentric_map_is_continuous_on_the_diagonals() {
        // The two branches meet where |a| = |b|.
        for (a, b) in [(0.3, 0.3), (0.3, -0.3), (-0.7, 0.7), (-0.2, -0.2)] {
            let p = concentric_disk(DVec2::new((a + 1.0) / 2.0, (b + 1.0) / 2.0));
            let q = concentric_disk(DVec2::new((a * (1.0 + 1e-12) + 1.0) / 2.0, (b + 1.0) / 2.0));
            assert!((p - q).length() < 1e-9, "({a}, {b})");
        }
    }
}
