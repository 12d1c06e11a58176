//! The WGSL intersection routines themselves, on the GPU: the real
//! `shaders/*.wgsl` (the embedded source, not a copy) plus a small compute
//! entry point that runs `hit_sphere`, `hit_plane`, `hit_cube` and
//! `offset_ray` on the cases the property tests generate (a fixed seed), and
//! the answers compared with the exact ones (double-double), with the f32
//! CPU port, and, for rays spawned from the GPU's own hit points, with the
//! self-intersection rules. Robust variant; the naive one must show its
//! failures on the same cases.

mod common;
mod support;

use bytemuck::{Pod, Zeroable};
use glam::{DMat3, DVec3, Mat3, Vec3};
use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::TestRunner;
use raysandbox::gpu::{Gpu, ShaderSource};
use raysandbox::stress::f32_intersect as r32;
use support::cases::*;
use support::exact;

/// One ray and one shape, laid out like `TestCase` below (vec3 + scalar).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct GpuCase {
    origin: [f32; 3],
    kind: u32,
    dir: [f32; 3],
    _pad0: u32,
    a: [f32; 3],
    radius: f32,
    b: [f32; 3],
    _pad1: u32,
    r0: [f32; 4],
    r1: [f32; 4],
    r2: [f32; 4],
}

#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct GpuResult {
    t: f32,
    hit: u32,
    error_scale: f32,
    _pad: u32,
    point: [f32; 3],
    _p1: u32,
    normal: [f32; 3],
    _p2: u32,
    /// offset_ray(point, normal, error_scale) and with -normal.
    along_n: [f32; 3],
    _p3: u32,
    against_n: [f32; 3],
    _p4: u32,
}

const HARNESS: &str = r#"
struct TestCase {
    origin: vec3<f32>,
    kind: u32,
    dir: vec3<f32>,
    _pad0: u32,
    a: vec3<f32>,
    radius: f32,
    b: vec3<f32>,
    _pad1: u32,
    r0: vec3<f32>,
    _r0: u32,
    r1: vec3<f32>,
    _r1: u32,
    r2: vec3<f32>,
    _r2: u32,
}

struct TestResult {
    t: f32,
    hit: u32,
    error_scale: f32,
    _pad: u32,
    point: vec3<f32>,
    _p1: u32,
    normal: vec3<f32>,
    _p2: u32,
    along_n: vec3<f32>,
    _p3: u32,
    against_n: vec3<f32>,
    _p4: u32,
}

@group(1) @binding(0) var<storage, read> test_cases: array<TestCase>;
@group(1) @binding(1) var<storage, read_write> test_results: array<TestResult>;

@compute @workgroup_size(64)
fn test_intersections(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&test_cases) {
        return;
    }
    let c = test_cases[i];
    let ray = Ray(c.origin, c.dir, 0.0);
    var h = no_hit(T_FAR);
    switch c.kind {
        case 1u: {
            h = hit_sphere(ray, Sphere(c.a, c.radius, 0u), 0u, h);
        }
        case 2u: {
            h = hit_plane(ray, Plane(c.a, 0u, c.b), 0u, h);
        }
        default: {
            h = hit_cube(ray, Cube(c.a, 0u, mat3x3<f32>(c.r0, c.r1, c.r2), c.b), 0u, h);
        }
    }
    var out: TestResult;
    out.t = h.t;
    out.hit = select(0u, 1u, h.kind != KIND_NONE);
    out.error_scale = h.error_scale;
    out.point = h.point;
    out.normal = h.normal;
    out.along_n = offset_ray(h.point, h.normal, h.error_scale);
    out.against_n = offset_ray(h.point, -h.normal, h.error_scale);
    test_results[i] = out;
}
"#;

/// Runs the harness on `cases` with the shader's `ROBUST` constant.
fn run(gpu: &Gpu, cases: &[GpuCase], robust: bool) -> Vec<GpuResult> {
    let embedded = ShaderSource::embedded();
    let source = ShaderSource::from_parts(
        embedded
            .parts()
            .map(|(name, text)| (name.to_string(), text.to_string()))
            .chain([("harness.wgsl".to_string(), HARNESS.to_string())]),
    );
    let kernel = raysandbox::gpu::compute::Kernel {
        label: "intersection harness",
        source: &source,
        entry: "test_intersections",
        constants: &[("ROBUST", if robust { 1.0 } else { 0.0 })],
        group: 1,
    };
    kernel.run(gpu, cases, cases.len())
}

