//! Small source rewrites for WebGL GLSL that naga's GLSL front end does not
//! take (docs/sandbox.md, "The GLSL rewrite", its paragraph "Front-end
//! gaps"). Each is local to one line:
//!
//! - `const` in a parameter list (`float f(const in float x)`): blanked;
//! - a matrix built from one argument (`mat2(vec4)`, which naga rejects):
//!   `mat2(` becomes `rsb_mat2(`, overloads the prelude adds;
//! - a prototype with unnamed parameters (`float f(float);`, which naga
//!   ignores): each gets a name, `float f(float rsb_p0);`;
//! - a name that is a keyword of GLSL 4.50 but not of WebGL GLSL
//!   (`float sample = 0.0;`): `rsb_sample`;
//! - WebGL's texture functions (`texture2D(`, `texture2DLod(`,
//!   `textureCube(`, `texture3D(`, ...): GLSL 4.50's (`texture  (`,
//!   `textureLod  (`), padded with spaces;
//! - a float literal too big for a float (`1e39`, which WebGL reads as
//!   infinity and naga rejects), or a positive one divided by a zero
//!   literal (`1.0 / 0.0`): the largest float, `3.4028235e38`;
//! - `dot(`, which naga lacks for two floats: `rsb_dot(`, overloads the
//!   prelude adds for floats and float vectors;
//! - `matrixCompMult(`, which naga lacks: `rsb_matrixCompMult(`, overloads
//!   the prelude adds for square matrices;
//! - a `sampler2D` parameter, which naga's Vulkan GLSL has no type for:
//!   a `texture2D` parameter, each use of it in the function's body wrapped
//!   as `sampler2D(NAME, rsb_linear_sampler)` with the prelude's sampler
//!   (`samplerCube` and `sampler3D` likewise, as `textureCube`, `texture3D`);
//! - a precision qualifier (`highp vec2 p`), which naga rejects in a
//!   parameter list: blanked everywhere, it means nothing in Vulkan GLSL;
//! - a local `const int N = 4;` used as an array size (`float a[N];`),
//!   which naga does not know as a constant: `[N]` becomes `[4]`; also a
//!   constant computed from numbers and such constants with `+ - * /`
//!   and brackets (`const int L = (2*C+1)*(2*C+1);`), written as its value.
//!
//! - an array declared without its size and sized by its initializer
//!   (`float w[] = float[](0.2, 0.5, 0.3);`, `const int[] f = int[](...)`),
//!   which naga takes for an array of run-time size and refuses as a
//!   global or a constant: the count of the constructor's arguments is
//!   written into both empty brackets, `w[3] = float[3](...)`.
//!
//! - a declaration of several names, one of them an array before the
//!   last (`vec4 B[4], P[3];`, `float a[2], x;`), where naga gives the
//!   names after it the array's type: one declaration per name,
//!   `vec4 B[4]; vec4 P[3];` (the comma becomes `;` and the type is
//!   written again after it).
//!
//! - `mix(x, y, a)` in the declaration of a global `const`, which naga
//!   cannot evaluate as a constant: its definition in GLSL,
//!   `((x) * (1.0 - (a)) + (y) * (a))`; also in the body of a `#define`
//!   that such a declaration uses (`const vec3 c = HSV2RGB(...);`), or
//!   that a macro it uses does.
//!
//! The rewrites of names and calls (not `dot`) also apply inside the body
//! of a `#define`, and `const in` there (`#define _in(T) const in T`, for
//! parameter lists) loses its `const`, so that a macro expands to what
//! naga takes. `dot(` in the declaration of a global `const` (a constant expression, where naga
//! takes no call of a function), is left as it is.
//!
//! Blanking keeps every offset. An insertion moves the rest of its line to
//! the right, never to another line, and [`Bridged::original_column`] moves
//! an error's column back, so errors show the user's line and column.

use crate::shader_params::scan::{self, Kind, Scan, Token};

/// The overloads behind `rsb_mat2(...)`, for the prelude.
pub const MAT2_OVERLOADS: &str = "\
// mat2(x) with one argument, as WebGL GLSL allows it (docs/sandbox.md).
mat2 rsb_mat2(vec4 v) { return mat2(v.xy, v.zw); }
mat2 rsb_mat2(float s) { return mat2(s); }
mat2 rsb_mat2(mat2 m) { return m; }
mat2 rsb_mat2(mat3 m) { return mat2(m); }
mat2 rsb_mat2(mat4 m) { return mat2(m); }
";

/// The overloads behind `rsb_dot(...)`, for the prelude.
pub const DOT_OVERLOADS: &str = "\
// dot(x, y) of two floats too, as WebGL GLSL has it (docs/sandbox.md).
float rsb_dot(float a, float b) { return a * b; }
float rsb_dot(vec2 a, vec2 b) { return dot(a, b); }
float rsb_dot(vec3 a, vec3 b) { return dot(a, b); }
float rsb_dot(vec4 a, vec4 b) { return dot(a, b); }
";

/// The overloads behind `rsb_matrixCompMult(...)`, for the prelude.
pub const COMP_MULT_OVERLOADS: &str = "\
// matrixCompMult(a, b): the product of each component (docs/sandbox.md).
mat2 rsb_matrixCompMult(mat2 a, mat2 b) { return mat2(a[0] * b[0], a[1] * b[1]); }
mat3 rsb_matrixCompMult(mat3 a, mat3 b) { return mat3(a[0] * b[0], a[1] * b[1], a[2] * b[2]); }
mat4 rsb_matrixCompMult(mat4 a, mat4 b) {
    return mat4(a[0] * b[0], a[1] * b[1], a[2] * b[2], a[3] * b[3]);
}
";

