//! The pieces of the GLSL preludes (docs/sandbox.md, "The GLSL rewrite",
//! "Textures"): the frame block of each style, the texture names, the
//! Shadertoy names of before 2017, GLSL Sandbox's surface.

use std::fmt::Write as _;

use super::glsl_decls::UniformDecl;
use super::glslviewer;
use super::{CHANNELS, Style, error_at};
use crate::gpu::ShaderError;
use crate::sandbox::channels_3d::{ChannelKind, ChannelKinds};
use crate::sandbox::gaps;
use crate::sandbox::uniforms::FrameUniforms;
use crate::shader_params::scan::Scan;

/// The standard uniforms of a style: (name, GLSL type). The members of the
/// frame block, in order, are given by [`glsl_frame_block`].
pub(super) fn standard_uniforms(style: Style) -> &'static [(&'static str, &'static str)] {
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
        Style::GlslViewer => glslviewer::UNIFORMS,
        _ => &[
            ("time", "float"),
            ("mouse", "vec2"),
            ("resolution", "vec2"),
            ("surfaceSize", "vec2"),
        ],
    }
}

/// The GLSL declaration of the frame uniforms for `style`. In the GLSL
/// Sandbox and glslViewer styles a standard name is only given to the
/// members the user declared (as on glslsandbox.com, where you declare what
/// you use); the others get an `rsb_` name, so they cannot clash with the
/// user's names.
pub(super) fn glsl_frame_block(style: Style, declared: &[&str]) -> String {
    // The name a style gives a slot of the block, if it has one.
    let conventional = |slot: &str| match style {
        Style::GlslViewer => glslviewer::slot_name(slot),
        _ => ["resolution", "time", "mouse"]
            .into_iter()
            .find(|&name| name == slot),
    };
    let mut text = String::from("layout(set = 0, binding = 0) uniform RsbFrame {\n");
    for field in FrameUniforms::FIELDS {
        let (glsl, name) = match (style, field.shadertoy) {
            (Style::Shadertoy, None) => continue,
            (Style::Shadertoy, Some((glsl, name))) => (glsl, name.to_string()),
            _ => match conventional(field.slot) {
                Some(name) if declared.contains(&name) => (field.glsl, name.to_string()),
                _ => (field.glsl, format!("rsb_{}", field.slot)),
            },
        };
        let _ = writeln!(text, "    {glsl} {name};");
    }
    text.push_str("};\n");
    text
}

/// `mat2` .. `mat4`, `mat2x3`, ...: a uniform that cannot be a parameter
/// (the panel has no control for it), zero as WebGL leaves it.
pub(super) fn is_matrix(type_name: &str) -> bool {
    let Some(size) = type_name.strip_prefix("mat") else {
        return false;
    };
    let sizes = [
        "2", "3", "4", "2x2", "2x3", "2x4", "3x2", "3x3", "3x4", "4x2", "4x3", "4x4",
    ];
    sizes.contains(&size)
}

/// GLSL types a parameter may have.
pub(super) fn glsl_param_type(type_name: &str) -> Option<&'static str> {
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

