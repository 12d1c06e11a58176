//! What the sandbox window does with the panel's and the keys' requests
//! ([`Actions`]): the clock, the parameters, channels, screenshots.

use super::{Actions, SandboxApp};
use crate::app::controls::ClockAction;
use crate::app::shell;
use crate::sandbox::channels;
use std::path::{Path, PathBuf};
use std::time::Instant;
use winit::event_loop::ActiveEventLoop;

impl SandboxApp {
    pub(super) fn apply(&mut self, actions: &Actions, event_loop: &ActiveEventLoop) {
        let now = Instant::now();
        match actions.clock {
            Some(ClockAction::Toggle) => self.clock.toggle(now),
            Some(ClockAction::Restart) => {
                self.clock.restart(now);
                if let (Some(multi), Some(gfx)) = (&mut self.multi, &self.gfx) {
                    multi.reset(&gfx.gpu);
                    self.after_present.push("buffers-cleared".into());
                }
                self.draw_next = true;
            }
            Some(ClockAction::Step) => {
                self.clock.step(now);
                self.draw_next = true;
            }
            None => {}
        }
        if let Some(scale) = actions.scale {
            self.scale = scale.clamp(0.25, 1.0);
            self.resize_canvas();
        }
        if actions.params_changed || actions.mouse_changed {
            self.draw_next = true;
        }
        if actions.reset_params {
            self.session.params.reset();
            self.draw_next = true;
        }
        if actions.save_params {
            self.panel.message = Some(match self.session.save_params() {
                Ok(path) => {
                    self.events
                        .event(&format!("params-saved {}", path.display()));
                    format!("parameters saved to {}", path.display())
                }
                Err(e) => format!("not saved: {e}"),
            });
        }
        if actions.load_params {
            self.panel.message = Some(match self.session.load_params() {
                Ok(warnings) if warnings.is_empty() => "parameters loaded".to_string(),
                Ok(warnings) => warnings.join("\n"),
                Err(e) => e,
            });
            self.draw_next = true;
        }
        if let Some((k, path)) = &actions.channel {
            self.set_channel(*k, path.as_deref());
        }
        if actions.screenshot {
            self.screenshot();
        }
        if let Some(gfx) = &self.gfx {
            if actions.toggle_fullscreen {
                shell::toggle_fullscreen(&gfx.window);
            }
            if actions.leave_fullscreen {
                gfx.window.set_fullscreen(None);
            }
        }
        if actions.quit {
            event_loop.exit();
        }
    }

    /// Gives channel `k` the image at `path` (None: the noise). An image
    /// that cannot be read leaves the channel as it was, with the error in
    /// the panel.
    pub(super) fn set_channel(&mut self, k: usize, path: Option<&Path>) {
        let Some(gfx) = &mut self.gfx else { return };
        let image = match path.map(channels::load).transpose() {
            Ok(image) => image,
            Err(e) => {
                self.panel.message = Some(e);
                return;
            }
        };
        gfx.canvas
            .set_channel(&gfx.gpu, &gfx.sandbox, k, image.as_ref());
        self.channels.images[k] = image;
        self.panel.message = Some(match path {
            Some(path) => format!("iChannel{k}: {}", path.display()),
            None => format!("iChannel{k}: the built-in noise"),
        });
        self.events.event(&format!("channel-set {k}"));
        self.draw_next = true;
    }

    pub(super) fn screenshot(&mut self) {
        let Some(gfx) = &self.gfx else { return };
        let path = screenshot_path(&self.options.file);
        self.panel.message = Some(match gfx.canvas.capture(&gfx.gpu, &gfx.sandbox) {
            Err(e) => format!("no screenshot: {e}"),
            Ok(image) => match image.save(&path) {
                Ok(()) => {
                    self.events.event(&format!("screenshot {}", path.display()));
                    format!("screenshot saved to {}", path.display())
                }
                Err(e) => format!("{}: {e}", path.display()),
            },
        });
    }
}

/// A screenshot path next to the shader that does not overwrite an earlier one.
pub(super) fn screenshot_path(shader: &Path) -> PathBuf {
    let dir = shader.parent().map(Path::to_path_buf).unwrap_or_default();
    let stem = shader
        .file_stem()
        .map_or("shader".into(), |s| s.to_string_lossy().into_owned());
    (1..)
        .map(|n| dir.join(format!("{stem}-screenshot-{n}.png")))
        .find(|p| !p.exists())
        .expect("some screenshot number is free")
}
