//! The sandbox in the page (docs/web.md, "Editing in the page"): the shader
//! document drawn full-screen into the canvas with the sandbox's uniforms,
//! animated frame after frame, as the native sandbox window does
//! (docs/sandbox.md). A new text is compiled by naga at once (quick), its
//! pipeline built without blocking; until it is ready, and when it fails,
//! the last good shader keeps drawing.

use std::path::Path;

use web_time::{Duration, Instant};
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};

use super::dropped_images::DroppedImages;
use super::editor::Problem;
use super::multipass_page::{self, ChannelReport, MultiBuilt, PageMulti};
use super::page;
use crate::gpu::{Gpu, ShaderError};
use crate::sandbox::clock::Clock;
use crate::sandbox::mouse::Mouse;
use crate::sandbox::multipass::json;
use crate::sandbox::render::{Canvas, NanColor, PipelineBuilder, SandboxGpu, ShaderPipeline};
use crate::sandbox::{Compiled, ReloadError, Session, compile};

/// The name errors give the shader document: no extension, so its text
/// tells its language (docs/sandbox.md, "Which kind of file").
pub const SHADER_NAME: &str = "shader";

/// A pipeline built for a text, handed back to the page's event loop.
pub struct Built {
    generation: u64,
    /// The text it was built from.
    text: String,
    /// How long naga took (composing, parsing, validating), then the
    /// pipeline's build (wgpu and the browser).
    times: (Duration, Duration),
    pipelines: Pipelines,
}

/// What a text was built into: one shader's pipeline, or the passes of a
/// multipass shader (a JSON text).
enum Pipelines {
    Single(Box<Compiled>, Result<ShaderPipeline, String>),
    Multi(MultiBuilt),
}

impl Built {
    pub fn text(&self) -> &str {
        &self.text
    }

    /// `naga=MS pipeline=MS`: how long the text took to compile and to build.
    pub fn times(&self) -> String {
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        format!(
            "naga={:.0}ms pipeline={:.0}ms",
            ms(self.times.0),
            ms(self.times.1)
        )
    }
}

/// The shader document on the GPU: the last good pipeline, the clock, the
/// mouse and the canvas the shader draws into.
pub struct ShaderView {
    sandbox: SandboxGpu,
    builder: PipelineBuilder,
    canvas: Canvas,
    session: Session,
    /// The multipass shader, while the document is JSON (docs/web.md,
    /// "Multipass shaders"); else `session`'s shader runs.
    multi: Option<PageMulti>,
    /// The images dropped on the canvas, for a multipass shader's texture
    /// channels.
    images: DroppedImages,
    clock: Clock,
    mouse: Mouse,
    /// Counts texts sent to be built: a build finishing after a newer text
    /// was sent is dropped.
    generation: u64,
    /// The canvas's size in physical pixels, for the mouse.
    size: (u32, u32),
    /// The right button is down: the pointer pans GLSL Sandbox's surface.
    panning: bool,
}

impl ShaderView {
    /// The sandbox's passes for a surface of `format` and `size` pixels.
    pub fn new(gpu: &Gpu, format: wgpu::TextureFormat, size: (u32, u32)) -> Self {
        let sandbox = SandboxGpu::new(gpu, &[format], NanColor::Black);
        let builder = sandbox.builder(&gpu.device);
        let canvas = Canvas::new(gpu, &sandbox, size);
        ShaderView {
            sandbox,
            builder,
            canvas,
            session: Session::new(Path::new(SHADER_NAME)),
            multi: None,
            images: DroppedImages::default(),
            clock: Clock::new(false, Instant::now()),
            mouse: Mouse::default(),
            generation: 0,
            size,
            panning: false,
        }
    }

    /// Compiles `text` (naga, on this thread: quick) and, when it compiles,
    /// starts building its pipeline without blocking; `done` receives the
    /// build for [`Self::built`]. A compile error is returned at once, at
    /// the user's line.
    pub fn compile(
        &mut self,
        text: &str,
        done: impl FnOnce(Built) + 'static,
    ) -> Result<(), Problem> {
        let start = Instant::now();
        let builder = self.builder.clone();
        let owned = text.to_string();
        if json::is_json(text) {
            let pending = self.multi.get_or_insert_default().compile(text)?;
            let generation = self.next_generation();
            let compiled_at = Instant::now();
            wasm_bindgen_futures::spawn_local(async move {
                let built = multipass_page::build(builder, pending).await;
                done(Built {
                    generation,
                    text: owned,
                    times: (compiled_at - start, compiled_at.elapsed()),
                    pipelines: Pipelines::Multi(built),
                });
            });
            return Ok(());
        }
        let compiled = compile(SHADER_NAME, text).map_err(|e| shader_problem(&e))?;
        let compiled_at = Instant::now();
        let generation = self.next_generation();
        wasm_bindgen_futures::spawn_local(async move {
            let result = builder.build_async(&compiled).await;
            done(Built {
                generation,
                text: owned,
                times: (compiled_at - start, compiled_at.elapsed()),
                pipelines: Pipelines::Single(Box::new(compiled), result),
            });
        });
        Ok(())
    }

    /// Counts a text sent to be built.
    fn next_generation(&mut self) -> u64 {
        self.generation += 1;
        self.generation
    }

