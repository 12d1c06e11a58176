//! The sandbox on the GPU: the user's fragment shader draws into a canvas
//! (an `Rgba32Float` texture at the render resolution, so NaN and values
//! above 1 survive for the checks), and a display pass scales the canvas to
//! the window or the PNG, showing NaN and infinities black (as browsers do)
//! or magenta ([`NanColor`]).

use std::borrow::Cow;

use super::channels::{self, CHANNELS};
use super::channels_3d;
use super::compose::Compiled;
use super::uniforms::{FRAME_UNIFORMS_SIZE, FrameUniforms};
use crate::gpu::{
    EXPORT_FORMAT, Gpu, GpuWaitError, OwnedTexture, fullscreen, read_texels, read_texture,
    readback_target, render_target,
};
use crate::shader_params::ParamSet;

/// What the user's shader draws into.
pub const CANVAS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

const VERTEX_WGSL: &str = "\
/// One triangle that covers the whole viewport; no vertex buffer needed.
@vertex
fn vs_fullscreen(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4(uv * 2.0 - 1.0, 0.0, 1.0);
}
";

const DISPLAY_WGSL: &str = "\
struct VertexOut {
    @builtin(position) position: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

@vertex
fn vs_display(@builtin(vertex_index) i: u32) -> VertexOut {
    let uv = vec2(f32((i << 1u) & 2u), f32(i & 2u));
    return VertexOut(vec4(uv * 2.0 - 1.0, 0.0, 1.0), uv);
}

@group(0) @binding(0) var canvas: texture_2d<f32>;

/// NaN and infinite pixels are drawn magenta instead of black.
override NAN_MAGENTA: bool = false;

/// Upside down: the copy of the canvas the next frame reads as its
/// previous frame, whose texture coordinates have y up like the shader's.
override FLIP_Y: bool = false;

/// True for an *Srgb target, which encodes by itself: the shader's values
/// are display values (as on Shadertoy), so they are decoded first.
override DECODE_SRGB: bool = false;

fn is_finite(x: vec3<f32>) -> vec3<bool> {
    return (bitcast<vec3<u32>>(x) & vec3(0x7f800000u)) != vec3(0x7f800000u);
}

fn srgb_decode(c: vec3<f32>) -> vec3<f32> {
    return select(pow((c + 0.055) / 1.055, vec3(2.4)), c / 12.92, c <= vec3(0.04045));
}

@fragment
fn fs_display(in: VertexOut) -> @location(0) vec4<f32> {
    // Nearest texel: each output pixel shows the canvas pixel under it.
    let size = textureDimensions(canvas);
    let at = vec2(in.uv.x, select(1.0 - in.uv.y, in.uv.y, FLIP_Y)) * vec2<f32>(size);
    let texel = min(vec2<u32>(at), size - 1u);
    let c = textureLoad(canvas, texel, 0).rgb;
    if any(!is_finite(c)) {
        return select(vec4(0.0, 0.0, 0.0, 1.0), vec4(1.0, 0.0, 1.0, 1.0), NAN_MAGENTA);
    }
    var rgb = clamp(c, vec3(0.0), vec3(1.0));
    if DECODE_SRGB {
        rgb = srgb_decode(rgb);
    }
    return vec4(rgb, 1.0);
}
";

/// Layouts and passes shared by every sandbox shader on one device.
pub struct SandboxGpu {
    bind_layout: wgpu::BindGroupLayout,
    pipeline_layout: wgpu::PipelineLayout,
    vertex: wgpu::ShaderModule,
    display_layout: wgpu::BindGroupLayout,
    display: Vec<(wgpu::TextureFormat, wgpu::RenderPipeline)>,
    /// The display pass upside down into [`BACKBUFFER_FORMAT`].
    backbuffer_copy: wgpu::RenderPipeline,
    /// How every texture is sampled: linear, repeating (Shadertoy's
    /// default for its textures).
    sampler: wgpu::Sampler,
    /// [`channels::noise_image`], the channel where no image is given.
    noise: wgpu::TextureView,
    /// The built-in cube map ([`channels_3d::cube_faces`]).
    cube: wgpu::TextureView,
    /// The built-in noise volume ([`channels_3d::noise_volume`]).
    volume: wgpu::TextureView,
}