/// The shapes of the cases, as the CPU port and the exact answer see them.
#[derive(Debug, Clone, Copy)]
enum Shape {
    Sphere(r32::Sphere),
    Plane(r32::Plane),
    Cube(r32::Cube),
}

fn gpu_case(ray: &r32::Ray, shape: &Shape) -> GpuCase {
    let mut c = GpuCase::zeroed();
    c.origin = ray.origin.to_array();
    c.dir = ray.dir.to_array();
    match shape {
        Shape::Sphere(s) => {
            c.kind = 1;
            c.a = s.center.to_array();
            c.radius = s.radius;
        }
        Shape::Plane(p) => {
            c.kind = 2;
            c.a = p.point.to_array();
            c.b = p.normal.to_array();
        }
        Shape::Cube(b) => {
            c.kind = 3;
            c.a = b.center.to_array();
            c.b = b.half_size.to_array();
            c.r0 = b.rotation.x_axis.extend(0.0).to_array();
            c.r1 = b.rotation.y_axis.extend(0.0).to_array();
            c.r2 = b.rotation.z_axis.extend(0.0).to_array();
        }
    }
    c
}

fn port(ray: &r32::Ray, shape: &Shape, robust: bool) -> Option<r32::Hit> {
    match shape {
        Shape::Sphere(s) => r32::hit_sphere(ray, s, r32::T_FAR, robust),
        Shape::Plane(p) => r32::hit_plane(ray, p, r32::T_FAR, robust),
        Shape::Cube(b) => r32::hit_cube(ray, b, r32::T_FAR, robust),
    }
}

/// The exact answer: t (None = miss), whether the case is within rounding
/// of tangency (either answer acceptable), and the condition number.
fn exact_answer(ray: &r32::Ray, shape: &Shape) -> (Option<f64>, bool, f64) {
    let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
    let eps = f64::from(f32::EPSILON) / 2.0;
    match shape {
        Shape::Sphere(s) => {
            let (c, r) = (s.center.as_dvec3(), f64::from(s.radius));
            let e = exact::sphere(o, d, c, r);
            let scale = o.abs().max_element().max(c.abs().max_element());
            let near = e.chord2.abs() < 64.0 * eps * (scale / r + 1.0);
            (e.t, near, 1.0 / e.half_chord().max(1e-30))
        }
        Shape::Plane(p) => {
            let e = exact::plane(o, d, p.point.as_dvec3(), p.normal.as_dvec3());
            let t = (e.t > 0.0 && e.t.is_finite()).then_some(e.t);
            (t, false, 1.0 / e.cos.abs())
        }
        Shape::Cube(b) => {
            let e = exact::cube(
                o,
                d,
                b.center.as_dvec3(),
                b.half_size.as_dvec3(),
                b.rotation.as_dmat3(),
            );
            let scale = o
                .abs()
                .max_element()
                .max(b.center.as_dvec3().abs().max_element())
                + e.t.unwrap_or(0.0);
            let near = e.slack.abs() < 256.0 * eps * scale / e.cos.max(1e-12);
            (e.t, near, 1.0 / e.cos.max(1e-12))
        }
    }
}

