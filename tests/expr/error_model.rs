//! How far the GPU's f32 evaluation of a function may be from the exact
//! one: a first-order error model. Every operation of the function is
//! evaluated exactly (in dual numbers, so the gradient comes too) and then
//! moved by the error WGSL allows that operation in f32 (the WGSL
//! specification's accuracy table: `atan` 4096 ulps, `sin` and `cos` 2^-11
//! absolute, `exp` 3 + 2|x| ulps, a rounding of every arithmetic result,
//! ...), each error with a sign of its own. Over several sign patterns, the
//! largest change of the value and of each gradient component says how much
//! this function at this point amplifies the allowed errors: a cancellation
//! such as `sinh(sin(y)) + asin(0.9 * sin(z))` near 0 turns `asin`'s small
//! relative error into a large one, and a power of the sum carries it into
//! the gradient while the value hardly moves.

use glam::DVec3;
use raysandbox::expr::{Dual, Function, Scalar, Unary};
use std::ops::{Add, Div, Mul, Sub};

/// One unit in the last place of an f32, relative.
const ULP: f64 = f32::EPSILON as f64;

/// The sign patterns tried: each allowed error is pushed one way or the
/// other by a hash of the pattern and the operation's place in the tree.
const PATTERNS: u64 = 24;

/// The largest change of the value, and of each gradient component, that
/// the allowed errors make to `f` at `p` over [`PATTERNS`] sign patterns.
pub fn deviation(f: &Function, p: DVec3) -> (f64, DVec3) {
    let (value, gradient) = f.value_and_gradient(p);
    let mut worst = (0.0f64, DVec3::ZERO);
    for pattern in 0..PATTERNS {
        let variables = Dual::variables(p);
        let inputs = [0u64, 1, 2].map(|axis| Perturbed {
            exact: variables[axis as usize],
            seed: mix(pattern.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ axis),
        });
        let moved = f.eval(inputs).exact;
        worst.0 = worst.0.max((moved.value - value).abs());
        worst.1 = worst.1.max((moved.gradient - gradient).abs());
    }
    worst
}

/// A dual number that carries the seed of the sign pattern through the
/// tree: every operation mixes its operands' seeds into its own.
#[derive(Debug, Clone, Copy)]
struct Perturbed {
    exact: Dual,
    seed: u64,
}

/// SplitMix64's finaliser: a well-spread hash of a 64-bit seed.
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

impl Perturbed {
    /// `result` moved by `value_error` (absolute) and each gradient
    /// component by `gradient_error` times its size, each with a sign from
    /// the seed.
    fn moved(result: Dual, seed: u64, value_error: f64, gradient_error: f64) -> Perturbed {
        let sign = |bit: u32| if seed >> bit & 1 == 1 { 1.0 } else { -1.0 };
        let gradient = result.gradient
            + gradient_error * DVec3::new(sign(1), sign(2), sign(3)) * result.gradient.abs();
        Perturbed {
            exact: Dual {
                value: result.value + sign(0) * value_error,
                gradient,
            },
            seed,
        }
    }

    /// A result of arithmetic: rounded to f32 (`ulps` units) in value and
    /// gradient.
    fn rounded(result: Dual, seed: u64, ulps: f64) -> Perturbed {
        Self::moved(result, seed, ulps * ULP * result.value.abs(), ulps * ULP)
    }

    fn seed_with(self, other: Perturbed, op: u64) -> u64 {
        mix(self.seed ^ other.seed.rotate_left(23) ^ op)
    }
}

macro_rules! arithmetic {
    ($trait:ident, $method:ident, $op:tt, $tag:expr, $ulps:expr) => {
        impl $trait for Perturbed {
            type Output = Perturbed;
            fn $method(self, b: Perturbed) -> Perturbed {
                let seed = self.seed_with(b, $tag);
                Perturbed::rounded(self.exact $op b.exact, seed, $ulps)
            }
        }
    };
}

arithmetic!(Add, add, +, 1, 1.0);
arithmetic!(Sub, sub, -, 2, 1.0);
arithmetic!(Mul, mul, *, 3, 1.0);
// WGSL allows division 2.5 ulps.
arithmetic!(Div, div, /, 4, 2.5);

