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

use std::fmt::Write as _;
use std::path::Path;

use super::params::{self, ParamSet, ParamSpec, ParamType, Scalar};
use super::scan::{self, Kind, Scan, Token};
use super::uniforms::WGSL_STRUCT;
use super::{gaps, repair};
use crate::gpu::{ShaderError, ShaderSource};

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
}

impl Style {
    pub fn describe(&self) -> &'static str {
        match self {
            Style::Wgsl => "WGSL",
            Style::GlslSandbox => "GLSL (GLSL Sandbox style)",
            Style::Shadertoy => "GLSL (Shadertoy style)",
        }
    }
}

/// The name errors give the program's code before the user's file.
pub const PRELUDE_NAME: &str = "<sandbox prelude>";
/// The name errors give the program's code after the user's file.
pub const EPILOGUE_NAME: &str = "<sandbox epilogue>";

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
}

/// Reads and compiles a shader file. Unreadable files are errors too, named
/// like compile errors.
pub fn compile_file(path: &Path) -> Result<Compiled, ShaderError> {
    let name = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| ShaderError {
        file: name.clone(),
        line: 0,
        column: 0,
        message: format!("cannot read the file: {e}"),
        source_line: String::new(),
        label: String::new(),
    })?;
    compile(&name, &text)
}

