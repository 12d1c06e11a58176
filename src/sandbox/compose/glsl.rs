//! GLSL files: the style, the prelude assembled around the rewritten text,
//! the front-end gaps bridged, the module parsed, repaired and validated.

use std::fmt::Write as _;

use super::glsl_decls::{name_macros, rewrite_glsl, through_macros};
use super::glsl_prelude::{
    GLSL_TEXTURES, SURFACE_EPILOGUE, glsl_frame_block, glsl_param_type, glsl_sandbox_surface,
    glsl_texture_names, is_matrix, old_shadertoy_names, sampler_kind, shadertoy_channels,
    standard_uniforms,
};
use super::glslviewer;
use super::param_block::{GLSL_BOOL_PREFIX, read_params};
use super::silent_zeros::{self, Warning, WarningKind};
use super::{
    Compiled, EPILOGUE_NAME, GLSL_ENTRY, PRELUDE_NAME, Style, Target, at_end_of_file, error_at,
    find_pair,
};
use crate::gpu::{ShaderError, ShaderSource};
use crate::sandbox::channels_3d::ChannelKinds;
use crate::sandbox::{gaps, repair};
use crate::shader_params::scan::{self, Kind, Scan, Token, top_level};

/// Whether `word` occurs in `text` as a whole identifier.
fn has_word(text: &str, word: &str) -> bool {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .any(|w| w == word)
}

/// Whether a top-level `uniform` declares one of `names`.
fn declares_uniform(tokens: &[Token], names: &[&str]) -> bool {
    tokens.iter().enumerate().any(|(i, t)| {
        t.is("uniform")
            && tokens[i + 1..]
                .iter()
                .take_while(|n| !n.is(";"))
                .any(|n| names.contains(&n.text))
    })
}

/// `text` with each top-level use of an object-like macro whose body
/// declares what the prelude replaces (`#define init precision highp
/// float; uniform float time;` then `init`, as code golf has it) written
/// out in place, on the same line, so that the rewrite finds the
/// declarations; None when there is none.
pub(super) fn expand_declaring_macros(text: &str) -> Option<String> {
    let scan = Scan::new(text);
    let tokens = &scan.tokens;
    let bodies: Vec<(&str, &str)> = tokens
        .iter()
        .filter(|t| t.kind == Kind::Directive)
        .filter_map(|t| {
            let inner = Scan::new(t.text.strip_prefix('#')?);
            let [define, name, rest @ ..] = &inner.tokens[..] else {
                return None;
            };
            let function_like = rest
                .first()
                .is_some_and(|r| r.is("(") && r.start == name.end());
            let declares = rest
                .iter()
                .any(|r| ["uniform", "precision", "varying"].contains(&r.text));
            let body = &inner.text[rest.first()?.start..];
            (define.is("define") && !function_like && declares && !body.contains('\n'))
                .then_some((name.text, body))
        })
        .collect();
    let uses: Vec<(usize, &str)> = top_level(tokens)
        .filter(|&i| tokens[i].kind == Kind::Ident)
        .filter_map(|i| {
            let body = bodies.iter().find(|(n, _)| *n == tokens[i].text)?.1;
            Some((i, body))
        })
        .collect();
    if uses.is_empty() {
        return None;
    }
    let mut expanded = text.to_string();
    for &(i, body) in uses.iter().rev() {
        expanded.replace_range(tokens[i].start..tokens[i].end(), body);
    }
    Some(expanded)
}

