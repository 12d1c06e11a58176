//! The parameters of a validated module: the members of its uniform block
//! at binding 1, with naga's types and offsets and the annotations of the
//! declarations in the user's text (docs/sandbox.md, "Parameters").

use super::error_at;
use crate::gpu::ShaderError;
use crate::shader_params::scan::Scan;
use crate::shader_params::{self, ParamSet, ParamSpec, ParamType, Scalar};

/// Prefix of the int member that stores a GLSL `bool` parameter.
pub(super) const GLSL_BOOL_PREFIX: &str = "rsb_bool_";

/// The parameters of the uniform block at `@group(0) @binding(1)`: naga's
/// layout, the annotations found for each member by `lookup` (byte offset of
/// the declaration in the user's text and an initializer).
pub(super) fn read_params(
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
        let annotation = shader_params::parse_annotation(&scan.comments_for_line(line))
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
