//! One shader file being worked on: the last good pipeline, the parameter
//! values, and reloading that keeps both when the new text fails.
//!
//! Used by the window (which builds pipelines on another thread: compile
//! with [`Session::compile`], build with a [`PipelineBuilder`], then
//! [`Session::install`]) and by tests and headless renders ([`Session::reload`]).

use std::fmt;
use std::path::{Path, PathBuf};

use super::channels_3d::ChannelKinds;
use super::compose::{Compiled, Style, compile_expanded, compile_file};
use super::include;
use super::render::{PipelineBuilder, ShaderPipeline};
use crate::files::write_atomically;
use crate::gpu::ShaderError;
use crate::shader_params::{ParamSet, sidecar_path};

/// Why a reload did not take.
#[derive(Debug, Clone)]
pub enum ReloadError {
    /// The source is wrong: located in the user's file.
    Shader(ShaderError),
    /// wgpu refused a module naga accepted (rare: an adapter limit).
    Gpu(String),
    /// A multipass shader's `channels.toml` or JSON file is wrong: the
    /// message names the file and the key.
    Project(String),
}

impl fmt::Display for ReloadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReloadError::Shader(e) => write!(f, "{e}"),
            ReloadError::Gpu(e) | ReloadError::Project(e) => write!(f, "{e}"),
        }
    }
}

impl ReloadError {
    /// `FILE:LINE:COLUMN` (or the message's first line), for one-line reports.
    pub fn location(&self) -> String {
        match self {
            ReloadError::Shader(e) => format!("{}:{}:{}", e.file, e.line, e.column),
            ReloadError::Gpu(e) | ReloadError::Project(e) => {
                e.lines().next().unwrap_or_default().to_string()
            }
        }
    }
}

pub struct Session {
    path: PathBuf,
    /// The last shader that compiled, and its pipeline: none while a new
    /// device replaces a lost one ([`Session::drop_pipeline`]).
    current: Option<(Compiled, Option<ShaderPipeline>)>,
    /// Parameter values (of the current shader, or kept from the last one).
    pub params: ParamSet,
    /// The last reload's error, until a reload succeeds.
    pub error: Option<ReloadError>,
    /// The text of the last compile attempt, includes joined in: a change
    /// event that leaves the text as it was (a touch, a save without edits)
    /// is not a reload.
    last_text: Option<String>,
    /// The files the last compile attempt included, to watch.
    includes: Vec<PathBuf>,
    /// What each channel holds (`--channel0 cube`, docs/sandbox.md, "Cube
    /// maps and volumes"), which the prelude's names follow.
    pub kinds: ChannelKinds,
}

