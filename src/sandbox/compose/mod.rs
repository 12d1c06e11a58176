//! From the user's file to a validated naga module: the language and style
//! are recognised, the program's prelude (and epilogue) are joined around the
//! user's text with [`ShaderSource`], and the parameters are read from the
//! module and the comments.
//!
//! The user's text is never edited on disk. For GLSL it is rewritten in
//! memory by blanking: declarations the prelude replaces (`#version`,
//! `uniform float time;`, `out vec4 fragColor;`) are overwritten with spaces,
//! newlines kept, so every byte of the user's text keeps its offset, and
//! naga's error spans map back to the user's line and column exactly.
//! docs/sandbox.md documents the preludes for users.

//!
//! | module | what |
//! | --- | --- |
//! | `wgsl` | the WGSL prelude and epilogue, `struct Params` |
//! | `glsl` | the GLSL style, the prelude's assembly, validation |
//! | `glsl_decls` | the blanking rewrite of the user's top-level declarations |
//! | `glslviewer` | glslViewer's and The Book of Shaders' uniforms |
//! | `glsl_prelude` | the pieces of the GLSL preludes: frame block, textures, old names |
//! | `silent_zeros` | the warnings for uniforms that nothing sets |
//! | `param_block` | the parameters read from the validated module's uniform block |

mod glsl;
mod glsl_decls;
mod glsl_prelude;
mod glslviewer;
mod param_block;
mod silent_zeros;
mod wgsl;

use std::path::{Path, PathBuf};

use super::channels_3d::ChannelKinds;
use super::include::{self, Expanded, include_target};
use crate::gpu::{ShaderError, ShaderSource};
use crate::shader_params::ParamSet;
use crate::shader_params::scan::{Scan, Token, top_level};
use glsl::{GLSL_DEFINES, compile_glsl, expand_declaring_macros};
pub use silent_zeros::{Warning, WarningKind};
use wgsl::compile_wgsl;

/// Which kind of shader the file is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// WGSL with `fn main_image(frag_coord: vec2<f32>) -> vec4<f32>`.
    Wgsl,
    /// GLSL with `void main()`, `gl_FragColor` and the uniforms `time`,
    /// `mouse`, `resolution` (glslsandbox.com).
    GlslSandbox,
    /// GLSL with `void mainImage(out vec4 fragColor, in vec2 fragCoord)`
    /// and `iTime`, `iResolution`, `iMouse`, ... (shadertoy.com).
    Shadertoy,
    /// GLSL with `void main()`, `gl_FragColor` and the uniforms `u_time`,
    /// `u_resolution`, `u_mouse`, ... (glslViewer, The Book of Shaders).
    GlslViewer,
}

impl Style {
    pub fn describe(&self) -> &'static str {
        match self {
            Style::Wgsl => "WGSL",
            Style::GlslSandbox => "GLSL (GLSL Sandbox style)",
            Style::Shadertoy => "GLSL (Shadertoy style)",
            Style::GlslViewer => "GLSL (glslViewer style)",
        }
    }
}

/// The name errors give the program's code before the user's file.
pub const PRELUDE_NAME: &str = "<sandbox prelude>";
/// The name errors give the program's code after the user's file.
pub const EPILOGUE_NAME: &str = "<sandbox epilogue>";

/// Channels are numbered 0 to 3 (docs/sandbox.md, "Textures").
const CHANNELS: usize = 4;

/// The fragment entry point of a compiled shader.
pub const WGSL_ENTRY: &str = "rsb_fragment";
pub const GLSL_ENTRY: &str = "main";

/// A user's shader, validated, with its parameters.
#[derive(Debug, Clone)]
pub struct Compiled {
    pub style: Style,
    /// The name errors use for the user's file.
    pub file: String,
    /// The joined source (prelude, the user's text, epilogue).
    pub source: ShaderSource,
    pub module: naga::Module,
    /// The fragment entry point in `module`.
    pub entry_point: &'static str,
    /// Parameters with their default values.
    pub params: ParamSet,
    /// The shader reads the previous frame (GLSL Sandbox's `backbuffer`):
    /// each frame is copied for the next one to read (docs/sandbox.md,
    /// "Textures").
    pub reads_backbuffer: bool,
    /// The files `#include`d, to reload when one changes.
    pub includes: Vec<PathBuf>,
    /// Uniforms that stay 0 (docs/sandbox.md, "Uniforms nobody sets"), and
    /// functions that return 0 where they end without a value.
    pub warnings: Vec<Warning>,
}