/// Compiles the text of a shader file called `name` (its extension, if any,
/// tells the language: `.wgsl` is WGSL, `.glsl`, `.frag`, `.fs`, `.fsh` are
/// GLSL; otherwise the text decides).
pub fn compile(name: &str, text: &str) -> Result<Compiled, ShaderError> {
    let scan = Scan::new(text);
    let extension = Path::new(name)
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let wgsl = match extension.as_deref() {
        Some("wgsl") => true,
        Some("glsl" | "frag" | "fs" | "fsh" | "fragment") => false,
        _ => scan.tokens.iter().any(|t| t.is("fn")),
    };
    let result = if wgsl {
        compile_wgsl(name, text, &scan)
    } else {
        let mut scan = Scan::new(text);
        scan.drop_inactive_branches(GLSL_DEFINES);
        compile_glsl(name, &scan)
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
    let mut depth = 0i32;
    for (i, t) in tokens.iter().enumerate() {
        match t.text {
            "{" => depth += 1,
            "}" => depth -= 1,
            _ => {}
        }
        if depth == 0 && t.is(a) && tokens.get(i + 1).is_some_and(|n| n.is(b)) {
            return Some(i);
        }
    }
    None
}

// ---------------------------------------------------------------- WGSL ----

/// A field of the user's `struct Params`, as found in the text.
struct Field {
    name: String,
    /// Byte offset of the name in the user's text.
    offset: usize,
}

fn wgsl_prelude() -> String {
    format!(
        "// raysandbox WGSL prelude: the values every sandbox shader can read.\n\
         {WGSL_STRUCT}\
         @group(0) @binding(0) var<uniform> u: Uniforms;\n\
         {WGSL_TEXTURES}"
    )
}

/// The textures of the WGSL prelude (docs/sandbox.md, "Textures"): the four
/// channels, their sampler and the previous frame.
const WGSL_TEXTURES: &str = "\
@group(0) @binding(2) var channel0: texture_2d<f32>;
@group(0) @binding(3) var channel1: texture_2d<f32>;
@group(0) @binding(4) var channel2: texture_2d<f32>;
@group(0) @binding(5) var channel3: texture_2d<f32>;
@group(0) @binding(6) var channel_sampler: sampler;
@group(0) @binding(7) var backbuffer: texture_2d<f32>;
";

fn wgsl_epilogue(has_params: bool) -> String {
    let mut text = String::from("// raysandbox WGSL epilogue\n");
    if has_params {
        text.push_str("@group(0) @binding(1) var<uniform> params: Params;\n");
    }
    let _ = write!(
        text,
        "@fragment\n\
         fn {WGSL_ENTRY}(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{\n\
         \x20   // Shadertoy's convention: pixel centres at +0.5, y up.\n\
         \x20   return main_image(vec2<f32>(position.x, u.resolution.y - position.y));\n\
         }}\n"
    );
    text
}

fn compile_wgsl(name: &str, text: &str, scan: &Scan) -> Result<Compiled, ShaderError> {
    let tokens = &scan.tokens;
    if find_pair(tokens, "fn", "main_image").is_none() {
        return Err(at_end_of_file(
            name,
            scan,
            "no `fn main_image(frag_coord: vec2<f32>) -> vec4<f32>` in this WGSL file: \
             the sandbox calls it for every pixel (see docs/sandbox.md)"
                .into(),
        ));
    }
    let fields = match find_pair(tokens, "struct", "Params") {
        Some(i) => Some(wgsl_params_fields(name, scan, i + 2)?),
        None => None,
    };
    let source = ShaderSource::from_parts([
        (PRELUDE_NAME.to_string(), wgsl_prelude()),
        (name.to_string(), text.to_string()),
        (EPILOGUE_NAME.to_string(), wgsl_epilogue(fields.is_some())),
    ]);
    let (module, info) = source.validate()?;
    source.check_translation(&module, &info)?;
    let params = match &fields {
        Some(fields) => read_params(&module, name, scan, |member| {
            let field = fields.iter().find(|f| f.name == member)?;
            Some((field.offset, None))
        })?,
        None => ParamSet::default(),
    };
    Ok(Compiled {
        style: Style::Wgsl,
        file: name.to_string(),
        source,
        module,
        entry_point: WGSL_ENTRY,
        params,
        reads_backbuffer: tokens.iter().any(|t| t.is("backbuffer")),
    })
}

/// The fields of `struct Params { ... }`, whose `{` is at token `open`.
fn wgsl_params_fields(name: &str, scan: &Scan, open: usize) -> Result<Vec<Field>, ShaderError> {
    let tokens = &scan.tokens;
    if !tokens.get(open).is_some_and(|t| t.is("{")) {
        return Ok(Vec::new());
    }
    let mut fields = Vec::new();
    let mut i = open + 1;
    while i < tokens.len() && !tokens[i].is("}") {
        // Attributes such as @align(16) or @size(32).
        while tokens[i].is("@") {
            i += 2;
            if tokens.get(i).is_some_and(|t| t.is("(")) {
                while i < tokens.len() && !tokens[i].is(")") {
                    i += 1;
                }
                i += 1;
            }
        }
        let Some(field_name) = tokens.get(i).filter(|t| t.kind == Kind::Ident) else {
            break;
        };
        if !tokens.get(i + 1).is_some_and(|t| t.is(":")) {
            break;
        }
        i += 2;
        let type_start = i;
        let mut angle = 0;
        while i < tokens.len() {
            let t = &tokens[i];
            match t.text {
                "<" => angle += 1,
                ">" => angle -= 1,
                "," | "}" if angle == 0 => break,
                _ => {}
            }
            i += 1;
        }
        let type_text: String = tokens[type_start..i].iter().map(|t| t.text).collect();
        if type_text.contains("bool") {
            return Err(error_at(
                name,
                scan,
                field_name.start,
                format!(
                    "`{}: {type_text}`: a bool cannot be in a uniform buffer; \
                     use u32 (0 or 1) with // @checkbox",
                    field_name.text
                ),
            ));
        }
        fields.push(Field {
            name: field_name.text.to_string(),
            offset: field_name.start,
        });
        if tokens.get(i).is_some_and(|t| t.is(",")) {
            i += 1;
        }
    }
    Ok(fields)
}

/// The parameters of the uniform block at `@group(0) @binding(1)`: naga's
/// layout, the annotations found for each member by `lookup` (byte offset of
/// the declaration in the user's text and an initializer).
fn read_params(
    module: &naga::Module,
    name: &str,
    scan: &Scan,
    lookup: impl Fn(&str) -> Option<(usize, Option<Vec<f64>>)>,
) -> Result<ParamSet, ShaderError> {
    let Some(global) = module.global_variables.iter().find(|(_, g)| {
        g.space == naga::AddressSpace::Uniform
            && g.binding
                == Some(naga::ResourceBinding {
                    group: 0,
                    binding: 1,
                })
    }) else {
        return Ok(ParamSet::default());
    };
    let naga::TypeInner::Struct { members, span } = &module.types[global.1.ty].inner else {
        return Ok(ParamSet::default());
    };
    let mut specs = Vec::new();
    for member in members {
        let Some(member_name) = &member.name else {
            continue;
        };
        let (shown_name, bool_int) = match member_name.strip_prefix(GLSL_BOOL_PREFIX) {
            Some(n) => (n, true),
            None => (member_name.as_str(), false),
        };
        let Some((offset, initializer)) = lookup(shown_name) else {
            continue;
        };
        let line = scan.line_of(offset);
        let annotation = params::parse_annotation(&scan.comments_for_line(line))
            .map_err(|(at, message)| error_at(name, scan, at, message))?;
        let mut ty = param_type(&module.types[member.ty].inner);
        if bool_int {
            ty = Ok(ParamType {
                scalar: Scalar::Bool,
                len: 1,
            });
        }
        let spec = ParamSpec::new(shown_name, ty, member.offset, annotation, initializer, line)
            .map_err(|message| error_at(name, scan, offset, message))?;
        specs.push(spec);
    }
    Ok(ParamSet::new(specs, *span))
}

fn param_type(inner: &naga::TypeInner) -> Result<ParamType, String> {
    let scalar = |s: &naga::Scalar| match (s.kind, s.width) {
        (naga::ScalarKind::Float, 4) => Some(Scalar::F32),
        (naga::ScalarKind::Sint, 4) => Some(Scalar::I32),
        (naga::ScalarKind::Uint, 4) => Some(Scalar::U32),
        _ => None,
    };
    let found = match inner {
        naga::TypeInner::Scalar(s) => scalar(s).map(|scalar| ParamType { scalar, len: 1 }),
        naga::TypeInner::Vector { size, scalar: s } => scalar(s).map(|scalar| ParamType {
            scalar,
            len: *size as usize,
        }),
        _ => None,
    };
    found.ok_or_else(|| match inner {
        naga::TypeInner::Matrix { columns, rows, .. } => {
            format!("mat{}x{}", *columns as u8, *rows as u8)
        }
        naga::TypeInner::Array { .. } => "an array".to_string(),
        naga::TypeInner::Struct { .. } => "a struct".to_string(),
        _ => "this type".to_string(),
    })
}

// ---------------------------------------------------------------- GLSL ----

/// Prefix of the int member that stores a GLSL `bool` parameter.
const GLSL_BOOL_PREFIX: &str = "rsb_bool_";

/// A `uniform` declaration at the top level of the user's GLSL.
struct UniformDecl<'a> {
    /// The type as written, with `[N]` for an array (`vec3[4]`).
    type_name: String,
    name: &'a str,
    /// Byte offset of the name in the user's text.
    offset: usize,
    initializer: Option<Vec<f64>>,
}

