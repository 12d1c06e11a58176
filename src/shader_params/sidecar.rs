//! The parameters' values saved next to the shader (`FILE.params.toml`) and
//! read back (docs/sandbox.md, "Parameters", Saving).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::{Control, ParamSet, ParamSpec, Scalar, fill};

impl ParamSet {
    /// The values as TOML: numbers, arrays, booleans for checkboxes and the
    /// label for selections.
    pub fn to_toml(&self, shader: &str) -> String {
        let mut table = toml::Table::new();
        for (spec, value) in self.specs.iter().zip(&self.values) {
            if let Some(v) = toml_value(spec, value) {
                table.insert(spec.name.clone(), v);
            }
        }
        let mut text = String::new();
        let _ = writeln!(
            text,
            "# Parameters of {shader}, saved by raysandbox; loaded when the shader opens."
        );
        text.push_str(&toml::to_string(&table).unwrap_or_default());
        text
    }

    /// Applies values read from TOML. Returns a warning per value that does
    /// not fit (unknown name, wrong type); the others are applied.
    pub fn apply_toml(&mut self, text: &str) -> Result<Vec<String>, String> {
        let table: toml::Table = text.parse().map_err(|e: toml::de::Error| e.to_string())?;
        let mut warnings = Vec::new();
        for (name, value) in &table {
            let Some(i) = self.specs.iter().position(|s| &s.name == name) else {
                warnings.push(format!("{name}: no such parameter in the shader"));
                continue;
            };
            match from_toml(&self.specs[i], value) {
                Some(v) => self.values[i] = self.specs[i].clamp(v),
                None => warnings.push(format!(
                    "{name}: {value} does not fit {} ({})",
                    self.specs[i].ty.name(),
                    self.specs[i].control.kind()
                )),
            }
        }
        Ok(warnings)
    }
}

fn toml_value(spec: &ParamSpec, value: &[f64; 4]) -> Option<toml::Value> {
    let one = |v: f64| match spec.ty.scalar {
        Scalar::F32 => toml::Value::Float(v),
        Scalar::Bool => toml::Value::Boolean(v != 0.0),
        _ => toml::Value::Integer(v as i64),
    };
    Some(match &spec.control {
        Control::Fixed(_) => return None,
        Control::Checkbox => toml::Value::Boolean(value[0] != 0.0),
        Control::Select(labels) => {
            toml::Value::String(labels.get(value[0] as usize).cloned().unwrap_or_default())
        }
        _ if spec.ty.len == 1 => one(value[0]),
        _ => toml::Value::Array(value[..spec.ty.len].iter().map(|v| one(*v)).collect()),
    })
}

fn from_toml(spec: &ParamSpec, value: &toml::Value) -> Option<[f64; 4]> {
    // A NaN or infinity (TOML has `nan` and `inf`) would reach the shader:
    // it does not fit any parameter.
    let number = |v: &toml::Value| match v {
        toml::Value::Float(f) if f.is_finite() => Some(*f),
        toml::Value::Integer(i) => Some(*i as f64),
        toml::Value::Boolean(b) => Some(f64::from(u8::from(*b))),
        _ => None,
    };
    let mut out = [0.0; 4];
    match (value, &spec.control) {
        (toml::Value::String(label), Control::Select(labels)) => {
            out[0] = labels.iter().position(|l| l == label)? as f64;
        }
        (toml::Value::Array(items), _) => {
            if items.len() != spec.ty.len {
                return None;
            }
            for (slot, item) in out.iter_mut().zip(items) {
                *slot = number(item)?;
            }
        }
        (v, _) => {
            let n = number(v)?;
            fill(&mut out, &[n], spec.ty.len);
        }
    }
    Some(out)
}

/// Where the parameters of `shader` are saved: `FILE.params.toml` next to it.
pub fn sidecar_path(shader: &Path) -> PathBuf {
    let mut name = shader.as_os_str().to_owned();
    name.push(".params.toml");
    PathBuf::from(name)
}