/// The binding of channel 0 as a cube map (channel k at `+ k`).
pub const CUBE_BINDING: u32 = 8;
/// The binding of channel 0 as a volume (channel k at `+ k`).
pub const VOLUME_BINDING: u32 = 12;

/// What one channel binds: a 2-D view, a cube view and a 3-D view. The
/// prelude names the one of the channel's kind ([`channels_3d::ChannelKind`]);
/// the others hold the built-ins, so that every binding is filled.
#[derive(Clone)]
pub struct ChannelViews {
    pub flat: wgpu::TextureView,
    pub cube: wgpu::TextureView,
    pub volume: wgpu::TextureView,
}

/// The previous frame as the shader reads it: 8 bits per component,
/// clamped to 0..1, NaN black, as GLSL Sandbox's `backbuffer` holds it.
pub const BACKBUFFER_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// The user's shader as a pipeline.
pub struct ShaderPipeline {
    pub(crate) pipeline: wgpu::RenderPipeline,
    /// Each frame is copied for the next one to read.
    reads_backbuffer: bool,
}

/// What can build a [`ShaderPipeline`] on another thread.
#[derive(Clone)]
pub struct PipelineBuilder {
    device: wgpu::Device,
    pipeline_layout: wgpu::PipelineLayout,
    vertex: wgpu::ShaderModule,
    /// The format drawn into: [`CANVAS_FORMAT`], or a multipass buffer's.
    format: wgpu::TextureFormat,
}

/// How NaN and infinite pixels are shown. Browsers (so Shadertoy and GLSL
/// Sandbox) show them black, which is what the author saw; magenta makes
/// them stand out. Either way the checks warn about them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum NanColor {
    #[default]
    Black,
    Magenta,
}

impl SandboxGpu {
    /// Builds the shared parts, with a display pass for each of `formats`
    /// that shows NaN pixels in `nan`.
    pub fn new(gpu: &Gpu, formats: &[wgpu::TextureFormat], nan: NanColor) -> Self {
        let device = &gpu.device;
        let of_dimension = |binding, view_dimension| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: true },
                view_dimension,
                multisampled: false,
            },
            count: None,
        };
        let texture = |binding| of_dimension(binding, wgpu::TextureViewDimension::D2);
        let cube = |binding| of_dimension(binding, wgpu::TextureViewDimension::Cube);
        let volume = |binding| of_dimension(binding, wgpu::TextureViewDimension::D3);
        // The bindings of the preludes (docs/sandbox.md, "Textures", "Cube
        // maps and volumes"): frame uniforms, parameters, four channels, the
        // sampler, the previous frame, then each channel as a cube map and
        // as a volume (13 textures: WebGPU allows 16 per stage).
        let bind_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("sandbox uniforms"),
            entries: &[
                fullscreen::uniform_entry(0),
                fullscreen::uniform_entry(1),
                texture(2),
                texture(3),
                texture(4),
                texture(5),
                wgpu::BindGroupLayoutEntry {
                    binding: 6,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
                texture(7),
                cube(CUBE_BINDING),
                cube(CUBE_BINDING + 1),
                cube(CUBE_BINDING + 2),
                cube(CUBE_BINDING + 3),
                volume(VOLUME_BINDING),
                volume(VOLUME_BINDING + 1),
                volume(VOLUME_BINDING + 2),
                volume(VOLUME_BINDING + 3),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("sandbox"),
            bind_group_layouts: &[Some(&bind_layout)],
            immediate_size: 0,
        });
        let vertex = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("sandbox vertex"),
            source: wgpu::ShaderSource::Wgsl(VERTEX_WGSL.into()),
        });
        let display_layout = fullscreen::texture_layout(device, "sandbox canvas");
        let display_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("sandbox display"),
            source: wgpu::ShaderSource::Wgsl(DISPLAY_WGSL.into()),
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("sandbox display"),
            bind_group_layouts: &[Some(&display_layout)],
            immediate_size: 0,
        });
        let display = formats
            .iter()
            .map(|&format| {
                let decode = if format.is_srgb() { 1.0 } else { 0.0 };
                let magenta = if nan == NanColor::Magenta { 1.0 } else { 0.0 };
                let pipeline = fullscreen::pipeline(
                    device,
                    &layout,
                    (&display_module, "vs_display"),
                    (&display_module, "fs_display"),
                    &[("DECODE_SRGB", decode), ("NAN_MAGENTA", magenta)],
                    format,
                );
                (format, pipeline)
            })
            .collect();
        let backbuffer_copy = fullscreen::pipeline(
            device,
            &layout,
            (&display_module, "vs_display"),
            (&display_module, "fs_display"),
            &[("FLIP_Y", 1.0)],
            BACKBUFFER_FORMAT,
        );
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("sandbox channels"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let noise = channels::upload(device, &gpu.queue, &channels::noise_image())
            .create_view(&Default::default());
        let cube = channels_3d::upload_cube(device, &gpu.queue);
        let volume = channels_3d::upload_volume(device, &gpu.queue);
        SandboxGpu {
            bind_layout,
            pipeline_layout,
            vertex,
            display_layout,
            display,
            backbuffer_copy,
            sampler,
            noise,
            cube,
            volume,
        }
    }

    /// What a thread needs to build pipelines for this device.
    pub fn builder(&self, device: &wgpu::Device) -> PipelineBuilder {
        PipelineBuilder {
            device: device.clone(),
            pipeline_layout: self.pipeline_layout.clone(),
            vertex: self.vertex.clone(),
            format: CANVAS_FORMAT,
        }
    }

    /// The built-in noise channel image.
    pub(crate) fn noise(&self) -> &wgpu::TextureView {
        &self.noise
    }

    /// A channel reading `flat` as a 2-D image, the built-in cube map and
    /// noise volume as the other kinds.
    pub(crate) fn views(&self, flat: &wgpu::TextureView) -> ChannelViews {
        ChannelViews {
            flat: flat.clone(),
            cube: self.cube.clone(),
            volume: self.volume.clone(),
        }
    }

    fn display(&self, format: wgpu::TextureFormat) -> &wgpu::RenderPipeline {
        self.display
            .iter()
            .find(|(f, _)| *f == format)
            .map(|(_, p)| p)
            .unwrap_or_else(|| panic!("no sandbox display pipeline for {format:?}"))
    }
}