/// Shadertoy's names from before 2017, defined when the file uses them:
/// `iGlobalTime` (now `iTime`), `iChannelTime` (each channel's playback
/// time: the clock, as channels here are still images), `iSampleRate`.
pub(super) fn old_shadertoy_names(used: &dyn Fn(&str) -> bool) -> String {
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
pub(super) const GLSL_TEXTURES: &str = "\
layout(set = 0, binding = 2) uniform texture2D rsb_channel0;
layout(set = 0, binding = 3) uniform texture2D rsb_channel1;
layout(set = 0, binding = 4) uniform texture2D rsb_channel2;
layout(set = 0, binding = 5) uniform texture2D rsb_channel3;
layout(set = 0, binding = 6) uniform sampler rsb_linear_sampler;
layout(set = 0, binding = 7) uniform texture2D rsb_backbuffer;
layout(set = 0, binding = 8) uniform textureCube rsb_cube0;
layout(set = 0, binding = 9) uniform textureCube rsb_cube1;
layout(set = 0, binding = 10) uniform textureCube rsb_cube2;
layout(set = 0, binding = 11) uniform textureCube rsb_cube3;
layout(set = 0, binding = 12) uniform texture3D rsb_volume0;
layout(set = 0, binding = 13) uniform texture3D rsb_volume1;
layout(set = 0, binding = 14) uniform texture3D rsb_volume2;
layout(set = 0, binding = 15) uniform texture3D rsb_volume3;
";

/// The kind of channel a GLSL sampler type reads (docs/sandbox.md, "Cube
/// maps and volumes").
pub(super) fn sampler_kind(type_name: &str) -> Option<ChannelKind> {
    match type_name {
        "sampler2D" => Some(ChannelKind::Flat),
        "samplerCube" => Some(ChannelKind::Cube),
        "sampler3D" => Some(ChannelKind::Volume),
        _ => None,
    }
}

/// Channel `k` as a GLSL sampler of `kind`: the prelude's texture of that
/// kind joined with its sampler, as naga's Vulkan GLSL makes one.
fn channel_sampler(k: usize, kind: ChannelKind) -> String {
    match kind {
        ChannelKind::Flat => format!("sampler2D(rsb_channel{k}, rsb_linear_sampler)"),
        ChannelKind::Cube => format!("samplerCube(rsb_cube{k}, rsb_linear_sampler)"),
        ChannelKind::Volume => format!("sampler3D(rsb_volume{k}, rsb_linear_sampler)"),
    }
}

/// `#define`s for the `uniform sampler2D` names the file declared: GLSL
/// Sandbox's `backbuffer` is the previous frame, Shadertoy's `iChannelN`
/// and glslViewer's `u_texN` channel N, and any other name the next free
/// channel in the order declared. A `samplerCube` or `sampler3D` reads
/// its channel as a cube map or a volume.
pub(super) fn glsl_texture_names(
    name: &str,
    scan: &Scan,
    style: Style,
    uniforms: &[UniformDecl],
    textures: &[(&str, ChannelKind)],
) -> Result<String, ShaderError> {
    let mut text = String::new();
    let numbered = |texture: &str| match style {
        Style::GlslViewer => glslviewer::texture_channel(texture),
        _ => None,
    };
    let mut taken: Vec<usize> = textures.iter().filter_map(|(t, _)| numbered(t)).collect();
    for (texture, kind) in textures {
        if style == Style::GlslSandbox && *texture == "backbuffer" {
            text.push_str("#define backbuffer sampler2D(rsb_backbuffer, rsb_linear_sampler)\n");
            continue;
        }
        let free = (0..CHANNELS).find(|k| !taken.contains(k));
        let Some(channel) = numbered(texture).or(free) else {
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
        };
        // The front-end gaps rename a variable called `texture` or `buffer`.
        let renamed = gaps::declared_name(texture);
        let _ = writeln!(
            text,
            "#define {renamed} {}",
            channel_sampler(channel, *kind)
        );
        if numbered(texture).is_none() {
            taken.push(channel);
        }
    }
    Ok(text)
}

/// Shadertoy's channels where the file reads them: `iChannel0..3`, each a
/// sampler of its kind, and `iChannelResolution[4]` (each channel's size in
/// pixels: z = 1 for a 2-D image or a cube map's face, the depth of a
/// volume).
pub(super) fn shadertoy_channels(used: &dyn Fn(&str) -> bool, kinds: &ChannelKinds) -> String {
    let mut text = String::new();
    for (k, kind) in kinds.iter().enumerate() {
        if used(&format!("iChannel{k}")) {
            let _ = writeln!(text, "#define iChannel{k} {}", channel_sampler(k, *kind));
        }
    }
    if used("iChannelResolution") {
        let size = |k: usize| {
            let sampler = channel_sampler(k, kinds[k]);
            match kinds[k] {
                ChannelKind::Volume => format!("vec3(textureSize({sampler}, 0))"),
                _ => format!("vec3(vec2(textureSize({sampler}, 0)), 1.0)"),
            }
        };
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
/// `surfacePosition` is a variable, as the site's varying is, which
/// [`SURFACE_EPILOGUE`] sets before it calls the file's `main`: a file may
/// then declare a local of that name made from it (`vec2 surfacePosition
/// = surfacePosition * 2.0;`) or a macro that uses it in its own body.
pub(super) fn glsl_sandbox_surface(resolution: &str, position: bool, size: bool) -> String {
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
             vec2 surfacePosition;\n\
             #define main rsb_user_main\n"
        );
    }
    text
}

/// After a GLSL Sandbox file that reads `surfacePosition`: the entry point,
/// which sets it and calls the file's `main` (renamed by the prelude); a
/// macro of the file's named `surfacePosition` is left behind first.
pub(super) const SURFACE_EPILOGUE: &str = "\n// raysandbox epilogue (surfacePosition)\n\
     #undef main\n\
     #undef surfacePosition\n\
     void main() {\n\
     \x20   surfacePosition = rsb_surface_position();\n\
     \x20   rsb_user_main();\n\
     }\n";
