//! A multipass shader being worked on: each pass's last good pipeline,
//! reloads that rebuild only the passes whose text changed, and keep a
//! pass's last good pipeline when its new text fails (docs/sandbox.md,
//! "Multipass"). The window builds on another thread: [`MultiSession::compile`],
//! build each pass, then [`MultiSession::install`]; tests use
//! [`MultiSession::reload`].

use std::path::{Path, PathBuf};

use super::compile::{CompiledPass, compile_joined, joined};
use super::gpu::{Binding, PassDraw, pass_builder};
use super::{PassKind, Project};
use crate::sandbox::render::{PipelineBuilder, ShaderPipeline};
use crate::sandbox::session::ReloadError;

/// A pass that runs: compiled, with its pipeline.
pub struct LivePass {
    pub pass: CompiledPass,
    pub pipeline: ShaderPipeline,
}

/// What a reload asks the caller to build.
pub struct Pending {
    /// The project as read now: its bindings apply at once.
    pub project: Project,
    /// The passes whose text changed and compiled.
    pub build: Vec<CompiledPass>,
    /// The first pass that did not compile (it keeps its last good
    /// pipeline).
    pub error: Option<ReloadError>,
}

pub struct MultiSession {
    path: PathBuf,
    project: Option<Project>,
    passes: Vec<LivePass>,
    /// The last reload's error, until a reload succeeds.
    pub error: Option<ReloadError>,
    /// Each pass's joined text at its last compile: a change event that
    /// leaves a pass's text as it was does not rebuild it.
    texts: Vec<(PassKind, String)>,
    /// The files the passes include, to watch.
    includes: Vec<PathBuf>,
}

impl MultiSession {
    pub fn new(path: &Path) -> Self {
        MultiSession {
            path: path.to_path_buf(),
            project: None,
            passes: Vec::new(),
            error: None,
            texts: Vec::new(),
            includes: Vec::new(),
        }
    }

    /// The files whose change is a reload: the project's, the ones its
    /// passes include, and in a folder the pass files it may gain.
    pub fn files(&self) -> Vec<PathBuf> {
        let mut files = match &self.project {
            Some(project) => project.files(),
            None => vec![self.path.clone()],
        };
        if self.path.is_dir() {
            let dir = self
                .path
                .canonicalize()
                .unwrap_or_else(|_| self.path.clone());
            for kind in PassKind::all() {
                files.push(dir.join(format!("{}.glsl", kind.stem())));
            }
            files.push(dir.join(super::folder::COMMON_FILE));
            files.push(dir.join(super::folder::CHANNELS_FILE));
        }
        for f in &self.includes {
            if !files.contains(f) {
                files.push(f.clone());
            }
        }
        files
    }

    /// Reads the project and compiles the passes whose text changed (naga
    /// only; quick). `Ok(None)`: nothing changed. A project that cannot be
    /// read is an error, and everything running stays.
    pub fn compile(&mut self) -> Result<Option<Pending>, ReloadError> {
        let project =
            Project::load(&self.path).map_err(|e| self.failed(ReloadError::Project(e)))?;
        Ok(self.compile_project(project))
    }

    /// Compiles every pass of `project`, read by the caller (the page's
    /// JSON text): no pass is taken as unchanged, since the page drops the
    /// build of a text that a newer one overtook.
    pub fn compile_every_pass(&mut self, project: Project) -> Option<Pending> {
        self.texts.clear();
        self.compile_project(project)
    }

    /// Compiles the passes of `project` whose text changed.
    fn compile_project(&mut self, project: Project) -> Option<Pending> {
        let mut build = Vec::new();
        let mut error = None;
        let mut texts = Vec::new();
        let mut includes = Vec::new();
        for pass in &project.passes {
            let expanded = match joined(&project, pass) {
                Ok(expanded) => expanded,
                Err(e) => {
                    error.get_or_insert(ReloadError::Shader(e));
                    continue;
                }
            };
            includes.extend(expanded.included().iter().cloned());
            let unchanged = self
                .texts
                .iter()
                .any(|(k, t)| *k == pass.kind && *t == expanded.text);
            texts.push((pass.kind, expanded.text.clone()));
            if unchanged {
                continue;
            }
            match compile_joined(pass, &expanded) {
                Ok(compiled) => build.push(compiled),
                Err(e) => {
                    error.get_or_insert(ReloadError::Shader(e));
                }
            }
        }
        self.includes = includes;
        let same_project = self.project.as_ref() == Some(&project);
        self.texts = texts;
        if same_project && build.is_empty() && error.is_none() {
            return None;
        }
        Some(Pending {
            project,
            build,
            error,
        })
    }

