//! A multipass Shadertoy shader in the page (docs/web.md, "Multipass
//! shaders"): the shader document holds the JSON that Shadertoy's API and
//! export tools write (docs/sandbox.md, "Multipass"); its passes run into
//! the sandbox's float buffers as in the native window. The page has no
//! files: a texture a pass names is read as the built-in noise (the JSON
//! reader warns), and there is no keyboard texture input yet (all keys up).

use std::path::Path;

use super::editor::Problem;
use crate::gpu::Gpu;
use crate::sandbox::multipass::compile::CompiledPass;
use crate::sandbox::multipass::gpu::{Buffers, pass_builder};
use crate::sandbox::multipass::json;
use crate::sandbox::multipass::session::{MultiSession, Pending};
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
}

impl Default for PageMulti {
    fn default() -> Self {
        PageMulti {
            session: MultiSession::new(Path::new(JSON_NAME)),
            buffers: None,
            prepared: false,
        }
    }
}

impl PageMulti {
    /// Reads and compiles every pass of the JSON `text` (naga, on this
    /// thread); the passes' pipelines are built by [`build`].
    pub fn compile(&mut self, text: &str) -> Result<Pending, Problem> {
        let project = json::parse(Path::new(JSON_NAME), text).map_err(|message| Problem {
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

    /// Makes the built passes current; returns what to show under the
    /// editor. Their buffers are made at the next [`draw`](Self::draw).
    pub fn install(&mut self, built: MultiBuilt) -> Result<String, Problem> {
        self.prepared = false;
        if let Some(e) = self.session.install(built.pending, built.built) {
            return Err(reload_problem(&e));
        }
        let passes = self.session.draws().len();
        let mut said = format!("GLSL (Shadertoy style), multipass: {passes} passes: compiled");
        if let Some(first) = self.session.warnings().first() {
            said.push_str(&format!("; {first}"));
        }
        Ok(said)
    }

    /// Whether the Image pass runs.
    pub fn runs(&self) -> bool {
        self.session.runs()
    }

    /// Encodes one frame: the buffer passes, then the Image pass into
    /// `canvas` (at the canvas's size: the buffers follow it).
    pub fn draw(
        &mut self,
        gpu: &Gpu,
        sandbox: &SandboxGpu,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameUniforms,
        canvas: &mut Canvas,
    ) {
        let (buffers, _) = Buffers::at_size(&mut self.buffers, gpu, canvas.size());
        if !self.prepared {
            // Cannot fail here: the page has no image files, its channels
            // read noise (see the module's comment).
            if let Err(e) = buffers.prepare(gpu, &self.session.bindings()) {
                log::error!("{e}");
            }
            self.prepared = true;
        }
        buffers.draw(gpu, sandbox, encoder, &self.session.draws(), frame, canvas);
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
