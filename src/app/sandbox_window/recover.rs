//! The sandbox window after a lost GPU device (docs/reliability.md, "The
//! GPU's limits and a lost device"): everything made from the device is
//! dropped and made again on a new one, in the same window. The shader's
//! last good text, its parameter values, the clock, the mouse and the
//! channel images stay; the pipelines are built again from the compiled
//! shader. A multipass shader's buffers start again, black, with the clock
//! at time and frame 0, as after `R`: a buffer that averages over the
//! frames would otherwise weigh its lost history as black.

use winit::event_loop::ActiveEventLoop;

use super::reload::build_within_limit;
use super::{SandboxApp, SandboxEvent};
use crate::app::window::replace_lost_device;
use crate::sandbox::multipass::compile::CompiledPass;
use crate::sandbox::multipass::gpu::pass_builder;
use crate::sandbox::render::ShaderPipeline;
use crate::sandbox::{Compiled, ReloadError};

/// What runs and must be built again on a new device.
enum Rebuild {
    Single(Box<Compiled>),
    Passes(Vec<CompiledPass>),
}

/// The running shader's pipelines, built again on a new device.
pub(super) enum Rebuilt {
    Single(Result<ShaderPipeline, String>),
    Passes(Vec<(CompiledPass, Result<ShaderPipeline, String>)>),
}

impl SandboxApp {
    /// The GPU device was lost (a driver reset, SIGUSR1): the window's
    /// graphics are made again on a new device and the running shader is
    /// built again; `ready` is told again once it draws.
    pub(super) fn recover_lost_device(&mut self, event_loop: &ActiveEventLoop, reason: &str) {
        let Some(lost) = self.gfx.take() else {
            return;
        };
        let window = lost.window.clone();
        drop(lost);
        // Builds still running on the lost device are dropped when done.
        self.generation += 1;
        self.devices += 1;
        let was_building = std::mem::take(&mut self.building);
        let rebuild = match &mut self.multi {
            Some(multi) => {
                self.clock.restart(std::time::Instant::now());
                Some(Rebuild::Passes(multi.device_lost()))
            }
            None => self
                .session
                .drop_pipeline()
                .map(|c| Rebuild::Single(Box::new(c))),
        };
        let lost = (reason, "the shader, its parameters and channels are");
        match replace_lost_device(window, lost, self.events, |window, gpu, surface| {
            self.gfx = Some(self.graphics(window, gpu, surface));
            Ok(())
        }) {
            Ok(message) => {
                self.panel.message = Some(message);
                self.ready = false;
                if let Some(rebuild) = rebuild {
                    self.rebuild(rebuild);
                }
                if was_building {
                    // The text whose build was dropped (the sessions
                    // forgot it with the pipelines).
                    self.load(true);
                }
                self.request_redraw();
            }
            Err(e) => {
                self.fatal = Some(e);
                event_loop.exit();
            }
        }
    }

    /// Builds the running shader (or passes) again on the new device, on
    /// another thread. The trial frame is not drawn again: the watchdog
    /// passed this shader already.
    fn rebuild(&mut self, rebuild: Rebuild) {
        let device = self.devices;
        self.spawn_with_builder(move |builder, _, _, _| {
            let rebuilt = match rebuild {
                Rebuild::Single(compiled) => {
                    Rebuilt::Single(build_within_limit(builder, &compiled))
                }
                Rebuild::Passes(passes) => Rebuilt::Passes(
                    passes
                        .into_iter()
                        .map(|pass| {
                            let builder = pass_builder(builder, pass.kind);
                            let result = build_within_limit(&builder, &pass.compiled);
                            (pass, result)
                        })
                        .collect(),
                ),
            };
            SandboxEvent::Rebuilt {
                device,
                rebuilt: Box::new(rebuilt),
            }
        });
    }

    /// The rebuilt pipelines run; a build that failed on the new device is
    /// reported as a reload's would be.
    pub(super) fn rebuilt(&mut self, rebuilt: Rebuilt) {
        let error = match rebuilt {
            Rebuilt::Single(Ok(pipeline)) => {
                self.session.restore_pipeline(pipeline);
                None
            }
            Rebuilt::Single(Err(e)) => Some(ReloadError::Gpu(e)),
            Rebuilt::Passes(built) => {
                let restored = self
                    .multi
                    .as_mut()
                    .and_then(|multi| multi.session.restore(built));
                restored.or(self.prepare_buffers())
            }
        };
        self.draw_next = true;
        self.check_next = true;
        if let Some(e) = error {
            self.session.fail(e.clone());
            self.failed(&e);
        }
    }
}
