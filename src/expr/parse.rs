//! The syntax of `f` (docs/scene-format.md, "Implicit surfaces"), read by
//! recursive descent, one function per level of precedence:
//!
//! ```text
//! sum     = product { ("+" | "-") product }
//! product = unary { ("*" | "/") unary }
//! unary   = "-" unary | "+" unary | power
//! power   = atom [ "^" unary ]            (right to left: 2^3^2 = 2^9)
//! atom    = number | "x" | "y" | "z" | "pi" | name "(" sum { "," sum } ")" | "(" sum ")"
//! ```
//!
//! As in mathematics `-x^2` is `-(x^2)`. Columns count characters from 1.

use super::FUNCTIONS;
use super::error::ExprError;
use super::ops::{Binary, Unary};
use super::tree::{Node, check_f32};

/// Deepest nesting of parentheses, calls and unary signs: bounds the
/// parser's recursion (and the shader's size) on hostile input.
const MAX_DEPTH: usize = 64;

#[derive(Debug, Clone, PartialEq)]
enum Token {
    Number(f64),
    Name(String),
    /// One of `+ - * / ^ ( ) ,`.
    Symbol(char),
    End,
}

/// Parses and folds a whole function.
pub(super) fn parse(source: &str) -> Result<Node, ExprError> {
    let tokens = tokenize(source)?;
    if tokens[0].0 == Token::End {
        return Err(error(
            1,
            "empty function: write an expression in x, y and z",
        ));
    }
    let mut parser = Parser {
        tokens,
        at: 0,
        depth: 0,
    };
    let node = parser.sum()?;
    match parser.peek() {
        Token::End => Ok(node),
        Token::Symbol(')') => Err(error(
            parser.column(),
            "unbalanced parenthesis: this `)` has no `(`",
        )),
        _ => Err(error(
            parser.column(),
            format!(
                "expected an operator (+ - * / ^) before {}",
                parser.describe()
            ),
        )),
    }
}

fn error(column: usize, message: impl Into<String>) -> ExprError {
    ExprError {
        column,
        message: message.into(),
    }
}

/// Splits the text into tokens, each with its column; the last is `End`.
fn tokenize(source: &str) -> Result<Vec<(Token, usize)>, ExprError> {
    let chars: Vec<char> = source.chars().collect();
    let mut tokens = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let column = i + 1;
        if c.is_whitespace() {
            i += 1;
        } else if c.is_ascii_digit() || c == '.' {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            // An exponent: `e` or `E`, an optional sign, digits.
            if i < chars.len() && (chars[i] == 'e' || chars[i] == 'E') {
                let mut j = i + 1;
                if j < chars.len() && (chars[j] == '+' || chars[j] == '-') {
                    j += 1;
                }
                if j < chars.len() && chars[j].is_ascii_digit() {
                    while j < chars.len() && chars[j].is_ascii_digit() {
                        j += 1;
                    }
                    i = j;
                }
            }
            let text: String = chars[start..i].iter().collect();
            let value: f64 = text
                .parse()
                .map_err(|_| error(column, format!("`{text}` is not a number")))?;
            check_f32(value, column)?;
            tokens.push((Token::Number(value), column));
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            tokens.push((Token::Name(chars[start..i].iter().collect()), column));
        } else if "+-*/^(),".contains(c) {
            tokens.push((Token::Symbol(c), column));
            i += 1;
        } else {
            return Err(error(column, format!("unexpected character `{c}`")));
        }
    }
    tokens.push((Token::End, chars.len() + 1));
    Ok(tokens)
}

struct Parser {
    tokens: Vec<(Token, usize)>,
    at: usize,
    depth: usize,
}

impl Parser {
    fn peek(&self) -> &Token {
        &self.tokens[self.at].0
    }

    fn column(&self) -> usize {
        self.tokens[self.at].1
    }

    /// Consumes the next token if it is the symbol `c`.
    fn eat(&mut self, c: char) -> bool {
        let found = *self.peek() == Token::Symbol(c);
        if found {
            self.at += 1;
        }
        found
    }

    /// The next token as a message shows it.
    fn describe(&self) -> String {
        match self.peek() {
            Token::Number(v) => format!("the number {v}"),
            Token::Name(name) => format!("`{name}`"),
            Token::Symbol(c) => format!("`{c}`"),
            Token::End => "the end".to_string(),
        }
    }

