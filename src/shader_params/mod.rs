//! Parameters declared in a shader's source and annotated in a comment
//! (`// @slider(0, 5, 0.1)`), their values, the bytes the GPU reads, and the
//! sidecar file (`FILE.params.toml`) they are saved to. Both the sandbox
//! (its uniforms) and the viewer (the tracer's annotated constants,
//! [`SourceParams`]) use them, so they live below both.
//!
//! The types and byte offsets come from naga's module (the compiler decides
//! the layout, not this code); the controls come from the comments.
//!
//! | module | what |
//! | --- | --- |
//! | `annotation` | the `@tags` of the comments |
//! | `scan` | the lexer that finds declarations and their comments |
//! | `sidecar` | the values saved to and read from `FILE.params.toml` |
//! | `source` | the annotated `const`s and `override`s of the tracer's shader folder |
//! | this file | the types, the controls, the values and their bytes |

mod annotation;
pub mod scan;
mod sidecar;
mod source;

pub use annotation::{
    Annotation, AnnotationError, annotation_of_line, parse_annotation, parse_number,
};
pub use sidecar::sidecar_path;
pub use source::SourceParams;

/// The scalar type of a parameter's components.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scalar {
    F32,
    I32,
    U32,
    /// A GLSL `bool` uniform, stored as an `int` (0 or 1): booleans cannot
    /// live in a uniform buffer.
    Bool,
}

/// A scalar or vector type, e.g. `vec3<f32>` = (F32, 3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ParamType {
    pub scalar: Scalar,
    /// 1 for a scalar, 2..=4 for a vector.
    pub len: usize,
}

impl ParamType {
    pub fn is_float(&self) -> bool {
        self.scalar == Scalar::F32
    }

    /// The type's name in WGSL spelling, for messages.
    pub fn name(&self) -> String {
        let scalar = match self.scalar {
            Scalar::F32 => "f32",
            Scalar::I32 => "i32",
            Scalar::U32 => "u32",
            Scalar::Bool => "bool",
        };
        if self.len == 1 {
            scalar.to_string()
        } else {
            format!("vec{}<{scalar}>", self.len)
        }
    }
}

/// The control a parameter gets in the panel.
#[derive(Debug, Clone, PartialEq)]
pub enum Control {
    /// No annotation: a plain drag field per component.
    Drag { speed: Option<f64> },
    /// `@slider(min, max[, step])`, per component.
    Slider {
        min: f64,
        max: f64,
        step: Option<f64>,
    },
    /// `@log(min, max)`: a logarithmic slider, 0 < min < max.
    Log { min: f64, max: f64 },
    /// `@color` (the shader gets the sRGB values the picker shows) or
    /// `@color(linear)` (linear values); vec3 or vec4 of floats.
    Color { linear: bool },
    /// `@checkbox`: 0 or 1 (a GLSL `bool` is true or false).
    Checkbox,
    /// `@select(a, b, c)`: the index of the chosen label.
    Select(Vec<String>),
    /// A type no control can edit (a matrix or array); stays zero.
    Fixed(String),
}

impl Control {
    /// The annotation's name, as written after `@`.
    pub fn kind(&self) -> &'static str {
        match self {
            Control::Drag { .. } => "drag",
            Control::Slider { .. } => "slider",
            Control::Log { .. } => "log",
            Control::Color { .. } => "color",
            Control::Checkbox => "checkbox",
            Control::Select(_) => "select",
            Control::Fixed(_) => "fixed",
        }
    }
}

/// One parameter: a field of the uniform block the shader reads.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamSpec {
    pub name: String,
    pub ty: ParamType,
    /// Byte offset in the parameter block.
    pub offset: u32,
    pub control: Control,
    /// Value when nothing else is known; components past `ty.len` are 0.
    pub default: [f64; 4],
    /// The rest of the annotating comment, shown as a tooltip.
    pub help: String,
    /// 1-based line of the declaration in the user's file.
    pub line: u32,
}

