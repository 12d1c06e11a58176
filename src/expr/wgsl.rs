//! The function as WGSL: one `let` per operation of the tree, so the shader
//! computes what [`super::Function::eval`] computes, in the same order, in
//! f32. The dual-number twin keeps a value and its gradient in a
//! `vec4<f32>` (`.x` the value, `.yzw` the gradient) and writes out the rules
//! of `src/expr/dual.rs`.

use std::fmt::Write;

use super::ops::{Binary, Unary};
use super::tree::{Node, Op};

/// `fn NAME(p: vec3<f32>) -> f32` and `fn NAME_dual(p: vec3<f32>) -> vec4<f32>`.
pub(super) fn function(root: &Node, name: &str, source: &str) -> String {
    let source: Vec<&str> = source.split_whitespace().collect();
    let mut out = format!("// f(x, y, z) = {}\n", source.join(" "));

    let mut value = Emitter::default();
    let result = value.value(root);
    write_fn(&mut out, name, "f32", &value.lines, &result);

    let mut dual = Emitter {
        lines: variables_as_duals(),
        count: 0,
    };
    let result = dual.dual(root);
    write_fn(
        &mut out,
        &format!("{name}_dual"),
        "vec4<f32>",
        &dual.lines,
        &result,
    );
    out
}

/// `let dx = vec4<f32>(p.x, 1, 0, 0);` and so on: each variable with its
/// unit gradient.
fn variables_as_duals() -> Vec<String> {
    ["x", "y", "z"]
        .iter()
        .enumerate()
        .map(|(i, axis)| {
            let mut unit = ["0.0f"; 3];
            unit[i] = "1.0f";
            format!("let d{axis} = vec4<f32>(p.{axis}, {});", unit.join(", "))
        })
        .collect()
}

fn write_fn(out: &mut String, name: &str, ty: &str, lines: &[String], result: &str) {
    writeln!(out, "fn {name}(p: vec3<f32>) -> {ty} {{").unwrap();
    for line in lines {
        writeln!(out, "    {line}").unwrap();
    }
    writeln!(out, "    return {result};\n}}").unwrap();
}

/// A number as an f32 literal (subnormals flushed to 0, as GPUs may do).
fn literal(c: f64) -> String {
    let f = c as f32;
    if f.abs() < f32::MIN_POSITIVE {
        "0.0f".to_string()
    } else if f < 0.0 {
        format!("(-{:?}f)", -f)
    } else {
        format!("{f:?}f")
    }
}

/// The WGSL of `f(x)` for a real `x`.
fn apply(f: Unary, x: &str) -> String {
    let name = match f {
        Unary::Neg => return format!("-{x}"),
        Unary::Sin => "sin",
        Unary::Cos => "cos",
        Unary::Tan => "tan",
        Unary::Asin => "asin",
        Unary::Acos => "acos",
        Unary::Atan => "atan",
        Unary::Sinh => "sinh",
        Unary::Cosh => "cosh",
        Unary::Tanh => "tanh",
        Unary::Exp => "exp",
        Unary::Log => "log",
        Unary::Sqrt => "sqrt",
        Unary::Abs => "abs",
        Unary::Floor => "floor",
    };
    format!("{name}({x})")
}

/// The WGSL of `f'(x)` where `f(x) = fx`: the table of `dual::derivative`.
fn derivative(f: Unary, x: &str, fx: &str) -> String {
    match f {
        Unary::Neg => "-1.0f".to_string(),
        Unary::Sin => format!("cos({x})"),
        Unary::Cos => format!("-sin({x})"),
        Unary::Tan => format!("1.0f + {fx} * {fx}"),
        Unary::Asin => format!("1.0f / sqrt(1.0f - {x} * {x})"),
        Unary::Acos => format!("-1.0f / sqrt(1.0f - {x} * {x})"),
        Unary::Atan => format!("1.0f / (1.0f + {x} * {x})"),
        Unary::Sinh => format!("cosh({x})"),
        Unary::Cosh => format!("sinh({x})"),
        Unary::Tanh => format!("1.0f - {fx} * {fx}"),
        Unary::Exp => fx.to_string(),
        Unary::Log => format!("1.0f / {x}"),
        Unary::Sqrt => format!("0.5f / {fx}"),
        Unary::Abs => format!("sign({x})"),
        Unary::Floor => "0.0f".to_string(),
    }
}

/// Statements written so far and a counter for fresh names.
#[derive(Default)]
struct Emitter {
    lines: Vec<String>,
    count: usize,
}

impl Emitter {
    /// `let vN = expr;`, returning `vN`.
    fn let_(&mut self, expr: String) -> String {
        let name = format!("v{}", self.count);
        self.count += 1;
        self.lines.push(format!("let {name} = {expr};"));
        name
    }