impl Session {
    /// A session with nothing compiled yet.
    pub fn new(path: &Path) -> Self {
        Session {
            path: path.to_path_buf(),
            current: None,
            params: ParamSet::default(),
            error: None,
            last_text: None,
            includes: Vec::new(),
            kinds: ChannelKinds::default(),
        }
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The files the shader includes (as far as the last compile read
    /// them): a change in any is a change of the shader.
    pub fn includes(&self) -> &[PathBuf] {
        &self.includes
    }

    /// Reads and compiles the file (naga only; quick), unless its text is
    /// the one compiled last time: then `Ok(None)`. Does not change the
    /// running shader; a failure is also kept in `error`.
    pub fn compile(&mut self) -> Result<Option<Compiled>, ReloadError> {
        let name = self.path.display().to_string();
        let text = match std::fs::read_to_string(&self.path) {
            Ok(text) => text,
            // Unreadable (e.g. replaced this instant): compile_file says why.
            Err(_) => return self.compiled_or_error(compile_file(&self.path)).map(Some),
        };
        let (expanded, included) = include::expand(&self.path, &text);
        self.includes = expanded.included().to_vec();
        if let Err(e) = included {
            self.last_text = None;
            return self.compiled_or_error(Err(e)).map(Some);
        }
        if self.last_text.as_deref() == Some(expanded.text.as_str()) {
            return Ok(None);
        }
        let result = compile_expanded(&name, &expanded, &self.kinds);
        self.last_text = Some(expanded.text);
        self.compiled_or_error(result).map(Some)
    }

    fn compiled_or_error(
        &mut self,
        result: Result<Compiled, ShaderError>,
    ) -> Result<Compiled, ReloadError> {
        result.map_err(|e| {
            let e = ReloadError::Shader(e);
            self.error = Some(e.clone());
            e
        })
    }

    /// Makes a compiled shader and its pipeline the current ones. Parameter
    /// values carry over by name; on the first install the sidecar file is
    /// read if there is one (returns its warnings).
    pub fn install(&mut self, compiled: Compiled, pipeline: ShaderPipeline) -> Vec<String> {
        let mut params = compiled.params.clone();
        let mut warnings = Vec::new();
        if self.current.is_none() {
            warnings = self.load_sidecar_into(&mut params);
        } else {
            params.keep_values_from(&self.params);
        }
        self.params = params;
        self.current = Some((compiled, Some(pipeline)));
        self.error = None;
        warnings
    }

    /// A pipeline build failed: the current one stays.
    pub fn fail(&mut self, error: ReloadError) {
        self.error = Some(error);
    }

    /// Compiles and builds on this thread; on failure everything that ran
    /// before stays.
    /// Returns the warnings of a sidecar file read on the first load, and
    /// nothing when the text did not change.
    pub fn reload(&mut self, builder: &PipelineBuilder) -> Result<Vec<String>, ReloadError> {
        let Some(compiled) = self.compile()? else {
            return Ok(Vec::new());
        };
        match builder.build(&compiled) {
            Ok(pipeline) => Ok(self.install(compiled, pipeline)),
            Err(e) => {
                let e = ReloadError::Gpu(e);
                self.fail(e.clone());
                Err(e)
            }
        }
    }

    /// The last good pipeline, if any shader compiled yet.
    pub fn pipeline(&self) -> Option<&ShaderPipeline> {
        self.current.as_ref().and_then(|(_, p)| p.as_ref())
    }

    /// The GPU device the pipeline was made on is lost: the pipeline goes,
    /// the shader, its parameter values and the error shown stay. Returns
    /// the shader to build again on the new device and give back with
    /// [`Session::restore_pipeline`] (docs/reliability.md, "The GPU's
    /// limits and a lost device"). The text compiled last is forgotten:
    /// a build of it may have been running on the lost device, so the next
    /// compile takes the file's text even if unchanged.
    pub fn drop_pipeline(&mut self) -> Option<Compiled> {
        self.last_text = None;
        let (compiled, pipeline) = self.current.as_mut()?;
        *pipeline = None;
        Some(compiled.clone())
    }

    /// The pipeline of the shader [`Session::drop_pipeline`] returned,
    /// built on the new device, unless a reload installed a newer one
    /// meanwhile. Returns whether it was taken.
    pub fn restore_pipeline(&mut self, pipeline: ShaderPipeline) -> bool {
        match &mut self.current {
            Some((_, slot @ None)) => {
                *slot = Some(pipeline);
                true
            }
            _ => false,
        }
    }

    pub fn compiled(&self) -> Option<&Compiled> {
        self.current.as_ref().map(|(c, _)| c)
    }

    pub fn style(&self) -> Option<Style> {
        self.compiled().map(|c| c.style)
    }

    /// `FILE.params.toml` next to the shader.
    pub fn sidecar(&self) -> PathBuf {
        sidecar_path(&self.path)
    }

    /// Writes the parameter values to the sidecar file.
    pub fn save_params(&self) -> Result<PathBuf, String> {
        let path = self.sidecar();
        let name = self
            .path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        write_atomically(&path, &self.params.to_toml(&name))
            .map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(path)
    }

    /// Reads the sidecar file into the current values; returns warnings.
    pub fn load_params(&mut self) -> Result<Vec<String>, String> {
        let path = self.sidecar();
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        self.params
            .apply_toml(&text)
            .map_err(|e| format!("{}: {e}", path.display()))
    }

    fn load_sidecar_into(&self, params: &mut ParamSet) -> Vec<String> {
        let path = self.sidecar();
        match std::fs::read_to_string(&path) {
            Ok(text) => match params.apply_toml(&text) {
                Ok(warnings) => warnings
                    .into_iter()
                    .map(|w| format!("{}: {w}", path.display()))
                    .collect(),
                Err(e) => vec![format!("{}: {e}", path.display())],
            },
            Err(_) => Vec::new(),
        }
    }
}