/// Why [`PipelineBuilder::build_within`] gave no pipeline.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum BuildFailed {
    /// wgpu refused the shader: the message, at the file.
    Refused(String),
    /// The GPU driver did not finish compiling the pipeline within the
    /// limit. It is still at it, so the device must be neither waited on
    /// nor dropped, as after [`TooSlow`].
    TooSlow,
}

impl PipelineBuilder {
    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    /// The same builder for pipelines that draw into `format` (a multipass
    /// buffer, docs/sandbox.md, "Multipass").
    pub fn for_format(&self, format: wgpu::TextureFormat) -> Self {
        PipelineBuilder {
            format,
            ..self.clone()
        }
    }

    /// [`build`](Self::build) on a thread of its own, waited for at most
    /// `limit`. A driver compiling a shader's pipeline can take without end
    /// (lavapipe was seen recursing for minutes on a 200-line GLSL Sandbox
    /// shader), which the frame's watchdog does not cover.
    pub fn build_within(
        &self,
        compiled: &Compiled,
        limit: std::time::Duration,
    ) -> Result<ShaderPipeline, BuildFailed> {
        let (builder, compiled) = (self.clone(), compiled.clone());
        let (sender, receiver) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let _ = sender.send(builder.build(&compiled));
        });
        match receiver.recv_timeout(limit) {
            Ok(built) => built.map_err(BuildFailed::Refused),
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => Err(BuildFailed::TooSlow),
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => Err(BuildFailed::Refused(
                "the GPU driver failed while compiling the shader".into(),
            )),
        }
    }

    /// Hands the validated module to wgpu. naga has checked it already, so an
    /// error here is rare (a limit of the adapter); it is returned, never
    /// panicked on, so the last good pipeline can keep running.
    pub fn build(&self, compiled: &Compiled) -> Result<ShaderPipeline, String> {
        pollster::block_on(self.build_async(compiled))
    }

    /// [`build`](Self::build) without blocking: in the browser wgpu reports
    /// a pipeline's validation errors only once control returns to the
    /// page's event loop (docs/web.md); natively the future is ready at once.
    pub async fn build_async(&self, compiled: &Compiled) -> Result<ShaderPipeline, String> {
        let device = &self.device;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(&compiled.file),
            source: wgpu::ShaderSource::Naga(Cow::Owned(compiled.module.clone())),
        });
        let pipeline = fullscreen::pipeline(
            device,
            &self.pipeline_layout,
            (&self.vertex, "vs_fullscreen"),
            (&module, compiled.entry_point),
            &[],
            self.format,
        );
        match scope.pop().await {
            Some(error) => Err(format!(
                "{}: wgpu rejected the shader: {error}",
                compiled.file
            )),
            None => Ok(ShaderPipeline {
                pipeline,
                reads_backbuffer: compiled.reads_backbuffer,
            }),
        }
    }
}

