//! Watertightness of the three ray-triangle tests (docs/accuracy.md,
//! "Triangle meshes: rays through shared edges and vertices"): rays aimed exactly at shared edges and vertices of a
//! closed mesh must meet one of the triangles there, whatever the rounding.
//! A ray that meets none of them slipped through a crack between
//! neighbours: a leak. Counted per test by the f64 reference
//! (`reference::shapes::mesh::hit_triangle`) and by the shader's own WGSL
//! in f32 (`hit_triangle` of `shaders/shapes/mesh.wgsl`, run by a compute
//! kernel, `leaks.wgsl`), on a tessellated sphere, the bunny, and a fan of
//! 1000 slivers around one vertex.

use std::path::Path;

use bytemuck::{Pod, Zeroable};
use glam::DVec3;
use rayon::prelude::*;

use super::table::table;
use crate::gpu::compute::{Kernel, with_kernel};
use crate::gpu::{Gpu, ShaderSource};
use crate::reference::ray::Ray;
use crate::reference::shapes::mesh::hit_triangle;
use crate::scene::{NamedOption, TriangleTest};

/// A mesh to aim at, its vertices already rounded to f32 (as the GPU gets
/// them), so that the f64 count and the f32 count test the same triangles.
pub struct LeakMesh {
    pub name: &'static str,
    pub positions: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
}

impl LeakMesh {
    fn new(name: &'static str, positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Self {
        let positions = positions.iter().map(|p| p.as_vec3().as_dvec3()).collect();
        LeakMesh {
            name,
            positions,
            triangles,
        }
    }

    fn normal(&self, triangle: u32) -> DVec3 {
        let p = self.triangles[triangle as usize].map(|v| self.positions[v as usize]);
        (p[1] - p[0]).cross(p[2] - p[0]).normalize()
    }
}

/// The three meshes of the count: a UV sphere of 24 x 48 quads (closed),
/// the bundled bunny (`assets/meshes/bunny.obj`; its decimation left a few
/// holes, so only edges with a triangle on each side are aimed at) and a
/// fan of 1000 slivers around the origin (open, but every spoke is shared).
pub fn meshes() -> Result<Vec<LeakMesh>, String> {
    let (sphere_p, sphere_t) = uv_sphere(24);
    let (fan_p, fan_t) = fan(1000);
    let bunny_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/meshes/bunny.obj");
    let bunny = crate::scene::load_file(&bunny_path, false)?;
    Ok(vec![
        LeakMesh::new("tessellated sphere", sphere_p, sphere_t),
        LeakMesh::new("bunny", bunny.positions, bunny.triangles),
        LeakMesh::new("fan of 1000 slivers", fan_p, fan_t),
    ])
}

/// A closed sphere of `n` x `2n` quads (each two triangles), counter-clockwise
/// from outside.
pub fn uv_sphere(n: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut positions = vec![DVec3::Y, -DVec3::Y];
    for i in 1..n {
        let theta = std::f64::consts::PI * f64::from(i) / f64::from(n);
        for j in 0..2 * n {
            let phi = std::f64::consts::PI * f64::from(j) / f64::from(n);
            positions.push(DVec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                -theta.sin() * phi.sin(),
            ));
        }
    }
    let ring = |i: u32, j: u32| 2 + (i - 1) * 2 * n + j % (2 * n);
    let mut triangles = Vec::new();
    for j in 0..2 * n {
        triangles.push([0, ring(1, j), ring(1, j + 1)]);
        triangles.push([1, ring(n - 1, j + 1), ring(n - 1, j)]);
        for i in 1..n - 1 {
            let (a, b, c, d) = (
                ring(i, j),
                ring(i, j + 1),
                ring(i + 1, j + 1),
                ring(i + 1, j),
            );
            triangles.push([a, d, c]);
            triangles.push([a, c, b]);
        }
    }
    (positions, triangles)
}

/// A fan of `n` thin triangles around the origin, in the plane z = 0.
pub fn fan(n: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut positions = vec![DVec3::ZERO];
    for k in 0..n {
        let a = std::f64::consts::TAU * f64::from(k) / f64::from(n);
        positions.push(DVec3::new(a.cos(), a.sin(), 0.0));
    }
    let triangles = (0..n).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect();
    (positions, triangles)
}

/// A small deterministic generator (xorshift): the same rays every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn direction(&mut self) -> DVec3 {
        let z = 2.0 * self.next() - 1.0;
        let a = std::f64::consts::TAU * self.next();
        let r = (1.0 - z * z).sqrt();
        DVec3::new(r * a.cos(), r * a.sin(), z)
    }
}

/// Which triangles meet where: per vertex the triangles around it, the
/// edges with a triangle on each side, and the vertices all of whose edges
/// are such (inside the surface, not on a hole's rim).
struct Topology {
    star: Vec<Vec<u32>>,
    shared: Vec<((u32, u32), [u32; 2])>,
    interior: Vec<bool>,
}