/// The largest finite float, written for a literal WebGL reads as infinity.
const LARGEST_FLOAT: &str = "3.4028235e38";

/// The user's text after the rewrites.
pub struct Bridged {
    pub text: String,
    /// The overloads that renamed calls need in the prelude
    /// ([`MAT2_OVERLOADS`], [`DOT_OVERLOADS`], [`COMP_MULT_OVERLOADS`]),
    /// each once.
    pub overloads: Vec<&'static str>,
    /// (offset in the original text, inserted text), in order.
    insertions: Vec<(usize, String)>,
}

/// Keywords of GLSL 4.50 (what naga reads) that WebGL GLSL shaders use as
/// names (`sampler` is a type of Vulkan GLSL, where a `sampler2D` is made of
/// a texture and a sampler).
const NEW_KEYWORDS: [&str; 21] = [
    "sample",
    "sampler",
    "subroutine",
    "coherent",
    "volatile",
    "restrict",
    "readonly",
    "writeonly",
    "smooth",
    "flat",
    "noperspective",
    "centroid",
    "buffer",
    "shared",
    "patch",
    "filter",
    "input",
    "output",
    "active",
    "common",
    "partition",
];

/// WebGL GLSL's texture functions and the GLSL 4.50 function each is.
const TEXTURE_FUNCTIONS: [(&str, &str); 12] = [
    ("texture2D", "texture"),
    ("textureCube", "texture"),
    ("textureCubeLod", "textureLod"),
    ("textureCubeLodEXT", "textureLod"),
    ("texture3D", "texture"),
    ("texture3DLod", "textureLod"),
    ("texture2DLod", "textureLod"),
    ("texture2DLodEXT", "textureLod"),
    ("texture2DProj", "textureProj"),
    ("texture2DProjLod", "textureProjLod"),
    ("texture2DGradEXT", "textureGrad"),
    ("texture2DProjLodEXT", "textureProjLod"),
];

/// GLSL ES's precision qualifiers.
const PRECISION: [&str; 3] = ["lowp", "mediump", "highp"];

/// Qualifiers that may come before a parameter's type.
const PARAMETER_QUALIFIERS: [&str; 8] = [
    "const", "in", "out", "inout", "lowp", "mediump", "highp", "precise",
];

/// Applies the rewrites to `text`, the user's text already blanked by the
/// GLSL rewrite (same offsets as `scan.text`).
pub fn bridge(scan: &Scan, mut text: String) -> Bridged {
    let tokens = &scan.tokens;
    let mut insertions: Vec<(usize, String)> = Vec::new();
    // First, so that a parameter whose name is renamed too (`sampler2D
    // sampler`) is wrapped around its new name: insertions at one offset
    // keep the order they are made in.
    // Before the others: a bracket opening a condition comes before what
    // they insert at its first token.
    for_conditions(tokens, &mut insertions);
    sampler_parameters(tokens, &mut text, &mut insertions);
    let mut overloads = Vec::new();
    let in_constants = macros_in_constants(tokens);
    let (mut braces, mut parens) = (0i32, 0i32);
    // In the declaration of a global `const` (a constant expression).
    let mut global_const = false;
    for (i, t) in tokens.iter().enumerate() {
        if text[t.start..t.end()].trim().is_empty() {
            // Blanked by the GLSL rewrite (a `uniform` declaration).
            continue;
        }
        if braces == 0 && parens == 0 && (t.is("const") || t.is(";")) {
            global_const = t.is("const");
        }
        match t.text {
            "{" => braces += 1,
            "}" => braces -= 1,
            "(" => parens += 1,
            ")" => parens -= 1,
            "const" if braces == 0 && parens > 0 => scan::blank(&mut text, t.start..t.end()),
            _ if t.kind == Kind::Directive => {
                let rewrites = &mut (&mut insertions, &mut overloads);
                define_body_rewrites(t, &mut text, rewrites, &in_constants);
            }
            "dot" if global_const => {}
            "mix" if global_const => mix_in_constant(tokens, i, &mut text, &mut insertions),
            _ => {
                let used = rewrite_token(tokens, i, &mut text, &mut insertions);
                note_overloads(&mut overloads, used);
            }
        }
        if braces == 0 && parens == 0 && t.kind == Kind::Ident {
            name_prototype_parameters(tokens, i, &mut insertions);
        }
    }
    const_array_sizes(tokens, &mut text, &mut insertions);
    unsized_array_sizes(tokens, &mut insertions);
    split_array_declarations(tokens, &mut text, &mut insertions);
    insertions.sort_by_key(|(offset, _)| *offset);
    for (offset, inserted) in insertions.iter().rev() {
        text.insert_str(*offset, inserted);
    }
    Bridged {
        text,
        overloads,
        insertions,
    }
}

/// The name a declared variable `name` has after the rewrites: a keyword of
/// GLSL 4.50, or `texture` (never followed by `(` where it is declared),
/// gets the prefix `rsb_`, as at every use.
pub(crate) fn declared_name(name: &str) -> std::borrow::Cow<'_, str> {
    if name == "texture" || NEW_KEYWORDS.contains(&name) {
        format!("rsb_{name}").into()
    } else {
        name.into()
    }
}

/// Adds `used` to `overloads` unless it is there.
fn note_overloads(overloads: &mut Vec<&'static str>, used: Option<&'static str>) {
    if let Some(used) = used
        && !overloads.contains(&used)
    {
        overloads.push(used);
    }
}