/// What the last frame's pixels say about the shader's output.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct CanvasStats {
    pub pixels: u64,
    /// Pixels with a NaN or infinite colour component.
    pub non_finite: u64,
    /// Pixels that are exactly (0, 0, 0, 0): nothing written.
    pub empty: u64,
    /// The colour every pixel is shown in (8-bit RGB, NaN drawn black), if
    /// they are all the same: a picture of one flat colour.
    pub flat: Option<[u8; 3]>,
}

impl CanvasStats {
    /// A warning for the user when the output looks like no output at all.
    pub fn warning(&self) -> Option<String> {
        if self.pixels == 0 {
            return None;
        }
        if self.non_finite == self.pixels {
            return Some(
                "every pixel is NaN or infinite (drawn black, magenta with --nan-color \
                 magenta): check divisions by zero, sqrt/log/pow of negative numbers and \
                 normalize(vec(0))"
                    .into(),
            );
        }
        if self.non_finite > 0 {
            return Some(format!(
                "{:.1}% of the pixels are NaN or infinite (drawn black, magenta with \
                 --nan-color magenta)",
                100.0 * self.non_finite as f64 / self.pixels as f64
            ));
        }
        if self.empty == self.pixels {
            return Some(
                "every pixel is (0, 0, 0, 0): does the shader write its output \
                 (gl_FragColor, fragColor, or main_image's return value)?"
                    .into(),
            );
        }
        None
    }
}

/// The image the user's shader draws into, and the buffers it reads.
pub struct Canvas {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    frame: wgpu::Buffer,
    params: wgpu::Buffer,
    /// The channel images; the noise where none was given.
    channels: [ChannelViews; CHANNELS],
    /// The textures of the images [`set_channel`](Self::set_channel) gave,
    /// destroyed when replaced (docs/web.md, "GPU memory").
    images: [Option<OwnedTexture>; CHANNELS],
    /// The previous frame, upside down ([`BACKBUFFER_FORMAT`]).
    backbuffer: wgpu::TextureView,
    bind_group: wgpu::BindGroup,
    display_bind_group: wgpu::BindGroup,
}

impl Canvas {
    pub fn new(gpu: &Gpu, sandbox: &SandboxGpu, size: (u32, u32)) -> Self {
        let device = &gpu.device;
        let frame = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sandbox frame uniforms"),
            size: FRAME_UNIFORMS_SIZE,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let params = Self::params_buffer(device, 16);
        let texture = Self::texture(device, size);
        let view = texture.create_view(&Default::default());
        let channels = std::array::from_fn(|_| sandbox.views(&sandbox.noise));
        let backbuffer = Self::backbuffer(device, size);
        let display_bind_group = Self::display_bind_group(device, sandbox, &view);
        let bind_group =
            Self::bind_group(device, sandbox, [&frame, &params], &channels, &backbuffer);
        Canvas {
            texture,
            view,
            frame,
            params,
            channels,
            images: Default::default(),
            backbuffer,
            bind_group,
            display_bind_group,
        }
    }

    /// Shows `image` in channel `k` (0..3), or the noise for None. The
    /// image it replaces is destroyed once the bind group no longer holds
    /// it (call between frames, after the last one was submitted).
    pub fn set_channel(
        &mut self,
        gpu: &Gpu,
        sandbox: &SandboxGpu,
        k: usize,
        image: Option<&image::RgbaImage>,
    ) {
        let texture =
            image.map(|image| OwnedTexture::new(channels::upload(&gpu.device, &gpu.queue, image)));
        self.channels[k].flat = texture
            .as_ref()
            .map_or_else(|| sandbox.noise.clone(), |t| t.view().clone());
        self.bind(&gpu.device, sandbox);
        // Dropping the image replaced destroys it, now that the bind group
        // no longer holds it.
        self.images[k] = texture;
    }

