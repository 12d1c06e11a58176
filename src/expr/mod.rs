//! User functions `f(x, y, z)` of implicit surfaces (docs/rendering-model.md,
//! "Implicit surfaces"): one parser that feeds both renderers.
//!
//! - [`Function::parse`] reads the syntax of docs/scene-format.md
//!   (`"x^2 + y^2 + z^2 - 1"`) with a small recursive-descent parser whose
//!   errors name the column ([`ExprError`]);
//! - [`Function::eval`] evaluates it on any [`Scalar`]: `f64` for the
//!   reference's values, [`Dual`] numbers for the exact gradient (forward-mode
//!   automatic differentiation, the lecture's normal `grad f`), `f32` to see
//!   what single precision makes of it;
//! - [`Function::to_wgsl`] writes the same function, and its dual-number
//!   twin for the gradient, as WGSL for the shader.
//!
//! Plain data and arithmetic: no scene, GPU or UI.

mod dual;
mod error;
mod ops;
mod parse;
mod scalar;
mod tree;
mod wgsl;

use glam::DVec3;

pub use dual::Dual;
pub use error::ExprError;
pub use ops::{Binary, Unary};
pub use scalar::{Scalar, wgsl_sign};
use tree::Node;

/// The names `f` may call, with their number of arguments, as
/// docs/scene-format.md lists them.
pub const FUNCTIONS: [(&str, usize); 22] = [
    ("sin", 1),
    ("cos", 1),
    ("tan", 1),
    ("asin", 1),
    ("acos", 1),
    ("atan", 1),
    ("atan2", 2),
    ("sinh", 1),
    ("cosh", 1),
    ("tanh", 1),
    ("exp", 1),
    ("log", 1),
    ("sqrt", 1),
    ("abs", 1),
    ("min", 2),
    ("max", 2),
    ("pow", 2),
    ("floor", 1),
    ("fract", 1),
    ("mod", 2),
    ("clamp", 3),
    ("mix", 3),
];

/// A parsed, checked function of x, y and z. Constant parts are already
/// folded to numbers, each of which an f32 can hold, so the WGSL it compiles
/// to never holds an infinity or NaN literal.
#[derive(Debug, Clone, PartialEq)]
pub struct Function {
    source: String,
    root: Node,
}

impl Function {
    /// Parses `source`; the error names the 1-based column (in characters)
    /// of what is wrong.
    pub fn parse(source: &str) -> Result<Function, ExprError> {
        Ok(Function {
            source: source.to_string(),
            root: parse::parse(source)?,
        })
    }

    /// The text it was parsed from.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// `f(p)` on any scalar type: the variables are `p[0]`, `p[1]`, `p[2]`.
    pub fn eval<T: Scalar>(&self, p: [T; 3]) -> T {
        self.root.eval(&p)
    }

    /// `f(p)` in f64, for the reference's root finding.
    pub fn value(&self, p: DVec3) -> f64 {
        self.eval(p.to_array())
    }

    /// `f(p)` and its exact gradient, by dual numbers.
    pub fn value_and_gradient(&self, p: DVec3) -> (f64, DVec3) {
        let d = self.eval(Dual::variables(p));
        (d.value, d.gradient)
    }

    /// WGSL for `fn NAME(p: vec3<f32>) -> f32` (the value) and
    /// `fn NAME_dual(p: vec3<f32>) -> vec4<f32>` (value in `.x`, gradient in
    /// `.yzw`), written with the same rules as [`Function::eval`].
    pub fn to_wgsl(&self, name: &str) -> String {
        wgsl::function(&self.root, name, &self.source)
    }
}

#[cfg(test)]
mod tests;
