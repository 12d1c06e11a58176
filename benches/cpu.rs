//! Criterion benchmarks of the CPU side: the reference's intersection
//! routines (robust and naive), BVH construction, the reference tracer's
//! rays per second, and what the viewer does when a mesh moves against when
//! its file is reloaded. `cargo bench`; results in target/criterion/.

use std::hint::black_box;
use std::sync::Arc;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::{DMat3, DVec3};
use raysandbox::bench::sphere_field;
use raysandbox::bvh::Bvh;
use raysandbox::gpu::layout::PackedScene;
use raysandbox::reference::ray::Ray;
use raysandbox::reference::shapes::cube::{Cube, hit_cube, hit_cube_naive};
use raysandbox::reference::shapes::plane::{Plane, hit_plane, hit_plane_naive};
use raysandbox::reference::shapes::sphere::{Sphere, hit_sphere, hit_sphere_naive};
use raysandbox::reference::{PreparedScene, render_linear};
use raysandbox::scene::{Instance, Loaded, Mesh, Placement, Scene, Shape, bundled};

/// Rays from a ring of origins at the unit shapes at the origin: about half
/// hit, so both branches of every routine are measured.
fn rays() -> Vec<Ray> {
    (0..256)
        .map(|k| {
            let a = k as f64 * 0.1;
            let origin = DVec3::new(5.0 * a.cos(), 2.0 * (a * 0.7).sin(), 5.0 * a.sin());
            let aim = DVec3::new((a * 3.1).sin(), (a * 1.3).cos(), (a * 2.3).sin()) * 1.2;
            Ray::new(origin, aim - origin)
        })
        .collect()
}

fn intersections(c: &mut Criterion) {
    let rays = rays();
    let sphere = Sphere::new(DVec3::ZERO, 1.0);
    let plane = Plane::new(DVec3::ZERO, DVec3::new(0.2, 1.0, 0.1));
    let rotation = DMat3::from_rotation_y(0.5) * DMat3::from_rotation_x(0.3);
    let cube = Cube::new(DVec3::ZERO, DVec3::new(1.0, 2.0, 1.5), rotation);
    let mut group = c.benchmark_group("intersect");
    group.throughput(Throughput::Elements(rays.len() as u64));
    let mut run = |name: &str, hit: &dyn Fn(&Ray) -> bool| {
        group.bench_function(name, |b| {
            b.iter(|| rays.iter().filter(|r| hit(black_box(r))).count())
        });
    };
    run("sphere robust", &|r| {
        hit_sphere(&sphere, r, f64::MAX).is_some()
    });
    run("sphere naive", &|r| {
        hit_sphere_naive(&sphere, r, f64::MAX).is_some()
    });
    run("plane robust", &|r| {
        hit_plane(&plane, r, f64::MAX).is_some()
    });
    run("plane naive", &|r| {
        hit_plane_naive(&plane, r, f64::MAX).is_some()
    });
    run("box robust", &|r| hit_cube(&cube, r, f64::MAX).is_some());
    run("box naive", &|r| {
        hit_cube_naive(&cube, r, f64::MAX).is_some()
    });
    group.finish();
}

fn bvh_build(c: &mut Criterion) {
    let mut group = c.benchmark_group("bvh build");
    for n in [256usize, 4096, 16384] {
        let scene = sphere_field(n);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &scene, |b, scene| {
            b.iter(|| Bvh::build(black_box(scene)))
        });
    }
    group.finish();
}

fn reference_tracer(c: &mut Criterion) {
    let mut group = c.benchmark_group("reference tracer");
    group.sample_size(10);
    let (width, height) = (160u32, 90u32);
    for name in ["whitted", "many_spheres"] {
        let scene = Scene::from_toml_str(bundled::text(name).unwrap(), None).unwrap();
        let prepared = PreparedScene::new(&scene);
        // Primary rays per second (each may spawn shadow and secondary rays).
        group.throughput(Throughput::Elements(u64::from(width * height)));
        group.bench_function(name, |b| {
            b.iter(|| render_linear(black_box(&prepared), width, height, 1))
        });
    }
    group.finish();
}

/// Packing a scene for the GPU after a mesh was moved (its geometry, BVH
/// and packed triangles are reused) against after its file was reloaded (a
/// new geometry: BVH built and triangles packed again), on the bundled
/// 48k-triangle dragon.
fn mesh_repack(c: &mut Criterion) {
    let mut group = c.benchmark_group("mesh repack");
    group.sample_size(10);
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mesh = Mesh::from_file("assets/meshes/dragon_res3.ply".into(), Some(dir)).unwrap();
    let mut scene = Scene::from_toml_str(bundled::text("whitted").unwrap(), None).unwrap();
    scene.meshes.push(Instance::new(mesh, Placement::default()));
    PackedScene::new(&scene, 1, 1);
    group.bench_function("moved", |b| {
        b.iter(|| {
            scene.meshes[0].placement.translate.x += 1e-3;
            PackedScene::new(black_box(&scene), 1, 1)
        })
    });
    group.bench_function("reloaded", |b| {
        b.iter(|| {
            let fresh = Arc::new((*scene.meshes[0].geometry.0).clone());
            scene.meshes[0].geometry = Loaded(fresh);
            PackedScene::new(black_box(&scene), 1, 1)
        })
    });
    group.finish();
}

criterion_group! {
    name = benches;
    // Criterion's HTML plots need a system font (plotters' font feature is
    // set for the bench command's own plots, which bring their font along).
    config = Criterion::default().without_plots();
    targets = intersections, bvh_build, reference_tracer, mesh_repack
}
criterion_main!(benches);