/// Whether the file defines the function `entry` at the top level, itself,
/// under a name that is a macro for it (`#define mainImage main`, then
/// `void mainImage(void)`), or through a macro it uses there (`#define
/// Main void mainImage(out vec4 Q, vec2 U)`, then `Main { ... }`, as some
/// Common tabs have it; a whole `void main() { ... }` in a macro).
fn defines_entry(tokens: &[Token], entry: &str) -> bool {
    let names = name_macros(tokens);
    let named = |i: usize| {
        tokens.get(i + 1).is_some_and(|n| n.is("("))
            && through_macros(&names, tokens[i].text, tokens[i].start) == entry
    };
    if top_level(tokens).any(named) {
        return true;
    }
    let macros: Vec<&str> = tokens
        .iter()
        .filter(|t| t.kind == Kind::Directive)
        .filter_map(|t| {
            let inner = Scan::new(t.text.strip_prefix('#')?);
            match &inner.tokens[..] {
                [define, name, rest @ ..] if define.is("define") => {
                    find_pair(rest, entry, "(").map(|_| name.text)
                }
                _ => None,
            }
        })
        .collect();
    top_level(tokens).any(|i| tokens[i].kind == Kind::Ident && macros.contains(&tokens[i].text))
}

/// Macros defined before the user's GLSL, as WebGL defines them: shaders
/// written `#ifdef GL_ES precision mediump float; #endif` expect it.
pub(super) const GLSL_DEFINES: &[&str] = &["GL_ES"];