/// The same cases as the property tests: 2048 of each shape, fixed seed.
fn cases() -> Vec<(r32::Ray, Shape)> {
    let mut runner = TestRunner::deterministic();
    let mut out = Vec::new();
    for _ in 0..2048 {
        let c = sphere_case().new_tree(&mut runner).unwrap().current();
        let s = r32::Sphere {
            center: c.centre.as_vec3(),
            radius: c.radius as f32,
        };
        out.push((ray32(c.origin, c.dir), Shape::Sphere(s)));
        let c = plane_case().new_tree(&mut runner).unwrap().current();
        let p = r32::Plane {
            point: c.point.as_vec3(),
            normal: c.normal.as_vec3().normalize(),
        };
        out.push((ray32(c.origin, c.dir), Shape::Plane(p)));
        let c = box_case().new_tree(&mut runner).unwrap().current();
        out.push((ray32(c.origin, c.dir), Shape::Cube(cube32(&c))));
    }
    // Axis-aligned rays along box faces and edges, from slab planes.
    let cube = r32::Cube {
        center: Vec3::new(0.5, -0.25, 2.0),
        half_size: Vec3::new(1.0, 0.5, 0.25),
        rotation: Mat3::IDENTITY,
    };
    for corner in 0..27 {
        let at = Vec3::new(
            (corner % 3) as f32 - 1.0,
            (corner / 3 % 3) as f32 - 1.0,
            (corner / 9) as f32 - 1.0,
        );
        for dir in [
            Vec3::X,
            -Vec3::Y,
            Vec3::Z,
            Vec3::new(1.0, 1.0, 0.0).normalize(),
        ] {
            let origin = cube.center + at * cube.half_size - 3.0 * dir;
            out.push((r32::Ray { origin, dir }, Shape::Cube(cube)));
        }
    }
    let _ = DMat3::IDENTITY;
    out
}

fn finite(r: &GpuResult) -> bool {
    [r.t].iter().all(|x| x.is_finite())
        && [r.point, r.normal, r.along_n, r.against_n]
            .iter()
            .all(|v| v.iter().all(|x| x.is_finite()))
}

