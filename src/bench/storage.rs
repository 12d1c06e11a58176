//! Storage variants of a mesh's triangles on the GPU, timed against each
//! other (docs/performance.md, "Storage"), in the spirit of Kensler and
//! Shirley's point that the ray-triangle test and the storage layout are
//! one trade-off. A compute kernel (`storage.wgsl`) tests the same rays
//! against the same blocks of triangles with the shader's own
//! `hit_triangle` (the watertight test), reading the triangles either as
//! the renderer stores them (three vertices per triangle in BVH leaf order,
//! `src/gpu/shapes/mesh.rs`) or as an index triple into a shared vertex
//! array. Both return the nearest hit of every ray, so the timing compares
//! equal work and the bench checks that the hits are identical.

use std::fmt::Write as _;
use std::time::Duration;

use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use super::measure::median;
use crate::bvh::build_triangle_bvh;
use crate::gpu::compute::{Kernel, Prepared, with_kernel};
use crate::gpu::{Gpu, ShaderSource};
use crate::scene::{Geometry, TriangleTest};

/// `StorageRay` of `storage.wgsl`: a ray and the block of triangles (in
/// leaf order) it is tested against.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct StorageRay {
    origin: [f32; 3],
    first: u32,
    dir: [f32; 3],
    count: u32,
}

/// The rays and both layouts of one mesh, as the kernel reads them.
pub struct Layouts {
    rays: Vec<StorageRay>,
    /// Three vertices per triangle, in BVH leaf order: the renderer's.
    leaf_triangles: Vec<[f32; 4]>,
    /// The same triangles in the same order, as indices into `vertices`.
    indices: Vec<[u32; 4]>,
    vertices: Vec<[f32; 4]>,
}

impl Layouts {
    /// `rays` rays from a camera outside the mesh through a grid covering
    /// its bounding box; each workgroup of 64 rays (as a coherent bundle
    /// reaching one BVH leaf) is tested against the next `block` triangles
    /// in leaf order, so that the rays together read the whole mesh.
    pub fn new(geometry: &Geometry, rays: usize, block: usize) -> Layouts {
        let order = build_triangle_bvh(geometry).prims;
        let vertex = |p: DVec3| p.as_vec3().extend(0.0).to_array();
        let leaf_triangles = order
            .iter()
            .flat_map(|&t| {
                geometry.triangles[t as usize].map(|v| vertex(geometry.positions[v as usize]))
            })
            .collect();
        let indices = order
            .iter()
            .map(|&t| {
                let [a, b, c] = geometry.triangles[t as usize];
                [a, b, c, 0]
            })
            .collect();
        let vertices = geometry.positions.iter().map(|&p| vertex(p)).collect();
        Layouts {
            rays: camera_rays(geometry, rays, block.min(order.len())),
            leaf_triangles,
            indices,
            vertices,
        }
    }

    fn triangles(&self) -> usize {
        self.indices.len()
    }

    /// Ray-triangle tests in one dispatch.
    pub fn tests(&self) -> usize {
        self.rays.iter().map(|r| r.count as usize).sum()
    }

    /// Bytes per triangle of the renderer's layout.
    pub fn leaf_bytes_per_triangle(&self) -> f64 {
        std::mem::size_of_val(self.leaf_triangles.as_slice()) as f64 / self.triangles() as f64
    }

    /// Bytes per triangle of the indexed layout: its indices and its share
    /// of the vertex array.
    pub fn indexed_bytes_per_triangle(&self) -> f64 {
        let bytes = std::mem::size_of_val(self.indices.as_slice())
            + std::mem::size_of_val(self.vertices.as_slice());
        bytes as f64 / self.triangles() as f64
    }
}

/// The camera rays of [`Layouts::new`]: from 2.5 bounding radii away, one
/// per cell of a square grid through the box's centre, as wide as its
/// largest extent.
fn camera_rays(geometry: &Geometry, rays: usize, block: usize) -> Vec<StorageRay> {
    let lo = geometry
        .positions
        .iter()
        .fold(DVec3::INFINITY, |a, &p| a.min(p));
    let hi = geometry
        .positions
        .iter()
        .fold(DVec3::NEG_INFINITY, |a, &p| a.max(p));
    let (centre, radius) = (0.5 * (lo + hi), 0.5 * (hi - lo).length());
    let half = 0.5 * (hi - lo).max_element();
    let back = DVec3::new(1.0, 0.7, 1.3).normalize();
    let origin = centre + 2.5 * radius * back;
    let right = DVec3::Y.cross(back).normalize();
    let up = back.cross(right);
    let side = (rays as f64).sqrt().ceil() as usize;
    let blocks = geometry.triangles.len() - block + 1;
    (0..rays)
        .map(|i| {
            let (u, v) = ((i % side) as f64, (i / side) as f64);
            let at = |k: f64| half * (2.0 * (k + 0.5) / side as f64 - 1.0);
            let target = centre + at(u) * right + at(v) * up;
            StorageRay {
                origin: origin.as_vec3().to_array(),
                first: ((i / 64 * block) % blocks) as u32,
                dir: (target - origin).as_vec3().to_array(),
                count: block as u32,
            }
        })
        .collect()
}

