//! A pixel's ray tree on the GPU (docs/ray-tree.md): the debug pass
//! `fs_ray_tree` of `shaders/ray_tree.wgsl` traces the ray through one
//! pixel's centre with the scene's own pipeline variant and `RAY_TREE` on,
//! writes every ray of the tree into a small `Rgba32Uint` target (ray x in
//! column x, the six rows of its `TreeNode`, then the counts), and this
//! reads it back as a [`RayTree`], the type the f64 reference records its
//! own tree in, so that the two can be set side by side.

use glam::{DVec3, Vec3};

use super::buffer;
use super::context::{Gpu, GpuWaitError};
use super::features::{ShaderOptions, borrowed};
use super::fullscreen;
use super::layout::PackedScene;
use super::offscreen::{RenderError, read_texels};
use super::outline::ID_FORMAT;
use super::shaders::ShaderSource;
use super::shapes::glue::DataAccess;
use super::texture::render_target;
use super::tracer::{
    PipelineError, SceneBuffers, in_error_scope, pipeline_source, scene_layout_entries,
};
use crate::reference::{RayKind, RayTree, TreeRay};
use crate::scene::{Scene, ShapeId, ShapeKind};

/// The rays the shader keeps (`TREE_MAX` in `shaders/ray_tree.wgsl`).
pub const TREE_MAX: usize = 256;

/// The shader's `TREE_NONE`: no parent.
const NONE: u32 = u32::MAX;

/// One ray as the shader writes it (`TreeNode`).
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GpuNode {
    kind: u32,
    depth: u32,
    parent: u32,
    shape_kind: u32,
    origin: [f32; 3],
    shape_index: u32,
    dir: [f32; 3],
    t: f32,
    normal: [f32; 3],
    fresnel: f32,
    throughput: [f32; 3],
    wr: f32,
    contribution: [f32; 3],
    wt: f32,
}

/// Rows of the target (`TREE_ROWS`): a node's six, then the counts.
const ROWS: u32 = 7;

/// The tree the GPU traced, and how many rays it traced in all (more than
/// it kept when the tree is larger than [`TREE_MAX`]).
#[derive(Debug, Clone, PartialEq)]
pub struct GpuRayTree {
    pub tree: RayTree,
    pub total: usize,
}

/// The debug pass for one scene's pipeline variant, run on any pixel.
pub struct RayTreeRenderer {
    pipeline: wgpu::RenderPipeline,
    scene_layout: wgpu::BindGroupLayout,
    bound_kinds: u32,
    /// Group 1 is the tracer's accumulation texture, which the pass does
    /// not read: an empty group stands in for it.
    empty: wgpu::BindGroup,
    pixel_layout: wgpu::BindGroupLayout,
}

impl RayTreeRenderer {
    /// Validates `source` and builds the pass for the variant `options`
    /// (with `RAY_TREE` on), as the tracer's pipelines are built.
    pub fn new(
        gpu: &Gpu,
        source: &ShaderSource,
        options: &ShaderOptions,
    ) -> Result<Self, PipelineError> {
        let options = ShaderOptions {
            ray_tree: true,
            ..options.clone()
        };
        let device = &gpu.device;
        let (source, access) = &pipeline_source(device, source, &options);
        source.validate()?;
        pollster::block_on(in_error_scope(device, || {
            Self::build(device, source, &options, *access)
        }))
    }

