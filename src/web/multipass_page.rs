//! A multipass Shadertoy shader in the page (docs/web.md, "Multipass
//! shaders"): the shader document holds the JSON that Shadertoy's API and
//! export tools write (docs/sandbox.md, "Multipass"); its passes run into
//! the sandbox's float buffers as in the native window. Keys pressed over
//! the canvas reach Shadertoy's keyboard texture; a texture channel reads
//! an image dropped on the canvas ([`DroppedImages`]), else the built-in
//! noise, and the page says which channel lacks its image.

use std::path::{Path, PathBuf};

use winit::event::KeyEvent;

use super::dropped_images::{Assigned, DroppedImages};
use super::editor::Problem;
use crate::gpu::Gpu;
use crate::sandbox::multipass::compile::CompiledPass;
use crate::sandbox::multipass::gpu::{Binding, Buffers, PassDraw, pass_builder};
use crate::sandbox::multipass::json;
use crate::sandbox::multipass::keyboard::Keyboard;
use crate::sandbox::multipass::session::{MultiSession, Pending};
use crate::sandbox::multipass::{Input, PassKind};
use crate::sandbox::render::{Canvas, PipelineBuilder, SandboxGpu, ShaderPipeline};
use crate::sandbox::{FrameUniforms, ReloadError};

/// The name errors give the JSON document.
pub const JSON_NAME: &str = "shader.json";

/// The passes of a JSON text built, handed back to the page's event loop.
pub struct MultiBuilt {
    pending: Pending,
    built: Vec<(CompiledPass, Result<ShaderPipeline, String>)>,
}

/// The multipass shader the page runs: its passes and their buffers.
pub struct PageMulti {
    session: MultiSession,
    buffers: Option<Buffers>,
    /// The buffers and images follow the passes installed last.
    prepared: bool,
    keyboard: Keyboard,
    /// Each pass's channels as drawn: a texture's `src` replaced by the
    /// key of the dropped image it reads, or by the noise
    /// ([`PageMulti::bind_images`]).
    channels: Vec<(PassKind, [Option<Input>; 4])>,
}

impl Default for PageMulti {
    fn default() -> Self {
        PageMulti {
            session: MultiSession::new(Path::new(JSON_NAME)),
            buffers: None,
            prepared: false,
            keyboard: Keyboard::default(),
            channels: Vec::new(),
        }
    }
}

/// What a texture channel reads in the page, said under the editor and on
/// the console (`channel Image iChannel0: ...`).
pub struct ChannelReport {
    pub line: String,
    /// The channel has no image: it reads the noise.
    pub missing: bool,
}

impl PageMulti {
    /// Reads and compiles every pass of the JSON `text` (naga, on this
    /// thread); the passes' pipelines are built by [`build`].
    pub fn compile(&mut self, text: &str) -> Result<Pending, Problem> {
        // Every `src` is kept: the page binds dropped images to them.
        let keep = |src: &str| Some(PathBuf::from(src));
        let parsed = json::parse_finding(Path::new(JSON_NAME), text, &keep);
        let project = parsed.map_err(|message| Problem {
            line: json::error_line(&message),
            message,
        })?;
        let pending = self
            .session
            .compile_every_pass(project)
            .expect("every pass is compiled, so there is something to build");
        match &pending.error {
            Some(e) => Err(reload_problem(e)),
            None => Ok(pending),
        }
    }

    /// Makes the built passes current, their texture channels bound to
    /// `images`; returns what to show under the editor (the warnings and
    /// what each texture channel reads among them) and the texture
    /// channels' reports. Their buffers are made at the next
    /// [`draw`](Self::draw).
    pub fn install(
        &mut self,
        built: MultiBuilt,
        images: &DroppedImages,
    ) -> Result<(String, Vec<ChannelReport>), Problem> {
        let error = self.session.install(built.pending, built.built);
        // Also after an error: the passes that kept running may read
        // other channels now.
        let reports = self.bind_images(images);
        if let Some(e) = error {
            return Err(reload_problem(&e));
        }
        Ok((self.status(&reports), reports))
    }

    /// The line under the editor: the passes, the warnings, and what the
    /// texture channels read.
    pub fn status(&self, reports: &[ChannelReport]) -> String {
        let passes = self.session.draws().len();
        let mut said = format!("GLSL (Shadertoy style), multipass: {passes} passes: compiled");
        let reported = reports.iter().map(|r| r.line.clone());
        for line in self.session.warnings().into_iter().chain(reported) {
            said.push_str(&format!("; {line}"));
        }
        said
    }