/// The standard uniforms of a style: (name, GLSL type). The members of the
/// frame block, in order, are given by [`glsl_frame_block`].
fn standard_uniforms(style: Style) -> &'static [(&'static str, &'static str)] {
    match style {
        Style::Shadertoy => &[
            ("iResolution", "vec3"),
            ("iTime", "float"),
            ("iTimeDelta", "float"),
            ("iFrame", "int"),
            ("iFrameRate", "float"),
            ("iMouse", "vec4"),
            ("iDate", "vec4"),
            ("iGlobalTime", "float"),
            ("iSampleRate", "float"),
            ("iChannelTime", "float[4]"),
            ("iChannelResolution", "vec3[4]"),
            ("iChannel0", "sampler2D"),
            ("iChannel1", "sampler2D"),
            ("iChannel2", "sampler2D"),
            ("iChannel3", "sampler2D"),
        ],
        _ => &[
            ("time", "float"),
            ("mouse", "vec2"),
            ("resolution", "vec2"),
            ("surfaceSize", "vec2"),
        ],
    }
}

/// The GLSL declaration of the frame uniforms for `style`. In the GLSL
/// Sandbox style a standard name is only given to the members the user
/// declared (as on glslsandbox.com, where you declare what you use); the
/// others get an `rsb_` name, so they cannot clash with the user's names.
fn glsl_frame_block(style: Style, declared: &[&str]) -> String {
    let members: Vec<(&str, String)> = if style == Style::Shadertoy {
        [
            ("vec3", "iResolution"),
            ("float", "iTime"),
            ("vec4", "iMouse"),
            ("vec4", "iDate"),
            ("float", "iTimeDelta"),
            ("int", "iFrame"),
            ("float", "iFrameRate"),
            ("float", "rsb_surface_height"),
            ("vec2", "rsb_mouse_uv"),
            ("vec2", "rsb_surface_center"),
        ]
        .iter()
        .map(|(t, n)| (*t, n.to_string()))
        .collect()
    } else {
        let named = |standard: &str| {
            if declared.contains(&standard) {
                standard.to_string()
            } else {
                format!("rsb_{standard}")
            }
        };
        vec![
            ("vec2", named("resolution")),
            ("float", "rsb_pixel_aspect".into()),
            ("float", named("time")),
            ("vec4", "rsb_mouse_px".into()),
            ("vec4", "rsb_date".into()),
            ("float", "rsb_time_delta".into()),
            ("int", "rsb_frame".into()),
            ("float", "rsb_frame_rate".into()),
            ("float", "rsb_surface_height".into()),
            ("vec2", named("mouse")),
            ("vec2", "rsb_surface_center".into()),
        ]
    };
    let mut text = String::from("layout(set = 0, binding = 0) uniform RsbFrame {\n");
    for (t, n) in &members {
        let _ = writeln!(text, "    {t} {n};");
    }
    text.push_str("};\n");
    text
}