impl Topology {
    fn of(mesh: &LeakMesh) -> Topology {
        let mut edges: Vec<((u32, u32), u32)> = mesh
            .triangles
            .iter()
            .zip(0u32..)
            .flat_map(|(t, i)| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])].map(|e| (e, i)))
            .map(|((a, b), i)| ((a.min(b), a.max(b)), i))
            .collect();
        edges.sort_unstable();
        let mut interior = vec![true; mesh.positions.len()];
        let mut shared = Vec::new();
        for run in edges.chunk_by(|x, y| x.0 == y.0) {
            let (a, b) = run[0].0;
            if let [(_, f), (_, g)] = run {
                shared.push(((a, b), [*f, *g]));
            } else {
                interior[a as usize] = false;
                interior[b as usize] = false;
            }
        }
        let mut star = vec![Vec::new(); mesh.positions.len()];
        for (t, i) in mesh.triangles.iter().zip(0u32..) {
            for v in t {
                star[*v as usize].push(i);
            }
        }
        Topology {
            star,
            shared,
            interior,
        }
    }
}

/// One aimed ray: from `origin` exactly (in f64) through `target`, a shared
/// vertex `a` (then `b = a`) or a point of the shared edge `a b`.
#[derive(Debug, Clone, Copy)]
struct Aim {
    origin: DVec3,
    target: DVec3,
    a: u32,
    b: u32,
}

/// `rays` rays aimed at shared vertices (one in four, interior vertices
/// only) and at random points of shared edges, each from a random point 3
/// units away in front of every triangle that meets at the target (so the
/// ray crosses the surface there rather than grazing it).
fn aims(mesh: &LeakMesh, topology: &Topology, rays: usize, seed: u64) -> Vec<Aim> {
    let mut rng = Rng(seed);
    let mut out = Vec::with_capacity(rays);
    while out.len() < rays {
        let k = (rng.next() * topology.shared.len() as f64) as usize;
        let ((a, b), faces) = topology.shared[k];
        let (target, b, faces) = if out.len() % 4 == 0 {
            if !topology.interior[a as usize] {
                continue;
            }
            (
                mesh.positions[a as usize],
                a,
                topology.star[a as usize].as_slice(),
            )
        } else {
            let (pa, pb) = (mesh.positions[a as usize], mesh.positions[b as usize]);
            (pa.lerp(pb, rng.next()), b, faces.as_slice())
        };
        let dir = rng.direction();
        if faces.iter().all(|&f| mesh.normal(f).dot(dir) > 0.05) {
            out.push(Aim {
                origin: target + 3.0 * dir,
                target,
                a,
                b,
            });
        }
    }
    out
}

/// Leaks of the f64 reference's `test`: rays that meet no triangle around
/// their target.
fn count_f64(mesh: &LeakMesh, topology: &Topology, aims: &[Aim], test: TriangleTest) -> usize {
    let meets = |ray: &Ray, v: u32| {
        topology.star[v as usize].iter().any(|&t| {
            let p = mesh.triangles[t as usize].map(|v| mesh.positions[v as usize]);
            hit_triangle(test, ray, p, f64::INFINITY).is_some()
        })
    };
    aims.par_iter()
        .filter(|aim| {
            let ray = Ray::new(aim.origin, aim.target - aim.origin);
            !meets(&ray, aim.a) && !meets(&ray, aim.b)
        })
        .count()
}

/// `LeakRay` of `leaks.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct GpuRay {
    origin: [f32; 3],
    a: u32,
    dir: [f32; 3],
    b: u32,
}

/// The mesh and its rays as the kernel reads them: the rays in f32 (origin
/// rounded, direction `target - origin` rounded), the vertices, triangles
/// and stars.
struct GpuInputs {
    rays: Vec<GpuRay>,
    vertices: Vec<[f32; 4]>,
    triangles: Vec<[u32; 4]>,
    star_start: Vec<u32>,
    star: Vec<u32>,
}

impl GpuInputs {
    fn new(mesh: &LeakMesh, topology: &Topology, aims: &[Aim]) -> GpuInputs {
        let rays = aims
            .iter()
            .map(|aim| {
                let origin = aim.origin.as_vec3();
                GpuRay {
                    origin: origin.to_array(),
                    a: aim.a,
                    dir: (aim.target - origin.as_dvec3()).as_vec3().to_array(),
                    b: aim.b,
                }
            })
            .collect();
        let mut star_start = vec![0u32];
        for around in &topology.star {
            star_start.push(star_start.last().copied().unwrap_or(0) + around.len() as u32);
        }
        GpuInputs {
            rays,
            vertices: mesh
                .positions
                .iter()
                .map(|p| p.as_vec3().extend(0.0).to_array())
                .collect(),
            triangles: mesh
                .triangles
                .iter()
                .map(|t| [t[0], t[1], t[2], 0])
                .collect(),
            star_start,
            star: topology.star.concat(),
        }
    }
}