    /// Binds views to the four channels (a multipass shader's buffers
    /// change every frame).
    pub fn set_channel_views(
        &mut self,
        device: &wgpu::Device,
        sandbox: &SandboxGpu,
        views: [ChannelViews; CHANNELS],
    ) {
        self.channels = views;
        self.bind(device, sandbox);
    }

    /// The previous frame starts black, as on GLSL Sandbox.
    fn backbuffer(device: &wgpu::Device, size: (u32, u32)) -> wgpu::TextureView {
        Self::target(device, "sandbox backbuffer", size, BACKBUFFER_FORMAT)
            .create_view(&Default::default())
    }

    fn texture(device: &wgpu::Device, size: (u32, u32)) -> wgpu::Texture {
        Self::target(device, "sandbox canvas", size, CANVAS_FORMAT)
    }

    /// A texture drawn into and read by later passes, at least 1x1.
    fn target(
        device: &wgpu::Device,
        label: &str,
        size: (u32, u32),
        format: wgpu::TextureFormat,
    ) -> wgpu::Texture {
        render_target(
            device,
            label,
            (size.0.max(1), size.1.max(1)),
            format,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC,
        )
    }

    pub(crate) fn params_buffer(device: &wgpu::Device, size: u64) -> wgpu::Buffer {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sandbox parameters"),
            size,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    /// The bind group of the user's pass, after a buffer, a channel or
    /// the previous frame changed.
    fn bind(&mut self, device: &wgpu::Device, sandbox: &SandboxGpu) {
        self.bind_group = Self::bind_group(
            device,
            sandbox,
            [&self.frame, &self.params],
            &self.channels,
            &self.backbuffer,
        );
    }

    /// The bindings of the preludes, in the order of [`SandboxGpu`]'s layout.
    pub(crate) fn bind_group(
        device: &wgpu::Device,
        sandbox: &SandboxGpu,
        [frame, params]: [&wgpu::Buffer; 2],
        channels: &[ChannelViews; CHANNELS],
        backbuffer: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        let view = |binding, view| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(view),
        };
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: 0,
                resource: frame.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: params.as_entire_binding(),
            },
            view(2, &channels[0].flat),
            view(3, &channels[1].flat),
            view(4, &channels[2].flat),
            view(5, &channels[3].flat),
            wgpu::BindGroupEntry {
                binding: 6,
                resource: wgpu::BindingResource::Sampler(&sandbox.sampler),
            },
            view(7, backbuffer),
        ];
        for (k, channel) in (0u32..).zip(channels) {
            entries.push(view(CUBE_BINDING + k, &channel.cube));
            entries.push(view(VOLUME_BINDING + k, &channel.volume));
        }
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sandbox uniforms"),
            layout: &sandbox.bind_layout,
            entries: &entries,
        })
    }

    fn display_bind_group(
        device: &wgpu::Device,
        sandbox: &SandboxGpu,
        view: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sandbox canvas"),
            layout: &sandbox.display_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(view),
            }],
        })
    }

    /// Size in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.texture.width(), self.texture.height())
    }

    /// Changes the render resolution (the content is lost).
    pub fn resize(&mut self, gpu: &Gpu, sandbox: &SandboxGpu, size: (u32, u32)) {
        let size = (size.0.max(1), size.1.max(1));
        if size != self.size() {
            self.texture = Self::texture(&gpu.device, size);
            self.view = self.texture.create_view(&Default::default());
            self.display_bind_group = Self::display_bind_group(&gpu.device, sandbox, &self.view);
            self.backbuffer = Self::backbuffer(&gpu.device, size);
            self.bind(&gpu.device, sandbox);
        }
    }

    /// Encodes the user's shader drawing one frame into the canvas. The
    /// uniforms are written through `queue`: submit before the next frame.
    pub fn draw(
        &mut self,
        gpu: &Gpu,
        sandbox: &SandboxGpu,
        encoder: &mut wgpu::CommandEncoder,
        pipeline: &ShaderPipeline,
        frame: &FrameUniforms,
        params: &ParamSet,
    ) {
        let bytes = params.bytes();
        if bytes.len() as u64 > self.params.size() {
            self.params = Self::params_buffer(&gpu.device, bytes.len() as u64);
            self.bind(&gpu.device, sandbox);
        }
        gpu.queue.write_buffer(&self.params, 0, &bytes);
        gpu.queue
            .write_buffer(&self.frame, 0, bytemuck::bytes_of(frame));
        fullscreen::pass(encoder, &pipeline.pipeline, &[&self.bind_group], &self.view);
        if pipeline.reads_backbuffer {
            // The next frame's `backbuffer` is this one.
            fullscreen::pass(
                encoder,
                &sandbox.backbuffer_copy,
                &[&self.display_bind_group],
                &self.backbuffer,
            );
        }
    }

    /// Encodes the display pass: the canvas scaled onto `target`.
    pub fn show(
        &self,
        sandbox: &SandboxGpu,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        format: wgpu::TextureFormat,
    ) {
        fullscreen::pass(
            encoder,
            sandbox.display(format),
            &[&self.display_bind_group],
            target,
        );
    }

    /// The canvas as 8-bit RGBA (what the display pass shows at 1:1), for
    /// screenshots, headless renders and tests. A GPU that does not finish
    /// (a shader running too long) is an error.
    pub fn capture(
        &self,
        gpu: &Gpu,
        sandbox: &SandboxGpu,
    ) -> Result<image::RgbaImage, GpuWaitError> {
        let texture = readback_target(&gpu.device, "sandbox export", self.size(), EXPORT_FORMAT);
        let view = texture.create_view(&Default::default());
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        self.show(sandbox, &mut encoder, &view, EXPORT_FORMAT);
        gpu.queue.submit([encoder.finish()]);
        read_texture(gpu, &texture)
    }

    /// The canvas's pixels as the shader wrote them (RGBA, f32), rows from
    /// the top of the picture, for tests that measure values.
    pub fn texels(&self, gpu: &Gpu) -> Result<Vec<[f32; 4]>, GpuWaitError> {
        let data = read_texels(gpu, &self.texture)?;
        Ok(data
            .chunks_exact(16)
            .map(bytemuck::pod_read_unaligned)
            .collect())
    }

    /// Reads the canvas back and counts NaN, infinite and empty pixels.
    pub fn stats(&self, gpu: &Gpu) -> Result<CanvasStats, GpuWaitError> {
        let (width, height) = self.size();
        let data = read_texels(gpu, &self.texture)?;
        let mut stats = CanvasStats {
            pixels: u64::from(width) * u64::from(height),
            ..Default::default()
        };
        let mut shown = Vec::with_capacity(data.len() / 16);
        for px in data.chunks_exact(16) {
            let c: [f32; 4] = bytemuck::pod_read_unaligned(px);
            if c[..3].iter().any(|v| !v.is_finite()) {
                stats.non_finite += 1;
            } else if c == [0.0; 4] {
                stats.empty += 1;
            }
            shown.push(shown_rgb(c));
        }
        stats.flat = shown
            .first()
            .copied()
            .filter(|first| shown.iter().all(|c| c == first));
        Ok(stats)
    }
}