/// The rewrites of one token (other than brackets) at `i`; returns the
/// overloads the prelude needs for a renamed call.
fn rewrite_token(
    tokens: &[Token],
    i: usize,
    text: &mut String,
    insertions: &mut Vec<(usize, String)>,
) -> Option<&'static str> {
    let t = &tokens[i];
    match t.text {
        word if t.kind == Kind::Ident && PRECISION.contains(&word) => {
            scan::blank(text, t.start..t.end());
        }
        word if t.kind == Kind::Ident && NEW_KEYWORDS.contains(&word) => {
            insertions.push((t.start, "rsb_".to_string()));
        }
        // A texture named `texture` (`uniform sampler2D texture;`), not
        // the function.
        "texture" if !tokens.get(i + 1).is_some_and(|n| n.is("(")) => {
            insertions.push((t.start, "rsb_".to_string()));
        }
        "mat2" if single_argument(tokens, i + 1) => {
            insertions.push((t.start, "rsb_".to_string()));
            return Some(MAT2_OVERLOADS);
        }
        name @ ("dot" | "matrixCompMult") if tokens.get(i + 1).is_some_and(|n| n.is("(")) => {
            insertions.push((t.start, "rsb_".to_string()));
            return Some(if name == "dot" {
                DOT_OVERLOADS
            } else {
                COMP_MULT_OVERLOADS
            });
        }
        // `1.0 / 0.0`, infinity in WebGL, which naga's constant evaluator
        // refuses: the largest float.
        number
            if t.kind == Kind::Number
                && tokens.get(i + 1).is_some_and(|n| n.is("/"))
                && tokens.get(i + 2).is_some_and(is_zero_literal)
                && float_value(number).is_some_and(|v| v > 0.0) =>
        {
            overwrite(text, t.start..tokens[i + 2].end(), "");
            insertions.push((t.start, LARGEST_FLOAT.to_string()));
        }
        number if t.kind == Kind::Number && is_infinite_float(number) => {
            overwrite(text, t.start..t.end(), "");
            insertions.push((t.start, LARGEST_FLOAT.to_string()));
        }
        word if tokens.get(i + 1).is_some_and(|n| n.is("(")) => {
            if let Some((_, new)) = TEXTURE_FUNCTIONS.iter().find(|(old, _)| *old == word) {
                overwrite(text, t.start..t.end(), new);
            }
        }
        _ => {}
    }
    None
}

/// The name and body of the `#define` directive token `t`: the macro's
/// tokens, from `define` on, at their offsets in the whole text.
fn define_tokens<'a>(t: &Token<'a>) -> Option<Vec<Token<'a>>> {
    let body = t.text.strip_prefix('#')?;
    let inner = Scan::new(body);
    if !inner.tokens.first().is_some_and(|d| d.is("define")) {
        return None;
    }
    Some(
        inner
            .tokens
            .iter()
            .map(|k| Token {
                start: t.start + 1 + k.start,
                ..*k
            })
            .collect(),
    )
}

/// The names of the macros that a global `const`'s declaration uses, or
/// that such a macro's body uses (their bodies are constant expressions).
fn macros_in_constants<'a>(tokens: &[Token<'a>]) -> Vec<&'a str> {
    let mut used: Vec<&str> = Vec::new();
    let mut macros: Vec<(&str, Vec<&str>)> = Vec::new();
    let (mut depth, mut global_const) = (0i32, false);
    for t in tokens {
        match t.text {
            "{" | "(" => depth += 1,
            "}" | ")" => depth -= 1,
            _ if depth == 0 && (t.is("const") || t.is(";")) => global_const = t.is("const"),
            _ if t.kind == Kind::Directive => {
                let Some(body) = t.text.strip_prefix('#') else {
                    continue;
                };
                let words: Vec<&str> = Scan::new(body)
                    .tokens
                    .iter()
                    .filter(|k| k.kind == Kind::Ident)
                    .map(|k| k.text)
                    .collect();
                if let ["define", name, rest @ ..] = words.as_slice() {
                    macros.push((name, rest.to_vec()));
                }
            }
            word if global_const && t.kind == Kind::Ident => used.push(word),
            _ => {}
        }
    }
    let mut found: Vec<&str> = Vec::new();
    while let Some(k) = macros.iter().position(|(name, _)| used.contains(name)) {
        let (name, body) = macros.swap_remove(k);
        found.push(name);
        used.extend(body);
    }
    found
}

