//! The GLSL rewrite by blanking (docs/sandbox.md, "The GLSL rewrite"): the
//! top-level declarations the prelude replaces (`#version`, `uniform`,
//! `out vec4`, `precision`, `varying vec2 surfacePosition`, a `varying`
//! never read) and the words after `#endif` are overwritten with spaces,
//! newlines kept, and what they declared is returned.

use super::error_at;
use crate::gpu::ShaderError;
use crate::shader_params;
use crate::shader_params::scan::{self, Kind, Scan, Token};

/// A `uniform` declaration at the top level of the user's GLSL.
pub(super) struct UniformDecl<'a> {
    /// The type as written, with `[N]` for an array (`vec3[4]`).
    pub(super) type_name: String,
    pub(super) name: &'a str,
    /// Byte offset of the name in the user's text.
    pub(super) offset: usize,
    pub(super) initializer: Option<Vec<f64>>,
}

const PRECISION: [&str; 3] = ["lowp", "mediump", "highp"];

/// The rewritten user text and what the rewrite found.
pub(super) struct GlslRewrite<'a> {
    pub(super) text: String,
    pub(super) uniforms: Vec<UniformDecl<'a>>,
    /// The name of a user-declared `out vec4 NAME;` (GLSL ES 3.0 style).
    pub(super) output: Option<&'a str>,
    /// `varying vec2 surfacePosition;` was declared (and blanked).
    pub(super) surface_position: bool,
}

pub(super) fn rewrite_glsl<'a>(
    name: &str,
    scan: &Scan<'a>,
) -> Result<GlslRewrite<'a>, ShaderError> {
    let tokens = &scan.tokens;
    let mut text = scan.text.to_string();
    let mut uniforms = Vec::new();
    let mut output = None;
    let mut surface_position = false;
    // `#define res resolution` then `uniform vec2 res;` declares `resolution`.
    let macros = name_macros(tokens);
    let (mut braces, mut parens) = (0i32, 0i32);
    let mut i = 0;
    while i < tokens.len() {
        let t = tokens[i];
        match t.text {
            "{" => braces += 1,
            "}" => braces -= 1,
            "(" => parens += 1,
            ")" => parens -= 1,
            _ => {}
        }
        if t.kind == Kind::Directive {
            let directive = t.text[1..].trim_start();
            if directive.starts_with("version") {
                scan::blank(&mut text, t.start..t.end());
            } else if let Some(rest) = ["endif", "else"]
                .iter()
                .find_map(|d| directive.strip_prefix(d))
                .filter(|rest| rest.starts_with([' ', '\t']))
            {
                // `#endif NAME`: WebGL ignores the words after it (a
                // warning), naga's preprocessor rejects them.
                scan::blank(&mut text, t.end() - rest.len()..t.end());
            }
            i += 1;
            continue;
        }
        let top = braces == 0 && parens == 0;
        if !top || t.kind != Kind::Ident {
            i += 1;
            continue;
        }
        // A `layout(...)` prefix belongs to the declaration it qualifies.
        let decl_start = |i: usize| -> usize {
            if i >= 1 && tokens[i - 1].is(")") {
                let mut k = i - 1;
                while k > 0 && !tokens[k].is("(") {
                    k -= 1;
                }
                if k >= 1 && tokens[k - 1].is("layout") {
                    return tokens[k - 1].start;
                }
            }
            tokens[i].start
        };
        let end_of_statement = |from: usize| -> Option<usize> {
            (from..tokens.len()).find(|&k| tokens[k].is(";") || tokens[k].is("{"))
        };
        match t.text {
            "precision" => {
                // `precision mediump float;`, also for sampler types naga
                // rejects: meaningless in Vulkan GLSL, blanked.
                if let Some(end) = (i..tokens.len()).find(|&k| tokens[k].is(";")) {
                    scan::blank(&mut text, t.start..tokens[end].end());
                    i = end + 1;
                    continue;
                }
            }
            "varying" if is_surface_position(&tokens[i + 1..]) => {
                let end = (i..tokens.len())
                    .find(|&k| tokens[k].is(";"))
                    .expect("checked");
                scan::blank(&mut text, t.start..tokens[end].end());
                surface_position = true;
                i = end + 1;
                continue;
            }
            "varying" | "attribute" if unused_input(tokens, i) => {
                // Declared and never read: WebGL links it without a vertex
                // shader output, so it is dropped.
                let end = (i..tokens.len())
                    .find(|&k| tokens[k].is(";"))
                    .expect("checked");
                scan::blank(&mut text, t.start..tokens[end].end());
                i = end + 1;
                continue;
            }
            "varying" | "attribute" => {
                return Err(error_at(
                    name,
                    scan,
                    t.start,
                    format!(
                        "`{}` inputs do not exist here: the sandbox draws one full-screen \
                         triangle; use gl_FragCoord.xy / resolution (of GLSL Sandbox's, \
                         `varying vec2 surfacePosition;` is provided)",
                        t.text
                    ),
                ));
            }
            "uniform" => {
                let mut k = i + 1;
                while tokens.get(k).is_some_and(|t| PRECISION.contains(&t.text)) {
                    k += 1;
                }
                let Some(end) = end_of_statement(k) else {
                    i += 1;
                    continue;
                };
                if tokens[end].is("{") {
                    // A user-declared block: left alone.
                    i += 1;
                    continue;
                }
                let type_name = tokens[k].text;
                // Names, each with an optional initializer, up to the `;`.
                let mut j = k + 1;
                while j < end {
                    let n = tokens[j];
                    if n.kind != Kind::Ident {
                        return Err(error_at(
                            name,
                            scan,
                            n.start,
                            format!("expected a uniform name, found `{}`", n.text),
                        ));
                    }
                    j += 1;
                    let mut declared_type = type_name.to_string();
                    // `[N]`: an array (only the standard iChannelTime is one).
                    while j < end && tokens[j].is("[") {
                        while j < end && !tokens[j].is("]") {
                            declared_type.push_str(tokens[j].text);
                            j += 1;
                        }
                        declared_type.push(']');
                        j += 1;
                    }
                    let mut initializer = None;
                    if tokens.get(j).is_some_and(|t| t.is("=")) {
                        let mut depth = 0;
                        let from = j + 1;
                        while j < end && !(depth == 0 && tokens[j].is(",")) {
                            match tokens[j].text {
                                "(" => depth += 1,
                                ")" => depth -= 1,
                                _ => {}
                            }
                            j += 1;
                        }
                        initializer = Some(initializer_values(&tokens[from..j]));
                    }
                    uniforms.push(UniformDecl {
                        type_name: declared_type,
                        name: through_macros(&macros, n.text, n.start),
                        offset: n.start,
                        initializer,
                    });
                    if tokens.get(j).is_some_and(|t| t.is(",")) {
                        j += 1;
                    }
                }
                scan::blank(&mut text, decl_start(i)..tokens[end].end());
                i = end + 1;
                continue;
            }
            "out" => {
                let mut k = i + 1;
                while tokens.get(k).is_some_and(|t| PRECISION.contains(&t.text)) {
                    k += 1;
                }
                let is_output = tokens.get(k).is_some_and(|t| t.is("vec4"))
                    && tokens.get(k + 1).is_some_and(|t| t.kind == Kind::Ident)
                    && tokens.get(k + 2).is_some_and(|t| t.is(";"));
                if is_output {
                    output = Some(tokens[k + 1].text);
                    scan::blank(&mut text, decl_start(i)..tokens[k + 2].end());
                    i = k + 3;
                    continue;
                }
            }
            _ => {}
        }
        i += 1;
    }
    Ok(GlslRewrite {
        text,
        uniforms,
        output,
        surface_position,
    })
}