/// The kernel of one layout, compiled and with its buffers bound.
fn prepare(gpu: &Gpu, layouts: &Layouts, indexed: bool) -> Result<Prepared, String> {
    let source = with_kernel(
        &ShaderSource::embedded(),
        "src/bench/storage.wgsl",
        include_str!("storage.wgsl"),
    );
    let kernel = Kernel {
        label: "storage",
        source: &source,
        entry: "nearest_in_block",
        constants: &[
            (
                "TRIANGLE_TEST",
                f64::from(TriangleTest::Watertight.number()),
            ),
            ("INDEXED", f64::from(u8::from(indexed))),
        ],
        group: 2,
    };
    let inputs: [&[u8]; 4] = [
        bytemuck::cast_slice(&layouts.rays),
        bytemuck::cast_slice(&layouts.leaf_triangles),
        bytemuck::cast_slice(&layouts.indices),
        bytemuck::cast_slice(&layouts.vertices),
    ];
    kernel.prepare(gpu, &inputs, 8 * layouts.rays.len())
}

/// Every ray's nearest hit in one layout: the bits of t (`T_FAR` when
/// none) and the triangle's place in leaf order (`u32::MAX` when none).
pub fn nearest_hits(gpu: &Gpu, layouts: &Layouts, indexed: bool) -> Result<Vec<[u32; 2]>, String> {
    let kernel = prepare(gpu, layouts, indexed)?;
    kernel.dispatch(gpu, layouts.rays.len())?;
    kernel.read(gpu)
}

/// One mesh: the time per ray-triangle test of each layout (median of
/// `runs` dispatches, the two timed in turn) and their bytes per triangle.
#[derive(Debug, Clone)]
pub struct StorageRow {
    pub mesh: &'static str,
    pub triangles: usize,
    pub tests: usize,
    pub leaf_ns: f64,
    pub indexed_ns: f64,
    /// Median of the per-pair ratios indexed / leaf order.
    pub ratio: f64,
    pub leaf_bytes: f64,
    pub indexed_bytes: f64,
    pub runs: usize,
}

impl StorageRow {
    /// The row's values, in the order of [`STORAGE_COLUMNS`], for the
    /// Markdown table and the CSV alike.
    fn fields(&self) -> [String; 9] {
        [
            self.mesh.to_string(),
            self.triangles.to_string(),
            self.tests.to_string(),
            self.runs.to_string(),
            format!("{:.3}", self.leaf_ns),
            format!("{:.3}", self.indexed_ns),
            format!("{:.3}", self.ratio),
            format!("{:.1}", self.leaf_bytes),
            format!("{:.1}", self.indexed_bytes),
        ]
    }
}

/// Times both layouts on `geometry` (see [`Layouts::new`]) after one
/// warm-up dispatch each, and fails if their hits differ.
pub fn measure(
    gpu: &Gpu,
    mesh: &'static str,
    geometry: &Geometry,
    rays: usize,
    block: usize,
    runs: usize,
) -> Result<StorageRow, String> {
    let layouts = Layouts::new(geometry, rays, block);
    let leaf = prepare(gpu, &layouts, false)?;
    let indexed = prepare(gpu, &layouts, true)?;
    let dispatch = |k: &Prepared| k.dispatch(gpu, layouts.rays.len());
    dispatch(&leaf)?;
    dispatch(&indexed)?;
    let (leaf_hits, indexed_hits): (Vec<[u32; 2]>, Vec<[u32; 2]>) =
        (leaf.read(gpu)?, indexed.read(gpu)?);
    if leaf_hits != indexed_hits {
        return Err(format!(
            "{mesh}: the two storage layouts found different hits"
        ));
    }
    let mut pairs: Vec<(Duration, Duration)> = Vec::new();
    for _ in 0..runs.max(1) {
        pairs.push((dispatch(&leaf)?, dispatch(&indexed)?));
    }
    let ns = |d: Duration| d.as_secs_f64() * 1e9 / layouts.tests() as f64;
    Ok(StorageRow {
        mesh,
        triangles: layouts.triangles(),
        tests: layouts.tests(),
        leaf_ns: median(pairs.iter().map(|p| ns(p.0))),
        indexed_ns: median(pairs.iter().map(|p| ns(p.1))),
        ratio: median(pairs.iter().map(|p| p.1.as_secs_f64() / p.0.as_secs_f64())),
        leaf_bytes: layouts.leaf_bytes_per_triangle(),
        indexed_bytes: layouts.indexed_bytes_per_triangle(),
        runs,
    })
}

/// The console line of one row.
pub fn console_line(r: &StorageRow) -> String {
    format!(
        "storage {}: leaf order {:.2} ns/test ({:.1} B/triangle), indexed {:.2} ns/test ({:.1} B/triangle), indexed/leaf {:.3}",
        r.mesh, r.leaf_ns, r.leaf_bytes, r.indexed_ns, r.indexed_bytes, r.ratio
    )
}

/// The storage table of `meshes.md`.
pub fn markdown(rows: &[StorageRow]) -> String {
    let mut md = String::from(
        "\n## Storage: triangles in leaf order against indexed vertices\n\n\
         Same rays, same blocks of triangles, the shader's watertight `hit_triangle`, \
         identical hits checked; median of the runs, the two layouts dispatched in turn.\n\n\
         | mesh | triangles | tests / dispatch | runs | leaf order (ns / test) | indexed (ns / test) | indexed / leaf order | leaf order (B / triangle) | indexed (B / triangle) |\n\
         | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n",
    );
    for r in rows {
        let _ = writeln!(md, "| {} |", r.fields().join(" | "));
    }
    md
}

/// The CSV columns of `storage.csv`.
pub const STORAGE_COLUMNS: &str = "mesh,triangles,tests_per_dispatch,runs,leaf_ns_per_test,indexed_ns_per_test,indexed_over_leaf,leaf_bytes_per_triangle,indexed_bytes_per_triangle";

pub fn csv(rows: &[StorageRow]) -> String {
    let mut out = format!("{STORAGE_COLUMNS}\n");
    for r in rows {
        let _ = writeln!(out, "{}", r.fields().join(","));
    }
    out
}
