//! Dual numbers `a + b ε` with `ε² = 0`, three infinitesimal parts at once:
//! forward-mode automatic differentiation. Evaluating `f` on
//! `x = (x, e_x)`, `y = (y, e_y)`, `z = (z, e_z)` carries, next to each
//! value, its exact gradient by the chain rule: no step size, no
//! cancellation, unlike a finite difference.

use std::ops::{Add, Div, Mul, Sub};

use glam::DVec3;

use super::ops::Unary;
use super::{Scalar, wgsl_sign};

/// A value and its gradient with respect to (x, y, z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dual {
    pub value: f64,
    pub gradient: DVec3,
}

impl Dual {
    /// The three variables at `p`, each with its own unit gradient.
    pub fn variables(p: DVec3) -> [Dual; 3] {
        [DVec3::X, DVec3::Y, DVec3::Z].map(|axis| Dual {
            value: p.dot(axis),
            gradient: axis,
        })
    }

    /// `g(self)` for a function `g` with value `gx` and derivative `dg` here.
    fn chain(self, gx: f64, dg: f64) -> Dual {
        Dual {
            value: gx,
            gradient: dg * self.gradient,
        }
    }
}

impl Add for Dual {
    type Output = Dual;
    fn add(self, b: Dual) -> Dual {
        Dual {
            value: self.value + b.value,
            gradient: self.gradient + b.gradient,
        }
    }
}

impl Sub for Dual {
    type Output = Dual;
    fn sub(self, b: Dual) -> Dual {
        Dual {
            value: self.value - b.value,
            gradient: self.gradient - b.gradient,
        }
    }
}

impl Mul for Dual {
    type Output = Dual;
    /// The product rule.
    fn mul(self, b: Dual) -> Dual {
        Dual {
            value: self.value * b.value,
            gradient: self.value * b.gradient + b.value * self.gradient,
        }
    }
}

impl Div for Dual {
    type Output = Dual;
    /// The quotient rule, as `q = a / b`, `q' = (a' - q b') / b`.
    fn div(self, b: Dual) -> Dual {
        let q = self.value / b.value;
        Dual {
            value: q,
            gradient: (self.gradient - q * b.gradient) / b.value,
        }
    }
}

/// The derivative of `f` at `x`, where `f(x) = fx`: the table the WGSL
/// (`src/expr/wgsl.rs`) writes out too.
pub fn derivative(f: Unary, x: f64, fx: f64) -> f64 {
    match f {
        Unary::Neg => -1.0,
        Unary::Sin => x.cos(),
        Unary::Cos => -x.sin(),
        Unary::Tan => 1.0 + fx * fx,
        Unary::Asin => 1.0 / (1.0 - x * x).sqrt(),
        Unary::Acos => -1.0 / (1.0 - x * x).sqrt(),
        Unary::Atan => 1.0 / (1.0 + x * x),
        Unary::Sinh => x.cosh(),
        Unary::Cosh => x.sinh(),
        Unary::Tanh => 1.0 - fx * fx,
        Unary::Exp => fx,
        Unary::Log => 1.0 / x,
        Unary::Sqrt => 0.5 / fx,
        // 0 at 0, as WGSL's sign().
        Unary::Abs => wgsl_sign(x),
        Unary::Floor => 0.0,
    }
}

impl Scalar for Dual {
    fn constant(c: f64) -> Self {
        Dual {
            value: c,
            gradient: DVec3::ZERO,
        }
    }

    fn value(self) -> f64 {
        self.value
    }

    fn unary(self, f: Unary) -> Self {
        let fx = self.value.unary(f);
        self.chain(fx, derivative(f, self.value, fx))
    }

    /// `(a^n)' = n a^(n-1) a'`.
    fn powi(self, n: u32) -> Self {
        let below = self.value.powi(n as i32 - 1);
        self.chain(below * self.value, f64::from(n) * below)
    }

    /// `(a^b)' = a^b (b' ln a + b a' / a)` where `a > 0`; 0 elsewhere, where
    /// the real power is the constant 0.
    fn powr(self, e: Self) -> Self {
        if self.value > 0.0 {
            let v = self.value.powf(e.value);
            Dual {
                value: v,
                gradient: v * (e.gradient * self.value.ln() + e.value * self.gradient / self.value),
            }
        } else {
            Dual::constant(0.0)
        }
    }

    /// `atan2(y, x)' = (x y' - y x') / (x² + y²)`.
    fn atan2(self, x: Self) -> Self {
        let y = self;
        Dual {
            value: y.value.atan2(x.value),
            gradient: (x.value * y.gradient - y.value * x.gradient)
                / (x.value * x.value + y.value * y.value),
        }
    }
}