/// The rewrites of [`rewrite_token`] inside the body of `#define` (the
/// directive token `t`), but `dot`: a macro with `dot` is also used in
/// constant expressions, which take no call of a helper. In a macro
/// that a global `const` uses (`in_constants`), `mix` becomes its
/// definition, as in the constant itself.
fn define_body_rewrites(
    t: &Token,
    text: &mut String,
    (insertions, overloads): &mut (&mut Vec<(usize, String)>, &mut Vec<&'static str>),
    in_constants: &[&str],
) {
    let Some(tokens) = define_tokens(t) else {
        return;
    };
    let constant = tokens
        .get(1)
        .is_some_and(|n| in_constants.contains(&n.text));
    // From the macro's name on (its parameters are names too).
    for i in 1..tokens.len() {
        if tokens[i].is("dot") {
            continue;
        }
        if constant && tokens[i].is("mix") {
            mix_in_constant(&tokens, i, text, insertions);
            continue;
        }
        // `#define _in(T) const in T`, for parameter lists.
        if tokens[i].is("const") && tokens.get(i + 1).is_some_and(|n| n.is("in")) {
            scan::blank(text, tokens[i].start..tokens[i].end());
            continue;
        }
        let used = rewrite_token(&tokens, i, text, insertions);
        note_overloads(overloads, used);
    }
}

/// A local `const int NAME = NUMBER;` is not a constant to naga: an array
/// size `[NAME]` after it in the same function becomes `[NUMBER]` (the
/// same value).
fn const_array_sizes(tokens: &[Token], text: &mut String, out: &mut Vec<(usize, String)>) {
    let mut braces = 0i32;
    let mut constants: Vec<(&str, i64)> = Vec::new();
    for (i, t) in tokens.iter().enumerate() {
        match t.text {
            "{" => braces += 1,
            "}" => {
                braces -= 1;
                if braces == 0 {
                    constants.clear();
                }
            }
            "const" if braces > 0 => {
                let words: Vec<&Token> = tokens[i + 1..].iter().take(3).collect();
                if let [ty, name, eq] = words[..]
                    && ty.is("int")
                    && name.kind == Kind::Ident
                    && eq.is("=")
                {
                    let mut at = i + 4;
                    if let Some(value) = int_sum(tokens, &mut at, &constants)
                        && tokens.get(at).is_some_and(|t| t.is(";"))
                    {
                        constants.push((name.text, value));
                    }
                }
            }
            word if t.kind == Kind::Ident
                && i > 0
                && tokens[i - 1].is("[")
                && tokens.get(i + 1).is_some_and(|n| n.is("]")) =>
            {
                if let Some((_, value)) = constants.iter().rev().find(|(n, _)| *n == word) {
                    overwrite(text, t.start..t.end(), "");
                    out.push((t.start, value.to_string()));
                }
            }
            _ => {}
        }
    }
}

/// The integer operators, lowest precedence first.
const INT_OPERATORS: [[&str; 2]; 2] = [["+", "-"], ["*", "/"]];

/// The value of the integer expression at `tokens[*at..]` (numbers,
/// `constants`, `+ - * /`, brackets), `*at` moved past it; `None` for
/// anything else, or a division by zero or an overflow.
fn int_sum(tokens: &[Token], at: &mut usize, constants: &[(&str, i64)]) -> Option<i64> {
    int_terms(tokens, at, constants, 0)
}

/// The terms joined by the operators of precedence `level` and above.
fn int_terms(
    tokens: &[Token],
    at: &mut usize,
    constants: &[(&str, i64)],
    level: usize,
) -> Option<i64> {
    let Some(operators) = INT_OPERATORS.get(level) else {
        return int_factor(tokens, at, constants);
    };
    let mut value = int_terms(tokens, at, constants, level + 1)?;
    while let Some(op) = tokens.get(*at).filter(|t| operators.contains(&t.text)) {
        *at += 1;
        let right = int_terms(tokens, at, constants, level + 1)?;
        value = match op.text {
            "+" => value.checked_add(right),
            "-" => value.checked_sub(right),
            "*" => value.checked_mul(right),
            _ => value.checked_div(right),
        }?;
    }
    Some(value)
}

fn int_factor(tokens: &[Token], at: &mut usize, constants: &[(&str, i64)]) -> Option<i64> {
    let t = tokens.get(*at)?;
    *at += 1;
    match t.text {
        "(" => {
            let value = int_sum(tokens, at, constants)?;
            tokens.get(*at).filter(|t| t.is(")"))?;
            *at += 1;
            Some(value)
        }
        "-" => int_factor(tokens, at, constants)?.checked_neg(),
        number if t.kind == Kind::Number => number.parse().ok(),
        name => constants
            .iter()
            .rev()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| *v),
    }
}

/// Each empty `[]` that an array constructor's arguments size: the
/// constructor's own (`float[](a, b)`) and a declaration's (`float w[] =
/// float[](a, b)`, `float[] w = ...`, and each name of `float[] a = ..., b
/// = ...`), which takes the size of the first constructor after its `=`.
/// An empty `[]` without an initializer (a parameter) is left as it is.
fn unsized_array_sizes(tokens: &[Token], out: &mut Vec<(usize, String)>) {
    for (i, t) in tokens.iter().enumerate() {
        if !(t.is("[") && tokens.get(i + 1).is_some_and(|n| n.is("]"))) {
            continue;
        }
        let open = if tokens.get(i + 2).is_some_and(|n| n.is("(")) {
            Some(i + 2)
        } else {
            initializer_constructor(tokens, i + 2)
        };
        if let Some((commas, _)) = open.and_then(|open| arguments(tokens, open)) {
            out.push((tokens[i + 1].start, (commas.len() + 1).to_string()));
        }
    }
}

/// From the token after a declaration's `[]`: the `(` of the array
/// constructor that its initializer starts with, if it has one, whether
/// the name comes after the brackets (`float[] w = ...`) or before them.
fn initializer_constructor(tokens: &[Token], from: usize) -> Option<usize> {
    let mut k = from;
    if tokens.get(k).is_some_and(|t| t.kind == Kind::Ident) {
        k += 1;
    }
    if !tokens.get(k).is_some_and(|t| t.is("=")) {
        return None;
    }
    // `T [ ]` or `T [ N ]`, then `(`.
    let rest = tokens.get(k + 1..k + 6)?;
    match rest {
        [ty, open, close, paren, ..]
            if ty.kind == Kind::Ident && open.is("[") && close.is("]") && paren.is("(") =>
        {
            Some(k + 4)
        }
        [ty, open, _, close, paren]
            if ty.kind == Kind::Ident && open.is("[") && close.is("]") && paren.is("(") =>
        {
            Some(k + 5)
        }
        _ => None,
    }
}

/// Words that start a statement but are not a type.
const STATEMENT_WORDS: [&str; 6] = ["return", "else", "case", "do", "while", "if"];

