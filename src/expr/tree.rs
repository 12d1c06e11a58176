//! The parsed function as a tree of a few operations: everything the syntax
//! offers is built from them (`fract(a)` is `a - floor(a)`, `mix(a, b, t)` is
//! `a (1 - t) + b t`, ...), so that the evaluation, the dual numbers and the
//! WGSL each write every rule once.
//!
//! The constructors fold constant parts into numbers as the parser builds the
//! tree, and reject a constant that an f32 cannot hold (`exp(1000)`,
//! `sqrt(-1)`, `1/0`) at its column: the GPU would meet it as inf or NaN.

use super::Scalar;
use super::error::ExprError;
use super::ops::{Binary, Unary};

#[derive(Debug, Clone, PartialEq)]
pub enum Op {
    Number(f64),
    /// x, y or z (0, 1, 2).
    Var(usize),
    Unary(Unary, Box<Node>),
    Binary(Binary, Box<Node>, Box<Node>),
    /// `a^n` for a whole `n >= 2`, by repeated multiplication: defined for
    /// negative `a` too, unlike the real power.
    PowI(Box<Node>, u32),
}

/// One operation and the 1-based column of the text it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Node {
    pub op: Op,
    pub column: usize,
}

/// The largest whole exponent taken as an integer power (more would only
/// overflow; larger exponents are real powers).
const MAX_INTEGER_EXPONENT: f64 = (1u32 << 30) as f64;

impl Node {
    pub fn number(value: f64, column: usize) -> Node {
        Node {
            op: Op::Number(value),
            column,
        }
    }

    pub fn var(axis: usize, column: usize) -> Node {
        Node {
            op: Op::Var(axis),
            column,
        }
    }

    pub fn unary(f: Unary, a: Node, column: usize) -> Result<Node, ExprError> {
        fold(Node {
            op: Op::Unary(f, Box::new(a)),
            column,
        })
    }

    pub fn binary(f: Binary, a: Node, b: Node, column: usize) -> Result<Node, ExprError> {
        fold(Node {
            op: Op::Binary(f, Box::new(a), Box::new(b)),
            column,
        })
    }

    /// `a^b`: an integer power when `b` is a constant whole number (negative
    /// ones as `1 / a^-b`, `a^0 = 1`), the real power otherwise.
    pub fn power(a: Node, b: Node, column: usize) -> Result<Node, ExprError> {
        match b.op {
            Op::Number(n) if n.fract() == 0.0 && n.abs() <= MAX_INTEGER_EXPONENT => {
                let positive = match n.abs() as u32 {
                    0 => return Ok(Node::number(1.0, column)),
                    1 => a,
                    n => fold(Node {
                        op: Op::PowI(Box::new(a), n),
                        column,
                    })?,
                };
                if n > 0.0 {
                    Ok(positive)
                } else {
                    Node::binary(Binary::Div, Node::number(1.0, column), positive, column)
                }
            }
            _ => Node::binary(Binary::Pow, a, b, column),
        }
    }

    /// The value of the tree at `p`, on any scalar type.
    pub fn eval<T: Scalar>(&self, p: &[T; 3]) -> T {
        match &self.op {
            Op::Number(c) => T::constant(*c),
            Op::Var(axis) => p[*axis],
            Op::Unary(f, a) => a.eval(p).unary(*f),
            Op::Binary(f, a, b) => {
                let (a, b) = (a.eval(p), b.eval(p));
                match f {
                    Binary::Add => a + b,
                    Binary::Sub => a - b,
                    Binary::Mul => a * b,
                    Binary::Div => a / b,
                    Binary::Min => {
                        if a.value() <= b.value() {
                            a
                        } else {
                            b
                        }
                    }
                    Binary::Max => {
                        if a.value() >= b.value() {
                            a
                        } else {
                            b
                        }
                    }
                    Binary::Atan2 => a.atan2(b),
                    Binary::Pow => a.powr(b),
                }
            }
            Op::PowI(a, n) => a.eval(p).powi(*n),
        }
    }

    fn is_constant(&self) -> bool {
        matches!(self.op, Op::Number(_))
    }
}

/// Replaces `node` by its value when all its operands are numbers; the value
/// must be finite and within f32 range.
fn fold(node: Node) -> Result<Node, ExprError> {
    let constant = match &node.op {
        Op::Number(_) | Op::Var(_) => false,
        Op::Unary(_, a) | Op::PowI(a, _) => a.is_constant(),
        Op::Binary(_, a, b) => a.is_constant() && b.is_constant(),
    };
    if !constant {
        return Ok(node);
    }
    let value: f64 = node.eval(&[0.0; 3]);
    check_f32(value, node.column)?;
    Ok(Node::number(value, node.column))
}

/// A number the GPU can hold: finite, and no larger than the largest f32.
pub fn check_f32(value: f64, column: usize) -> Result<(), ExprError> {
    if value.is_finite() && value.abs() <= f64::from(f32::MAX) {
        Ok(())
    } else {
        Err(ExprError {
            column,
            message: format!(
                "this constant part is {value}, which an f32 on the GPU cannot hold \
                 (at most 3.4e38 and finite)"
            ),
        })
    }
}
