//! Parameters of the ray tracer's shader folder: module-scope `const` and
//! `override` declarations annotated like the sandbox's uniforms,
//!
//! ```wgsl
//! const GLASS_TINT: vec3<f32> = vec3<f32>(1.0, 1.0, 1.0); // @color(linear)
//! override SHADOW_RAYS: bool = true;                       // @checkbox
//! ```
//!
//! get the same controls (the same [`ParamSet`], the same panel code); a
//! changed value is written into the source the viewer compiles, in place of
//! the initializer, and the pipelines are rebuilt. The tracer's bind groups
//! stay as they are, and a headless render uses the values in the file.
//! Unannotated constants are the program's own and get no control.

use std::ops::Range;

use super::scan::{Kind, Scan, top_level};
use super::{ParamSet, ParamSpec, ParamType, Scalar, parse_annotation, parse_number};
use crate::gpu::{ShaderError, ShaderSource};

/// Where a parameter's value is written: the initializer of its declaration.
#[derive(Debug, Clone, PartialEq)]
struct Site {
    /// Index of the part (file) in the source.
    part: usize,
    /// Byte range of the initializer in the part's text.
    range: Range<usize>,
}

/// The annotated constants of a source, with their current values.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SourceParams {
    pub params: ParamSet,
    sites: Vec<Site>,
}

impl SourceParams {
    /// Finds the annotated `const` and `override` declarations of every part.
    /// Annotation mistakes are errors at their file, line and column.
    pub fn read(source: &ShaderSource) -> Result<SourceParams, ShaderError> {
        let mut specs = Vec::new();
        let mut sites = Vec::new();
        for (part, (name, text)) in source.parts().enumerate() {
            let scan = Scan::new(text);
            let tokens = &scan.tokens;
            for i in top_level(tokens) {
                let t = &tokens[i];
                if !(t.is("const") || t.is("override")) {
                    continue;
                }
                let Some(decl_name) = tokens.get(i + 1).filter(|n| n.kind == Kind::Ident) else {
                    continue;
                };
                let line = scan.line_of(decl_name.start);
                let comments = scan.comments_for_line(line);
                let at = |offset: usize, message: String| ShaderError {
                    file: name.to_string(),
                    line: scan.line_of(offset),
                    column: scan.column_of(offset),
                    message,
                    source_line: scan.line_text(scan.line_of(offset)).to_string(),
                    label: String::new(),
                };
                let annotation =
                    parse_annotation(&comments).map_err(|(offset, message)| at(offset, message))?;
                if annotation.control.is_none() && annotation.default.is_none() {
                    continue;
                }
                // NAME : TYPE = INITIALIZER ;
                let Some(eq) =
                    (i + 2..tokens.len()).find(|&k| tokens[k].is("=") || tokens[k].is(";"))
                else {
                    continue;
                };
                let type_text: String =
                    tokens[(i + 3).min(eq)..eq].iter().map(|t| t.text).collect();
                let ty = if tokens.get(i + 2).is_some_and(|c| c.is(":")) {
                    wgsl_type(&type_text)
                } else {
                    None
                };
                let Some(ty) = ty else {
                    return Err(at(
                        decl_name.start,
                        format!(
                            "annotated constant `{}` needs a type of f32, i32, u32, bool or a \
                             vector of them: `const {}: f32 = 1.0;`",
                            decl_name.text, decl_name.text
                        ),
                    ));
                };
                let Some(end) = (eq..tokens.len()).find(|&k| tokens[k].is(";")) else {
                    continue;
                };
                if !tokens[eq].is("=") || end == eq + 1 {
                    return Err(at(
                        decl_name.start,
                        format!("annotated `{}` needs an initial value", decl_name.text),
                    ));
                }
                let range = tokens[eq + 1].start..tokens[end - 1].end();
                let values: Vec<f64> = tokens[eq + 1..end]
                    .iter()
                    .scan(false, |negative, t| {
                        Some(match (t.kind, t.text) {
                            (Kind::Punct, "-") => {
                                *negative = true;
                                None
                            }
                            (Kind::Number, n) => {
                                let v = parse_number(n).map(|v| if *negative { -v } else { v });
                                *negative = false;
                                v
                            }
                            (Kind::Ident, "true") => Some(1.0),
                            (Kind::Ident, "false") => Some(0.0),
                            _ => None,
                        })
                    })
                    .flatten()
                    .collect();
                let spec =
                    ParamSpec::new(decl_name.text, Ok(ty), 0, annotation, Some(values), line)
                        .map_err(|message| at(decl_name.start, message))?;
                specs.push(spec);
                sites.push(Site { part, range });
            }
        }
        Ok(SourceParams {
            params: ParamSet::new(specs, 0),
            sites,
        })
    }

    pub fn is_empty(&self) -> bool {
        self.params.is_empty()
    }

    /// The source with the current values written into the declarations.
    /// Everything else keeps its line, so errors still point at the files.
    pub fn apply(&self, source: &ShaderSource) -> ShaderSource {
        let parts: Vec<(String, String)> = source
            .parts()
            .enumerate()
            .map(|(index, (name, text))| {
                let mut text = text.to_string();
                let mut edits: Vec<(Range<usize>, String)> = self
                    .sites
                    .iter()
                    .zip(&self.params.specs)
                    .zip(&self.params.values)
                    .filter(|((site, _), _)| site.part == index)
                    .map(|((site, spec), value)| (site.range.clone(), literal(&spec.ty, value)))
                    .collect();
                // From the end, so earlier ranges stay valid.
                edits.sort_by_key(|(range, _)| std::cmp::Reverse(range.start));
                for (range, literal) in edits {
                    text.replace_range(range, &literal);
                }
                (name.to_string(), text)
            })
            .collect();
        ShaderSource::from_parts(parts)
    }
}