/// Splits each declaration of several names that declares an array before
/// its last name into one declaration per name (the module's comment says
/// why). A declaration is a statement that starts with two or more words
/// (qualifiers, a type, the first name).
fn split_array_declarations(tokens: &[Token], text: &mut String, out: &mut Vec<(usize, String)>) {
    let mut start = true;
    for (s, t) in tokens.iter().enumerate() {
        let at_start = start;
        start = matches!(t.text, ";" | "{" | "}") || (at_start && t.kind == Kind::Directive);
        // Blanked by the GLSL rewrite (a `uniform` declaration) or not a
        // declaration.
        let blanked = text[t.start..t.end()].trim().is_empty();
        if !at_start || blanked || t.kind != Kind::Ident || STATEMENT_WORDS.contains(&t.text) {
            continue;
        }
        let words = tokens[s..]
            .iter()
            .take_while(|w| w.kind == Kind::Ident)
            .count();
        let after = s + words;
        if words < 2
            || !tokens
                .get(after)
                .is_some_and(|n| matches!(n.text, "[" | "=" | "," | ";"))
        {
            continue;
        }
        let Some((commas, has_array)) = declarators(tokens, after) else {
            continue;
        };
        if commas.is_empty() || !has_array {
            continue;
        }
        let ty = text[t.start..tokens[after - 2].end()].to_string();
        for comma in commas {
            overwrite(text, tokens[comma].start..tokens[comma].end(), ";");
            out.push((tokens[comma].end(), format!(" {ty} ")));
        }
    }
}

/// From the token after a declaration's first name: the commas between its
/// names, and whether a name before the last is an array (`NAME [`).
fn declarators(tokens: &[Token], from: usize) -> Option<(Vec<usize>, bool)> {
    let mut depth = 0i32;
    let mut commas = Vec::new();
    let mut array_before_last = false;
    let mut array = tokens[from].is("[");
    for (i, t) in tokens.iter().enumerate().skip(from) {
        match t.text {
            "(" | "[" | "{" => depth += 1,
            ")" | "]" | "}" => depth -= 1,
            "," if depth == 0 => {
                commas.push(i);
                array_before_last |= array;
                array = tokens.get(i + 2).is_some_and(|n| n.is("["));
            }
            ";" if depth == 0 => return Some((commas, array_before_last)),
            _ => {}
        }
        if depth < 0 {
            return None;
        }
    }
    None
}

/// The value of a float literal (`1.5`, `2e3`, `0.f`); `None` for an
/// integer or hexadecimal one.
fn float_value(literal: &str) -> Option<f64> {
    let digits = literal.trim_end_matches(['f', 'F']);
    let float = digits.contains(['.', 'e', 'E']) && !digits.starts_with("0x");
    float.then(|| digits.parse().ok()).flatten()
}

/// A float literal beyond the largest float (`1e39`, `1e100`).
fn is_infinite_float(literal: &str) -> bool {
    float_value(literal).is_some_and(|v| v > f64::from(f32::MAX))
}

/// A float literal that is zero (`0.0`, `0.`, `0e0`).
fn is_zero_literal(t: &Token) -> bool {
    t.kind == Kind::Number && float_value(t.text) == Some(0.0)
}

/// Writes `new` over `range` of `text`, padded with spaces to its length.
fn overwrite(text: &mut String, range: std::ops::Range<usize>, new: &str) {
    let padded = format!("{new:<width$}", width = range.len());
    text.replace_range(range, &padded);
}

/// The sampler types of WebGL GLSL and the texture types of Vulkan GLSL
/// they are made from (each pair of the same length).
const SAMPLER_TYPES: [(&str, &str); 3] = [
    ("sampler2D", "texture2D"),
    ("samplerCube", "textureCube"),
    ("sampler3D", "texture3D"),
];

/// `sampler2D NAME` parameters become `texture2D NAME` (the same length),
/// and in the function's body each `NAME` becomes
/// `sampler2D(NAME, rsb_linear_sampler)`, which naga's texture functions
/// take; `samplerCube` and `sampler3D` likewise.
fn sampler_parameters(tokens: &[Token], text: &mut String, out: &mut Vec<(usize, String)>) {
    let (mut braces, mut parens) = (0i32, 0i32);
    let mut pending: Vec<(&str, &str)> = Vec::new();
    let mut in_body: Vec<(&str, &str)> = Vec::new();
    let sampler = |word: &str| SAMPLER_TYPES.iter().find(|(s, _)| *s == word).copied();
    for (i, t) in tokens.iter().enumerate() {
        match t.text {
            "{" => {
                if braces == 0 {
                    in_body = std::mem::take(&mut pending);
                }
                braces += 1;
            }
            "}" => {
                braces -= 1;
                if braces == 0 {
                    in_body.clear();
                }
            }
            "(" => parens += 1,
            ")" => parens -= 1,
            ";" if braces == 0 => pending.clear(),
            word if braces == 0 && parens > 0 && sampler(word).is_some() => {
                let (sampler_type, texture_type) = sampler(word).expect("a sampler type");
                overwrite(text, t.start..t.end(), texture_type);
                if let Some(n) = tokens.get(i + 1).filter(|n| n.kind == Kind::Ident) {
                    pending.push((n.text, sampler_type));
                }
            }
            word if braces > 0 && t.kind == Kind::Ident && !(i > 0 && tokens[i - 1].is(".")) => {
                if let Some((_, sampler_type)) = in_body.iter().find(|(n, _)| *n == word) {
                    out.push((t.start, format!("{sampler_type}(")));
                    out.push((t.end(), ", rsb_linear_sampler)".to_string()));
                }
            }
            _ => {}
        }
    }
}