/// The 8-bit colour a pixel of the canvas is shown in: clamped, NaN and
/// infinite pixels black (docs/sandbox.md, "The window").
fn shown_rgb(c: [f32; 4]) -> [u8; 3] {
    if c[..3].iter().any(|v| !v.is_finite()) {
        return [0; 3];
    }
    [0, 1, 2].map(|k| (c[k].clamp(0.0, 1.0) * 255.0).round() as u8)
}

/// The longest one frame of a user's shader may take without a window
/// before it is stopped. lavapipe (Vulkan on the CPU) ends every loop after
/// 65535 iterations, so there an endless loop is only very slow; elsewhere
/// it never ends.
pub const FRAME_LIMIT: std::time::Duration = std::time::Duration::from_secs(20);

/// The message for [`BuildFailed::TooSlow`].
pub fn build_too_slow(file: &str) -> String {
    format!(
        "{file}: the GPU driver did not finish compiling the shader in {} s and it was \
         abandoned (a shader too long or too deeply nested for this driver)",
        FRAME_LIMIT.as_secs()
    )
}

/// A frame did not finish within [`FRAME_LIMIT`]. The GPU is still running
/// it: its device must not be waited on again, nor dropped (dropping waits
/// for it), so the caller reports the error and leaks the device.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TooSlow;

impl std::fmt::Display for TooSlow {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the shader did not finish a frame in {} s and was stopped: \
             an endless loop, or too much work per pixel for this GPU \
             (try a smaller --size)",
            FRAME_LIMIT.as_secs()
        )
    }
}