#[test]
fn wgsl_intersections_match_exact_answers_and_the_cpu_port() {
    let gpu = common::gpu();
    let cases = cases();
    let input: Vec<GpuCase> = cases.iter().map(|(r, s)| gpu_case(r, s)).collect();
    let results = run(&gpu, &input, true);
    let eps = f64::from(f32::EPSILON) / 2.0;
    let (mut hits, mut checked, mut identical) = (0, 0, 0);
    let mut failures = Vec::new();
    for (i, ((ray, shape), r)) in cases.iter().zip(&results).enumerate() {
        let (t_exact, near, cond) = exact_answer(ray, shape);
        let gpu_t = (r.hit == 1).then_some(f64::from(r.t));
        if r.hit == 1 {
            hits += 1;
            if !finite(r) {
                failures.push(format!("case {i}: NaN/inf {r:?}"));
            }
        }
        let port_t = port(ray, shape, true).map(|h| f64::from(h.t));
        if gpu_t == port_t {
            identical += 1;
        }
        if near {
            continue;
        }
        checked += 1;
        let scale = ray
            .origin
            .as_dvec3()
            .abs()
            .max_element()
            .max(t_exact.unwrap_or(0.0));
        let bound = 64.0 * eps * scale * cond.max(1.0);
        match (gpu_t, t_exact) {
            (Some(t), Some(te)) if (t - te).abs() > bound => failures.push(format!(
                "case {i} {shape:?}: t {t}, exact {te}, bound {bound}"
            )),
            (Some(t), None) => {
                failures.push(format!("case {i} {shape:?}: hit at {t}, exact: miss"))
            }
            (None, Some(te)) => {
                failures.push(format!("case {i} {shape:?}: miss, exact: hit at {te}"))
            }
            _ => {}
        }
        if let (Some(t), Some(tp)) = (gpu_t, port_t)
            && (t - tp).abs() > bound
        {
            failures.push(format!("case {i}: GPU t {t}, CPU port {tp}"));
        }
    }
    println!(
        "{} cases, {hits} hits, {checked} away from tangency, {identical} bit-identical t with the CPU port",
        cases.len()
    );
    assert!(hits > cases.len() / 3, "too few hits to test anything");
    assert!(checked > cases.len() * 3 / 4);
    assert!(
        failures.is_empty(),
        "{}\n{}",
        failures.len(),
        failures.join("\n")
    );

    // Rays spawned from the GPU's own hit points, with its own offsets:
    // reflected (back to the side the ray came from) and straight on (to the
    // other side). A ray that starts inside a sphere or box must hit its far
    // side, not t ~ 0; any other (outside, or either side of a plane) must
    // never hit the shape again.
    let mut spawned = Vec::new();
    for ((ray, shape), r) in cases.iter().zip(&results) {
        if r.hit != 1 {
            continue;
        }
        let n = Vec3::from(r.normal);
        let into = ray.dir.dot(n) < 0.0;
        let ns = if into { n } else { -n };
        let (back, on) = if into {
            (r.along_n, r.against_n)
        } else {
            (r.against_n, r.along_n)
        };
        let closed = !matches!(shape, Shape::Plane(_));
        // On a box edge (within rounding) "inside" is the boundary of the
        // neighbouring face: the box's tangency, left out as in the
        // property tests.
        if let Shape::Cube(b) = shape {
            let local = b.rotation.transpose() * (Vec3::from(r.point) - b.center);
            let margin = 64.0 * f32::EPSILON * (ray.origin - b.center).length();
            let on_faces = (0..3)
                .filter(|&i| (local[i].abs() - b.half_size[i]).abs() <= margin)
                .count();
            if on_faces >= 2 {
                continue;
            }
        }
        let reflected = (ray.dir - 2.0 * ray.dir.dot(ns) * ns).normalize();
        let back = r32::Ray {
            origin: Vec3::from(back),
            dir: reflected,
        };
        let on = r32::Ray {
            origin: Vec3::from(on),
            dir: ray.dir,
        };
        // Reflected from inside stays inside; straight on from outside goes in.
        spawned.push((back, *shape, closed && !into));
        spawned.push((on, *shape, closed && into));
    }
    let input: Vec<GpuCase> = spawned.iter().map(|(r, s, _)| gpu_case(r, s)).collect();
    let again = run(&gpu, &input, true);
    let mut failures = Vec::new();
    for ((ray, shape, inside), r) in spawned.iter().zip(&again) {
        if *inside {
            let (t_exact, near, _) = exact_answer(ray, shape);
            let Some(te) = t_exact else {
                failures.push(format!(
                    "{shape:?}: spawned origin {} not inside",
                    ray.origin
                ));
                continue;
            };
            if r.hit != 1 && !near {
                failures.push(format!("{shape:?}: missed the far side at {te}"));
            } else if r.hit == 1 && f64::from(r.t) < 0.5 * te && !near {
                failures.push(format!("{shape:?}: t {} before the far side at {te}", r.t));
            }
        } else if r.hit == 1 {
            failures.push(format!(
                "{shape:?}: spawned ray {ray:?} hit its own surface at t {}",
                r.t
            ));
        }
    }
    println!("{} spawned rays", spawned.len());
    assert!(
        failures.is_empty(),
        "{}\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn wgsl_naive_routines_show_their_failures() {
    let gpu = common::gpu();
    // A small sphere 1e3 away, rays across it: the naive quadratic gets many
    // wrong. A ray along a box's slab plane: the naive slab test misses.
    let sphere = Shape::Sphere(r32::Sphere {
        center: Vec3::ZERO,
        radius: 0.1,
    });
    let mut cases: Vec<(r32::Ray, Shape)> = (0..256)
        .map(|i| {
            let y = -0.15 + 0.3 * f64::from(i) / 256.0;
            (
                ray32(DVec3::new(0.0, 0.0, 1e3), DVec3::new(0.0, y * 1e-3, -1.0)),
                sphere,
            )
        })
        .collect();
    let cube = Shape::Cube(r32::Cube {
        center: Vec3::ZERO,
        half_size: Vec3::ONE,
        rotation: Mat3::IDENTITY,
    });
    cases.push((
        r32::Ray {
            origin: Vec3::new(-1.0, 0.0, 5.0),
            dir: -Vec3::Z,
        },
        cube,
    ));
    let input: Vec<GpuCase> = cases.iter().map(|(r, s)| gpu_case(r, s)).collect();
    let robust = run(&gpu, &input, true);
    let naive = run(&gpu, &input, false);
    let wrong = |results: &[GpuResult]| {
        cases
            .iter()
            .zip(results)
            .filter(|((ray, shape), r)| {
                let (te, near, _) = exact_answer(ray, shape);
                !near
                    && match te {
                        None => r.hit == 1,
                        Some(te) => r.hit != 1 || (f64::from(r.t) - te).abs() > 1e-3,
                    }
            })
            .count()
    };
    assert_eq!(wrong(&robust), 0, "robust");
    let naive_wrong = wrong(&naive);
    println!("naive: {naive_wrong} of {} wrong", cases.len());
    assert!(naive_wrong > 25, "only {naive_wrong} naive answers wrong");
    assert_eq!(robust.last().unwrap().t, 4.0);
}

/// How far apart two f32 results of the same computation may be: a few
/// units in the last place of the larger, for a GPU that fuses a multiply
/// and an add or rounds a square root differently. A changed formula on one
/// side only is far outside this on some of the thousands of cases.
fn same_within_ulps(a: &[f32], b: &[f32]) -> bool {
    let magnitude = a.iter().chain(b).fold(0f32, |m, x| m.max(x.abs()));
    let bound = 4.0 * f32::EPSILON * magnitude;
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= bound)
}