pub(super) fn compile_glsl(
    name: &str,
    scan: &Scan,
    target: Target,
    kinds: &ChannelKinds,
) -> Result<Compiled, ShaderError> {
    let mut kinds = *kinds;
    if let Some(offset) = scan.too_deep() {
        let message = format!(
            "nested more than {} levels deep (brackets and signs): more than the GLSL \
             compiler can parse",
            scan::MAX_NESTING
        );
        return Err(error_at(name, scan, offset, message));
    }
    let tokens = &scan.tokens;
    // A file with `mainImage` is Shadertoy's, also with a `main()` of its own
    // that calls it (as exports for other sites have), unless it declares
    // GLSL Sandbox's uniforms: then it is a port to GLSL Sandbox.
    let user_main = defines_entry(tokens, "main");
    let sandbox_port = user_main && declares_uniform(tokens, &["time", "resolution", "mouse"]);
    let style = if defines_entry(tokens, "mainImage") && !sandbox_port {
        Style::Shadertoy
    } else if user_main && glslviewer::is_glslviewer(tokens) {
        Style::GlslViewer
    } else if user_main {
        Style::GlslSandbox
    } else {
        return Err(at_end_of_file(
            name,
            scan,
            "neither `void main()` (GLSL Sandbox style) nor \
             `void mainImage(out vec4 fragColor, in vec2 fragCoord)` (Shadertoy style) \
             in this GLSL file (see docs/sandbox.md)"
                .into(),
        ));
    };
    let rewrite = rewrite_glsl(name, scan)?;
    let standard = standard_uniforms(style);
    let mut declared = Vec::new();
    let mut user_params = Vec::new();
    let mut textures = Vec::new();
    // Declared but never set by GLSL Sandbox: zero, as in WebGL.
    let mut zero = Vec::new();
    let mut warnings = Vec::new();
    for decl in &rewrite.uniforms {
        match standard.iter().find(|(n, _)| *n == decl.name) {
            Some((n, t)) if *t == decl.type_name => declared.push(*n),
            // Exports for other players declare `uniform samplerCube
            // iChannel0;`: that channel is a cube map (or a volume).
            Some((n, "sampler2D")) if sampler_kind(&decl.type_name).is_some() => {
                let k = usize::from(n.as_bytes()[n.len() - 1] - b'0');
                kinds[k] = sampler_kind(&decl.type_name).expect("a sampler");
                declared.push(*n);
            }
            // `uniform vec4 mouse;`: the pointer in xy, zw zero.
            Some((n @ ("mouse" | "u_mouse"), _))
                if ["vec3", "vec4"].contains(&decl.type_name.as_str()) =>
            {
                let xy = if *n == "mouse" {
                    "rsb_mouse"
                } else {
                    declared.push(glslviewer::MOUSE_PIXELS);
                    "rsb_u_mouse()"
                };
                zero.push(format!(
                    "#define {n} {}({xy}, {})\n",
                    decl.type_name,
                    if decl.type_name == "vec3" {
                        "0.0"
                    } else {
                        "0.0, 0.0"
                    }
                ));
            }
            // Old exports declare it `uniform float iChannelTime[4];` or so.
            Some((n, t)) if t.starts_with(decl.type_name.as_str()) => declared.push(*n),
            Some((n, t)) => {
                return Err(error_at(
                    name,
                    scan,
                    decl.offset,
                    format!(
                        "`{n}` is a {t} in the {}, not a {}",
                        style.describe(),
                        decl.type_name
                    ),
                ));
            }
            None if sampler_kind(&decl.type_name).is_some() => {
                textures.push((decl.name, sampler_kind(&decl.type_name).expect("a sampler")));
            }
            None if is_matrix(&decl.type_name) => {
                warnings.push(silent_zeros::warning(name, scan, decl, false));
                zero.push(format!(
                    "const {0} {1} = {0}(0.0);\n",
                    decl.type_name, decl.name
                ));
            }
            None => match glsl_param_type(&decl.type_name) {
                Some(_) => {
                    if silent_zeros::is_unset(scan, decl) {
                        warnings.push(silent_zeros::warning(name, scan, decl, true));
                    }
                    user_params.push(decl);
                }
                None => {
                    return Err(error_at(
                        name,
                        scan,
                        decl.offset,
                        format!(
                            "uniform `{}`: a {} cannot be a parameter here (no matrices, \
                             the textures are sampler2D, samplerCube, sampler3D); use float, int, uint, bool \
                             or a vector of them",
                            decl.name, decl.type_name
                        ),
                    ));
                }
            },
        }
    }

    let mut prelude = format!(
        "#version 450\n// raysandbox prelude for {}, see docs/sandbox.md\n",
        style.describe()
    );
    prelude.push_str(&glsl_frame_block(style, &declared));
    prelude.push_str(GLSL_TEXTURES);
    prelude.push_str(&zero.concat());
    let reads_backbuffer =
        style == Style::GlslSandbox && textures.iter().any(|(t, _)| *t == "backbuffer");
    prelude.push_str(&glsl_texture_names(
        name,
        scan,
        style,
        &rewrite.uniforms,
        &textures,
    )?);
    if !user_params.is_empty() {
        prelude.push_str("layout(set = 0, binding = 1) uniform RsbParams {\n");
        for decl in &user_params {
            if decl.type_name == "bool" {
                let _ = writeln!(prelude, "    int {GLSL_BOOL_PREFIX}{};", decl.name);
            } else {
                let _ = writeln!(prelude, "    {} {};", decl.type_name, decl.name);
            }
        }
        prelude.push_str("};\n");
        for decl in user_params.iter().filter(|d| d.type_name == "bool") {
            let _ = writeln!(
                prelude,
                "#define {0} ({GLSL_BOOL_PREFIX}{0} != 0)",
                decl.name
            );
        }
    }
    let resolution = match style {
        Style::Shadertoy => "iResolution",
        Style::GlslViewer if declared.contains(&"u_resolution") => "u_resolution",
        Style::GlslSandbox if declared.contains(&"resolution") => "resolution",
        _ => "rsb_resolution",
    };
    // A buffer keeps fragCoord's rows in the texture's order (Target::Buffer).
    let y = match target {
        Target::Canvas => format!("{resolution}.y - gl_FragCoord.y"),
        Target::Buffer => "gl_FragCoord.y".to_string(),
    };
    let _ = write!(
        prelude,
        "layout(location = 0) out vec4 rsb_frag_color;\n\
         // Shadertoy's and GLSL Sandbox's convention: y up (Vulkan's gl_FragCoord is y down).\n\
         vec4 rsb_frag_coord() {{\n\
         \x20   return vec4(gl_FragCoord.x, {y}, gl_FragCoord.z, gl_FragCoord.w);\n\
         }}\n\
         #define gl_FragCoord rsb_frag_coord()\n\
         #define gl_FragColor rsb_frag_color\n"
    );
    if let Some(output) = rewrite.output {
        let _ = writeln!(prelude, "#define {output} rsb_frag_color");
    }
    // Names the file uses and does not `#define` itself.
    // Also in the body of a `#define` (`#define FONT iChannel0`).
    let used = |word: &str| {
        tokens
            .iter()
            .any(|t| t.is(word) || (t.kind == Kind::Directive && has_word(t.text, word)))
            && !tokens.iter().any(|t| {
                t.kind == Kind::Directive
                    && t.text[1..].split_whitespace().take(2).eq(["define", word])
            })
    };
    match style {
        Style::Shadertoy => {
            prelude.push_str(&old_shadertoy_names(&used));
            prelude.push_str(&shadertoy_channels(&used, &kinds));
        }
        Style::GlslViewer => prelude.push_str(&glslviewer::prelude(&declared, resolution)),
        _ => prelude.push_str(&glsl_sandbox_surface(
            resolution,
            rewrite.surface_position,
            declared.contains(&"surfaceSize"),
        )),
    }
    let epilogue = match style {
        Style::Shadertoy if user_main => String::new(),
        Style::Shadertoy => "\n// raysandbox epilogue (Shadertoy style)\n\
             void main() {\n\
             \x20   vec4 color = vec4(0.0);\n\
             \x20   mainImage(color, gl_FragCoord.xy);\n\
             \x20   rsb_frag_color = color;\n\
             }\n"
        .to_string(),
        Style::GlslSandbox if rewrite.surface_position => SURFACE_EPILOGUE.to_string(),
        _ => String::new(),
    };
    let bridged = gaps::bridge(scan, rewrite.text);
    for overloads in &bridged.overloads {
        prelude.push_str(overloads);
    }
    let mut parts = vec![
        (PRELUDE_NAME.to_string(), prelude),
        (name.to_string(), bridged.text.clone()),
    ];
    if !epilogue.is_empty() {
        parts.push((EPILOGUE_NAME.to_string(), epilogue));
    }
    let source = ShaderSource::from_parts(parts);
    // Errors in the user's text are at the rewritten column: move it back.
    let at_users_column = |mut e: ShaderError| {
        if e.file == name && e.line > 0 {
            e.column = bridged.original_column(scan, e.line, e.column);
        }
        e
    };
    let mut module = parse_glsl_fragment(&source, GLSL_DEFINES).map_err(at_users_column)?;
    repair::define_before_use(&mut module);
    repair::spill_pointer_arguments(&mut module);
    for (function, span) in repair::return_zero_at_end(&mut module) {
        let at = source.error_at(span, String::new());
        warnings.push(Warning {
            file: at.file,
            line: at.line,
            message: format!(
                "function `{function}` can end without returning a value: it returns 0 there"
            ),
            kind: WarningKind::MissingReturn,
        });
    }
    let (module, info) = source.validate_module(module).map_err(at_users_column)?;
    source
        .check_translation(&module, &info)
        .map_err(at_users_column)?;
    let params = read_params(&module, name, scan, |member| {
        let decl = user_params.iter().find(|d| d.name == member)?;
        Some((decl.offset, decl.initializer.clone()))
    })?;
    Ok(Compiled {
        style,
        file: name.to_string(),
        source,
        module,
        entry_point: GLSL_ENTRY,
        params,
        includes: Vec::new(),
        warnings,
        reads_backbuffer,
    })
}

/// Parses the joined source as a GLSL fragment shader (naga's GLSL front
/// end: `#version 450`, Vulkan-style resources), with each of `defines`
/// defined as a macro (`1`). Errors are located like WGSL errors: naga's
/// spans are byte offsets of the joined text, mapped back to the part they
/// fall in.
fn parse_glsl_fragment(
    source: &ShaderSource,
    defines: &[&str],
) -> Result<naga::Module, ShaderError> {
    let mut options = naga::front::glsl::Options::from(naga::ShaderStage::Fragment);
    for name in defines {
        options.defines.insert(name.to_string(), "1".to_string());
    }
    let parsed = source
        .without_panics(|| naga::front::glsl::Frontend::default().parse(&options, source.text()))?;
    parsed.map_err(|errors| match errors.errors.first() {
        Some(e) => source.error_at(e.meta, e.kind.to_string()),
        None => source.error_at(naga::Span::default(), errors.to_string()),
    })
}
