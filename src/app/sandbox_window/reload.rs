//! The sandbox window's reloads: the file read and compiled, the pipeline
//! built on a thread and tried on the watchdog's device, the files watched.

use super::{SandboxApp, SandboxEvent};
use crate::app::watch;
use crate::sandbox::render::{
    BuildFailed, FRAME_LIMIT, PipelineBuilder, ShaderPipeline, build_too_slow,
};
use crate::sandbox::watchdog::Probe;
use crate::sandbox::{Compiled, ReloadError};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};

impl SandboxApp {
    /// The first load and every change of the file: compile now (naga,
    /// quick), build the pipeline on another thread while the window keeps
    /// drawing (the last good shader, if any). The first load takes the same
    /// path, so that a driver stuck on the first shader never freezes the
    /// window either.
    pub(super) fn load(&mut self, reloaded: bool) {
        if self.gfx.is_none() {
            return;
        }
        if self.multi.is_some() {
            return self.load_multipass(reloaded);
        }
        let compiled = self.session.compile();
        self.watch_files();
        let compiled = match compiled {
            Ok(Some(c)) => c,
            Ok(None) => return,
            Err(e) => {
                // A build still running is for older text: drop its result.
                self.generation += 1;
                self.building = false;
                return self.failed(&e);
            }
        };
        self.spawn_build(move |builder, probe, size, generation| {
            let result = build_checked(builder, probe, &compiled, size);
            SandboxEvent::Built {
                generation,
                compiled: Box::new(compiled),
                result,
                reloaded,
            }
        });
    }

    /// Starts a build on another thread: `build` gets the pipeline
    /// builder, the watchdog's probe, the render size and the reload's
    /// generation, and its event is sent back to the event loop.
    pub(super) fn spawn_build(
        &mut self,
        build: impl FnOnce(&PipelineBuilder, &Mutex<Probe>, (u32, u32), u64) -> SandboxEvent
        + Send
        + 'static,
    ) {
        self.generation += 1;
        self.spawn_with_builder(build);
    }

    /// [`SandboxApp::spawn_build`] without a new generation: a rebuild
    /// after a lost device does not overtake a reload.
    pub(super) fn spawn_with_builder(
        &mut self,
        build: impl FnOnce(&PipelineBuilder, &Mutex<Probe>, (u32, u32), u64) -> SandboxEvent
        + Send
        + 'static,
    ) {
        let Some(gfx) = &self.gfx else { return };
        let builder = gfx.builder.clone();
        let size = gfx.canvas.size();
        let probe = Arc::clone(&self.probe);
        let proxy = self.proxy.clone();
        let generation = self.generation;
        self.building = true;
        std::thread::spawn(move || {
            let _ = proxy.send_event(build(&builder, &probe, size, generation));
        });
    }

    /// The warnings of the shader's source (uniforms nothing sets,
    /// docs/sandbox.md): logged and announced once, when they change, and
    /// shown at the top of the window while the shader runs.
    pub(super) fn note_source_warnings(&mut self) {
        let warnings: Vec<String> = self
            .session
            .compiled()
            .map(|c| c.warnings.iter().map(ToString::to_string).collect())
            .unwrap_or_default();
        self.announce_warnings(warnings);
    }

    /// Logs and announces the source's warnings when they changed.
    pub(super) fn announce_warnings(&mut self, warnings: Vec<String>) {
        if warnings == self.source_warnings {
            return;
        }
        for w in &warnings {
            log::warn!("{w}");
        }
        if !warnings.is_empty() {
            self.after_present
                .push(format!("shader-warning {}", warnings.len()));
        }
        self.source_warnings = warnings;
    }

    /// Watches the shader file and the files it includes (docs/sandbox.md,
    /// "Includes"): after a compile that changed the includes, the watch is
    /// made again for the new set.
    pub(super) fn watch_files(&mut self) {
        let includes = self.session.includes().to_vec();
        let file = self.options.file.clone();
        self.watch_set(Some(&file), includes);
    }

    /// Watches `file` (if any) and `files`, unless the watch is for them
    /// already.
    pub(super) fn watch_set(&mut self, file: Option<&Path>, files: Vec<PathBuf>) {
        if self.watch.is_some() && self.watched_includes == files {
            return;
        }
        self.watched_includes = files;
        let proxy = self.proxy.clone();
        let notify = move |_| {
            let _ = proxy.send_event(SandboxEvent::FileChanged);
        };
        match watch::watch(None, file, &self.watched_includes, notify) {
            Ok(w) => self.watch = Some(w),
            Err(e) => self.panel.message = Some(e),
        }
    }

    pub(super) fn built(
        &mut self,
        compiled: Compiled,
        result: Result<ShaderPipeline, String>,
        reloaded: bool,
    ) {
        match result {
            Ok(pipeline) => {
                let warnings = self.session.install(compiled, pipeline);
                self.loaded(warnings, reloaded);
            }
            Err(e) => {
                let e = ReloadError::Gpu(e);
                self.session.fail(e.clone());
                self.failed(&e);
            }
        }
    }

    pub(super) fn loaded(&mut self, warnings: Vec<String>, reloaded: bool) {
        for w in &warnings {
            log::warn!("{w}");
        }
        self.note_source_warnings();
        self.panel.message = warnings.into_iter().next();
        self.draw_next = true;
        self.check_next = true;
        self.warning = None;
        if reloaded {
            self.after_present.push("shader-reloaded".into());
        }
    }

    pub(super) fn failed(&mut self, error: &ReloadError) {
        log::error!("{error}");
        self.after_present
            .push(format!("shader-error {}", error.location()));
    }
}

/// Builds the pipeline of a compiled shader within [`FRAME_LIMIT`] (a
/// driver compiling for ever is reported, not waited for), then lets the
/// watchdog draw a trial frame with it: a shader that would freeze the
/// window at `size` is refused like a compile error.
pub(super) fn build_checked(
    builder: &PipelineBuilder,
    probe: &Mutex<Probe>,
    compiled: &Compiled,
    size: (u32, u32),
) -> Result<ShaderPipeline, String> {
    let pipeline = build_within_limit(builder, compiled)?;
    probe
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .check(compiled, size)?;
    Ok(pipeline)
}

/// Builds the pipeline of a compiled shader within [`FRAME_LIMIT`]; the
/// error names the shader's file.
pub(super) fn build_within_limit(
    builder: &PipelineBuilder,
    compiled: &Compiled,
) -> Result<ShaderPipeline, String> {
    match builder.build_within(compiled, FRAME_LIMIT) {
        Ok(pipeline) => Ok(pipeline),
        Err(BuildFailed::Refused(m)) => Err(m),
        Err(BuildFailed::TooSlow) => Err(build_too_slow(&compiled.file)),
    }
}