impl ParamSpec {
    /// Combines what naga says (name, type, offset) with the annotation and
    /// an initializer from the source (GLSL `uniform float a = 1.5;`).
    pub fn new(
        name: &str,
        ty: Result<ParamType, String>,
        offset: u32,
        annotation: Annotation,
        initializer: Option<Vec<f64>>,
        line: u32,
    ) -> Result<ParamSpec, String> {
        let ty = match ty {
            Ok(ty) => ty,
            Err(type_name) => {
                return Ok(ParamSpec {
                    name: name.to_string(),
                    ty: ParamType {
                        scalar: Scalar::F32,
                        len: 0,
                    },
                    offset,
                    control: Control::Fixed(type_name),
                    default: [0.0; 4],
                    help: annotation.help,
                    line,
                });
            }
        };
        let control = annotation.control.unwrap_or(match ty.scalar {
            Scalar::Bool if ty.len == 1 => Control::Checkbox,
            _ => Control::Drag { speed: None },
        });
        let type_name = ty.name();
        let needs = |ok: bool, what: &str| {
            if ok {
                Ok(())
            } else {
                Err(format!(
                    "@{} needs {what}, but `{name}` is {type_name}",
                    control.kind()
                ))
            }
        };
        match &control {
            Control::Color { .. } => needs(
                ty.is_float() && (ty.len == 3 || ty.len == 4),
                "a vec3 or vec4 of floats",
            )?,
            Control::Checkbox | Control::Select(_) => needs(ty.len == 1, "a scalar")?,
            Control::Slider { .. } | Control::Log { .. } | Control::Drag { .. } => {
                needs(ty.scalar != Scalar::Bool, "a number")?
            }
            Control::Fixed(_) => {}
        }
        let mut default = [0.0; 4];
        if let Some(values) = initializer {
            fill(&mut default, &values, ty.len);
        } else {
            match &control {
                Control::Slider { min, max, .. } => default = [0f64.clamp(*min, *max); 4],
                Control::Log { min, .. } => default = [*min; 4],
                Control::Color { .. } => default = [1.0; 4],
                _ => {}
            }
        }
        if let Some(args) = &annotation.default {
            let values: Result<Vec<f64>, String> = args
                .iter()
                .map(|a| match (a.as_str(), &control) {
                    ("true", _) => Ok(1.0),
                    ("false", _) => Ok(0.0),
                    (label, Control::Select(labels)) if parse_number(label).is_none() => labels
                        .iter()
                        .position(|l| l == label.trim_matches('"'))
                        .map(|i| i as f64)
                        .ok_or_else(|| format!("@default: {label:?} is not one of {labels:?}")),
                    (text, _) => parse_number(text)
                        .ok_or_else(|| format!("@default: {text:?} is not a number")),
                })
                .collect();
            let values = values?;
            if values.len() != 1 && values.len() != ty.len {
                return Err(format!(
                    "@default: `{name}` is {type_name}: give 1 or {} values",
                    ty.len
                ));
            }
            fill(&mut default, &values, ty.len);
        }
        let mut spec = ParamSpec {
            name: name.to_string(),
            ty,
            offset,
            control,
            default,
            help: annotation.help,
            line,
        };
        spec.default = spec.clamp(spec.default);
        Ok(spec)
    }

    /// Puts a value into the control's range and the type's domain.
    /// Components past the type's length are set to 0.
    pub fn clamp(&self, mut value: [f64; 4]) -> [f64; 4] {
        for v in value.iter_mut().skip(self.ty.len) {
            *v = 0.0;
        }
        for v in value.iter_mut().take(self.ty.len) {
            match &self.control {
                Control::Slider { min, max, .. } | Control::Log { min, max } => {
                    *v = v.clamp(*min, *max)
                }
                Control::Checkbox => *v = f64::from(u8::from(*v != 0.0)),
                Control::Select(labels) => *v = v.round().clamp(0.0, (labels.len() - 1) as f64),
                Control::Color { .. } => *v = v.clamp(0.0, 1.0),
                _ => {}
            }
            match self.ty.scalar {
                Scalar::F32 => {}
                Scalar::I32 => *v = v.round().clamp(f64::from(i32::MIN), f64::from(i32::MAX)),
                Scalar::U32 => *v = v.round().clamp(0.0, f64::from(u32::MAX)),
                Scalar::Bool => *v = f64::from(u8::from(*v != 0.0)),
            }
        }
        value
    }
}

/// Copies `values` into `out` (one value fills every component).
fn fill(out: &mut [f64; 4], values: &[f64], len: usize) {
    for (i, slot) in out.iter_mut().enumerate().take(len) {
        *slot = if values.len() == 1 {
            values[0]
        } else {
            values.get(i).copied().unwrap_or(0.0)
        };
    }
}

/// The parameters of one compiled shader and their current values.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ParamSet {
    pub specs: Vec<ParamSpec>,
    pub values: Vec<[f64; 4]>,
    /// Size of the uniform block in bytes (0: the shader declares none).
    pub block_size: u32,
}

