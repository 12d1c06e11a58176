//! [`Scalar`]: the numbers a function can be evaluated on, and the rules of
//! each operation for plain reals (`f64`, and `f32` to see what the GPU's
//! precision makes of a function).

use std::ops::{Add, Div, Mul, Sub};

use super::ops::Unary;

/// A number type [`super::Function::eval`] works on.
pub trait Scalar:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self>
{
    fn constant(c: f64) -> Self;
    /// The real value, for the comparisons of `min` and `max`.
    fn value(self) -> f64;
    fn unary(self, f: Unary) -> Self;
    /// `self^n`, `n >= 2`.
    fn powi(self, n: u32) -> Self;
    /// The real power: `exp(e ln self)` for `self > 0`, else 0.
    fn powr(self, e: Self) -> Self;
    /// `atan2(self, x)`: `self` is the y coordinate.
    fn atan2(self, x: Self) -> Self;
}

macro_rules! real_scalar {
    ($t:ty) => {
        impl Scalar for $t {
            fn constant(c: f64) -> Self {
                c as $t
            }

            fn value(self) -> f64 {
                f64::from(self)
            }

            fn unary(self, f: Unary) -> Self {
                let x = self;
                match f {
                    Unary::Neg => -x,
                    Unary::Sin => x.sin(),
                    Unary::Cos => x.cos(),
                    Unary::Tan => x.tan(),
                    Unary::Asin => x.asin(),
                    Unary::Acos => x.acos(),
                    Unary::Atan => x.atan(),
                    Unary::Sinh => x.sinh(),
                    Unary::Cosh => x.cosh(),
                    Unary::Tanh => x.tanh(),
                    Unary::Exp => x.exp(),
                    Unary::Log => x.ln(),
                    Unary::Sqrt => x.sqrt(),
                    Unary::Abs => x.abs(),
                    Unary::Floor => x.floor(),
                }
            }

            fn powi(self, n: u32) -> Self {
                self.powi(n as i32)
            }

            fn powr(self, e: Self) -> Self {
                if self > 0.0 { self.powf(e) } else { 0.0 }
            }

            fn atan2(self, x: Self) -> Self {
                <$t>::atan2(self, x)
            }
        }
    };
}

real_scalar!(f64);
real_scalar!(f32);

/// WGSL's `sign`: -1, 0 or +1 (Rust's `signum` gives +1 for +0): the
/// derivative of `abs`, and the sign of a box's normal in both renderers.
pub fn wgsl_sign<T: num_traits::Float>(x: T) -> T {
    if x > T::zero() {
        T::one()
    } else if x < T::zero() {
        -T::one()
    } else {
        T::zero()
    }
}
