//! glslViewer's and The Book of Shaders' conventions (docs/sandbox.md,
//! "glslViewer and The Book of Shaders"): a GLSL file with `void main()`
//! that reads `u_time`, `u_resolution`, `u_mouse`, ..., and `u_tex0` with
//! `u_tex0Resolution`. The values are the frame block's, under these names.

use std::fmt::Write as _;

use super::CHANNELS;
use crate::shader_params::scan::Token;

/// The uniforms glslViewer sets (name, GLSL type), other than the textures
/// `u_tex0..3` (see [`texture_channel`]).
pub(super) const UNIFORMS: &[(&str, &str)] = &[
    ("u_time", "float"),
    ("u_resolution", "vec2"),
    ("u_mouse", "vec2"),
    ("u_delta", "float"),
    ("u_frame", "int"),
    ("u_date", "vec4"),
    ("u_tex0Resolution", "vec2"),
    ("u_tex1Resolution", "vec2"),
    ("u_tex2Resolution", "vec2"),
    ("u_tex3Resolution", "vec2"),
];

/// Whether the file reads glslViewer's uniforms (any of them, `u_tex0`
/// too): its style is glslViewer's (a file with `main()` that does not is
/// GLSL Sandbox's).
pub(super) fn is_glslviewer(tokens: &[Token]) -> bool {
    tokens
        .iter()
        .any(|t| UNIFORMS.iter().any(|(name, _)| t.is(name)) || texture_channel(t.text).is_some())
}

/// The glslViewer name of a member of the frame block (its slot, as the
/// GLSL Sandbox prelude names it without `rsb_`), where the values agree.
/// The mouse is not one: glslViewer's is in pixels ([`prelude`]).
pub(super) fn slot_name(slot: &str) -> Option<&'static str> {
    Some(match slot {
        "resolution" => "u_resolution",
        "time" => "u_time",
        "time_delta" => "u_delta",
        "frame" => "u_frame",
        "date" => "u_date",
        _ => return None,
    })
}

/// The channel of a texture glslViewer numbers: `u_texN` is channel N.
pub(super) fn texture_channel(name: &str) -> Option<usize> {
    let n: usize = name.strip_prefix("u_tex")?.parse().ok()?;
    (n < CHANNELS && name.len() == "u_tex".len() + 1).then_some(n)
}

/// Stands for a `uniform vec3 u_mouse;` or `vec4` in the declared names:
/// the pixels' function is wanted, the file defines the name itself.
pub(super) const MOUSE_PIXELS: &str = "rsb_u_mouse";

/// The definitions of the declared uniforms that are not members of the
/// frame block: `u_mouse`, the pointer over the image in pixels, y up, no
/// click needed (glslViewer's), and `u_texNResolution`, channel N's size.
pub(super) fn prelude(declared: &[&str], resolution: &str) -> String {
    let mut text = String::new();
    if declared.contains(&"u_mouse") || declared.contains(&MOUSE_PIXELS) {
        let _ = writeln!(
            text,
            "vec2 {MOUSE_PIXELS}() {{ return rsb_mouse * {resolution}; }}"
        );
    }
    if declared.contains(&"u_mouse") {
        let _ = writeln!(text, "#define u_mouse {MOUSE_PIXELS}()");
    }
    for k in 0..CHANNELS {
        let name = format!("u_tex{k}Resolution");
        if declared.contains(&name.as_str()) {
            let _ = writeln!(
                text,
                "#define {name} vec2(textureSize(sampler2D(rsb_channel{k}, rsb_linear_sampler), 0))"
            );
        }
    }
    text
}