impl ParamSet {
    pub fn new(specs: Vec<ParamSpec>, block_size: u32) -> Self {
        let values = specs.iter().map(|s| s.default).collect();
        ParamSet {
            specs,
            values,
            block_size,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.specs.is_empty()
    }

    /// The value of the parameter `name` (its first `len` components).
    pub fn value(&self, name: &str) -> Option<&[f64]> {
        let i = self.specs.iter().position(|s| s.name == name)?;
        Some(&self.values[i][..self.specs[i].ty.len])
    }

    /// Sets the parameter `name`; returns false when there is none.
    pub fn set(&mut self, name: &str, value: &[f64]) -> bool {
        let Some(i) = self.specs.iter().position(|s| s.name == name) else {
            return false;
        };
        let mut v = self.values[i];
        fill(&mut v, value, self.specs[i].ty.len);
        self.values[i] = self.specs[i].clamp(v);
        true
    }

    /// After a reload: keeps the values of the parameters that are still
    /// there with the same type (matched by name). A value the user never
    /// changed follows a changed default in the file.
    pub fn keep_values_from(&mut self, old: &ParamSet) {
        for (spec, value) in self.specs.iter().zip(self.values.iter_mut()) {
            let Some(i) = old.specs.iter().position(|o| o.name == spec.name) else {
                continue;
            };
            let (old_spec, old_value) = (&old.specs[i], old.values[i]);
            if old_spec.ty != spec.ty || old_value == old_spec.default {
                continue;
            }
            *value = spec.clamp(old_value);
        }
    }

    /// Resets every value to its default.
    pub fn reset(&mut self) {
        for (spec, value) in self.specs.iter().zip(self.values.iter_mut()) {
            *value = spec.default;
        }
    }

    /// The uniform block as the GPU reads it (at least 16 bytes, so a
    /// buffer can always be bound).
    pub fn bytes(&self) -> Vec<u8> {
        let mut bytes = vec![0u8; (self.block_size as usize).max(16).next_multiple_of(16)];
        for (spec, value) in self.specs.iter().zip(&self.values) {
            for (k, v) in value.iter().enumerate().take(spec.ty.len) {
                let word = match spec.ty.scalar {
                    Scalar::F32 => (*v as f32).to_bits(),
                    Scalar::I32 | Scalar::Bool => (*v as i32) as u32,
                    Scalar::U32 => *v as u32,
                };
                let at = spec.offset as usize + 4 * k;
                if let Some(slot) = bytes.get_mut(at..at + 4) {
                    slot.copy_from_slice(&word.to_le_bytes());
                }
            }
        }
        bytes
    }
}

#[cfg(test)]
mod tests {
    use std::path::{Path, PathBuf};

    use super::*;

    fn annotation(comment: &str) -> Result<Annotation, AnnotationError> {
        annotation_of_line(&format!("x; // {comment}\n"), 1)
    }

    const F32: ParamType = ParamType {
        scalar: Scalar::F32,
        len: 1,
    };
    const VEC3: ParamType = ParamType {
        scalar: Scalar::F32,
        len: 3,
    };

    #[test]
    fn annotations_parse_into_controls() {
        let a = annotation("@slider(0.0, 5.0, 0.1) speed of the spin").unwrap();
        assert_eq!(
            a.control,
            Some(Control::Slider {
                min: 0.0,
                max: 5.0,
                step: Some(0.1)
            })
        );
        assert_eq!(a.help, "speed of the spin");
        assert_eq!(
            annotation("@log(1e-4, 1)").unwrap().control,
            Some(Control::Log {
                min: 1e-4,
                max: 1.0
            })
        );
        assert_eq!(
            annotation("@select(cube, sphere, \"torus\")")
                .unwrap()
                .control,
            Some(Control::Select(vec![
                "cube".into(),
                "sphere".into(),
                "torus".into()
            ]))
        );
        assert_eq!(
            annotation("@color(linear)").unwrap().control,
            Some(Control::Color { linear: true })
        );
        let a = annotation("@checkbox @default(true) mail me @ home").unwrap();
        assert_eq!(a.control, Some(Control::Checkbox));
        assert_eq!(a.default, Some(vec!["true".to_string()]));
        assert_eq!(a.help, "mail me @ home");
    }

    #[test]
    fn bad_annotations_are_errors_at_their_column() {
        let (offset, message) = annotation("@slidr(0, 1)").unwrap_err();
        assert_eq!(offset, 6, "the @ of the tag");
        assert!(message.contains("unknown annotation @slidr"), "{message}");
        assert!(annotation("@slider(1, 0)").is_err());
        assert!(annotation("@slider(0)").is_err());
        assert!(annotation("@log(0, 1)").is_err());
        assert!(annotation("@slider(0, 1) @checkbox").is_err());
    }