/// Drawing without a window (headless renders, tests): the shared passes
/// and a canvas that follows the size of the frames drawn.
pub struct Offscreen {
    sandbox: SandboxGpu,
    canvas: Option<Canvas>,
    /// The channel images (None: the noise).
    channels: [Option<image::RgbaImage>; CHANNELS],
}

impl Offscreen {
    /// Shows NaN pixels black, as browsers do.
    pub fn new(gpu: &Gpu) -> Self {
        Self::with_nan_color(gpu, NanColor::Black)
    }

    pub fn with_nan_color(gpu: &Gpu, nan: NanColor) -> Self {
        Offscreen {
            sandbox: SandboxGpu::new(gpu, &[EXPORT_FORMAT], nan),
            canvas: None,
            channels: Default::default(),
        }
    }

    /// The images of `iChannel0..3` (None: the noise).
    pub fn with_channels(mut self, images: [Option<image::RgbaImage>; CHANNELS]) -> Self {
        self.channels = images;
        self
    }

    /// Builds pipelines that this can draw with.
    pub fn builder(&self, gpu: &Gpu) -> PipelineBuilder {
        self.sandbox.builder(&gpu.device)
    }

    /// Draws one frame at the size of `frame.resolution` and waits for it,
    /// at most [`FRAME_LIMIT`]: a shader that takes longer (an endless loop,
    /// on most GPUs) is stopped with an error. The GPU may still be busy
    /// with it then: the device is no use any more, see [`TooSlow`].
    pub fn draw(
        &mut self,
        gpu: &Gpu,
        pipeline: &ShaderPipeline,
        params: &ParamSet,
        frame: &FrameUniforms,
    ) -> Result<(), TooSlow> {
        let size = (frame.resolution[0] as u32, frame.resolution[1] as u32);
        let sandbox = &self.sandbox;
        let channels = &self.channels;
        let canvas = self.canvas.get_or_insert_with(|| {
            let mut canvas = Canvas::new(gpu, sandbox, size);
            for (k, image) in channels.iter().enumerate() {
                if image.is_some() {
                    canvas.set_channel(gpu, sandbox, k, image.as_ref());
                }
            }
            canvas
        });
        canvas.resize(gpu, sandbox, size);
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        canvas.draw(gpu, sandbox, &mut encoder, pipeline, frame, params);
        let submission = gpu.queue.submit([encoder.finish()]);
        wait_for_frame(gpu, submission)
    }

    /// The last frame as 8-bit RGBA.
    pub fn image(&self, gpu: &Gpu) -> Result<image::RgbaImage, GpuWaitError> {
        let canvas = self.canvas.as_ref().expect("draw before reading");
        canvas.capture(gpu, &self.sandbox)
    }

    /// NaN, infinite and empty pixels of the last frame.
    pub fn stats(&self, gpu: &Gpu) -> Result<CanvasStats, GpuWaitError> {
        let canvas = self.canvas.as_ref().expect("draw before reading");
        canvas.stats(gpu)
    }
}

/// Waits for a frame's submission at most [`FRAME_LIMIT`]; see [`TooSlow`].
pub(crate) fn wait_for_frame(gpu: &Gpu, submission: wgpu::SubmissionIndex) -> Result<(), TooSlow> {
    gpu.device
        .poll(wgpu::PollType::Wait {
            submission_index: Some(submission),
            timeout: Some(FRAME_LIMIT),
        })
        .map(|_| ())
        .map_err(|_| TooSlow)
}

/// Renders one frame of a compiled shader without a window.
pub fn render_once(
    gpu: &Gpu,
    compiled: &Compiled,
    params: &ParamSet,
    frame: &FrameUniforms,
) -> Result<(image::RgbaImage, CanvasStats), String> {
    let mut offscreen = Offscreen::new(gpu);
    let pipeline = offscreen.builder(gpu).build(compiled)?;
    if let Err(stopped) = offscreen.draw(gpu, &pipeline, params, frame) {
        std::mem::forget((offscreen, pipeline));
        return Err(format!("{}: {stopped}", compiled.file));
    }
    let wait = |e: GpuWaitError| e.to_string();
    Ok((
        offscreen.image(gpu).map_err(wait)?,
        offscreen.stats(gpu).map_err(wait)?,
    ))
}
