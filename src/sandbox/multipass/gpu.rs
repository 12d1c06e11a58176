//! A multipass shader on the GPU: each buffer is two textures (ping-pong),
//! one written this frame while the other holds the previous frame. The
//! passes are drawn in Shadertoy's order, A, B, C, D, then Image into the
//! canvas that is shown; a pass reading a buffer drawn before it this frame
//! gets this frame's content, one reading itself or a later buffer the
//! previous frame's (docs/sandbox.md, "Multipass").

use std::path::{Path, PathBuf};

use super::keyboard::Keyboard;
use super::{BUFFERS, Input, PassKind};
use crate::gpu::{Gpu, fullscreen, render_target};
use crate::sandbox::channels;
use crate::sandbox::render::{Canvas, ChannelViews, PipelineBuilder, SandboxGpu, ShaderPipeline};
use crate::sandbox::uniforms::{FRAME_UNIFORMS_SIZE, FrameUniforms};
use crate::shader_params::ParamSet;

/// The buffers' format: 32-bit floats where the device can filter them
/// (as Shadertoy's buffers, so that a path tracer's sum of thousands of
/// frames keeps its precision), else 16-bit floats, which every WebGPU
/// device filters.
pub fn buffer_format(device: &wgpu::Device) -> wgpu::TextureFormat {
    if device
        .features()
        .contains(wgpu::Features::FLOAT32_FILTERABLE)
    {
        wgpu::TextureFormat::Rgba32Float
    } else {
        wgpu::TextureFormat::Rgba16Float
    }
}

/// The builder for a pass: buffers are drawn in [`buffer_format`].
pub fn pass_builder(builder: &PipelineBuilder, kind: PassKind) -> PipelineBuilder {
    match kind {
        PassKind::Buffer(_) => builder.for_format(buffer_format(builder.device())),
        PassKind::Image => builder.clone(),
    }
}

/// One buffer: the two textures it alternates between.
struct Buffer {
    textures: [wgpu::Texture; 2],
    views: [wgpu::TextureView; 2],
    params: wgpu::Buffer,
}

/// A channel's image, by the file it came from.
struct Image {
    path: PathBuf,
    texture: wgpu::Texture,
    view: wgpu::TextureView,
}

/// The buffers, the keyboard, the images the channels read, and which of
/// each buffer's textures is this frame's.
pub struct Buffers {
    format: wgpu::TextureFormat,
    size: (u32, u32),
    buffers: [Option<Buffer>; BUFFERS],
    frame: wgpu::Buffer,
    keyboard: wgpu::Texture,
    keyboard_view: wgpu::TextureView,
    /// An empty channel: black, as on Shadertoy.
    black: wgpu::TextureView,
    /// The images of the channels, by file (at most 4 per pass).
    images: Vec<Image>,
    /// Textures replaced (buffers cleared or resized, images no longer
    /// named), destroyed once the canvas no longer binds their views: in
    /// the browser a texture only dropped waits for JavaScript's garbage
    /// collector (docs/web.md, "GPU memory"), and a destroyed one must
    /// not be in a bind group made or used after it.
    retired: Vec<wgpu::Texture>,
    /// Frames drawn since the buffers were cleared: its parity picks the
    /// texture written.
    drawn: u64,
}

/// A pass to draw: its pipeline, channels and parameter values.
pub struct PassDraw<'a> {
    pub kind: PassKind,
    pub channels: &'a [Option<Input>; 4],
    pub pipeline: &'a ShaderPipeline,
    pub params: &'a ParamSet,
}

/// A pass's kind and channels, as [`Buffers::prepare`] reads them.
pub type Binding<'a> = (PassKind, &'a [Option<Input>; 4]);