/// Reads and compiles a shader file. Unreadable files are errors too, named
/// like compile errors.
pub fn compile_file(path: &Path) -> Result<Compiled, ShaderError> {
    compile_file_with(path, &ChannelKinds::default())
}

/// [`compile_file`] with channels of `kinds` (`--channel0 cube`).
pub fn compile_file_with(path: &Path, kinds: &ChannelKinds) -> Result<Compiled, ShaderError> {
    let name = path.display().to_string();
    let text =
        std::fs::read_to_string(path).map_err(|e| ShaderError::unreadable(name.clone(), &e))?;
    let (expanded, included) = include::expand(path, &text);
    included?;
    compile_expanded(&name, &expanded, kinds)
}

/// Compiles a file whose includes are joined in, its channels of `kinds`
/// (docs/sandbox.md, "Cube maps and volumes"): errors are at the line of
/// the file, included or not, that they are in.
pub fn compile_expanded(
    name: &str,
    expanded: &Expanded,
    kinds: &ChannelKinds,
) -> Result<Compiled, ShaderError> {
    let compiled = compile_with(name, &expanded.text, None, Target::Canvas, kinds)
        .map_err(|e| expanded.locate(e, name))?;
    Ok(located(compiled, expanded))
}

/// Compiles one pass of a multipass Shadertoy shader (docs/sandbox.md,
/// "Multipass"): GLSL whatever its name, in the Shadertoy style, with
/// `fragCoord` in the rows `target` stores and its channels of `kinds`.
/// `expanded` holds the Common code and the pass's text, each line mapped
/// to its own file.
pub fn compile_pass(
    name: &str,
    expanded: &Expanded,
    target: Target,
    kinds: &ChannelKinds,
) -> Result<Compiled, ShaderError> {
    let compiled = compile_with(name, &expanded.text, Some(false), target, kinds)
        .map_err(|e| expanded.locate(e, name))?;
    if compiled.style != Style::Shadertoy {
        let scan = Scan::new(&expanded.text);
        let e = at_end_of_file(
            name,
            &scan,
            "a pass of a multipass shader defines \
             `void mainImage(out vec4 fragColor, in vec2 fragCoord)` (Shadertoy style)"
                .into(),
        );
        return Err(expanded.locate(e, name));
    }
    Ok(located(compiled, expanded))
}

/// Moves the warnings and the parameters' lines of a compiled joined text
/// to the files and lines they came from.
fn located(mut compiled: Compiled, expanded: &Expanded) -> Compiled {
    compiled.includes = expanded.included().to_vec();
    for w in &mut compiled.warnings {
        if let Some((file, line)) = expanded.origin(w.line) {
            w.file = file.display().to_string();
            w.line = line;
        }
    }
    // The panel's tooltips name the declaration's line in its own file.
    for spec in &mut compiled.params.specs {
        if let Some((_, line)) = expanded.origin(spec.line) {
            spec.line = line;
        }
    }
    compiled
}

/// Compiles the text of a shader file called `name` (its extension, if any,
/// tells the language: `.wgsl` is WGSL, `.glsl`, `.frag`, `.fs`, `.fsh` are
/// GLSL; otherwise the text decides).
pub fn compile(name: &str, text: &str) -> Result<Compiled, ShaderError> {
    compile_with(name, text, None, Target::Canvas, &ChannelKinds::default())
}

/// Where a shader's pixels go, which decides how `fragCoord`'s rows lie in
/// the texture (docs/sandbox.md, "Multipass").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Target {
    /// The canvas that is shown: y up in the shader, its bottom row the
    /// texture's last.
    #[default]
    Canvas,
    /// A buffer that passes read: `fragCoord.y = 0.5` is the texture's
    /// first row, so that `texelFetch(iChannel0, ivec2(fragCoord), 0)` and
    /// `texture(iChannel0, fragCoord / iResolution.xy)` read the same pixel
    /// back, as on Shadertoy.
    Buffer,
}