/// The absolute error WGSL allows `f(x) = fx` in f32, and the relative
/// error of the derivative as the generated WGSL computes it
/// (src/expr/wgsl.rs), where `dg` is the exact derivative.
fn allowed_error(f: Unary, x: f64, fx: f64, dg: f64) -> (f64, f64) {
    let exp_ulps = (3.0 + 2.0 * x.abs()) * ULP;
    let value = match f {
        Unary::Neg | Unary::Abs | Unary::Floor => 0.0,
        Unary::Sin | Unary::Cos => 2f64.powi(-11),
        Unary::Tan => 2f64.powi(-11) * (1.0 + fx.abs()) / x.cos().abs(),
        Unary::Asin | Unary::Acos | Unary::Atan => 4096.0 * ULP * fx.abs(),
        // (exp(x) -+ exp(-x)) / 2: each exponential's error, absolute.
        Unary::Sinh | Unary::Cosh => exp_ulps * x.cosh(),
        Unary::Tanh => 2.0 * exp_ulps,
        Unary::Exp => exp_ulps * fx,
        Unary::Log => 2f64.powi(-21) + 3.0 * ULP * fx.abs(),
        Unary::Sqrt => 3.0 * ULP * fx,
    };
    let derivative_absolute = match f {
        Unary::Neg | Unary::Abs | Unary::Floor => 0.0,
        Unary::Sin | Unary::Cos => 2f64.powi(-11),
        // 1 + fx² and 1 - fx²: the error of fx, doubled by the square.
        Unary::Tan | Unary::Tanh => 2.0 * fx.abs() * value,
        // 1 / sqrt(1 - x²): the cancellation of 1 - x² near |x| = 1.
        Unary::Asin | Unary::Acos => (4.0 + x * x / (1.0 - x * x).abs()) * ULP * dg.abs(),
        Unary::Atan | Unary::Log => 3.0 * ULP * dg.abs(),
        Unary::Sinh | Unary::Cosh => exp_ulps * x.cosh(),
        Unary::Exp => value,
        // 0.5 / fx: fx's own error, and the division's.
        Unary::Sqrt => 6.0 * ULP * dg.abs(),
    };
    let derivative = if dg == 0.0 {
        0.0
    } else {
        derivative_absolute / dg.abs()
    };
    (value, derivative)
}

impl Scalar for Perturbed {
    fn constant(c: f64) -> Self {
        Perturbed {
            exact: Dual::constant(c),
            seed: mix(c.to_bits()),
        }
    }

    fn value(self) -> f64 {
        self.exact.value
    }

    fn unary(self, f: Unary) -> Self {
        let x = self.exact.value;
        let result = self.exact.unary(f);
        let dg = Dual::variables(DVec3::splat(x))[0].unary(f).gradient.x;
        let (value_error, derivative_error) = allowed_error(f, x, result.value, dg);
        let seed = mix(self.seed ^ (f as u64 + 16));
        Perturbed::moved(result, seed, value_error, derivative_error + ULP)
    }

    fn powi(self, n: u32) -> Self {
        let seed = mix(self.seed ^ (u64::from(n) << 8));
        Perturbed::rounded(self.exact.powi(n), seed, f64::from(n))
    }

    /// WGSL's `pow` is `exp2(e * log2(a))`: exp2's 3 + 2|x| ulps and log2's
    /// 2^-21 absolute error, scaled by |e|.
    fn powr(self, e: Self) -> Self {
        let seed = self.seed_with(e, 5);
        let result = self.exact.powr(e.exact);
        let exponent = e.exact.value * self.exact.value.abs().log2();
        let relative = (3.0 + 2.0 * exponent.abs()) * ULP + e.exact.value.abs() * 2f64.powi(-21);
        Perturbed::moved(result, seed, relative * result.value.abs(), relative + ULP)
    }

    fn atan2(self, x: Self) -> Self {
        let seed = self.seed_with(x, 6);
        let result = self.exact.atan2(x.exact);
        Perturbed::moved(result, seed, 4096.0 * ULP * result.value.abs(), 4.0 * ULP)
    }
}