    /// Binds the texture channels of the passes installed to the images
    /// dropped on the page (the buffers take them at the next draw), and
    /// says what each texture channel reads.
    pub fn bind_images(&mut self, images: &DroppedImages) -> Vec<ChannelReport> {
        let passes: Vec<(PassKind, [Option<Input>; 4])> = self
            .session
            .bindings()
            .into_iter()
            .map(|(kind, channels)| (kind, channels.clone()))
            .collect();
        let mut srcs: Vec<String> = Vec::new();
        for input in passes.iter().flat_map(|(_, channels)| channels.iter()) {
            if let Some(Input::Texture(src)) = input {
                let src = src.display().to_string();
                if !srcs.contains(&src) {
                    srcs.push(src);
                }
            }
        }
        let assigned = images.assign(&srcs);
        let mut reports = Vec::new();
        self.channels = passes;
        for (kind, channels) in &mut self.channels {
            for (k, input) in channels.iter_mut().enumerate() {
                let Some(Input::Texture(src)) = input else {
                    continue;
                };
                let src = src.display().to_string();
                let at = format!("{} iChannel{k}", kind.title());
                let index = srcs.iter().position(|s| *s == src).expect("listed above");
                reports.push(match &assigned[index] {
                    Assigned::Image { key, name } => {
                        *input = Some(Input::Texture(key.clone()));
                        ChannelReport {
                            line: format!("{at}: the texture `{src}` reads {name}"),
                            missing: false,
                        }
                    }
                    Assigned::Missing => {
                        *input = Some(Input::Noise);
                        ChannelReport {
                            line: format!(
                                "{at}: the texture `{src}` is not in the page: the built-in \
                                 noise instead (drop the image on the canvas)"
                            ),
                            missing: true,
                        }
                    }
                });
            }
        }
        self.prepared = false;
        reports
    }

    /// Clears the buffers: every pass starts again from black.
    pub fn clear_buffers(&mut self, gpu: &Gpu) {
        if let Some(buffers) = &mut self.buffers {
            buffers.reset(gpu);
        }
    }

    /// A key went down or up over the canvas.
    pub fn key(&mut self, event: &KeyEvent) {
        self.keyboard.key(event);
    }

    /// Whether the Image pass runs.
    pub fn runs(&self) -> bool {
        self.session.runs()
    }

    /// Encodes one frame: the buffer passes, then the Image pass into
    /// `canvas` (at the canvas's size: the buffers follow it). The
    /// channels' images come from `images`, as [`bind_images`](Self::bind_images) bound them.
    pub fn draw(
        &mut self,
        gpu: &Gpu,
        sandbox: &SandboxGpu,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameUniforms,
        canvas: &mut Canvas,
        images: &DroppedImages,
    ) {
        let (buffers, _) = Buffers::at_size(&mut self.buffers, gpu, canvas.size());
        if !self.prepared {
            let bindings: Vec<Binding> = self.channels.iter().map(|(k, c)| (*k, c)).collect();
            // Cannot fail: every image bound is one of `images`.
            if let Err(e) = buffers.prepare(gpu, &bindings, &|key| images.load(key)) {
                log::error!("{e}");
            }
            self.prepared = true;
        }
        let draws: Vec<PassDraw> = self
            .session
            .draws()
            .into_iter()
            .map(|draw| PassDraw {
                channels: self
                    .channels
                    .iter()
                    .find(|(kind, _)| *kind == draw.kind)
                    .map_or(draw.channels, |(_, channels)| channels),
                ..draw
            })
            .collect();
        buffers.set_keyboard(gpu, &self.keyboard);
        buffers.draw(gpu, sandbox, encoder, &draws, frame, canvas);
        self.keyboard.frame_drawn();
    }
}

/// Builds the pipelines of the compiled passes without blocking.
pub async fn build(builder: PipelineBuilder, pending: Pending) -> MultiBuilt {
    let mut built = Vec::new();
    for pass in &pending.build {
        let result = pass_builder(&builder, pass.kind)
            .build_async(&pass.compiled)
            .await;
        built.push((pass.clone(), result));
    }
    MultiBuilt { pending, built }
}

/// A pass's error as the editor shows it. Its line is in the pass's own
/// code, a string inside the JSON, so no line of the document is marked:
/// the message names the pass (`shader.json [Buffer A]:12:5: ...`).
fn reload_problem(e: &ReloadError) -> Problem {
    Problem {
        message: e.to_string(),
        line: None,
    }
}