/// [`compile`], with the language forced (`Some(true)`: WGSL,
/// `Some(false)`: GLSL) or told by the name and text (`None`).
fn compile_with(
    name: &str,
    text: &str,
    wgsl: Option<bool>,
    target: Target,
    kinds: &ChannelKinds,
) -> Result<Compiled, ShaderError> {
    let scan = Scan::new(text);
    if let Some(t) = scan
        .tokens
        .iter()
        .find(|t| include_target(t.text).is_some())
    {
        // Without a file there is no folder to find it in.
        return Err(error_at(
            name,
            &scan,
            t.start,
            "`#include` needs the shader as a file on disk (raysandbox shader FILE): \
             the included file is found next to it"
                .into(),
        ));
    }
    let extension = Path::new(name)
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let wgsl = match (wgsl, extension.as_deref()) {
        (Some(wgsl), _) => wgsl,
        (None, Some("wgsl")) => true,
        (None, Some("glsl" | "frag" | "fs" | "fsh" | "fragment")) => false,
        (None, _) => scan.tokens.iter().any(|t| t.is("fn")),
    };
    let result = if wgsl {
        compile_wgsl(name, text, &scan)
    } else {
        let expanded = expand_declaring_macros(text);
        let mut scan = Scan::new(expanded.as_deref().unwrap_or(text));
        scan.drop_inactive_branches(GLSL_DEFINES);
        compile_glsl(name, &scan, target, kinds)
    };
    result.map_err(|mut e| {
        if e.line == 0 {
            // No position (naga failed as a whole): the user's file it is,
            // at its end.
            e = at_end_of_file(name, &scan, e.message);
        }
        if e.file == name {
            point_at_missing_semicolon(&mut e, &scan);
            // The joined text may hold the user's line blanked in part: show
            // the line as the user wrote it.
            e.source_line = scan.line_text(e.line).to_string();
        }
        if e.file == EPILOGUE_NAME || e.file == PRELUDE_NAME {
            blame_the_users_file(&mut e, name, &scan);
        }
        e
    })
}

/// An error naga found in the code the sandbox joins around the user's
/// file is caused by the file (a name that clashes, an entry function
/// missing or misspelt, a sandbox macro used wrongly): it is reported at
/// the line of the file that caused it, saying where it surfaced, so that
/// every error names the user's file and line (docs/sandbox.md, "Line numbers").
fn blame_the_users_file(e: &mut ShaderError, name: &str, scan: &Scan) {
    let (part, hint) = if e.file == EPILOGUE_NAME {
        (
            "after",
            "it calls your entry function: check its name and signature",
        )
    } else {
        (
            "before",
            "it declares the names of docs/sandbox.md: check that your file does not \
             declare them too",
        )
    };
    e.message = format!(
        "{} (in the code the sandbox adds {part} your file, at {}:{}: {hint}; see \
         docs/sandbox.md)",
        e.message, e.line, e.column
    );
    let culprit = if e.file == EPILOGUE_NAME {
        ["mainImage", "main_image", "main"]
            .iter()
            .find_map(|entry| scan.tokens.iter().find(|t| t.is(entry)))
    } else {
        // naga places an error inside a macro of the sandbox (`gl_FragCoord`
        // and the old Shadertoy names are macros) at the macro's `#define`:
        // the user's first use of that name is what went wrong.
        let line = e.source_line.trim_start();
        let defined = line
            .strip_prefix("#define")
            .and_then(|rest| rest.split_whitespace().next());
        defined.and_then(|macro_name| scan.tokens.iter().find(|t| t.is(macro_name)))
    };
    *e = match culprit {
        Some(token) => ShaderError {
            label: "caused by this".to_string(),
            ..error_at(name, scan, token.start, std::mem::take(&mut e.message))
        },
        None => at_end_of_file(name, scan, std::mem::take(&mut e.message)),
    };
}

/// naga reports a missing `;` at the token after it, often on the next line.
/// Like rustc, point just after the token that wants the `;` instead, so
/// the error is on the line with the mistake.
fn point_at_missing_semicolon(e: &mut ShaderError, scan: &Scan) {
    let wants_semicolon = e.message.contains("Semicolon") || e.message.contains("expected `;`");
    if !wants_semicolon {
        return;
    }
    let Some(offset) = scan.offset_of(e.line, e.column) else {
        return;
    };
    let Some(previous) = scan.tokens.iter().rev().find(|t| t.end() <= offset) else {
        return;
    };
    let line = scan.line_of(previous.start);
    if line == e.line {
        return;
    }
    e.line = line;
    e.column = scan.column_of(previous.end());
    e.label = "expected `;` after this".to_string();
}