    /// One level deeper; an error past [`MAX_DEPTH`].
    fn descend(&mut self) -> Result<(), ExprError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(error(
                self.column(),
                format!("nested more than {MAX_DEPTH} levels deep"),
            ));
        }
        Ok(())
    }

    fn sum(&mut self) -> Result<Node, ExprError> {
        let mut left = self.product()?;
        loop {
            let column = self.column();
            let op = if self.eat('+') {
                Binary::Add
            } else if self.eat('-') {
                Binary::Sub
            } else {
                return Ok(left);
            };
            left = Node::binary(op, left, self.product()?, column)?;
        }
    }

    fn product(&mut self) -> Result<Node, ExprError> {
        let mut left = self.unary()?;
        loop {
            let column = self.column();
            let op = if self.eat('*') {
                Binary::Mul
            } else if self.eat('/') {
                Binary::Div
            } else {
                return Ok(left);
            };
            left = Node::binary(op, left, self.unary()?, column)?;
        }
    }

    fn unary(&mut self) -> Result<Node, ExprError> {
        self.descend()?;
        let column = self.column();
        let node = if self.eat('-') {
            Node::unary(Unary::Neg, self.unary()?, column)?
        } else if self.eat('+') {
            self.unary()?
        } else {
            self.power()?
        };
        self.depth -= 1;
        Ok(node)
    }

    fn power(&mut self) -> Result<Node, ExprError> {
        let base = self.atom()?;
        let column = self.column();
        if self.eat('^') {
            Node::power(base, self.unary()?, column)
        } else {
            Ok(base)
        }
    }

    fn atom(&mut self) -> Result<Node, ExprError> {
        let column = self.column();
        match self.peek().clone() {
            Token::Number(value) => {
                self.at += 1;
                Ok(Node::number(value, column))
            }
            Token::Name(name) => {
                self.at += 1;
                if *self.peek() == Token::Symbol('(') {
                    self.call(&name, column)
                } else {
                    name_value(&name, column)
                }
            }
            Token::Symbol('(') => {
                self.at += 1;
                let inner = self.sum()?;
                self.close(column)?;
                Ok(inner)
            }
            _ => Err(error(
                column,
                format!(
                    "expected a number, x, y, z, pi, a function or `(`, found {}",
                    { self.describe() }
                ),
            )),
        }
    }

    /// The `)` that closes the `(` at column `open`.
    fn close(&mut self, open: usize) -> Result<(), ExprError> {
        if self.eat(')') {
            return Ok(());
        }
        Err(match self.peek() {
            Token::End => error(
                open,
                "unbalanced parenthesis: this `(` is never closed".to_string(),
            ),
            _ => error(
                self.column(),
                format!(
                    "expected `)` (closing the `(` at column {open}) or an operator, found {}",
                    self.describe()
                ),
            ),
        })
    }

    /// `name(arguments)`, the `(` being next.
    fn call(&mut self, name: &str, column: usize) -> Result<Node, ExprError> {
        let open = self.column();
        self.at += 1;
        let Some(&(_, arity)) = FUNCTIONS.iter().find(|(known, _)| *known == name) else {
            let known: Vec<&str> = FUNCTIONS.iter().map(|(n, _)| *n).collect();
            return Err(error(
                column,
                format!(
                    "unknown function `{name}` (the functions are {})",
                    known.join(", ")
                ),
            ));
        };
        let mut args = Vec::new();
        if *self.peek() != Token::Symbol(')') {
            args.push(self.sum()?);
            while self.eat(',') {
                args.push(self.sum()?);
            }
        }
        self.close(open)?;
        if args.len() != arity {
            let plural = if arity == 1 { "" } else { "s" };
            return Err(error(
                column,
                format!(
                    "`{name}` takes {arity} argument{plural}, got {}",
                    args.len()
                ),
            ));
        }
        build_call(name, args, column)
    }
}

/// A name without arguments: a variable or `pi`.
fn name_value(name: &str, column: usize) -> Result<Node, ExprError> {
    match name {
        "x" => Ok(Node::var(0, column)),
        "y" => Ok(Node::var(1, column)),
        "z" => Ok(Node::var(2, column)),
        "pi" => Ok(Node::number(std::f64::consts::PI, column)),
        _ if FUNCTIONS.iter().any(|(known, _)| *known == name) => Err(error(
            column,
            format!("`{name}` is a function: write {name}(...)"),
        )),
        _ => Err(error(
            column,
            format!("unknown name `{name}` (the variables are x, y and z, the constant pi)"),
        )),
    }
}

/// A call with the right number of arguments, written with the tree's
/// operations.
fn build_call(name: &str, args: Vec<Node>, column: usize) -> Result<Node, ExprError> {
    let binary = |f, a: Node, b: Node| Node::binary(f, a, b, column);
    let floor = |a: Node| Node::unary(Unary::Floor, a, column);
    let mut args = args.into_iter();
    let mut next = || args.next().expect("the number of arguments is checked");
    if let Some(f) = unary_function(name) {
        return Node::unary(f, next(), column);
    }
    match name {
        "atan2" => binary(Binary::Atan2, next(), next()),
        "min" => binary(Binary::Min, next(), next()),
        "max" => binary(Binary::Max, next(), next()),
        "pow" => Node::power(next(), next(), column),
        // fract(a) = a - floor(a), in [0, 1) for negative a too.
        "fract" => {
            let a = next();
            binary(Binary::Sub, a.clone(), floor(a)?)
        }
        // mod(a, b) = a - b floor(a / b): the sign of b, as GLSL's mod.
        "mod" => {
            let (a, b) = (next(), next());
            let quotient = floor(binary(Binary::Div, a.clone(), b.clone())?)?;
            binary(Binary::Sub, a, binary(Binary::Mul, b, quotient)?)
        }
        // clamp(a, lo, hi) = min(max(a, lo), hi).
        "clamp" => {
            let (a, lo, hi) = (next(), next(), next());
            binary(Binary::Min, binary(Binary::Max, a, lo)?, hi)
        }
        // mix(a, b, t) = a (1 - t) + b t.
        "mix" => {
            let (a, b, t) = (next(), next(), next());
            let one_minus_t = binary(Binary::Sub, Node::number(1.0, column), t.clone())?;
            binary(
                Binary::Add,
                binary(Binary::Mul, a, one_minus_t)?,
                binary(Binary::Mul, b, t)?,
            )
        }
        _ => unreachable!("every name of FUNCTIONS is built: {name}"),
    }
}

/// The functions of one argument that are operations of the tree.
fn unary_function(name: &str) -> Option<Unary> {
    Some(match name {
        "sin" => Unary::Sin,
        "cos" => Unary::Cos,
        "tan" => Unary::Tan,
        "asin" => Unary::Asin,
        "acos" => Unary::Acos,
        "atan" => Unary::Atan,
        "sinh" => Unary::Sinh,
        "cosh" => Unary::Cosh,
        "tanh" => Unary::Tanh,
        "exp" => Unary::Exp,
        "log" => Unary::Log,
        "sqrt" => Unary::Sqrt,
        "abs" => Unary::Abs,
        "floor" => Unary::Floor,
        _ => return None,
    })
}