/// `f32`, `vec3<f32>`, `vec3f`, ... as a parameter type.
fn wgsl_type(text: &str) -> Option<ParamType> {
    let scalar = |s: &str| match s {
        "f32" | "f" => Some(Scalar::F32),
        "i32" | "i" => Some(Scalar::I32),
        "u32" | "u" => Some(Scalar::U32),
        "bool" => Some(Scalar::Bool),
        _ => None,
    };
    if let Some(s) = scalar(text) {
        return Some(ParamType { scalar: s, len: 1 });
    }
    let rest = text.strip_prefix("vec")?;
    let len = rest
        .get(..1)?
        .parse::<usize>()
        .ok()
        .filter(|n| (2..=4).contains(n))?;
    let inner = rest[1..].trim_start_matches('<').trim_end_matches('>');
    let s = scalar(inner).filter(|s| *s != Scalar::Bool)?;
    Some(ParamType { scalar: s, len })
}

/// A WGSL literal of `value` with the type `ty`.
fn literal(ty: &ParamType, value: &[f64; 4]) -> String {
    let one = |v: f64| match ty.scalar {
        Scalar::F32 => format!("{:?}", v as f32),
        Scalar::I32 => format!("{}i", v as i32),
        Scalar::U32 => format!("{}u", v as u32),
        Scalar::Bool => (v != 0.0).to_string(),
    };
    if ty.len == 1 {
        return one(value[0]);
    }
    let items: Vec<String> = value[..ty.len].iter().map(|v| one(*v)).collect();
    format!("{}({})", ty.name(), items.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn source() -> ShaderSource {
        ShaderSource::from_parts([
            (
                "a.wgsl".to_string(),
                "const PLAIN: f32 = 2.0;\n\
                 const GAIN: f32 = 1.5; // @slider(0, 4) brightness\n\
                 // @color(linear)\n\
                 const TINT: vec3<f32> = vec3<f32>(1.0, 0.5, 0.25);\n"
                    .to_string(),
            ),
            (
                "b.wgsl".to_string(),
                "override SHADOWS: bool = true; // @checkbox\n\
                 const STEPS: i32 = -3; // @slider(-8, 8)\n\
                 fn f() -> vec3<f32> {\n    const LOCAL: f32 = 1.0; // @slider(0, 1)\n    \
                 return TINT * GAIN * PLAIN * f32(STEPS) * LOCAL * select(0.0, 1.0, SHADOWS);\n}\n"
                    .to_string(),
            ),
        ])
    }

    #[test]
    fn annotated_constants_become_parameters() {
        let found = SourceParams::read(&source()).unwrap_or_else(|e| panic!("{e}"));
        let names: Vec<(&str, &str, f64)> = found
            .params
            .specs
            .iter()
            .map(|s| (s.name.as_str(), s.control.kind(), s.default[0]))
            .collect();
        assert_eq!(
            names,
            [
                ("GAIN", "slider", 1.5),
                ("TINT", "color", 1.0),
                ("SHADOWS", "checkbox", 1.0),
                ("STEPS", "slider", -3.0)
            ]
        );
        assert_eq!(found.params.specs[1].default, [1.0, 0.5, 0.25, 0.0]);
        assert_eq!(found.params.specs[0].help, "brightness");
    }

    #[test]
    fn values_are_written_into_the_source_that_still_validates() {
        let source = source();
        let mut found = SourceParams::read(&source).unwrap();
        found.params.set("GAIN", &[2.25]);
        found.params.set("TINT", &[0.0, 0.5, 1.0]);
        found.params.set("SHADOWS", &[0.0]);
        found.params.set("STEPS", &[5.0]);
        let applied = found.apply(&source);
        let text = applied.text();
        assert!(
            text.contains("const GAIN: f32 = 2.25; // @slider"),
            "{text}"
        );
        assert!(
            text.contains("const TINT: vec3<f32> = vec3<f32>(0.0, 0.5, 1.0);"),
            "{text}"
        );
        assert!(text.contains("override SHADOWS: bool = false;"), "{text}");
        assert!(text.contains("const STEPS: i32 = 5i;"), "{text}");
        assert_eq!(text.lines().count(), source.text().lines().count());
        applied.validate().unwrap_or_else(|e| panic!("{e}"));
        // Read again from the applied text: the values are the new defaults.
        let again = SourceParams::read(&applied).unwrap();
        assert_eq!(again.params.values, found.params.values);
    }

    #[test]
    fn annotation_errors_name_the_file_and_line() {
        let source = ShaderSource::from_parts([(
            "c.wgsl".to_string(),
            "\nconst A = 1.0; // @slider(0, 1)\n".to_string(),
        )]);
        let e = SourceParams::read(&source).unwrap_err();
        assert_eq!((e.file.as_str(), e.line, e.column), ("c.wgsl", 2, 7), "{e}");
        let source = ShaderSource::from_parts([(
            "d.wgsl".to_string(),
            "const A: f32 = 1.0; // @slidr(0, 1)\n".to_string(),
        )]);
        let e = SourceParams::read(&source).unwrap_err();
        assert_eq!((e.line, e.column), (1, 24), "{e}");
    }
}
