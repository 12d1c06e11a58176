//! The sandbox window with a multipass Shadertoy shader (docs/sandbox.md,
//! "Multipass"): each pass reloads on its own (a pass that fails keeps its
//! last good pipeline, the error at its file and line), `R` clears the
//! buffers with the clock, and the keys held reach Shadertoy's keyboard
//! texture.

use winit::event::KeyEvent;

use super::reload::build_checked;
use super::{SandboxApp, SandboxEvent};
use crate::gpu::Gpu;
use crate::sandbox::multipass::compile::CompiledPass;
use crate::sandbox::multipass::gpu::{Buffers, pass_builder};
use crate::sandbox::multipass::keyboard::Keyboard;
use crate::sandbox::multipass::session::{MultiSession, Pending};
use crate::sandbox::render::{Canvas, SandboxGpu, ShaderPipeline};
use crate::sandbox::{FrameUniforms, ReloadError, channels};

/// A multipass shader's state in the window.
pub(super) struct Multi {
    pub(super) session: MultiSession,
    /// Made with the window's GPU.
    buffers: Option<Buffers>,
    keyboard: Keyboard,
    /// The clock's frame the passes last ran for: a paused clock does not
    /// run them again (the buffers would go on accumulating), unless the
    /// buffers were cleared or a pass reloaded.
    drawn_frame: Option<u32>,
}

/// A build of the passes that changed, sent back to the event loop.
pub(super) struct MultiBuilt {
    pub(super) pending: Pending,
    pub(super) built: Vec<(CompiledPass, Result<ShaderPipeline, String>)>,
}

impl Multi {
    pub(super) fn new(path: &std::path::Path) -> Self {
        Multi {
            session: MultiSession::new(path),
            buffers: None,
            keyboard: Keyboard::default(),
            drawn_frame: None,
        }
    }

    /// The panel's line for the kind of shader.
    pub(super) fn describe(&self) -> String {
        let passes = self.session.draws().len();
        format!("GLSL (Shadertoy style), multipass: {passes} passes")
    }

    /// Clears the buffers: `R`, with the clock's restart.
    pub(super) fn reset(&mut self, gpu: &Gpu) {
        if let Some(buffers) = &mut self.buffers {
            buffers.reset(gpu);
        }
        self.drawn_frame = None;
    }

    pub(super) fn resize(&mut self, gpu: &Gpu, size: (u32, u32)) {
        if Buffers::at_size(&mut self.buffers, gpu, size).1 {
            self.drawn_frame = None;
        }
    }

    /// The GPU device was lost: the buffers go (they start again, black,
    /// on the new device), and the passes to build again are returned.
    pub(super) fn device_lost(&mut self) -> Vec<CompiledPass> {
        self.buffers = None;
        self.drawn_frame = None;
        self.session.drop_pipelines()
    }

    /// A key went down or up: its JavaScript code in the keyboard texture.
    pub(super) fn key(&mut self, event: &KeyEvent) {
        self.keyboard.key(event);
    }

    /// Encodes the passes of one frame, unless the clock is paused on the
    /// frame drawn already. Returns whether it drew.
    pub(super) fn draw(
        &mut self,
        gpu: &Gpu,
        sandbox: &SandboxGpu,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameUniforms,
        canvas: &mut Canvas,
    ) -> bool {
        if self.drawn_frame == Some(frame.frame) {
            return false;
        }
        let size = canvas.size();
        self.resize(gpu, size);
        let buffers = self.buffers.as_mut().expect("made by resize");
        buffers.set_keyboard(gpu, &self.keyboard);
        buffers.draw(gpu, sandbox, encoder, &self.session.draws(), frame, canvas);
        self.keyboard.frame_drawn();
        self.drawn_frame = Some(frame.frame);
        true
    }
}

impl SandboxApp {
    /// The first load and every change of a multipass shader's files:
    /// read and compile now, build the passes that changed on another
    /// thread (each tried by the watchdog), while the last good ones draw.
    pub(super) fn load_multipass(&mut self, reloaded: bool) {
        let Some(multi) = &mut self.multi else {
            return;
        };
        let compiled = multi.session.compile();
        self.watch_multipass_files();
        let pending = match compiled {
            Ok(Some(pending)) => pending,
            Ok(None) => return,
            Err(e) => {
                self.generation += 1;
                self.building = false;
                self.session.error = Some(e.clone());
                return self.failed(&e);
            }
        };
        self.spawn_build(move |builder, probe, size, generation| {
            let built = pending
                .build
                .iter()
                .map(|pass| {
                    let builder = pass_builder(builder, pass.kind);
                    let result = build_checked(&builder, probe, &pass.compiled, size);
                    (pass.clone(), result)
                })
                .collect();
            SandboxEvent::MultiBuilt {
                generation,
                built: Box::new(MultiBuilt { pending, built }),
                reloaded,
            }
        });
    }

    /// The passes built: the new ones run, the images the channels name
    /// are read.
    pub(super) fn multipass_built(&mut self, built: MultiBuilt, reloaded: bool) {
        let (Some(multi), Some(_)) = (&mut self.multi, &self.gfx) else {
            return;
        };
        let installed = multi.session.install(built.pending, built.built);
        let warnings = multi.session.warnings();
        // The buffers are prepared whatever failed.
        let error = installed.or(self.prepare_buffers());
        self.session.error = error.clone();
        self.announce_warnings(warnings);
        self.draw_next = true;
        self.check_next = true;
        match error {
            Some(e) => self.failed(&e),
            None if reloaded => self.after_present.push("shader-reloaded".into()),
            None => {}
        }
    }

    /// Makes the buffers at the canvas's size for the passes of the
    /// project and reads the images their channels name; they draw from
    /// the start again. Returns what could not be bound.
    pub(super) fn prepare_buffers(&mut self) -> Option<ReloadError> {
        let (Some(multi), Some(gfx)) = (&mut self.multi, &self.gfx) else {
            return None;
        };
        multi.resize(&gfx.gpu, gfx.canvas.size());
        let buffers = multi.buffers.as_mut().expect("made by resize");
        let bound = buffers.prepare(&gfx.gpu, &multi.session.bindings(), &channels::load);
        multi.drawn_frame = None;
        bound.err().map(ReloadError::Project)
    }

    /// Watches every file of the shader: the pass files (also those a
    /// folder may gain), Common, the bindings or the JSON file, includes.
    fn watch_multipass_files(&mut self) {
        let Some(multi) = &self.multi else { return };
        let files = multi.session.files();
        self.watch_set(None, files);
    }
}