/// The condition of a `for` loop goes in brackets (`for (int i = 0;
/// (int(t[i]) != 15 && i < 15); i++)`): naga reads a condition that starts
/// with a type as a declaration and stops at the `(` of a constructor
/// (`Expected identifier, found LeftParen`), often through a macro
/// (`#define V(t, j) int(t[j])`, `V(t, i) != 15`). A condition that is a
/// declaration (`TYPE NAME = ...`) stays as it is.
fn for_conditions(tokens: &[Token], out: &mut Vec<(usize, String)>) {
    for (i, t) in tokens.iter().enumerate() {
        if !(t.is("for") && tokens.get(i + 1).is_some_and(|n| n.is("("))) {
            continue;
        }
        let mut depth = 0;
        let mut semicolons = Vec::new();
        for (k, t) in tokens.iter().enumerate().skip(i + 1) {
            match t.text {
                "(" | "[" | "{" => depth += 1,
                ")" | "]" | "}" => depth -= 1,
                ";" if depth == 1 => semicolons.push(k),
                _ => {}
            }
            if depth == 0 || semicolons.len() == 2 {
                break;
            }
        }
        let [first, second] = semicolons[..] else {
            continue;
        };
        let declares = second - first > 2 && tokens[first + 2].kind == Kind::Ident;
        if second - first > 1 && !declares {
            out.push((tokens[first + 1].start, "(".to_string()));
            out.push((tokens[second].start, ")".to_string()));
        }
    }
}

/// `(` at `open` starts a call with exactly one argument.
fn single_argument(tokens: &[Token], open: usize) -> bool {
    arguments(tokens, open).is_some_and(|(commas, _)| commas.is_empty())
}

/// For the call whose `(` is the token at `open`: the tokens of the commas
/// between its arguments and of its closing `)`.
fn arguments(tokens: &[Token], open: usize) -> Option<(Vec<usize>, usize)> {
    if !tokens.get(open).is_some_and(|t| t.is("(")) {
        return None;
    }
    let mut depth = 0;
    let mut commas = Vec::new();
    for (i, t) in tokens.iter().enumerate().skip(open) {
        match t.text {
            "(" | "[" => depth += 1,
            ")" | "]" => {
                depth -= 1;
                if depth == 0 {
                    return Some((commas, i));
                }
            }
            "," if depth == 1 => commas.push(i),
            _ => {}
        }
    }
    None
}

/// `mix(x, y, a)` in a constant expression, which naga cannot evaluate,
/// becomes GLSL's definition of it, `((x) * (1.0 - (a)) + (y) * (a))`
/// (the commas overwritten, the rest inserted, `a`'s text written twice).
fn mix_in_constant(
    tokens: &[Token],
    name: usize,
    text: &mut String,
    out: &mut Vec<(usize, String)>,
) {
    let Some((commas, close)) = arguments(tokens, name + 1) else {
        return;
    };
    let &[first, second] = commas.as_slice() else {
        return;
    };
    let a = text[tokens[second].end()..tokens[close].start]
        .trim()
        .to_string();
    scan::blank(text, tokens[name].start..tokens[name].end());
    out.push((tokens[name + 1].end(), "(".to_string()));
    overwrite(text, tokens[first].start..tokens[first].end(), ")");
    out.push((tokens[first].end(), format!(" * (1.0 - ({a})) + (")));
    overwrite(text, tokens[second].start..tokens[second].end(), ")");
    out.push((tokens[second].end(), " * (".to_string()));
    out.push((tokens[close].start, ")".to_string()));
}

/// If the identifier at `name` starts a prototype `NAME(...);` (at the top
/// level), names its unnamed parameters.
fn name_prototype_parameters(tokens: &[Token], name: usize, out: &mut Vec<(usize, String)>) {
    if name == 0 || tokens[name - 1].kind != Kind::Ident {
        return;
    }
    let open = name + 1;
    if !tokens.get(open).is_some_and(|t| t.is("(")) {
        return;
    }
    let Some(close) = (open..tokens.len()).find(|&k| tokens[k].is(")")) else {
        return;
    };
    if !tokens.get(close + 1).is_some_and(|t| t.is(";")) {
        return;
    }
    let mut from = open + 1;
    let mut index = 0;
    while from < close {
        let to = (from..close).find(|&k| tokens[k].is(",")).unwrap_or(close);
        let words: Vec<&Token> = tokens[from..to]
            .iter()
            .filter(|t| t.kind == Kind::Ident && !PARAMETER_QUALIFIERS.contains(&t.text))
            .collect();
        if let [only] = words[..]
            && !only.is("void")
            && tokens[to - 1] == *only
        {
            out.push((only.end(), format!(" rsb_p{index}")));
        }
        index += 1;
        from = to + 1;
    }
}

