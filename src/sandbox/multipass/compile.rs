//! Each pass compiled with the Common code joined before it, as Shadertoy
//! does; errors at the line of the file (or JSON pass) they are in.

use std::path::PathBuf;

use super::{Code, Input, Pass, PassKind, Project};
use crate::gpu::ShaderError;
use crate::sandbox::compose::{Compiled, Target, compile_pass};
use crate::sandbox::include::{self, Expanded};

/// A pass ready for a pipeline.
#[derive(Debug, Clone)]
pub struct CompiledPass {
    pub kind: PassKind,
    pub compiled: Compiled,
    pub channels: [Option<Input>; 4],
}

/// Every pass of a project, compiled.
#[derive(Debug, Clone)]
pub struct CompiledProject {
    pub passes: Vec<CompiledPass>,
}

impl CompiledProject {
    /// The files the passes include, Common's included.
    pub fn includes(&self) -> Vec<PathBuf> {
        let mut files: Vec<PathBuf> = Vec::new();
        for pass in &self.passes {
            for f in &pass.compiled.includes {
                if !files.contains(f) {
                    files.push(f.clone());
                }
            }
        }
        files
    }
}

/// The text of `code` with its includes joined in, named `name`.
fn expand(name: &str, code: &Code) -> Result<Expanded, ShaderError> {
    match code {
        Code::Text(text) => Ok(Expanded::of_text(name, text)),
        Code::File(path) => {
            let text = std::fs::read_to_string(path)
                .map_err(|e| ShaderError::unreadable(name.to_string(), &e))?;
            let (expanded, included) = include::expand(path, &text);
            included.map(|()| expanded)
        }
    }
}

/// The text a pass compiles: Common's, then the pass's, includes joined.
pub fn joined(project: &Project, pass: &Pass) -> Result<Expanded, ShaderError> {
    let mut expanded = expand(&pass.name, &pass.code)?;
    if let Some((name, code)) = &project.common {
        expanded = expanded.after(&expand(name, code)?);
    }
    Ok(expanded)
}

/// Compiles one pass.
pub fn compile_one(project: &Project, pass: &Pass) -> Result<CompiledPass, ShaderError> {
    compile_joined(pass, &joined(project, pass)?)
}

/// Compiles one pass from its [`joined`] text.
pub fn compile_joined(pass: &Pass, expanded: &Expanded) -> Result<CompiledPass, ShaderError> {
    let target = match pass.kind {
        PassKind::Buffer(_) => Target::Buffer,
        PassKind::Image => Target::Canvas,
    };
    let kinds = super::kinds(&pass.channels);
    let compiled = compile_pass(&pass.name, expanded, target, &kinds)?;
    Ok(CompiledPass {
        kind: pass.kind,
        compiled,
        channels: pass.channels.clone(),
    })
}

/// Compiles every pass; the first error stops it.
pub fn compile_project(project: &Project) -> Result<CompiledProject, ShaderError> {
    let passes = project
        .passes
        .iter()
        .map(|pass| compile_one(project, pass))
        .collect::<Result<_, _>>()?;
    Ok(CompiledProject { passes })
}
