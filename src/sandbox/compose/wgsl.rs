//! WGSL files: the prelude of the frame uniforms and textures, the epilogue
//! that calls `main_image`, and the user's `struct Params` (docs/sandbox.md,
//! "The WGSL prelude and epilogue").

use std::fmt::Write as _;

use super::param_block::read_params;
use super::{
    Compiled, EPILOGUE_NAME, PRELUDE_NAME, Style, WGSL_ENTRY, at_end_of_file, error_at, find_pair,
};
use crate::gpu::{ShaderError, ShaderSource};
use crate::sandbox::uniforms;
use crate::shader_params::ParamSet;
use crate::shader_params::scan::{Kind, Scan};

/// A field of the user's `struct Params`, as found in the text.
struct Field {
    name: String,
    /// Byte offset of the name in the user's text.
    offset: usize,
}

fn wgsl_prelude() -> String {
    format!(
        "// raysandbox WGSL prelude: the values every sandbox shader can read.\n\
         {}\
         @group(0) @binding(0) var<uniform> u: Uniforms;\n\
         {WGSL_TEXTURES}",
        uniforms::wgsl_struct()
    )
}

/// The textures of the WGSL prelude (docs/sandbox.md, "Textures", "Cube
/// maps and volumes"): the four channels, their sampler, the previous
/// frame, and each channel as a cube map and as a volume.
const WGSL_TEXTURES: &str = "\
@group(0) @binding(2) var channel0: texture_2d<f32>;
@group(0) @binding(3) var channel1: texture_2d<f32>;
@group(0) @binding(4) var channel2: texture_2d<f32>;
@group(0) @binding(5) var channel3: texture_2d<f32>;
@group(0) @binding(6) var channel_sampler: sampler;
@group(0) @binding(7) var backbuffer: texture_2d<f32>;
@group(0) @binding(8) var channel0_cube: texture_cube<f32>;
@group(0) @binding(9) var channel1_cube: texture_cube<f32>;
@group(0) @binding(10) var channel2_cube: texture_cube<f32>;
@group(0) @binding(11) var channel3_cube: texture_cube<f32>;
@group(0) @binding(12) var channel0_volume: texture_3d<f32>;
@group(0) @binding(13) var channel1_volume: texture_3d<f32>;
@group(0) @binding(14) var channel2_volume: texture_3d<f32>;
@group(0) @binding(15) var channel3_volume: texture_3d<f32>;
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

pub(super) fn compile_wgsl(name: &str, text: &str, scan: &Scan) -> Result<Compiled, ShaderError> {
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
        includes: Vec::new(),
        warnings: Vec::new(),
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