/// Whether the `varying` (or `attribute`) declaration at `at` ends with a
/// `;` and none of the names it declares occurs anywhere else.
fn unused_input(tokens: &[Token], at: usize) -> bool {
    let Some(end) = (at..tokens.len()).find(|&k| tokens[k].is(";") || tokens[k].is("{")) else {
        return false;
    };
    let names = tokens[at + 1..end]
        .iter()
        .filter(|t| t.kind == Kind::Ident && !PRECISION.contains(&t.text))
        .skip(1);
    tokens[end].is(";")
        && names
            .clone()
            .all(|n| tokens.iter().filter(|t| t.text == n.text).count() == 1)
}

/// `[precision] vec2 surfacePosition;` (after `varying`): GLSL Sandbox's
/// position on the plane, which the prelude provides.
fn is_surface_position(tokens: &[Token]) -> bool {
    let mut k = 0;
    while tokens.get(k).is_some_and(|t| PRECISION.contains(&t.text)) {
        k += 1;
    }
    let texts: Vec<&str> = tokens.iter().skip(k).take(3).map(|t| t.text).collect();
    texts == ["vec2", "surfacePosition", ";"]
}

/// The numbers of an initializer: `1.5`, `-2`, `vec3(1.0, 0.5, 0.2)`, `true`.
fn initializer_values(tokens: &[Token]) -> Vec<f64> {
    let mut values = Vec::new();
    let mut negative = false;
    for t in tokens {
        match (t.kind, t.text) {
            (Kind::Punct, "-") => negative = true,
            (Kind::Number, n) => {
                if let Some(v) = shader_params::parse_number(n) {
                    values.push(if negative { -v } else { v });
                }
                negative = false;
            }
            (Kind::Ident, "true") => values.push(1.0),
            (Kind::Ident, "false") => values.push(0.0),
            _ => negative = false,
        }
    }
    values
}

/// The object-like macros that stand for one name (`#define mainImage
/// main`, `#define res resolution`): (where defined, macro, name).
pub(super) type NameMacro<'a> = (usize, &'a str, &'a str);

pub(super) fn name_macros<'a>(tokens: &[Token<'a>]) -> Vec<NameMacro<'a>> {
    tokens
        .iter()
        .filter(|t| t.kind == Kind::Directive)
        .filter_map(|t| {
            let inner = Scan::new(t.text.strip_prefix('#')?);
            match &inner.tokens[..] {
                [define, name, body] if define.is("define") && body.kind == Kind::Ident => {
                    Some((t.start, name.text, body.text))
                }
                _ => None,
            }
        })
        .collect()
}

/// `name` written at byte `at`, or the name the macro `name` defined
/// before it stands for.
pub(super) fn through_macros<'a>(macros: &[NameMacro<'a>], name: &'a str, at: usize) -> &'a str {
    macros
        .iter()
        .rfind(|(defined, m, _)| *m == name && *defined < at)
        .map_or(name, |(_, _, body)| body)
}