/// `src/stress/f32_intersect.rs` is a hand port of the WGSL for the property
/// tests; this holds it to the WGSL, robust and naive: the same hits and
/// misses, and the same t, point, normal, error scale and offsets.
#[test]
fn the_cpu_port_computes_what_the_wgsl_computes() {
    let gpu = common::gpu();
    let cases = cases();
    let input: Vec<GpuCase> = cases.iter().map(|(r, s)| gpu_case(r, s)).collect();
    for robust in [true, false] {
        let results = run(&gpu, &input, robust);
        let (mut identical, mut failures) = (0, Vec::new());
        for (i, ((ray, shape), r)) in cases.iter().zip(&results).enumerate() {
            // The naive slab test meets 0 * inf on a box when a direction
            // component is 0; what min and max make of the NaN is the
            // driver's choice there.
            let driver_defined =
                !robust && matches!(shape, Shape::Cube(_)) && ray.dir.to_array().contains(&0.0);
            if driver_defined {
                continue;
            }
            let (_, near, _) = exact_answer(ray, shape);
            let Some(hit) = port(ray, shape, robust) else {
                if r.hit == 1 && !near {
                    failures.push(format!(
                        "case {i} {shape:?}: WGSL hits at {}, port misses",
                        r.t
                    ));
                }
                continue;
            };
            if r.hit != 1 {
                if !near {
                    failures.push(format!(
                        "case {i} {shape:?}: port hits at {}, WGSL misses",
                        hit.t
                    ));
                }
                continue;
            }
            let (point, normal) = (Vec3::from(r.point), Vec3::from(r.normal));
            let along = r32::offset_ray(point, normal, r.error_scale, robust);
            let against = r32::offset_ray(point, -normal, r.error_scale, robust);
            let pairs: [(&str, Vec<f32>, Vec<f32>); 6] = [
                ("t", vec![r.t], vec![hit.t]),
                ("point", r.point.to_vec(), hit.point.to_array().to_vec()),
                ("normal", r.normal.to_vec(), hit.normal.to_array().to_vec()),
                ("error_scale", vec![r.error_scale], vec![hit.error_scale]),
                (
                    "offset along n",
                    r.along_n.to_vec(),
                    along.to_array().to_vec(),
                ),
                (
                    "offset against n",
                    r.against_n.to_vec(),
                    against.to_array().to_vec(),
                ),
            ];
            if pairs.iter().all(|(_, a, b)| a == b) {
                identical += 1;
            }
            for (what, wgsl, cpu) in pairs {
                if !same_within_ulps(&wgsl, &cpu) {
                    failures.push(format!(
                        "case {i} {shape:?}: {what}: WGSL {wgsl:?}, port {cpu:?}"
                    ));
                }
            }
        }
        println!(
            "robust {robust}: {identical} of {} cases bit-identical in every output",
            cases.len()
        );
        assert!(
            failures.is_empty(),
            "robust {robust}: the port and the WGSL differ in {} cases:\n{}",
            failures.len(),
            failures[..failures.len().min(20)].join("\n")
        );
    }
}