    #[test]
    fn defaults_come_from_initializer_annotation_or_range() {
        let slider = annotation("@slider(1, 5)").unwrap();
        let spec = ParamSpec::new("a", Ok(F32), 0, slider.clone(), None, 1).unwrap();
        assert_eq!(spec.default[0], 1.0, "0 clamped into the range");
        let spec = ParamSpec::new("a", Ok(F32), 0, slider, Some(vec![2.5]), 1).unwrap();
        assert_eq!(spec.default[0], 2.5, "the initializer");
        let color = annotation("@color @default(1, 0.5, 0)").unwrap();
        let spec = ParamSpec::new("c", Ok(VEC3), 16, color, None, 1).unwrap();
        assert_eq!(spec.default, [1.0, 0.5, 0.0, 0.0]);
        let select = annotation("@select(a, b, c) @default(c)").unwrap();
        let spec = ParamSpec::new("s", Ok(F32), 0, select, None, 1).unwrap();
        assert_eq!(spec.default[0], 2.0);
        let err = ParamSpec::new("c", Ok(F32), 0, annotation("@color").unwrap(), None, 1);
        assert!(err.unwrap_err().contains("vec3 or vec4"));
    }

    fn set() -> ParamSet {
        let specs = vec![
            ParamSpec::new(
                "speed",
                Ok(F32),
                0,
                annotation("@slider(0, 5)").unwrap(),
                Some(vec![1.0]),
                1,
            )
            .unwrap(),
            ParamSpec::new("tint", Ok(VEC3), 16, annotation("@color").unwrap(), None, 2).unwrap(),
            ParamSpec::new(
                "mode",
                Ok(ParamType {
                    scalar: Scalar::I32,
                    len: 1,
                }),
                28,
                annotation("@select(a, b)").unwrap(),
                None,
                3,
            )
            .unwrap(),
            ParamSpec::new(
                "on",
                Ok(ParamType {
                    scalar: Scalar::Bool,
                    len: 1,
                }),
                32,
                Annotation::default(),
                None,
                4,
            )
            .unwrap(),
        ];
        ParamSet::new(specs, 36)
    }

    #[test]
    fn bytes_follow_the_offsets() {
        let mut params = set();
        assert!(params.set("speed", &[2.0]));
        params.set("mode", &[1.0]);
        params.set("on", &[1.0]);
        let bytes = params.bytes();
        assert_eq!(bytes.len(), 48);
        let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
        assert_eq!(f32::from_bits(word(0)), 2.0);
        assert_eq!(f32::from_bits(word(16)), 1.0);
        assert_eq!(word(28), 1);
        assert_eq!(word(32), 1);
    }

    #[test]
    fn values_survive_a_reload_by_name() {
        let mut old = set();
        old.set("speed", &[3.0]);
        old.set("tint", &[0.5, 0.25, 0.0]);
        let mut new = set();
        // The reloaded file moved `speed` and changed the range of `tint`.
        new.specs[0].offset = 4;
        new.specs.remove(2);
        new.values.remove(2);
        new.keep_values_from(&old);
        assert_eq!(new.value("speed"), Some(&[3.0][..]));
        assert_eq!(new.value("tint"), Some(&[0.5, 0.25, 0.0][..]));
        // An untouched value follows a new default.
        let mut newer = set();
        newer.specs[2].default[0] = 1.0;
        newer.values[2][0] = 1.0;
        newer.keep_values_from(&old);
        assert_eq!(newer.value("mode"), Some(&[1.0][..]));
    }

    #[test]
    fn toml_round_trip() {
        let mut params = set();
        params.set("speed", &[4.5]);
        params.set("tint", &[0.0, 0.5, 1.0]);
        params.set("mode", &[1.0]);
        params.set("on", &[1.0]);
        let text = params.to_toml("x.frag");
        assert!(text.contains("mode = \"b\""), "{text}");
        assert!(text.contains("on = true"), "{text}");
        let mut loaded = set();
        let warnings = loaded.apply_toml(&format!("{text}\nghost = 1\n")).unwrap();
        assert_eq!(loaded.values, params.values);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert!(loaded.apply_toml("speed = [1, 2]").unwrap().len() == 1);
        assert!(loaded.apply_toml("speed = ").is_err());
    }

    /// TOML spells NaN and infinity; neither reaches the shader (found by
    /// the fuzzer, docs/reliability.md).
    #[test]
    fn non_finite_sidecar_values_are_refused() {
        let mut loaded = set();
        let warnings = loaded
            .apply_toml(
                "speed = nan
tint = [0.1, inf, 0.3]
",
            )
            .unwrap();
        assert_eq!(warnings.len(), 2, "{warnings:?}");
        assert_eq!(loaded.values, set().values);
    }

    #[test]
    fn sidecar_is_next_to_the_shader() {
        assert_eq!(
            sidecar_path(Path::new("a/b.frag")),
            PathBuf::from("a/b.frag.params.toml")
        );
    }
}