impl Buffers {
    pub fn new(gpu: &Gpu, size: (u32, u32)) -> Self {
        let device = &gpu.device;
        let keyboard = Keyboard::default().texture(device, &gpu.queue);
        let black = channels::upload(device, &gpu.queue, &image::RgbaImage::new(1, 1))
            .create_view(&Default::default());
        Buffers {
            format: buffer_format(device),
            size: (size.0.max(1), size.1.max(1)),
            buffers: Default::default(),
            frame: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("multipass frame uniforms"),
                size: FRAME_UNIFORMS_SIZE,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            keyboard_view: keyboard.create_view(&Default::default()),
            keyboard,
            black,
            images: Vec::new(),
            retired: Vec::new(),
            drawn: 0,
        }
    }

    /// Makes the buffers of `project` (the others are dropped; those it
    /// keeps keep their content) and gets the images its channels name from
    /// `load` (the window reads files, [`channels::load`]; the page has the
    /// images dropped on it), each once while it stays named.
    /// An image that cannot be had is `load`'s error, naming the file.
    pub fn prepare(
        &mut self,
        gpu: &Gpu,
        passes: &[Binding],
        load: &dyn Fn(&Path) -> Result<image::RgbaImage, String>,
    ) -> Result<(), String> {
        let mut images: Vec<Image> = Vec::new();
        for (_, channels) in passes {
            for input in channels.iter().flatten() {
                let Input::Texture(path) = input else {
                    continue;
                };
                if images.iter().any(|i| &i.path == path) {
                    continue;
                }
                let image = match self.images.iter().position(|i| &i.path == path) {
                    Some(at) => self.images.swap_remove(at),
                    None => {
                        let texture = channels::upload(&gpu.device, &gpu.queue, &load(path)?);
                        Image {
                            path: path.clone(),
                            view: texture.create_view(&Default::default()),
                            texture,
                        }
                    }
                };
                images.push(image);
            }
        }
        let unnamed = std::mem::replace(&mut self.images, images);
        self.retired.extend(unnamed.into_iter().map(|i| i.texture));
        for k in 0..BUFFERS {
            let used = passes.iter().any(|(kind, _)| *kind == PassKind::Buffer(k));
            match (used, self.buffers[k].is_some()) {
                (true, false) => self.buffers[k] = Some(self.buffer(gpu)),
                (false, true) => self.retire(k, None),
                _ => {}
            }
        }
        Ok(())
    }

    /// Puts `buffer` in slot `k`, the textures it replaces to be destroyed
    /// after the next frame.
    fn retire(&mut self, k: usize, buffer: Option<Buffer>) {
        if let Some(old) = std::mem::replace(&mut self.buffers[k], buffer) {
            self.retired.extend(old.textures);
        }
    }

    fn buffer(&self, gpu: &Gpu) -> Buffer {
        let textures = [(); 2].map(|_| {
            render_target(
                &gpu.device,
                "multipass buffer",
                self.size,
                self.format,
                wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC,
            )
        });
        Buffer {
            views: textures
                .each_ref()
                .map(|t| t.create_view(&Default::default())),
            textures,
            params: Canvas::params_buffer(&gpu.device, 16),
        }
    }

    /// Clears every buffer (new textures start as zeros) and counts frames
    /// from 0 again: the `R` of the window.
    pub fn reset(&mut self, gpu: &Gpu) {
        for k in 0..BUFFERS {
            if self.buffers[k].is_some() {
                let buffer = self.buffer(gpu);
                self.retire(k, Some(buffer));
            }
        }
        self.drawn = 0;
    }

    /// A new render size clears the buffers.
    pub fn resize(&mut self, gpu: &Gpu, size: (u32, u32)) {
        let size = (size.0.max(1), size.1.max(1));
        if size != self.size {
            self.size = size;
            self.reset(gpu);
        }
    }

    pub fn size(&self) -> (u32, u32) {
        self.size
    }