/// `mat2` .. `mat4`, `mat2x3`, ...: a uniform that cannot be a parameter
/// (the panel has no control for it), zero as WebGL leaves it.
fn is_matrix(type_name: &str) -> bool {
    let Some(size) = type_name.strip_prefix("mat") else {
        return false;
    };
    let sizes = [
        "2", "3", "4", "2x2", "2x3", "2x4", "3x2", "3x3", "3x4", "4x2", "4x3", "4x4",
    ];
    sizes.contains(&size)
}

/// GLSL types a parameter may have.
fn glsl_param_type(type_name: &str) -> Option<&'static str> {
    Some(match type_name {
        "float" => "float",
        "int" => "int",
        "uint" => "uint",
        "bool" => "bool",
        "vec2" => "vec2",
        "vec3" => "vec3",
        "vec4" => "vec4",
        "ivec2" => "ivec2",
        "ivec3" => "ivec3",
        "ivec4" => "ivec4",
        "uvec2" => "uvec2",
        "uvec3" => "uvec3",
        "uvec4" => "uvec4",
        _ => return None,
    })
}

const PRECISION: [&str; 3] = ["lowp", "mediump", "highp"];

/// The rewritten user text and what the rewrite found.
struct GlslRewrite<'a> {
    text: String,
    uniforms: Vec<UniformDecl<'a>>,
    /// The name of a user-declared `out vec4 NAME;` (GLSL ES 3.0 style).
    output: Option<&'a str>,
    /// `varying vec2 surfacePosition;` was declared (and blanked).
    surface_position: bool,
}