/// An error in the user's file at a byte offset of its text.
fn error_at(name: &str, scan: &Scan, offset: usize, message: String) -> ShaderError {
    let line = scan.line_of(offset);
    ShaderError {
        file: name.to_string(),
        line,
        column: scan.column_of(offset),
        message,
        source_line: scan.line_text(line).to_string(),
        label: String::new(),
    }
}

/// An error about the file as a whole (no entry function): like rustc's
/// missing `main`, it points at the end of the file, where the function
/// would go, so that it has a line like every other error.
fn at_end_of_file(name: &str, scan: &Scan, message: String) -> ShaderError {
    let end = scan.tokens.last().map_or(0, |t| t.end());
    ShaderError {
        label: "the file ends here".to_string(),
        ..error_at(name, scan, end, message)
    }
}

/// Index of the first token `a` directly followed by `b`, at brace depth 0.
fn find_pair(tokens: &[Token], a: &str, b: &str) -> Option<usize> {
    top_level(tokens).find(|&i| tokens[i].is(a) && tokens.get(i + 1).is_some_and(|n| n.is(b)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shader_params::scan;
    use crate::shader_params::{Control, Scalar};

    const WGSL: &str = "\
struct Params {
    speed: f32, // @slider(0.0, 5.0, 0.1) how fast
    // @color
    tint: vec3<f32>,
    mode: u32, // @select(a, b, c) @default(b)
    gain: f32, // @log(1e-4, 1)
    show: u32, // @checkbox
    plain: vec2<i32>,
}

fn main_image(frag_coord: vec2<f32>) -> vec4<f32> {
    let uv = frag_coord / u.resolution;
    return vec4<f32>(params.tint * uv.x * params.speed, f32(params.mode) + params.gain);
}
";

    /// naga's GLSL front end recurses once per level and overflowed the
    /// stack at 1,600 (found by the fuzzer, docs/reliability.md): a file
    /// nested deeper than the limit is an error at the first token past it.
    #[test]
    fn glsl_nested_too_deep_is_an_error_at_its_line() {
        let deep = scan::MAX_NESTING + 1;
        for (nested, line) in [
            (format!("{}1.0{}", "(".repeat(deep), ")".repeat(deep)), 2),
            (format!("{}1.0", "- ".repeat(deep)), 2),
            (
                format!(
                    "1.0;\n#if {}1{}\n#endif",
                    "(".repeat(deep),
                    ")".repeat(deep)
                ),
                3,
            ),
        ] {
            let text = format!(
                "void mainImage(out vec4 c, in vec2 p) {{\n    float x = {nested};\n    \
                 c = vec4(x);\n}}\n"
            );
            let e = compile("deep.glsl", &text).unwrap_err();
            assert_eq!((e.file.as_str(), e.line), ("deep.glsl", line), "{e}");
            assert!(e.message.contains("nested more than 200"), "{e}");
        }
        let fine = format!("{}1.0{}", "(".repeat(100), ")".repeat(100));
        let text = format!("void mainImage(out vec4 c, in vec2 p) {{ c = vec4({fine}); }}\n");
        compile("fine.glsl", &text).unwrap_or_else(|e| panic!("{e}"));
    }

    #[test]
    fn wgsl_params_are_read_with_naga_offsets_and_comment_controls() {
        let compiled = compile("t.wgsl", WGSL).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(compiled.style, Style::Wgsl);
        let specs = &compiled.params.specs;
        let summary: Vec<(&str, u32, usize, &str, f64, u32)> = specs
            .iter()
            .map(|s| {
                (
                    s.name.as_str(),
                    s.offset,
                    s.ty.len,
                    s.control.kind(),
                    s.default[0],
                    s.line,
                )
            })
            .collect();
        assert_eq!(
            summary,
            [
                ("speed", 0, 1, "slider", 0.0, 2),
                ("tint", 16, 3, "color", 1.0, 4),
                ("mode", 28, 1, "select", 1.0, 5),
                ("gain", 32, 1, "log", 1e-4, 6),
                ("show", 36, 1, "checkbox", 0.0, 7),
                ("plain", 40, 2, "drag", 0.0, 8),
            ]
        );
        assert_eq!(
            specs[0].control,
            Control::Slider {
                min: 0.0,
                max: 5.0,
                step: Some(0.1)
            }
        );
        assert_eq!(specs[0].help, "how fast");
        assert_eq!(compiled.params.block_size, 48);
    }

    #[test]
    fn glsl_uniforms_become_params_and_standard_ones_do_not() {
        let text = "\
#ifdef GL_ES
precision mediump float;
#endif
uniform float time;
uniform vec2 resolution;
uniform float speed; // @slider(0, 4) @default(2)
uniform vec3 tint = vec3(1.0, 0.5, -0.25); // @color(linear)
uniform bool flip; // @checkbox
uniform int count = 3;

void main() {
    vec2 uv = gl_FragCoord.xy / resolution;
    if (flip) { uv = 1.0 - uv; }
    gl_FragColor = vec4(tint * uv.x * speed, float(count) + time);
}
";
        let compiled = compile("t.frag", text).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(compiled.style, Style::GlslSandbox);
        let specs = &compiled.params.specs;
        let names: Vec<&str> = specs.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["speed", "tint", "flip", "count"]);
        assert_eq!(specs[0].default[0], 2.0);
        assert_eq!(
            specs[1].default[..3],
            [1.0, 0.5, 0.0],
            "clamped to a colour"
        );
        assert_eq!(specs[2].ty.scalar, Scalar::Bool);
        assert_eq!(specs[2].control, Control::Checkbox);
        assert_eq!(specs[3].default[0], 3.0);
        assert_eq!(specs[3].line, 9);
    }

    #[test]
    fn frame_uniform_offsets_agree_in_every_style() {
        let expected = [
            ("resolution", 0),
            ("time", 12),
            ("mouse", 16),
            ("date", 32),
            ("time_delta", 48),
            ("frame", 52),
            ("frame_rate", 56),
            ("mouse_uv", 64),
        ];
        let shadertoy_names = [
            ("iResolution", "resolution"),
            ("iTime", "time"),
            ("iMouse", "mouse"),
            ("iDate", "date"),
            ("iTimeDelta", "time_delta"),
            ("iFrame", "frame"),
            ("iFrameRate", "frame_rate"),
            ("rsb_mouse_uv", "mouse_uv"),
        ];
        let sandbox_names = [
            ("resolution", "resolution"),
            ("time", "time"),
            ("rsb_mouse_px", "mouse"),
            ("rsb_date", "date"),
            ("rsb_time_delta", "time_delta"),
            ("rsb_frame", "frame"),
            ("rsb_frame_rate", "frame_rate"),
            ("mouse", "mouse_uv"),
        ];
        let sources = [
            ("a.wgsl", WGSL, &[][..]),
            (
                "b.frag",
                "void mainImage(out vec4 c, in vec2 p) { c = vec4(iTime); }",
                &shadertoy_names[..],
            ),
            (
                "c.frag",
                "uniform float time; uniform vec2 mouse, resolution;\n\
                 void main() { gl_FragColor = vec4(time + mouse.x + resolution.x); }",
                &sandbox_names[..],
            ),
        ];
        for (file, text, names) in sources {
            let compiled = compile(file, text).unwrap_or_else(|e| panic!("{e}"));
            let module = &compiled.module;
            let (_, global) = module
                .global_variables
                .iter()
                .find(|(_, g)| g.binding.as_ref().is_some_and(|b| b.binding == 0))
                .unwrap();
            let naga::TypeInner::Struct { members, span } = &module.types[global.ty].inner else {
                panic!("a struct");
            };
            assert_eq!(*span, 80, "{file}");
            for (field, offset) in expected {
                let member_name = names
                    .iter()
                    .find(|(_, f)| *f == field)
                    .map_or(field, |(n, _)| n);
                let member = members
                    .iter()
                    .find(|m| m.name.as_deref() == Some(member_name))
                    .unwrap_or_else(|| panic!("{file}: {member_name}"));
                assert_eq!(member.offset, offset, "{file}: {member_name}");
            }
        }
    }

    fn error(file: &str, text: &str) -> ShaderError {
        compile(file, text).expect_err("an error")
    }

    /// The error of `text` as the file `file`, asserted to be in that file
    /// at `line` and `column`.
    #[track_caller]
    fn error_in(file: &str, text: &str, line: u32, column: u32) -> ShaderError {
        let e = error(file, text);
        assert_eq!(
            (e.file.as_str(), e.line, e.column),
            (file, line, column),
            "{e}"
        );
        e
    }

    #[test]
    fn main_image_defined_through_a_macro_is_shadertoy_style() {
        let text = "#define Main void mainImage(out vec4 Q, vec2 U)\n\
                    Main {\n    Q = vec4(U / iResolution.xy, 0.0, 1.0);\n}\n";
        let compiled = compile("toy.glsl", text).expect("compiles");
        assert_eq!(compiled.style, Style::Shadertoy);
        // A macro that is defined but never used at the top level is not
        // an entry point.
        let unused = error(
            "u.glsl",
            "#define Main void mainImage(out vec4 Q, vec2 U)\nfloat f() { return 1.0; }\n",
        );
        assert!(unused.message.starts_with("neither"), "{unused}");
    }

    #[test]
    fn errors_about_the_whole_file_have_a_line_too() {
        // No entry function: at the end of the file, where it would go.
        let missing = error(
            "m.frag",
            "uniform float time;\nfloat f() {\n    return time;\n}\n\n",
        );
        assert_eq!(
            (missing.file.as_str(), missing.line),
            ("m.frag", 4),
            "{missing}"
        );
        assert_eq!(missing.source_line, "}");
        assert!(
            missing
                .to_string()
                .starts_with("m.frag:4:2: error: neither"),
            "{missing}"
        );
        let wgsl = error("m.wgsl", "fn main() -> f32 {\n    return 1.0;\n}\n");
        assert_eq!((wgsl.file.as_str(), wgsl.line), ("m.wgsl", 3), "{wgsl}");
        // A sandbox macro misused (`gl_FragCoord` as a parameter name): naga
        // places it in the prelude; it is reported at the user's use.
        let misused = error_in(
            "p.frag",
            "uniform vec2 resolution;\nvoid main(gl_FragCoord.xy / resolution) {\n    gl_FragColor = vec4(1.0);\n}\n",
            2,
            11,
        );
        assert!(misused.message.contains("before your file"), "{misused}");
    }

    #[test]
    fn errors_are_at_the_users_line_and_column() {
        // naga finds the missing `;` at `return`; it is reported after `1.0`.
        let wgsl = error_in(
            "w.wgsl",
            "fn main_image(p: vec2<f32>) -> vec4<f32> {\n    let x = 1.0\n    return vec4(x);\n}\n",
            2,
            16,
        );
        assert_eq!(wgsl.source_line, "    let x = 1.0");
        let sandbox = error_in(
            "s.frag",
            "#version 100\nuniform float time;\nvoid main() {\n    gl_FragColor = vec4(time, y, 0.0, 1.0);\n}\n",
            4,
            31,
        );
        assert_eq!(
            sandbox.source_line,
            "    gl_FragColor = vec4(time, y, 0.0, 1.0);"
        );
        let toy = error(
            "t.glsl",
            "// comment\n\nvoid mainImage(out vec4 c, in vec2 p) {\n    c = vec4(iTime)\n}\n",
        );
        assert_eq!((toy.file.as_str(), toy.line), ("t.glsl", 4), "{toy}");
        error_in(
            "a.frag",
            "uniform float a; // @slidr(0, 1)\nvoid main() { gl_FragColor = vec4(a); }\n",
            1,
            21,
        );
        let missing = error("m.wgsl", "fn f() {}\n");
        assert!(missing.message.contains("main_image"), "{missing}");
        let bool_field = error(
            "b.wgsl",
            "struct Params {\n    on: bool,\n}\nfn main_image(p: vec2<f32>) -> vec4<f32> { return vec4(1.0); }\n",
        );
        assert_eq!(bool_field.line, 2, "{bool_field}");
        let sampler = error(
            "x.frag",
            "uniform sampler2DArray sky;\nvoid main() { gl_FragColor = vec4(1.0); }\n",
        );
        assert_eq!(sampler.line, 1, "{sampler}");
    }

    #[test]
    fn glsl_es3_output_and_layout_are_rewritten() {
        let text = "#version 300 es\nprecision highp float;\nuniform vec2 resolution;\nout vec4 color;\nvoid main() { color = vec4(gl_FragCoord.xy / resolution, 0.0, 1.0); }\n";
        compile("es3.frag", text).unwrap_or_else(|e| panic!("{e}"));
    }
}