    fn build(
        device: &wgpu::Device,
        source: &ShaderSource,
        options: &ShaderOptions,
        access: DataAccess,
    ) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("raysandbox ray tree"),
            source: wgpu::ShaderSource::Wgsl(source.text().into()),
        });
        let bound_kinds = options.features.shape_kinds;
        let layout = |label, entries: &[wgpu::BindGroupLayoutEntry]| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(label),
                entries,
            })
        };
        let scene_layout = layout(
            "scene (ray tree)",
            &scene_layout_entries(bound_kinds, access),
        );
        let empty_layout = layout("nothing", &[]);
        let pixel_layout = layout("ray tree pixel", &[fullscreen::uniform_entry(0)]);
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("ray tree"),
            bind_group_layouts: &[
                Some(&scene_layout),
                Some(&empty_layout),
                Some(&pixel_layout),
            ],
            immediate_size: 0,
        });
        let constants = options.constants();
        let pipeline = fullscreen::pipeline(
            device,
            &pipeline_layout,
            (&module, "vs_fullscreen"),
            (&module, "fs_ray_tree"),
            &borrowed(&constants),
            ID_FORMAT,
        );
        let empty = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("nothing"),
            layout: &empty_layout,
            entries: &[],
        });
        RayTreeRenderer {
            pipeline,
            scene_layout,
            bound_kinds,
            empty,
            pixel_layout,
        }
    }

    /// The tree of the ray through the centre of pixel `(i, j)` of a
    /// `width x height` image of `scene` (row 0 at the top) and the lens
    /// centre, positions in world coordinates.
    pub fn trace(
        &self,
        gpu: &Gpu,
        scene: &Scene,
        (width, height): (u32, u32),
        (i, j): (u32, u32),
    ) -> Result<GpuRayTree, RenderError> {
        let device = &gpu.device;
        let packed = PackedScene::new(scene, width, height);
        let origin = packed.frame.origin;
        let buffers = SceneBuffers::with_layout(
            (device, &gpu.queue),
            (&self.scene_layout, self.bound_kinds),
            packed,
            None,
        )?;
        let pixel = [i as f32 + 0.5, j as f32 + 0.5, 0.0, 0.0];
        let pixel = buffer::with_contents(
            device,
            "ray tree pixel",
            bytemuck::bytes_of(&pixel),
            wgpu::BufferUsages::UNIFORM,
        );
        let pixel_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ray tree pixel"),
            layout: &self.pixel_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: pixel.as_entire_binding(),
            }],
        });
        let target = render_target(
            device,
            "ray tree",
            (TREE_MAX as u32, ROWS),
            ID_FORMAT,
            wgpu::TextureUsages::COPY_SRC,
        );
        let view = target.create_view(&Default::default());
        let mut encoder = device.create_command_encoder(&Default::default());
        let groups = [&buffers.bind_group, &self.empty, &pixel_group];
        fullscreen::pass(&mut encoder, &self.pipeline, &groups, &view);
        gpu.queue.submit([encoder.finish()]);
        let texels = read_texels(gpu, &target)?;
        Ok(decode(&texels, origin)?)
    }
}

/// The tree in the target's texels (row by row), moved from the frame
/// `origin` to world coordinates.
fn decode(texels: &[u8], origin: DVec3) -> Result<GpuRayTree, GpuWaitError> {
    const TEXEL: usize = 16;
    let texel = |x: usize, y: usize| &texels[(y * TREE_MAX + x) * TEXEL..][..TEXEL];
    let counts: [u32; 4] = bytemuck::pod_read_unaligned(texel(0, ROWS as usize - 1));
    let rays = (0..(counts[0] as usize).min(TREE_MAX))
        .map(|x| {
            let bytes: Vec<u8> = (0..6).flat_map(|y| texel(x, y).to_vec()).collect();
            tree_ray(&bytemuck::pod_read_unaligned(&bytes), origin)
        })
        .collect::<Option<Vec<TreeRay>>>()
        .ok_or_else(|| GpuWaitError::Lost("the ray tree's target holds no tree".into()))?;
    Ok(GpuRayTree {
        tree: RayTree::from_rays(rays),
        total: counts[1] as usize,
    })
}

/// One node as the reference records it; `None` for a kind or shape the
/// shader does not have.
fn tree_ray(n: &GpuNode, origin: DVec3) -> Option<TreeRay> {
    let kind = RayKind::from_number(n.kind)?;
    let v = |a: [f32; 3]| Vec3::from(a).as_dvec3();
    let shadow = kind == RayKind::Shadow;
    let shape = match n.shape_kind {
        _ if shadow => None,
        0 => None,
        k => Some(ShapeId::new(
            *ShapeKind::ALL.get(k as usize - 1)?,
            n.shape_index as usize,
        )),
    };
    Some(TreeRay {
        kind,
        depth: n.depth,
        parent: (n.parent != NONE).then_some(n.parent as usize),
        origin: v(n.origin) + origin,
        dir: v(n.dir),
        t: (n.t >= 0.0).then_some(f64::from(n.t)),
        shape,
        normal: v(n.normal),
        fresnel: f64::from(n.fresnel),
        wr: f64::from(n.wr),
        wt: f64::from(n.wt),
        throughput: v(n.throughput),
        contribution: v(n.contribution),
        light: shadow.then_some(n.shape_index as usize),
        blocked: shadow && n.shape_kind == 1,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_layout_is_the_shaders() {
        let source = ShaderSource::embedded();
        let text = source.text();
        assert!(text.contains(&format!("const TREE_MAX: u32 = {TREE_MAX}u;")));
        assert!(text.contains(&format!("const TREE_ROWS: u32 = {ROWS}u;")));
        assert_eq!(size_of::<GpuNode>(), 6 * 16);
    }
}
