//! The operations every function is written with: what the tree stores,
//! and what each [`super::Scalar`] and the WGSL know how to compute.

/// Functions of one argument.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unary {
    Neg,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sinh,
    Cosh,
    Tanh,
    Exp,
    Log,
    Sqrt,
    Abs,
    Floor,
}

/// Operations of two arguments.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Binary {
    Add,
    Sub,
    Mul,
    Div,
    /// `a` where `a <= b`, else `b` (so the tie takes `a`'s gradient).
    Min,
    /// `a` where `a >= b`, else `b`.
    Max,
    /// `atan2(y, x)`, the angle of (x, y).
    Atan2,
    /// The real power `exp(b ln a)` for `a > 0`, and 0 for `a <= 0` (its
    /// limit for `b > 0`): defined everywhere, with no NaN.
    Pow,
}