    /// Takes a finished build: `None` for a build of an older text (dropped),
    /// else what to show under the editor (the style, or wgpu's error).
    pub fn built(&mut self, built: Built) -> Option<Result<String, Problem>> {
        if built.generation != self.generation {
            return None;
        }
        let (compiled, result) = match built.pipelines {
            Pipelines::Single(compiled, result) => (compiled, result),
            Pipelines::Multi(built) => {
                let multi = self.multi.as_mut()?;
                return Some(multi.install(built, &self.images).map(|(status, reports)| {
                    announce(&reports);
                    status
                }));
            }
        };
        Some(match result {
            Ok(pipeline) => {
                let style = compiled.style.describe();
                self.session.install(*compiled, pipeline);
                self.multi = None;
                Ok(format!("{style}: compiled"))
            }
            Err(message) => {
                self.session.fail(ReloadError::Gpu(message.clone()));
                Err(Problem {
                    message,
                    line: None,
                })
            }
        })
    }

    /// Whether a shader has compiled yet.
    pub fn has_shader(&self) -> bool {
        self.multi.as_ref().is_some_and(PageMulti::runs) || self.session.pipeline().is_some()
    }

    /// Follows the canvas's size.
    pub fn resize(&mut self, gpu: &Gpu, size: (u32, u32)) {
        self.size = size;
        self.canvas.resize(gpu, &self.sandbox, size);
    }

    /// Encodes one frame of the shader (the clock advances) and shows it on
    /// `target`.
    pub fn draw(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        format: wgpu::TextureFormat,
    ) {
        let multi = self.multi.as_mut().filter(|m| m.runs());
        if multi.is_some() || self.session.pipeline().is_some() {
            let tick = self.clock.tick(Instant::now());
            let uniforms = self.mouse.frame_uniforms(&tick, self.canvas.size());
            match (multi, self.session.pipeline()) {
                (Some(multi), _) => multi.draw(
                    gpu,
                    &self.sandbox,
                    encoder,
                    &uniforms,
                    &mut self.canvas,
                    &self.images,
                ),
                (None, Some(pipeline)) => self.canvas.draw(
                    gpu,
                    &self.sandbox,
                    encoder,
                    pipeline,
                    &uniforms,
                    &self.session.params,
                ),
                (None, None) => {}
            }
            self.mouse.just_clicked = false;
        }
        self.canvas.show(&self.sandbox, encoder, target, format);
    }

    /// An image dropped on the canvas: kept for the texture channels; a
    /// multipass shader running binds it at once. Returns the new line
    /// under the editor then.
    pub fn add_image(&mut self, name: &str, image: image::RgbaImage) -> Option<String> {
        self.images.add(name, image);
        let multi = self.multi.as_mut().filter(|m| m.runs())?;
        let reports = multi.bind_images(&self.images);
        announce(&reports);
        Some(multi.status(&reports))
    }

    /// Starts the shader again, as `R` does in the native window: time
    /// and frame from 0, a multipass shader's buffers cleared.
    pub fn restart(&mut self, gpu: &Gpu) {
        self.clock.restart(Instant::now());
        if let Some(multi) = &mut self.multi {
            multi.clear_buffers(gpu);
        }
        page::event("shader-restarted");
    }

    /// The pointer over the canvas, as the shader's mouse uniforms
    /// (docs/sandbox.md, "The values every shader gets"), and the keys
    /// pressed there, as a multipass shader's keyboard texture.
    pub fn input(&mut self, event: &WindowEvent) {
        let (w, h) = (self.size.0.max(1) as f32, self.size.1.max(1) as f32);
        match event {
            WindowEvent::KeyboardInput { event, .. } => {
                if let Some(multi) = &mut self.multi {
                    multi.key(event);
                }
            }
            WindowEvent::CursorMoved { position, .. } => {
                let at = [position.x as f32, h - position.y as f32];
                let moved = [at[0] / w - self.mouse.uv[0], at[1] / h - self.mouse.uv[1]];
                self.mouse.uv = [at[0] / w, at[1] / h];
                if self.mouse.down {
                    self.mouse.position = at;
                }
                if self.panning {
                    self.mouse.surface.pan(moved, w / h);
                }
            }
            WindowEvent::MouseInput { state, button, .. } => {
                let pressed = *state == ElementState::Pressed;
                match button {
                    MouseButton::Left => {
                        if pressed && !self.mouse.down {
                            let at = [self.mouse.uv[0] * w, self.mouse.uv[1] * h];
                            self.mouse.click = at;
                            self.mouse.position = at;
                            self.mouse.just_clicked = true;
                        }
                        self.mouse.down = pressed;
                    }
                    MouseButton::Right => self.panning = pressed,
                    _ => {}
                }
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let lines = match delta {
                    MouseScrollDelta::LineDelta(_, y) => *y * 40.0,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32,
                };
                self.mouse
                    .surface
                    .zoom(0.998_f32.powf(lines), self.mouse.uv, w / h);
            }
            _ => {}
        }
    }
}

/// A shader error as the editor shows it: the message (the user's file and
/// line, the line and a caret) and the line to mark.
pub fn shader_problem(e: &ShaderError) -> Problem {
    Problem {
        message: e.to_string(),
        line: (e.line > 0).then_some(e.line as usize),
    }
}

/// Logs what each texture channel of a multipass shader reads, and shows
/// over the canvas which ones lack their image (never a silent noise);
/// once every one has its image, that message goes.
fn announce(reports: &[ChannelReport]) {
    for report in reports {
        page::event(&format!("channel {}", report.line));
    }
    let missing: Vec<&str> = reports
        .iter()
        .filter(|r| r.missing)
        .map(|r| r.line.as_str())
        .collect();
    if !missing.is_empty() {
        page::show_notice(&missing.join("\n"));
    } else if !reports.is_empty() {
        page::hide_message();
    }
}