    /// `var vN = expr;`: a value naga does not evaluate when it compiles.
    fn var(&mut self, expr: String) -> String {
        let name = format!("v{}", self.count);
        self.count += 1;
        self.lines.push(format!("var {name} = {expr};"));
        name
    }

    /// `a^n`, `n >= 1`, by squaring and multiplying.
    fn powi(&mut self, a: &str, mut n: u32) -> String {
        let mut result: Option<String> = None;
        let mut base = a.to_string();
        loop {
            if n & 1 == 1 {
                result = Some(match result {
                    None => base.clone(),
                    Some(r) => self.let_(format!("{r} * {base}")),
                });
            }
            n >>= 1;
            if n == 0 {
                return result.expect("n >= 1");
            }
            base = self.let_(format!("{base} * {base}"));
        }
    }

    /// The value of `node` (an f32 expression or name).
    fn value(&mut self, node: &Node) -> String {
        match &node.op {
            Op::Number(c) => literal(*c),
            Op::Var(axis) => format!("p.{}", ["x", "y", "z"][*axis]),
            Op::Unary(f, a) => {
                let a = self.value(a);
                self.let_(apply(*f, &a))
            }
            Op::Binary(f, a, b) => {
                let (a, b) = (self.value(a), self.value(b));
                self.let_(match f {
                    Binary::Add => format!("{a} + {b}"),
                    Binary::Sub => format!("{a} - {b}"),
                    Binary::Mul => format!("{a} * {b}"),
                    Binary::Div => format!("{a} / {b}"),
                    Binary::Min => format!("select({b}, {a}, {a} <= {b})"),
                    Binary::Max => format!("select({b}, {a}, {a} >= {b})"),
                    Binary::Atan2 => format!("atan2({a}, {b})"),
                    Binary::Pow => format!("select(0.0f, pow({a}, {b}), {a} > 0.0f)"),
                })
            }
            Op::PowI(a, n) => {
                let a = self.value(a);
                self.powi(&a, *n)
            }
        }
    }

    /// The dual number of `node` (a `vec4<f32>` expression or name).
    fn dual(&mut self, node: &Node) -> String {
        match &node.op {
            // A variable, not a constant expression: naga evaluates those
            // when it compiles and refuses a result out of f32's range, such
            // as log(0) or (-1e38)^2 in the rules below, even where a select
            // drops it (found by the fuzzer, docs/reliability.md).
            Op::Number(c) => self.var(format!("vec4<f32>({}, 0.0f, 0.0f, 0.0f)", literal(*c))),
            Op::Var(axis) => format!("d{}", ["x", "y", "z"][*axis]),
            Op::Unary(Unary::Neg, a) => {
                let a = self.dual(a);
                self.let_(format!("-{a}"))
            }
            Op::Unary(f, a) => {
                let a = self.dual(a);
                let x = format!("{a}.x");
                let fx = self.let_(apply(*f, &x));
                let d = derivative(*f, &x, &fx);
                self.let_(format!("vec4<f32>({fx}, ({d}) * {a}.yzw)"))
            }
            Op::Binary(f, a, b) => {
                let (a, b) = (self.dual(a), self.dual(b));
                let expr = match f {
                    Binary::Add => format!("{a} + {b}"),
                    Binary::Sub => format!("{a} - {b}"),
                    Binary::Mul => {
                        format!("vec4<f32>({a}.x * {b}.x, {a}.x * {b}.yzw + {b}.x * {a}.yzw)")
                    }
                    Binary::Div => {
                        let q = self.let_(format!("{a}.x / {b}.x"));
                        format!("vec4<f32>({q}, ({a}.yzw - {q} * {b}.yzw) / {b}.x)")
                    }
                    Binary::Min => format!("select({b}, {a}, {a}.x <= {b}.x)"),
                    Binary::Max => format!("select({b}, {a}, {a}.x >= {b}.x)"),
                    // a is y, b is x.
                    Binary::Atan2 => format!(
                        "vec4<f32>(atan2({a}.x, {b}.x), ({b}.x * {a}.yzw - {a}.x * {b}.yzw) \
                         / ({b}.x * {b}.x + {a}.x * {a}.x))"
                    ),
                    Binary::Pow => {
                        let v = self.let_(format!("select(0.0f, pow({a}.x, {b}.x), {a}.x > 0.0f)"));
                        format!(
                            "vec4<f32>({v}, select(vec3<f32>(0.0f), \
                             {v} * ({b}.yzw * log({a}.x) + {b}.x * {a}.yzw / {a}.x), {a}.x > 0.0f))"
                        )
                    }
                };
                self.let_(expr)
            }
            Op::PowI(a, n) => {
                let a = self.dual(a);
                let below = self.powi(&format!("{a}.x"), n - 1);
                self.let_(format!(
                    "vec4<f32>({below} * {a}.x, {} * {below} * {a}.yzw)",
                    literal(f64::from(*n))
                ))
            }
        }
    }
}