fn rewrite_glsl<'a>(name: &str, scan: &Scan<'a>) -> Result<GlslRewrite<'a>, ShaderError> {
    let tokens = &scan.tokens;
    let mut text = scan.text.to_string();
    let mut uniforms = Vec::new();
    let mut output = None;
    let mut surface_position = false;
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
                        name: n.text,
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
                if let Some(v) = params::parse_number(n) {
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

/// Macros defined before the user's GLSL, as WebGL defines them: shaders
/// written `#ifdef GL_ES precision mediump float; #endif` expect it.
const GLSL_DEFINES: &[&str] = &["GL_ES"];

/// Shadertoy's names from before 2017, defined when the file uses them:
/// `iGlobalTime` (now `iTime`), `iChannelTime` (each channel's playback
/// time: the clock, as channels here are still images), `iSampleRate`.
fn old_shadertoy_names(used: &dyn Fn(&str) -> bool) -> String {
    let mut text = String::new();
    if used("iGlobalTime") {
        text.push_str("#define iGlobalTime iTime\n");
    }
    if used("iChannelTime") {
        text.push_str(
            "float[4] rsb_channel_time() { return float[4](iTime, iTime, iTime, iTime); }\n\
             #define iChannelTime rsb_channel_time()\n",
        );
    }
    if used("iSampleRate") {
        text.push_str("#define iSampleRate 44100.0\n");
    }
    text
}

/// The textures of the GLSL preludes (docs/sandbox.md, "Textures"). naga
/// reads Vulkan GLSL, where a `sampler2D` is not a variable but a
/// constructor joining a `texture2D` and a `sampler`; the names the user's
/// file reads are `#define`d as such constructors.
const GLSL_TEXTURES: &str = "\
layout(set = 0, binding = 2) uniform texture2D rsb_channel0;
layout(set = 0, binding = 3) uniform texture2D rsb_channel1;
layout(set = 0, binding = 4) uniform texture2D rsb_channel2;
layout(set = 0, binding = 5) uniform texture2D rsb_channel3;
layout(set = 0, binding = 6) uniform sampler rsb_sampler;
layout(set = 0, binding = 7) uniform texture2D rsb_backbuffer;
";

/// Channels are numbered 0 to 3.
const CHANNELS: usize = 4;

/// `#define`s for the `uniform sampler2D` names the file declared: GLSL
/// Sandbox's `backbuffer` is the previous frame, Shadertoy's `iChannelN`
/// channel N, and any other name the next channel in the order declared.
fn glsl_texture_names(
    name: &str,
    scan: &Scan,
    style: Style,
    uniforms: &[UniformDecl],
    textures: &[&str],
) -> Result<String, ShaderError> {
    let mut text = String::new();
    let mut next = 0;
    for texture in textures {
        if style == Style::GlslSandbox && *texture == "backbuffer" {
            text.push_str("#define backbuffer sampler2D(rsb_backbuffer, rsb_sampler)\n");
            continue;
        }
        if next == CHANNELS {
            let decl = uniforms
                .iter()
                .find(|d| d.name == *texture)
                .expect("declared");
            return Err(error_at(
                name,
                scan,
                decl.offset,
                format!("`{texture}`: at most {CHANNELS} textures (channels 0 to 3)"),
            ));
        }
        // The front-end gaps rename a variable called `texture`.
        let renamed = if *texture == "texture" {
            "rsb_texture"
        } else {
            texture
        };
        let _ = writeln!(
            text,
            "#define {renamed} sampler2D(rsb_channel{next}, rsb_sampler)"
        );
        next += 1;
    }
    Ok(text)
}

/// Shadertoy's channels where the file reads them: `iChannel0..3` and
/// `iChannelResolution[4]` (each channel's size in pixels, z = 1).
fn shadertoy_channels(used: &dyn Fn(&str) -> bool) -> String {
    let mut text = String::new();
    for k in 0..CHANNELS {
        if used(&format!("iChannel{k}")) {
            let _ = writeln!(
                text,
                "#define iChannel{k} sampler2D(rsb_channel{k}, rsb_sampler)"
            );
        }
    }
    if used("iChannelResolution") {
        let size =
            |k| format!("vec3(vec2(textureSize(sampler2D(rsb_channel{k}, rsb_sampler), 0)), 1.0)");
        let _ = write!(
            text,
            "vec3[4] rsb_channel_resolution() {{\n\
             \x20   return vec3[4]({}, {}, {}, {});\n\
             }}\n\
             #define iChannelResolution rsb_channel_resolution()\n",
            size(0),
            size(1),
            size(2),
            size(3)
        );
    }
    text
}

/// GLSL Sandbox's `surfacePosition` (the pixel's point on a plane the
/// viewer pans and zooms, y up) and `surfaceSize` (the size of the part
/// shown), where the file declares them. glslsandbox.com interpolates the
/// corners of that rectangle over the screen; so does this, per pixel.
fn glsl_sandbox_surface(resolution: &str, position: bool, size: bool) -> String {
    if !position && !size {
        return String::new();
    }
    let mut text = format!(
        "vec2 rsb_surface_size() {{\n\
         \x20   return vec2(rsb_surface_height * {resolution}.x / {resolution}.y, rsb_surface_height);\n\
         }}\n"
    );
    if size {
        text.push_str("#define surfaceSize rsb_surface_size()\n");
    }
    if position {
        let _ = write!(
            text,
            "vec2 rsb_surface_position() {{\n\
             \x20   return rsb_surface_center + (rsb_frag_coord().xy / {resolution} - 0.5) * rsb_surface_size();\n\
             }}\n\
             #define surfacePosition rsb_surface_position()\n"
        );
    }
    text
}

fn compile_glsl(name: &str, scan: &Scan) -> Result<Compiled, ShaderError> {
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
    let user_main = find_pair(tokens, "main", "(").is_some();
    let sandbox_port = user_main && declares_uniform(tokens, &["time", "resolution", "mouse"]);
    let style = if find_pair(tokens, "mainImage", "(").is_some() && !sandbox_port {
        Style::Shadertoy
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
    for decl in &rewrite.uniforms {
        match standard.iter().find(|(n, _)| *n == decl.name) {
            Some((n, t)) if *t == decl.type_name => declared.push(*n),
            // `uniform vec4 mouse;`: the pointer in xy, zw zero.
            Some(("mouse", _)) if ["vec3", "vec4"].contains(&decl.type_name.as_str()) => {
                zero.push(format!(
                    "#define mouse {}(rsb_mouse, {})\n",
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
            None if decl.type_name == "sampler2D" => textures.push(decl.name),
            None if is_matrix(&decl.type_name) => zero.push(format!(
                "const {0} {1} = {0}(0.0);\n",
                decl.type_name, decl.name
            )),
            None => match glsl_param_type(&decl.type_name) {
                Some(_) => user_params.push(decl),
                None => {
                    return Err(error_at(
                        name,
                        scan,
                        decl.offset,
                        format!(
                            "uniform `{}`: a {} cannot be a parameter here (no matrices, \
                             the only textures are sampler2D); use float, int, uint, bool \
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
    let reads_backbuffer = style == Style::GlslSandbox && textures.contains(&"backbuffer");
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
        _ if declared.contains(&"resolution") => "resolution",
        _ => "rsb_resolution",
    };
    let _ = write!(
        prelude,
        "layout(location = 0) out vec4 rsb_frag_color;\n\
         // Shadertoy's and GLSL Sandbox's convention: y up (Vulkan's gl_FragCoord is y down).\n\
         vec4 rsb_frag_coord() {{\n\
         \x20   return vec4(gl_FragCoord.x, {resolution}.y - gl_FragCoord.y, gl_FragCoord.z, gl_FragCoord.w);\n\
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
            prelude.push_str(&shadertoy_channels(&used));
        }
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
        _ => String::new(),
    };
    let bridged = gaps::bridge(scan, rewrite.text);
    if bridged.uses_mat2 {
        prelude.push_str(gaps::MAT2_OVERLOADS);
    }
    if bridged.uses_dot {
        prelude.push_str(gaps::DOT_OVERLOADS);
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
    let mut module = source
        .parse_glsl_fragment(GLSL_DEFINES)
        .map_err(at_users_column)?;
    repair::define_before_use(&mut module);
    repair::spill_pointer_arguments(&mut module);
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
        reads_backbuffer,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sandbox::params::Control;

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
        let misused = error(
            "p.frag",
            "uniform vec2 resolution;\nvoid main(gl_FragCoord.xy / resolution) {\n    gl_FragColor = vec4(1.0);\n}\n",
        );
        assert_eq!(
            (misused.file.as_str(), misused.line, misused.column),
            ("p.frag", 2, 11),
            "{misused}"
        );
        assert!(misused.message.contains("before your file"), "{misused}");
    }

    #[test]
    fn errors_are_at_the_users_line_and_column() {
        let wgsl = error(
            "w.wgsl",
            "fn main_image(p: vec2<f32>) -> vec4<f32> {\n    let x = 1.0\n    return vec4(x);\n}\n",
        );
        // naga finds the missing `;` at `return`; it is reported after `1.0`.
        assert_eq!(
            (wgsl.file.as_str(), wgsl.line, wgsl.column),
            ("w.wgsl", 2, 16),
            "{wgsl}"
        );
        assert_eq!(wgsl.source_line, "    let x = 1.0");
        let sandbox = error(
            "s.frag",
            "#version 100\nuniform float time;\nvoid main() {\n    gl_FragColor = vec4(time, y, 0.0, 1.0);\n}\n",
        );
        assert_eq!(
            (sandbox.file.as_str(), sandbox.line, sandbox.column),
            ("s.frag", 4, 31),
            "{sandbox}"
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
        let annotation = error(
            "a.frag",
            "uniform float a; // @slidr(0, 1)\nvoid main() { gl_FragColor = vec4(a); }\n",
        );
        assert_eq!(
            (annotation.line, annotation.column),
            (1, 21),
            "{annotation}"
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
            "uniform samplerCube sky;\nvoid main() { gl_FragColor = vec4(1.0); }\n",
        );
        assert_eq!(sampler.line, 1, "{sampler}");
    }

    #[test]
    fn glsl_es3_output_and_layout_are_rewritten() {
        let text = "#version 300 es\nprecision highp float;\nuniform vec2 resolution;\nout vec4 color;\nvoid main() { color = vec4(gl_FragCoord.xy / resolution, 0.0, 1.0); }\n";
        compile("es3.frag", text).unwrap_or_else(|e| panic!("{e}"));
    }
}