    /// The buffers kept in `slot` at `size`: made on first use, cleared
    /// when the size changed. Returns whether they start empty.
    pub fn at_size<'a>(
        slot: &'a mut Option<Buffers>,
        gpu: &Gpu,
        size: (u32, u32),
    ) -> (&'a mut Buffers, bool) {
        let made = slot.is_none();
        let buffers = slot.get_or_insert_with(|| Buffers::new(gpu, size));
        let resized = buffers.size() != size;
        buffers.resize(gpu, size);
        (buffers, made || resized)
    }

    /// The keyboard's state for the next frame.
    pub fn set_keyboard(&self, gpu: &Gpu, keyboard: &Keyboard) {
        keyboard.write(&gpu.queue, &self.keyboard);
    }

    /// The views a channel of `reader` reads: for a buffer, the texture
    /// written this frame if the buffer was drawn before `reader`, else
    /// the previous frame's; a cube map or volume is the built-in one.
    fn views(&self, sandbox: &SandboxGpu, reader: PassKind, input: Option<&Input>) -> ChannelViews {
        sandbox.views(&self.view(sandbox, reader, input))
    }

    /// The 2-D view of [`views`](Self::views): black for a channel that is
    /// not a 2-D image.
    fn view(
        &self,
        sandbox: &SandboxGpu,
        reader: PassKind,
        input: Option<&Input>,
    ) -> wgpu::TextureView {
        let current = (self.drawn % 2) as usize;
        match input {
            None | Some(Input::Cube | Input::Volume) => self.black.clone(),
            Some(Input::Noise) => sandbox.noise().clone(),
            Some(Input::Keyboard) => self.keyboard_view.clone(),
            Some(Input::Texture(path)) => self
                .images
                .iter()
                .find(|i| &i.path == path)
                .map_or_else(|| sandbox.noise().clone(), |i| i.view.clone()),
            Some(Input::Buffer(k)) => {
                let done = PassKind::Buffer(*k) < reader;
                let slot = if done { current } else { 1 - current };
                match &self.buffers[*k] {
                    Some(buffer) => buffer.views[slot].clone(),
                    None => self.black.clone(),
                }
            }
        }
    }

    /// Encodes one frame: the buffer passes into their textures, the Image
    /// pass into `canvas`. Submit before the next frame. The textures
    /// replaced since the last frame are destroyed once the Image pass has
    /// bound the canvas to the new ones (the frames that used them were
    /// submitted before they were replaced; wgpu frees them after those).
    pub fn draw(
        &mut self,
        gpu: &Gpu,
        sandbox: &SandboxGpu,
        encoder: &mut wgpu::CommandEncoder,
        passes: &[PassDraw],
        frame: &FrameUniforms,
        canvas: &mut Canvas,
    ) {
        let device = &gpu.device;
        gpu.queue
            .write_buffer(&self.frame, 0, bytemuck::bytes_of(frame));
        let current = (self.drawn % 2) as usize;
        let mut rebound = false;
        for draw in passes {
            let views = draw
                .channels
                .each_ref()
                .map(|input| self.views(sandbox, draw.kind, input.as_ref()));
            let PassKind::Buffer(k) = draw.kind else {
                canvas.set_channel_views(device, sandbox, views);
                canvas.draw(gpu, sandbox, encoder, draw.pipeline, frame, draw.params);
                rebound = true;
                continue;
            };
            let Some(buffer) = &mut self.buffers[k] else {
                continue;
            };
            let bytes = draw.params.bytes();
            if bytes.len() as u64 > buffer.params.size() {
                buffer.params = Canvas::params_buffer(device, bytes.len() as u64);
            }
            gpu.queue.write_buffer(&buffer.params, 0, &bytes);
            let bind_group = Canvas::bind_group(
                device,
                sandbox,
                [&self.frame, &buffer.params],
                &views,
                &self.black,
            );
            fullscreen::pass(
                encoder,
                &draw.pipeline.pipeline,
                &[&bind_group],
                &buffer.views[current],
            );
        }
        self.drawn += 1;
        if rebound {
            self.retired.drain(..).for_each(|t| t.destroy());
        }
    }
}
