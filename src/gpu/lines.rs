//! A line overlay drawn over the picture, after it and before the UI: the
//! rays of a pixel's tree in 3D (docs/ray-tree.md), which stay where they
//! are in the scene while the camera orbits.
//!
//! Every point is projected on the CPU, in f64, with the scene's own
//! camera model: the pinhole (or the lens centre) at `from`, the film
//! basis `u, v, w` and height of `Camera::film`, the same numbers the
//! tracer's camera rays are made from (`shaders/camera.wgsl`), so a ray
//! drawn here lies on the pixels its rays went through. The few hundred
//! vertices are sent again whenever the camera or the window changes.

use glam::DVec3;

use super::buffer;
use crate::scene::Camera;

/// A coloured segment between two world points; the colour sRGB-encoded
/// (as the picture's pixels are).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    pub a: DVec3,
    pub b: DVec3,
    pub colour: [u8; 3],
}

/// One vertex as `shaders/lines.wgsl` reads it.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Vertex {
    clip: [f32; 4],
    colour: [f32; 4],
}

/// The clip coordinates of world point `p` seen by `camera` on a target
/// `aspect` times wider than high: film coordinates `x = dot(q, u)`,
/// `y = dot(q, v)` at depth `z = -dot(q, w)` of `q = p - from`, divided by
/// the film's half width and half height (`camera_ray`'s
/// `x = h aspect (px / W - 0.5)` turned around). The depth keeps
/// `0 <= z - near <= z`, so the hardware clips what lies closer than
/// `near` or behind the eye.
pub fn project(camera: &Camera, aspect: f64, p: DVec3) -> [f32; 4] {
    let film = camera.film();
    let q = p - camera.from;
    let z = -q.dot(film.w);
    let near = 1e-3 * (camera.from - camera.to).length();
    [
        (2.0 * q.dot(film.u) / (film.height * aspect)) as f32,
        (2.0 * q.dot(film.v) / film.height) as f32,
        (z - near) as f32,
        z as f32,
    ]
}

/// The overlay's pipeline and its vertices.
pub struct LineOverlay {
    pipeline: wgpu::RenderPipeline,
    /// Whether the target encodes sRGB by itself (the colours are then
    /// sent linear).
    srgb_target: bool,
    vertices: Option<(wgpu::Buffer, u32)>,
}

impl LineOverlay {
    /// The pipeline for targets of `format`.
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("lines"),
            source: wgpu::ShaderSource::Wgsl(include_str!("../../shaders/lines.wgsl").into()),
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("lines"),
            bind_group_layouts: &[],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("lines"),
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_line"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: size_of::<Vertex>() as u64,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x4],
                })],
            },
            primitive: wgpu::PrimitiveState {
                topology: wgpu::PrimitiveTopology::LineList,
                ..Default::default()
            },
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_line"),
                compilation_options: Default::default(),
                targets: &[Some(format.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        LineOverlay {
            pipeline,
            srgb_target: format.is_srgb(),
            vertices: None,
        }
    }

    /// Projects `segments` with `camera` for a target of `size` pixels and
    /// keeps them for [`Self::draw`]; none: nothing is drawn. A line is
    /// `width` pixels wide: drawn `width` x `width` times, shifted by a
    /// pixel each time (wgpu draws lines one pixel wide, and a class sees a
    /// projected picture from afar).
    pub fn set(
        &mut self,
        device: &wgpu::Device,
        camera: &Camera,
        (size, width): ((u32, u32), u32),
        segments: &[Segment],
    ) {
        if segments.is_empty() || size.0 == 0 || size.1 == 0 {
            self.vertices = None;
            return;
        }
        let aspect = f64::from(size.0) / f64::from(size.1);
        let pixel = [2.0 / size.0 as f32, -2.0 / size.1 as f32];
        let shifts: Vec<[f32; 2]> = (0..width.max(1))
            .flat_map(|i| (0..width.max(1)).map(move |j| [i as f32, j as f32]))
            .map(|[i, j]| [i * pixel[0], j * pixel[1]])
            .collect();
        let vertices: Vec<Vertex> = segments
            .iter()
            .flat_map(|s| {
                let colour = self.colour(s.colour);
                let ends = [s.a, s.b].map(|p| project(camera, aspect, p));
                shifts.iter().flat_map(move |[dx, dy]| {
                    ends.map(|[x, y, z, w]| Vertex {
                        clip: [x + dx * w, y + dy * w, z, w],
                        colour,
                    })
                })
            })
            .collect();
        let buffer = buffer::with_contents(
            device,
            "lines",
            bytemuck::cast_slice(&vertices),
            wgpu::BufferUsages::VERTEX,
        );
        self.vertices = Some((buffer, vertices.len() as u32));
    }

    /// The colour as the target wants it: linear for an sRGB target,
    /// whose hardware encodes it again.
    fn colour(&self, srgb: [u8; 3]) -> [f32; 4] {
        let c = srgb.map(|x| f32::from(x) / 255.0);
        let c = if self.srgb_target {
            c.map(|x| {
                if x <= 0.04045 {
                    x / 12.92
                } else {
                    ((x + 0.055) / 1.055).powf(2.4)
                }
            })
        } else {
            c
        };
        [c[0], c[1], c[2], 1.0]
    }

    /// Draws the lines over what `target` holds.
    pub fn draw(&self, encoder: &mut wgpu::CommandEncoder, target: &wgpu::TextureView) {
        let Some((buffer, count)) = &self.vertices else {
            return;
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("lines"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_vertex_buffer(0, buffer.slice(..));
        pass.draw(0..*count, 0..1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    /// A point on the ray through pixel (px, py) projects back onto that
    /// pixel: the overlay and the tracer share the camera model.
    #[test]
    fn points_on_a_camera_ray_project_onto_its_pixel() {
        let scene: crate::scene::Scene =
            toml::from_str("camera = { from = [0.2, 1.4, 5.8], to = [0.1, 0.8, 0.0], fov = 40 }")
                .unwrap();
        let camera = crate::reference::Camera::new(&scene.camera);
        let (width, height) = (320u32, 180u32);
        for (px, py) in [(0.5, 0.5), (160.0, 90.0), (300.25, 17.75)] {
            let ray = crate::reference::camera_ray(&camera, width, height, px, py, DVec2::ZERO);
            for t in [0.5, 3.0, 40.0] {
                let c = project(&scene.camera, 320.0 / 180.0, ray.origin + t * ray.dir);
                let x = (f64::from(c[0] / c[3]) + 1.0) / 2.0 * f64::from(width);
                let y = (1.0 - f64::from(c[1] / c[3])) / 2.0 * f64::from(height);
                assert!(
                    (x - px).abs() < 1e-3 && (y - py).abs() < 1e-3,
                    "{px} {py} {t}: {x} {y}"
                );
            }
        }
    }
}
