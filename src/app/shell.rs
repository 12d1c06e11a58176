//! What every window of the program has: the winit window, a GPU device that
//! can draw into it, egui (input, frame, painting on top of the image) and
//! the event lines for scripts. The scene viewer and the sandbox window
//! differ only in what they draw under the UI.

use web_time::{Duration, Instant};
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::window::{Fullscreen, Window};

use crate::gpu::Gpu;

/// Switches between a borderless fullscreen window and a normal one.
pub fn toggle_fullscreen(window: &Window) {
    let full = window.fullscreen().is_some();
    window.set_fullscreen((!full).then_some(Fullscreen::Borderless(None)));
}

/// egui's context, its winit input state and its wgpu renderer.
pub struct EguiLayer {
    pub ctx: egui::Context,
    pub state: egui_winit::State,
    renderer: egui_wgpu::Renderer,
}

/// One egui frame, tessellated and with its textures uploaded, ready to be
/// painted over the image; [`EguiLayer::finish`] frees what it no longer needs.
pub struct Painting {
    jobs: Vec<egui::ClippedPrimitive>,
    screen: egui_wgpu::ScreenDescriptor,
    free: Vec<egui::TextureId>,
    /// How soon egui wants to be drawn again (animations, tooltips).
    pub repaint_delay: Duration,
}

impl EguiLayer {
    pub fn new(window: &Window, gpu: &Gpu, format: wgpu::TextureFormat) -> Self {
        let ctx = egui::Context::default();
        let state = egui_winit::State::new(
            ctx.clone(),
            egui::ViewportId::ROOT,
            window,
            Some(window.scale_factor() as f32),
            window.theme(),
            Some(gpu.device.limits().max_texture_dimension_2d as usize),
        );
        let renderer =
            egui_wgpu::Renderer::new(&gpu.device, format, egui_wgpu::RendererOptions::default());
        EguiLayer {
            ctx,
            state,
            renderer,
        }
    }

    /// Runs the UI for one frame and hands the platform output (cursor,
    /// clipboard) to the window.
    pub fn run(&mut self, window: &Window, ui: impl FnMut(&mut egui::Ui)) -> egui::FullOutput {
        let raw = self.state.take_egui_input(window);
        let output = self.ctx.run_ui(raw, ui);
        self.state
            .handle_platform_output(window, output.platform_output.clone());
        output
    }

    /// Tessellates the frame and uploads its textures.
    pub fn prepare(
        &mut self,
        gpu: &Gpu,
        window: &Window,
        mut output: egui::FullOutput,
    ) -> Painting {
        let ppp = output.pixels_per_point;
        let jobs = self.ctx.tessellate(output.shapes, ppp);
        let mut textures = std::mem::take(&mut output.textures_delta);
        for (id, deltas) in &textures.set {
            for delta in deltas {
                self.renderer
                    .update_texture(&gpu.device, &gpu.queue, *id, delta);
            }
        }
        textures.set.clear();
        let free = textures.free.drain().collect();
        let size = window.inner_size();
        let repaint_delay = output
            .viewport_output
            .get(&egui::ViewportId::ROOT)
            .map_or(Duration::MAX, |v| v.repaint_delay);
        Painting {
            jobs,
            screen: egui_wgpu::ScreenDescriptor {
                size_in_pixels: [size.width, size.height],
                pixels_per_point: ppp,
            },
            free,
            repaint_delay,
        }
    }

    /// Paints the UI over what `view` holds; returns the command buffers to
    /// submit before the encoder's own.
    pub fn paint(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        view: &wgpu::TextureView,
        painting: &Painting,
    ) -> Vec<wgpu::CommandBuffer> {
        let buffers = self.renderer.update_buffers(
            &gpu.device,
            &gpu.queue,
            encoder,
            &painting.jobs,
            &painting.screen,
        );
        let mut pass = encoder
            .begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("egui"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            })
            .forget_lifetime();
        self.renderer
            .render(&mut pass, &painting.jobs, &painting.screen);
        buffers
    }

    /// Frees the textures the frame no longer needs (call after painting,
    /// also when the frame was skipped).
    pub fn finish(&mut self, painting: Painting) -> Duration {
        for id in &painting.free {
            self.renderer.free_texture(id);
        }
        painting.repaint_delay
    }
}

/// Event lines (`event: ready`, `event: shader-error FILE:LINE:COL`, ...)
/// printed on stdout for scripts and tests, and logged.
#[derive(Debug, Clone, Copy, Default)]
pub struct EventLog {
    pub print: bool,
}

impl EventLog {
    pub fn event(&self, line: &str) {
        log::info!("{line}");
        if self.print {
            use std::io::Write;
            let mut out = std::io::stdout().lock();
            let _ = writeln!(out, "event: {line}");
            let _ = out.flush();
        }
    }
}

/// Lets the event loop sleep until egui's next requested repaint (an
/// animation, a tooltip) or, without one, until an event arrives: an idle
/// window uses no CPU. True when that repaint is due now.
pub fn wait_for_repaint(repaint_at: &mut Option<Instant>, event_loop: &ActiveEventLoop) -> bool {
    match *repaint_at {
        Some(at) if at <= Instant::now() => {
            *repaint_at = None;
            event_loop.set_control_flow(ControlFlow::Wait);
            true
        }
        Some(at) => {
            event_loop.set_control_flow(ControlFlow::WaitUntil(at));
            false
        }
        None => {
            event_loop.set_control_flow(ControlFlow::Wait);
            false
        }
    }
}