    fn failed(&mut self, e: ReloadError) -> ReloadError {
        self.error = Some(e.clone());
        e
    }

    /// Makes the built passes current; the other passes of the project
    /// keep their last good pipeline. Returns the first error (of the
    /// compile or the builds), which is also kept in `error`.
    pub fn install(
        &mut self,
        pending: Pending,
        built: Vec<(CompiledPass, Result<ShaderPipeline, String>)>,
    ) -> Option<ReloadError> {
        let mut error = pending.error;
        let mut old = std::mem::take(&mut self.passes);
        let mut new = Vec::new();
        for (pass, result) in built {
            match result {
                Ok(pipeline) => new.push(LivePass { pass, pipeline }),
                Err(e) => {
                    error.get_or_insert(ReloadError::Gpu(e));
                }
            }
        }
        for pass in &pending.project.passes {
            if new.iter().any(|p| p.pass.kind == pass.kind) {
                continue;
            }
            if let Some(k) = old.iter().position(|p| p.pass.kind == pass.kind) {
                new.push(old.swap_remove(k));
            }
        }
        new.sort_by_key(|p| p.pass.kind);
        self.passes = new;
        self.project = Some(pending.project);
        self.error = error.clone();
        error
    }

    /// Compiles and builds on this thread (tests, headless use).
    pub fn reload(&mut self, builder: &PipelineBuilder) -> Result<(), ReloadError> {
        let Some(pending) = self.compile()? else {
            return Ok(());
        };
        let built = pending
            .build
            .iter()
            .map(|pass| {
                let result = pass_builder(builder, pass.kind).build(&pass.compiled);
                (pass.clone(), result)
            })
            .collect();
        match self.install(pending, built) {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// The GPU device the passes' pipelines were made on is lost: they go,
    /// and the compiled passes are returned, to build again on the new
    /// device and give back with [`MultiSession::restore`]. The texts
    /// compiled last are forgotten, as [`crate::sandbox::Session::drop_pipeline`]
    /// does.
    pub fn drop_pipelines(&mut self) -> Vec<CompiledPass> {
        self.texts.clear();
        std::mem::take(&mut self.passes)
            .into_iter()
            .map(|live| live.pass)
            .collect()
    }

    /// The passes [`MultiSession::drop_pipelines`] returned, built on the
    /// new device: each runs again unless a reload gave its kind a newer
    /// pipeline meanwhile or the project lost the pass. Returns the first
    /// build that failed.
    pub fn restore(
        &mut self,
        built: Vec<(CompiledPass, Result<ShaderPipeline, String>)>,
    ) -> Option<ReloadError> {
        let mut error = None;
        for (pass, result) in built {
            let kind = pass.kind;
            let wanted = self
                .project
                .as_ref()
                .is_some_and(|p| p.pass(kind).is_some());
            if !wanted || self.passes.iter().any(|p| p.pass.kind == kind) {
                continue;
            }
            match result {
                Ok(pipeline) => self.passes.push(LivePass { pass, pipeline }),
                Err(e) => {
                    error.get_or_insert(ReloadError::Gpu(e));
                }
            }
        }
        self.passes.sort_by_key(|p| p.pass.kind);
        error
    }

    /// The passes that run: in the project, with a pipeline.
    pub fn draws(&self) -> Vec<PassDraw<'_>> {
        let Some(project) = &self.project else {
            return Vec::new();
        };
        self.passes
            .iter()
            .filter_map(|live| {
                let pass = project.pass(live.pass.kind)?;
                Some(PassDraw {
                    kind: live.pass.kind,
                    channels: &pass.channels,
                    pipeline: &live.pipeline,
                    params: &live.pass.compiled.params,
                })
            })
            .collect()
    }

    /// Every pass's bindings, for [`super::gpu::Buffers::prepare`].
    pub fn bindings(&self) -> Vec<Binding<'_>> {
        self.project
            .iter()
            .flat_map(|p| p.passes.iter().map(|pass| (pass.kind, &pass.channels)))
            .collect()
    }

    /// Whether the Image pass runs (something to show).
    pub fn runs(&self) -> bool {
        self.passes.iter().any(|p| p.pass.kind == PassKind::Image)
    }

    pub fn project(&self) -> Option<&Project> {
        self.project.as_ref()
    }

    /// The warnings of the running passes' sources and of the project.
    pub fn warnings(&self) -> Vec<String> {
        let project = self.project.iter().flat_map(|p| p.warnings.iter().cloned());
        let passes = self
            .passes
            .iter()
            .flat_map(|p| p.pass.compiled.warnings.iter().map(ToString::to_string));
        project.chain(passes).collect()
    }
}