impl Bridged {
    /// The column in the user's own line of `column` in the rewritten
    /// `line` (both 1-based); a column inside inserted text maps to where
    /// the insertion is.
    pub fn original_column(&self, scan: &Scan, line: u32, column: u32) -> u32 {
        let Some(line_start) = scan.offset_of(line, 1) else {
            return column;
        };
        let line_end = line_start + scan.line_text(line).len();
        let mut at = (column as usize).saturating_sub(1);
        let mut shift = 0;
        for (offset, inserted) in &self.insertions {
            if *offset < line_start || *offset > line_end {
                continue;
            }
            let inserted_at = offset - line_start + shift;
            if at >= inserted_at + inserted.len() {
                shift += inserted.len();
            } else if at >= inserted_at {
                at = inserted_at;
                break;
            }
        }
        (at - shift) as u32 + 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bridged(text: &str) -> (Bridged, Scan<'_>) {
        let scan = Scan::new(text);
        (bridge(&scan, text.to_string()), scan)
    }

    #[test]
    fn unsized_arrays_take_the_size_of_their_initializer() {
        let (b, _) = bridged(
            "const int[] font = int[](7, 8, 9);\n\
             float w[] = float[](0.1, max(0.2, 0.3));\n\
             float[] a = float[](1., 2.), c = float[](3., 4.);\n\
             vec2 p[] = vec2[2](vec2(0), vec2(1));\n\
             float f(float x[]) { return float[](x[0], 1.0)[1]; }",
        );
        assert_eq!(
            b.text,
            "const int[3] font = int[3](7, 8, 9);\n\
             float w[2] = float[2](0.1, max(0.2, 0.3));\n\
             float[2] a = float[2](1., 2.), c = float[2](3., 4.);\n\
             vec2 p[2] = vec2[2](vec2(0), vec2(1));\n\
             float f(float x[]) { return float[2](x[0], 1.0)[1]; }"
        );
    }

    #[test]
    fn declarations_with_an_array_before_the_last_name_are_split() {
        let (b, _) = bridged(
            "vec4 B[4],P[3];\n\
             void f() { const float a[2] = float[2](1., 2.), x = max(1., 2.); float y, z[2]; }\n\
             float u, v; return a, b;",
        );
        assert_eq!(
            b.text,
            "vec4 B[4]; vec4 P[3];\n\
             void f() { const float a[2] = float[2](1., 2.); const float  x = max(1., 2.); float y, z[2]; }\n\
             float u, v; return a, b;"
        );
    }

    #[test]
    fn const_parameters_lose_const_and_keep_their_offsets() {
        let text = "float f(const in float x, const vec2 y) { const float z = 1.0; return z; }";
        let (b, _) = bridged(text);
        assert_eq!(b.text.len(), text.len());
        assert!(
            b.text
                .starts_with("float f(      in float x,       vec2 y)")
        );
        assert!(b.text.contains("{ const float z"), "{}", b.text);
    }

    #[test]
    fn one_argument_mat2_calls_are_renamed_others_are_not() {
        let (b, _) =
            bridged("mat2 m = mat2(cos(a + vec4(0, 1, 2, 3))); mat2 n = mat2(1.0, 0.0, 0.0, 1.0);");
        assert_eq!(
            b.text,
            "mat2 m = rsb_mat2(cos(a + vec4(0, 1, 2, 3))); mat2 n = mat2(1.0, 0.0, 0.0, 1.0);"
        );
        assert_eq!(b.overloads, [MAT2_OVERLOADS]);
    }

    #[test]
    fn unnamed_prototype_parameters_get_names() {
        let (b, _) = bridged(
            "float k(in float, vec2 p, vec3);\nvoid f(void);\nfloat k(in float a, vec2 p, vec3 c) { return a; }",
        );
        assert_eq!(
            b.text.lines().collect::<Vec<_>>(),
            [
                "float k(in float rsb_p0, vec2 p, vec3 rsb_p2);",
                "void f(void);",
                "float k(in float a, vec2 p, vec3 c) { return a; }"
            ]
        );
    }

    #[test]
    fn names_that_are_glsl_450_keywords_are_renamed() {
        let (b, _) =
            bridged("float sample = 1.0; vec3 filter(vec3 input) { return input * sample; }");
        assert_eq!(
            b.text,
            "float rsb_sample = 1.0; vec3 rsb_filter(vec3 rsb_input) { return rsb_input * rsb_sample; }"
        );
        let (b, _) = bridged("float f(float sampler) { return sampler * 0.5; }");
        assert_eq!(
            b.text,
            "float f(float rsb_sampler) { return rsb_sampler * 0.5; }"
        );
    }

    #[test]
    fn infinite_literals_become_the_largest_float_and_dot_is_renamed() {
        let (b, _) = bridged("float far = 1e39; float d = dot(a, b) + 1.5e3 + dot (c, c);");
        assert_eq!(
            b.text,
            "float far = 3.4028235e38    ; float d = rsb_dot(a, b) + 1.5e3 + rsb_dot (c, c);"
        );
        assert_eq!(b.overloads, [DOT_OVERLOADS]);
        let (inf, _) = bridged("const float inf = 1.0 / 0.0; float h = 0.0 / 0.0, k = x / 0.0;");
        assert_eq!(
            inf.text,
            "const float inf = 3.4028235e38         ; float h = 0.0 / 0.0, k = x / 0.0;"
        );
        let (m, _) = bridged("mat3 m = matrixCompMult(a, b);");
        assert_eq!(m.text, "mat3 m = rsb_matrixCompMult(a, b);");
        assert_eq!(m.overloads, [COMP_MULT_OVERLOADS]);
    }

    #[test]
    fn webgl_texture_functions_become_glsl_450_ones_in_place() {
        let text = "vec4 a = texture2D(t, uv) + texture2DLod(t, uv, 0.0); float texture2Dx;";
        let (b, _) = bridged(text);
        assert_eq!(
            b.text,
            "vec4 a = texture  (t, uv) + textureLod  (t, uv, 0.0); float texture2Dx;"
        );
    }

    #[test]
    fn for_conditions_go_in_brackets_unless_they_declare() {
        let (b, _) = bridged(
            "void f() { for (int i = 0; V(t, i) != 15 && i < 15; i += 3) {} \
             for (;;) {} for (; bool b = x;) {} }",
        );
        assert_eq!(
            b.text,
            "void f() { for (int i = 0; (V(t, i) != 15 && i < 15); i += 3) {} \
             for (;;) {} for (; bool b = x;) {} }"
        );
    }

    #[test]
    fn sampler2d_parameters_become_textures_wrapped_at_each_use() {
        let (b, _) = bridged(
            "vec4 f(sampler2D s, vec2 p);\nvec4 f(in sampler2D s, vec2 p) {\n    return texture(s, p) + v.s;\n}\nvec4 g() { return texture(s, p); }",
        );
        assert_eq!(
            b.text.lines().collect::<Vec<_>>(),
            [
                "vec4 f(texture2D s, vec2 p);",
                "vec4 f(in texture2D s, vec2 p) {",
                "    return texture(sampler2D(s, rsb_linear_sampler), p) + v.s;",
                "}",
                "vec4 g() { return texture(s, p); }",
            ]
        );
        // A parameter named `sampler`, a keyword renamed too.
        let (k, _) =
            bridged("vec4 h(sampler2D sampler) { return texelFetch(sampler, ivec2(0), 0); }");
        assert_eq!(
            k.text,
            "vec4 h(texture2D rsb_sampler) { return texelFetch(sampler2D(rsb_sampler, rsb_linear_sampler), ivec2(0), 0); }"
        );
        // Cube maps and volumes, WebGL's functions for them renamed too.
        let (c, _) = bridged(
            "vec4 f(samplerCube c, sampler3D v) { return textureCube(c, d) + texture3D(v, p); }",
        );
        assert_eq!(
            c.text,
            "vec4 f(textureCube c, texture3D v) { return texture    (samplerCube(c, rsb_linear_sampler), d) \
             + texture  (sampler3D(v, rsb_linear_sampler), p); }"
        );
    }

    #[test]
    fn precision_qualifiers_are_blanked_in_place() {
        let text = "float f(highp vec2 p) { lowp float s = 1.0; return s; }";
        let (b, _) = bridged(text);
        assert_eq!(
            b.text,
            "float f(      vec2 p) {      float s = 1.0; return s; }"
        );
    }

    #[test]
    fn local_const_int_array_sizes_become_their_value() {
        let (b, _) = bridged(
            "void f() {\n    const int N = 4;\n    const int M = (2*N+1)*(N - -1)/3;\n    float a[N]; float b[M]; a[i] = b[K];\n    const int Z = N / 0;\n    const int X = N * x;\n    float c[Z]; float d[X];\n}\nvoid g() { float c[N]; }",
        );
        assert_eq!(
            b.text.lines().collect::<Vec<_>>(),
            [
                "void f() {",
                "    const int N = 4;",
                "    const int M = (2*N+1)*(N - -1)/3;",
                "    float a[4 ]; float b[15 ]; a[i] = b[K];",
                "    const int Z = N / 0;",
                "    const int X = N * x;",
                "    float c[Z]; float d[X];",
                "}",
                "void g() { float c[N]; }",
            ]
        );
    }

    #[test]
    fn rewrites_reach_into_define_bodies_but_dot_stays_in_constants() {
        let (b, _) = bridged(
            "#define R(v) mat2(v)\n#define T(uv) texture2D(c, uv)\n#define sample 0.5\n#define D dot(a, b)\nconst float d = dot(a, a);\nvoid f() { float e = dot(a, b); }\n#define _in(T) const in T\n#define K const int",
        );
        assert_eq!(
            b.text.lines().collect::<Vec<_>>(),
            [
                "#define R(v) rsb_mat2(v)",
                "#define T(uv) texture  (c, uv)",
                "#define rsb_sample 0.5",
                "#define D dot(a, b)",
                "const float d = dot(a, a);",
                "void f() { float e = rsb_dot(a, b); }",
                "#define _in(T)       in T",
                "#define K const int",
            ]
        );
        assert_eq!(b.overloads, [MAT2_OVERLOADS, DOT_OVERLOADS]);
    }

    #[test]
    fn mix_in_a_global_constant_becomes_its_definition() {
        let (b, _) = bridged(
            "const vec3 c = mix(a, vec3(1.0, 2.0, 3.0), 0.25);\n\
             void f() { vec3 d = mix(a, b, t); }",
        );
        assert_eq!(
            b.text.lines().collect::<Vec<_>>(),
            [
                "const vec3 c =    ((a) * (1.0 - (0.25)) + ( vec3(1.0, 2.0, 3.0)) * ( 0.25));",
                "void f() { vec3 d = mix(a, b, t); }",
            ]
        );
    }

    #[test]
    fn mix_in_a_macro_that_a_global_constant_uses_becomes_its_definition() {
        let (b, _) = bridged(
            "#define M(c) mix(a, c, 0.5)\n\
             #define N(c) (M(c) * 2.0)\n\
             #define F(c) mix(a, c, t)\n\
             const vec3 k = N(b);\n\
             void f() { vec3 d = F(b); }",
        );
        assert_eq!(
            b.text.lines().collect::<Vec<_>>(),
            [
                "#define M(c)    ((a) * (1.0 - (0.5)) + ( c) * ( 0.5))",
                "#define N(c) (M(c) * 2.0)",
                "#define F(c) mix(a, c, t)",
                "const vec3 k = N(b);",
                "void f() { vec3 d = F(b); }",
            ]
        );
    }

    #[test]
    fn columns_after_an_insertion_map_back_to_the_users_line() {
        let text = "void f() {\n    mat2 m = mat2(v) * oops;\n}";
        let (b, scan) = bridged(text);
        let rewritten = b.text.lines().nth(1).unwrap();
        let oops = rewritten.find("oops").unwrap() as u32 + 1;
        let original = text.lines().nth(1).unwrap().find("oops").unwrap() as u32 + 1;
        assert_eq!(b.original_column(&scan, 2, oops), original);
        // Before the insertion nothing moves; inside it, the call's start.
        assert_eq!(b.original_column(&scan, 2, 5), 5);
        assert_eq!(b.original_column(&scan, 2, 16), 14);
        assert_eq!(b.original_column(&scan, 1, 3), 3);
    }
}