/// Leaks of the shader's `test` in f32 on the GPU.
fn count_gpu(
    gpu: &Gpu,
    source: &ShaderSource,
    inputs: &GpuInputs,
    test: TriangleTest,
) -> Result<usize, String> {
    let kernel = Kernel {
        label: "leak count",
        source,
        entry: "count_leaks",
        constants: &[("TRIANGLE_TEST", f64::from(test.number()))],
        group: 2,
    };
    let bytes: [&[u8]; 5] = [
        bytemuck::cast_slice(&inputs.rays),
        bytemuck::cast_slice(&inputs.vertices),
        bytemuck::cast_slice(&inputs.triangles),
        bytemuck::cast_slice(&inputs.star_start),
        bytemuck::cast_slice(&inputs.star),
    ];
    let hits: Vec<u32> = kernel.run_with(gpu, &bytes, inputs.rays.len(), inputs.rays.len())?;
    Ok(hits.iter().filter(|&&h| h == 0).count())
}

/// One mesh and test: rays shot, and leaks in f64 (reference) and in f32
/// (the shader on the GPU).
#[derive(Debug, Clone)]
pub struct LeakRow {
    pub mesh: &'static str,
    pub test: TriangleTest,
    pub rays: usize,
    pub f64_leaks: usize,
    pub gpu_leaks: usize,
}

impl LeakRow {
    pub fn f64_per_million(&self) -> f64 {
        per_million(self.f64_leaks, self.rays)
    }

    pub fn gpu_per_million(&self) -> f64 {
        per_million(self.gpu_leaks, self.rays)
    }
}

fn per_million(leaks: usize, rays: usize) -> f64 {
    leaks as f64 * 1e6 / rays.max(1) as f64
}

/// The seed of the rays: the same rays in every run and every report.
const SEED: u64 = 0x9e37_79b9_7f4a_7c15;

/// Counts the leaks of every test on every mesh of [`meshes`], `rays`
/// rays per mesh (the same rays for every test).
pub fn measure(gpu: &Gpu, source: &ShaderSource, rays: usize) -> Result<Vec<LeakRow>, String> {
    let source = with_kernel(source, "src/stress/leaks.wgsl", include_str!("leaks.wgsl"));
    let mut rows = Vec::new();
    for mesh in meshes()? {
        let topology = Topology::of(&mesh);
        let aims = aims(&mesh, &topology, rays, SEED);
        let inputs = GpuInputs::new(&mesh, &topology, &aims);
        for test in TriangleTest::ALL {
            rows.push(LeakRow {
                mesh: mesh.name,
                test,
                rays,
                f64_leaks: count_f64(&mesh, &topology, &aims, test),
                gpu_leaks: count_gpu(gpu, &source, &inputs, test)?,
            });
        }
    }
    Ok(rows)
}

/// The leak table, per mesh and test.
pub fn markdown(rows: &[LeakRow]) -> String {
    table(
        "| mesh | test | rays | leaks f64 | per million f64 | leaks f32 GPU | per million f32 GPU |\n\
         | --- | --- | ---: | ---: | ---: | ---: | ---: |",
        rows,
        |r| {
            format!(
                "| {} | {} | {} | {} | {:.0} | {} | {:.0} |",
                r.mesh,
                r.test.name(),
                r.rays,
                r.f64_leaks,
                r.f64_per_million(),
                r.gpu_leaks,
                r.gpu_per_million()
            )
        },
    )
}

/// The leak rows as CSV.
pub fn csv(rows: &[LeakRow]) -> String {
    table("mesh,test,rays,f64_leaks,gpu_f32_leaks", rows, |r| {
        format!(
            "{},{},{},{},{}",
            r.mesh,
            r.test.name(),
            r.rays,
            r.f64_leaks,
            r.gpu_leaks
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sphere_is_closed_and_every_aim_is_on_the_surface() {
        let (p, t) = uv_sphere(8);
        let mesh = LeakMesh::new("s", p, t);
        let topology = Topology::of(&mesh);
        assert!(topology.interior.iter().all(|&i| i));
        assert_eq!(topology.shared.len() * 2, mesh.triangles.len() * 3);
        let aims = aims(&mesh, &topology, 400, SEED);
        assert!(aims.iter().any(|a| a.a == a.b) && aims.iter().any(|a| a.a != a.b));
        for aim in &aims {
            let (pa, pb) = (
                mesh.positions[aim.a as usize],
                mesh.positions[aim.b as usize],
            );
            let off_edge = (aim.target - pa).cross(pb - pa).length();
            assert!(off_edge < 1e-12, "{aim:?}");
            assert!(((aim.origin - aim.target).length() - 3.0).abs() < 1e-12);
        }
    }

    #[test]
    fn the_fans_rim_is_not_interior_and_its_centre_is() {
        let (p, t) = fan(10);
        let topology = Topology::of(&LeakMesh::new("f", p, t));
        assert!(topology.interior[0]);
        assert!(!topology.interior[1..].iter().any(|&i| i));
        assert_eq!(topology.shared.len(), 10);
        assert_eq!(topology.star[0].len(), 10);
    }
}
