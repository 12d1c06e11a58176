//! Property tests of the intersection routines over wide ranges: the f32
//! port of the shader (`stress::f32_intersect`, robust) and the f64
//! reference (`reference::shapes`), each judged against the exact answer
//! for its own inputs (double-double, `support/exact.rs`).
//!
//! Scenes from 1e-3 to 1e6 in size, moved up to 1e3 of their size away from
//! the origin; grazing angles down to 1e-6 rad; rays that start on a surface
//! (from a computed hit point, moved by the renderer's offset). Properties:
//! - no NaN, ever;
//! - hit or miss as the exact answer says, unless the ray is within a
//!   rounding error of tangency (the exact half chord, or for boxes the
//!   exact slack t_far - t_near, tells how close);
//! - t within a bound of K ulps of max(|o|, t), times the condition number
//!   of the problem where it has one (1 / cos of incidence for planes and
//!   box faces, r / half chord for spheres): near grazing incidence any
//!   rounding of the direction moves the hit along the surface that much;
//! - a ray spawned from a hit point, to either side, starts on that side
//!   (exactly) and does not hit the surface it left (convex shapes), or, going
//!   into a sphere or box, hits its far side, not t ~ 0.

mod support;

use glam::{DMat3, DVec3, Mat3, Vec3};
use proptest::prelude::*;
use raysandbox::reference::ray::offset_ray as offset64;
use raysandbox::stress::f32_intersect as r32;
use support::cases::*;
use support::exact;

/// The f64 reference's hit tests of the kinds these properties cover.
mod r64 {
    pub use raysandbox::reference::shapes::cube::{Cube, hit_cube};
    pub use raysandbox::reference::shapes::plane::{Plane, hit_plane};
    pub use raysandbox::reference::shapes::sphere::{Sphere, hit_sphere};
}

const EPS32: f64 = f32::EPSILON as f64 / 2.0;
const EPS64: f64 = f64::EPSILON / 2.0;

/// Allowed error of t, in units of eps * max(|o|, t) * condition number.
const K_T: f64 = 64.0;

/// 1024 cases per property (a fraction of a second), or PROPTEST_CASES.
fn config() -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1024);
    ProptestConfig {
        cases,
        ..ProptestConfig::default()
    }
}

/// Whether `t` is within the allowed error of `exact`.
fn t_ok(t: f64, exact: f64, eps: f64, scale: f64, condition: f64) -> bool {
    (t - exact).abs() <= K_T * eps * scale * condition.max(1.0)
}

proptest! {
    #![proptest_config(config())]

    /// Spheres: hit or miss and t, for f32 (robust) and f64.
    #[test]
    fn sphere_hits_match_the_exact_answer(case in sphere_case()) {
        // f32: the shader's port on f32 inputs.
        let sph = r32::Sphere { center: case.centre.as_vec3(), radius: case.radius as f32 };
        let ray = ray32(case.origin, case.dir);
        let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
        let exact = exact::sphere(o, d, sph.center.as_dvec3(), f64::from(sph.radius));
        let hit = r32::hit_sphere(&ray, &sph, r32::T_FAR, true);
        check_sphere(hit.map(|h| (f64::from(h.t), finite3(h.point) && finite3(h.normal))), &exact, o, sph.center.as_dvec3(), f64::from(sph.radius), EPS32)?;
        // f64: the reference on f64 inputs.
        let sph64 = r64::Sphere::new(case.centre, case.radius);
        let exact = exact::sphere(case.origin, case.dir, case.centre, case.radius);
        let hit = r64::hit_sphere(&sph64, &ray64(case.origin, case.dir), f64::INFINITY);
        check_sphere(hit.map(|h| (h.t, h.p.is_finite() && h.n.is_finite())), &exact, case.origin, case.centre, case.radius, EPS64)?;
    }
}

/// Whether the line is within rounding of tangency, where hit or miss may
/// go either way: the squared half chord over r^2 is known to
/// ~eps (|o| + |centre|) / r (the rounding of o - centre, relative to r).
fn sphere_near_tangent(exact: &exact::SphereTruth, scale: f64, radius: f64, eps: f64) -> bool {
    exact.chord2.abs() < 64.0 * eps * (scale / radius + 1.0)
}

fn check_sphere(
    hit: Option<(f64, bool)>,
    exact: &exact::SphereTruth,
    o: DVec3,
    centre: DVec3,
    radius: f64,
    eps: f64,
) -> Result<(), TestCaseError> {
    let scale_o = o.abs().max_element();
    let near_tangent =
        sphere_near_tangent(exact, scale_o.max(centre.abs().max_element()), radius, eps);
    match (hit, exact.t) {
        (Some((t, finite)), Some(te)) => {
            prop_assert!(finite && t.is_finite(), "NaN or inf");
            if !near_tangent {
                let cond = 1.0 / exact.half_chord();
                prop_assert!(
                    t_ok(t, te, eps, scale_o.max(te), cond),
                    "t {t} exact {te}: {} ulps, condition {cond}",
                    (t - te).abs() / (eps * scale_o.max(te))
                );
            }
        }
        (None, None) => {}
        (Some((t, _)), None) => prop_assert!(near_tangent, "hit at {t}, exact: miss"),
        (None, Some(te)) => prop_assert!(near_tangent, "miss, exact: hit at {te}"),
    }
    Ok(())
}

/// Whether a box ray is within rounding of an edge, a corner or a face it
/// grazes: the exact slack t_far - t_near is below the error of the slab
/// bounds, ~eps (|o| + |centre| + |t|) / |d'_i|.
fn box_near_edge(exact: &exact::BoxTruth, scale: f64, eps: f64) -> bool {
    exact.slack.abs() < 256.0 * eps * scale / exact.cos.max(1e-12)
}

fn check_box(
    hit: Option<(f64, bool)>,
    exact: &exact::BoxTruth,
    o: DVec3,
    centre: DVec3,
    eps: f64,
) -> Result<(), TestCaseError> {
    let scale = o.abs().max_element().max(centre.abs().max_element());
    let near = box_near_edge(exact, scale + exact.t.unwrap_or(0.0).abs(), eps);
    match (hit, exact.t) {
        (Some((t, finite)), Some(te)) => {
            prop_assert!(finite && t.is_finite(), "NaN or inf");
            if !near {
                let scale = scale.max(te);
                prop_assert!(
                    t_ok(t, te, eps, scale, 1.0 / exact.cos),
                    "t {t} exact {te}: {} ulps, cos {}",
                    (t - te).abs() / (eps * scale),
                    exact.cos
                );
            }
        }
        (None, None) => {}
        (Some((t, _)), None) => prop_assert!(near, "hit at {t}, exact: miss"),
        (None, Some(te)) => prop_assert!(near, "miss, exact: hit at {te}"),
    }
    Ok(())
}

proptest! {
    #![proptest_config(config())]

    /// Planes at grazing angles down to 1e-6 rad: always a hit (t < 1e30),
    /// t within K ulps of max(|o|, |point|, t) / cos, and the re-projected
    /// hit point within K ulps of max(|p|, |point|) of the plane.
    #[test]
    fn plane_hits_at_grazing_angles(case in plane_case()) {
        // f32
        let pl = r32::Plane { point: case.point.as_vec3(), normal: case.normal.as_vec3().normalize() };
        let ray = ray32(case.origin, case.dir);
        let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
        let (point, n) = (pl.point.as_dvec3(), pl.normal.as_dvec3());
        let exact = exact::plane(o, d, point, n);
        let hit = r32::hit_plane(&ray, &pl, r32::T_FAR, true);
        let hit = hit.ok_or_else(|| TestCaseError::fail(format!("f32 missed, exact t {}", exact.t)))?;
        let p = hit.point.as_dvec3();
        prop_assert!(hit.t.is_finite() && p.is_finite(), "NaN");
        let scale = o.abs().max_element().max(point.abs().max_element());
        prop_assert!(t_ok(f64::from(hit.t), exact.t, EPS32, scale.max(exact.t), 1.0 / exact.cos.abs()),
            "t {} exact {} theta {}", hit.t, exact.t, case.theta);
        let height = exact::plane_height(p, point, n);
        prop_assert!(height.abs() <= K_T * EPS32 * p.abs().max_element().max(point.abs().max_element()),
            "hit point {height} off the plane");
        // f64
        let pl = r64::Plane::new(case.point, case.normal);
        let exact = exact::plane(case.origin, case.dir, pl.point, pl.normal);
        let hit = r64::hit_plane(&pl, &ray64(case.origin, case.dir), f64::INFINITY)
            .ok_or_else(|| TestCaseError::fail("f64 missed"))?;
        prop_assert!(hit.t.is_finite() && hit.p.is_finite(), "NaN");
        let scale = case.origin.abs().max_element().max(pl.point.abs().max_element());
        prop_assert!(t_ok(hit.t, exact.t, EPS64, scale.max(exact.t), 1.0 / exact.cos.abs()),
            "t {} exact {}", hit.t, exact.t);
        let height = exact::plane_height(hit.p, pl.point, pl.normal);
        prop_assert!(height.abs() <= K_T * EPS64 * hit.p.abs().max_element().max(scale));
    }

    /// A ray that leaves a plane hit point (offset to either side, any angle
    /// down to 1e-6 rad) starts strictly on its side and never hits the plane
    /// again; a ray exactly parallel to an axis plane misses without NaN.
    #[test]
    fn plane_spawned_rays_never_return(case in plane_case(), theta in -6.0..0.19f64,
                                       tangent in prop::array::uniform3(-1.0..1.0f64), through in prop::bool::ANY) {
        let theta = 10f64.powf(theta);
        // f32
        let pl = r32::Plane { point: case.point.as_vec3(), normal: case.normal.as_vec3().normalize() };
        let ray = ray32(case.origin, case.dir);
        let hit = r32::hit_plane(&ray, &pl, r32::T_FAR, true).unwrap();
        let ns = pl.normal * case.side as f32; // faces the incoming ray
        let (side, dir) = if through { (-ns, ray.dir) } else {
            (ns, at_angle(ns.as_dvec3(), unit(tangent), theta, 1.0).as_vec3().normalize())
        };
        let origin = r32::offset_ray(hit.point, side, hit.error_scale, true);
        let height = exact::plane_height(origin.as_dvec3(), pl.point.as_dvec3(), side.as_dvec3());
        prop_assert!(height > 0.0, "offset origin on the wrong side: {height}");
        let again = r32::hit_plane(&r32::Ray { origin, dir }, &pl, r32::T_FAR, true);
        prop_assert!(again.is_none(), "self-hit at t {:?}", again.map(|h| h.t));
        // f64
        let pl = r64::Plane::new(case.point, case.normal);
        let hit = r64::hit_plane(&pl, &ray64(case.origin, case.dir), f64::INFINITY).unwrap();
        let ns = pl.normal * case.side;
        let (side, dir) = if through { (-ns, case.dir) } else { (ns, at_angle(ns, unit(tangent), theta, 1.0)) };
        let origin = offset64(hit.p, side, hit.error_scale);
        prop_assert!(exact::plane_height(origin, pl.point, side) > 0.0);
        prop_assert!(r64::hit_plane(&pl, &ray64(origin, dir), f64::INFINITY).is_none());
    }

    /// Boxes, rotated or not (and by multiples of 90 degrees): hit or miss
    /// away from edges, t within K ulps / cos of the face.
    #[test]
    fn box_hits_match_the_exact_answer(case in box_case()) {
        let cube = cube32(&case);
        let ray = ray32(case.origin, case.dir);
        let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
        let exact = exact::cube(o, d, cube.center.as_dvec3(), cube.half_size.as_dvec3(), cube.rotation.as_dmat3());
        let hit = r32::hit_cube(&ray, &cube, r32::T_FAR, true);
        check_box(hit.map(|h| (f64::from(h.t), finite3(h.point) && finite3(h.normal))), &exact, o, cube.center.as_dvec3(), EPS32)?;
        let cube = cube64(&case);
        let exact = exact::cube(case.origin, case.dir, cube.center, cube.half, cube.rotation);
        let hit = r64::hit_cube(&cube, &ray64(case.origin, case.dir), f64::INFINITY);
        check_box(hit.map(|h| (h.t, h.p.is_finite() && h.n.is_finite())), &exact, case.origin, case.centre, EPS64)?;
    }

    /// Axis-aligned rays (direction components exactly 0) from origins on
    /// slab planes, along faces, edges and through corners of an unrotated
    /// box: never NaN, and the closed-slab answer.
    #[test]
    fn box_axis_aligned_rays(case in box_case(), axes in prop::array::uniform3(0u8..3), on in prop::array::uniform3(0u8..4),
                             dist in 1.0..50.0f64) {
        let half = case.half.as_vec3();
        let centre = case.centre.as_vec3();
        let cube = r32::Cube { center: centre, half_size: half, rotation: Mat3::IDENTITY };
        // Per axis: a direction component of -1, 0 or +1 ...
        let mut dir = Vec3::from(axes.map(|a| f32::from(a) - 1.0));
        if dir == Vec3::ZERO {
            dir = Vec3::X;
        }
        let dir = dir.normalize();
        // ... and an origin coordinate on the -h or +h slab plane, inside,
        // or outside, and for moving axes far enough back to start outside.
        let mut origin = Vec3::ZERO;
        for i in 0..3 {
            origin[i] = match on[i] { 0 => -half[i], 1 => half[i], 2 => 0.5 * half[i], _ => 1.5 * half[i] };
            origin[i] -= dir[i] * dist as f32 * half.max_element();
        }
        let origin = centre + origin;
        let ray = r32::Ray { origin, dir };
        let exact = exact::cube(origin.as_dvec3(), dir.as_dvec3(), centre.as_dvec3(), half.as_dvec3(), DMat3::IDENTITY);
        let hit = r32::hit_cube(&ray, &cube, r32::T_FAR, true);
        if let Some(h) = hit {
            prop_assert!(h.t.is_finite() && finite3(h.point) && finite3(h.normal), "NaN");
        }
        check_box(hit.map(|h| (f64::from(h.t), true)), &exact, origin.as_dvec3(), centre.as_dvec3(), EPS32)?;
        // f64: the same ray with its direction unit in f64 (the routines
        // rely on unit directions); the zero components stay zero.
        let dir64 = dir.as_dvec3().normalize();
        let exact = exact::cube(origin.as_dvec3(), dir64, centre.as_dvec3(), half.as_dvec3(), DMat3::IDENTITY);
        let cube = r64::Cube::new(centre.as_dvec3(), 2.0 * half.as_dvec3(), DMat3::IDENTITY);
        let hit = r64::hit_cube(&cube, &ray64(origin.as_dvec3(), dir64), f64::INFINITY);
        if let Some(h) = hit {
            prop_assert!(h.t.is_finite() && h.p.is_finite() && h.n.is_finite(), "NaN");
        }
        check_box(hit.map(|h| (h.t, true)), &exact, origin.as_dvec3(), centre.as_dvec3(), EPS64)?;
    }

    /// Rays spawned from sphere hit points: leaving to the outside (any
    /// angle down to 1e-6 rad) they start outside and never hit the sphere
    /// again; going in (refraction) they start inside and hit the far side,
    /// not the near one at t ~ 0.
    #[test]
    fn sphere_spawned_rays(case in sphere_case(), theta in -6.0..0.19f64,
                           tangent in prop::array::uniform3(-1.0..1.0f64), inward in prop::bool::ANY) {
        let theta = 10f64.powf(theta);
        // f32
        let sph = r32::Sphere { center: case.centre.as_vec3(), radius: case.radius as f32 };
        let ray = ray32(case.origin, case.dir);
        let Some(hit) = r32::hit_sphere(&ray, &sph, r32::T_FAR, true) else { return Ok(()) };
        let into = ray.dir.dot(hit.normal) < 0.0;
        let ns = if into { hit.normal } else { -hit.normal };
        let side = if inward { -ns } else { ns };
        let dir = at_angle(side.as_dvec3(), unit(tangent), theta, 1.0);
        let origin = r32::offset_ray(hit.point, side, hit.error_scale, true);
        let spawned = r32::Ray { origin, dir: dir.as_vec3().normalize() };
        check_spawned(
            r32::hit_sphere(&spawned, &sph, r32::T_FAR, true).map(|h| f64::from(h.t)),
            &exact::sphere(origin.as_dvec3(), spawned.dir.as_dvec3(), sph.center.as_dvec3(), f64::from(sph.radius)),
            side.dot(hit.normal) > 0.0,
        )?;
        // f64
        let sph = r64::Sphere::new(case.centre, case.radius);
        let Some(hit) = r64::hit_sphere(&sph, &ray64(case.origin, case.dir), f64::INFINITY) else { return Ok(()) };
        let ns = if case.dir.dot(hit.n) < 0.0 { hit.n } else { -hit.n };
        let side = if inward { -ns } else { ns };
        let dir = at_angle(side, unit(tangent), theta, 1.0);
        let origin = offset64(hit.p, side, hit.error_scale);
        check_spawned(
            r64::hit_sphere(&sph, &ray64(origin, dir), f64::INFINITY).map(|h| h.t),
            &exact::sphere(origin, dir, case.centre, case.radius),
            side.dot(hit.n) > 0.0,
        )?;
    }

    /// The same for boxes: spawned rays never hit the face they leave, and
    /// rays into the box hit the far side.
    #[test]
    fn box_spawned_rays(case in box_case(), theta in -6.0..0.19f64,
                        tangent in prop::array::uniform3(-1.0..1.0f64), inward in prop::bool::ANY) {
        let theta = 10f64.powf(theta);
        let cube = cube32(&case);
        let ray = ray32(case.origin, case.dir);
        let Some(hit) = r32::hit_cube(&ray, &cube, r32::T_FAR, true) else { return Ok(()) };
        // Within rounding of an edge the hit point may lie beyond it, so a
        // ray spawned "inward" can start outside the neighbouring face: the
        // box's tangency. Its tangential error is ~eps |o - centre|.
        let margin = 64.0 * EPS32 * (ray.origin - cube.center).length() as f64;
        prop_assume!(!near_box_edge(hit.point.as_dvec3(), cube.center.as_dvec3(), cube.half_size.as_dvec3(), cube.rotation.as_dmat3(), margin));
        let ns = if ray.dir.dot(hit.normal) < 0.0 { hit.normal } else { -hit.normal };
        let side = if inward { -ns } else { ns };
        let dir = at_angle(side.as_dvec3(), unit(tangent), theta, 1.0).as_vec3().normalize();
        let origin = r32::offset_ray(hit.point, side, hit.error_scale, true);
        let exact = exact::cube(origin.as_dvec3(), dir.as_dvec3(), cube.center.as_dvec3(), cube.half_size.as_dvec3(), cube.rotation.as_dmat3());
        check_spawned_box(r32::hit_cube(&r32::Ray { origin, dir }, &cube, r32::T_FAR, true).map(|h| f64::from(h.t)), &exact, side.dot(hit.normal) > 0.0)?;
        let cube = cube64(&case);
        let Some(hit) = r64::hit_cube(&cube, &ray64(case.origin, case.dir), f64::INFINITY) else { return Ok(()) };
        let margin = 64.0 * EPS64 * (case.origin - case.centre).length();
        prop_assume!(!near_box_edge(hit.p, cube.center, cube.half, cube.rotation, margin));
        let ns = if case.dir.dot(hit.n) < 0.0 { hit.n } else { -hit.n };
        let side = if inward { -ns } else { ns };
        let dir = at_angle(side, unit(tangent), theta, 1.0);
        let origin = offset64(hit.p, side, hit.error_scale);
        let exact = exact::cube(origin, dir, cube.center, cube.half, cube.rotation);
        check_spawned_box(r64::hit_cube(&cube, &ray64(origin, dir), f64::INFINITY).map(|h| h.t), &exact, side.dot(hit.n) > 0.0)?;
    }
}

/// Whether `p` (on the box surface) lies within `margin` of an edge: two of
/// its box coordinates within `margin` of the half edges.
fn near_box_edge(p: DVec3, centre: DVec3, half: DVec3, rotation: DMat3, margin: f64) -> bool {
    let local = rotation.transpose() * (p - centre);
    (0..3)
        .filter(|&i| (local[i].abs() - half[i]).abs() <= margin)
        .count()
        >= 2
}

/// A ray spawned to the outside (`outside`) must start outside and miss;
/// one spawned to the inside must start inside and hit the far side.
fn check_spawned(
    hit: Option<f64>,
    exact: &exact::SphereTruth,
    outside: bool,
) -> Result<(), TestCaseError> {
    if outside {
        prop_assert!(exact.c > 0.0, "spawned origin not outside: c = {}", exact.c);
        prop_assert!(hit.is_none(), "self-hit at t {hit:?}");
    } else {
        prop_assert!(exact.inside, "spawned origin not inside: c = {}", exact.c);
        let te = exact.t.expect("a ray from inside always leaves");
        let t = hit.ok_or_else(|| TestCaseError::fail(format!("missed the far side at {te}")))?;
        prop_assert!(
            t > 0.5 * te && t < 2.0 * te,
            "t {t}, the far side is at {te}"
        );
    }
    Ok(())
}

fn check_spawned_box(
    hit: Option<f64>,
    exact: &exact::BoxTruth,
    outside: bool,
) -> Result<(), TestCaseError> {
    if outside {
        prop_assert!(!exact.inside, "spawned origin not outside");
        // A convex box is not entered again by a ray leaving a face, unless
        // it grazes along the face within rounding (slack ~ 0).
        prop_assert!(hit.is_none() || exact.t.is_some(), "self-hit at t {hit:?}");
    } else {
        prop_assert!(exact.inside, "spawned origin not inside");
        let te = exact.t.expect("a ray from inside always leaves");
        let t = hit.ok_or_else(|| TestCaseError::fail(format!("missed the far side at {te}")))?;
        prop_assert!(
            t > 0.5 * te && t < 2.0 * te,
            "t {t}, the far side is at {te}"
        );
    }
    Ok(())
}

/// The naive routines (the shader's ROBUST = false), on cases the robust
/// ones get right: the lecture's quadratic loses a small sphere 1e3 away,
/// the plain slab test makes 0 * inf of a ray along a slab plane, the plane
/// test calls a 5e-7 rad ray parallel, and the fixed offset of 1e-3 is lost
/// in the rounding of a hit point 1e5 from the origin.
#[test]
fn naive_routines_fail_where_the_robust_ones_do_not() {
    // Small sphere, 1000 away: the ray passes 0.05 from the centre.
    let sph = r32::Sphere {
        center: Vec3::ZERO,
        radius: 0.1,
    };
    let mut naive_wrong = 0;
    for i in 0..200 {
        let y = -0.15 + 0.3 * i as f32 / 200.0;
        let ray = ray32(
            DVec3::new(0.0, 0.0, 1e3),
            DVec3::new(0.0, f64::from(y) * 1e-3, -1.0),
        );
        let exact = exact::sphere(ray.origin.as_dvec3(), ray.dir.as_dvec3(), DVec3::ZERO, 0.1);
        let robust = r32::hit_sphere(&ray, &sph, r32::T_FAR, true).map(|h| h.t);
        let naive = r32::hit_sphere(&ray, &sph, r32::T_FAR, false).map(|h| h.t);
        assert_eq!(robust.is_some(), exact.t.is_some(), "robust, y = {y}");
        let wrong = naive.is_some() != exact.t.is_some()
            || naive
                .zip(exact.t)
                .is_some_and(|(t, te)| (f64::from(t) - te).abs() > 1e-3);
        naive_wrong += usize::from(wrong);
    }
    assert!(
        naive_wrong > 20,
        "the naive quadratic got only {naive_wrong} of 200 wrong"
    );

    // Box: origin on the slab plane x = -1, moving along it.
    let cube = r32::Cube {
        center: Vec3::ZERO,
        half_size: Vec3::ONE,
        rotation: Mat3::IDENTITY,
    };
    let ray = r32::Ray {
        origin: Vec3::new(-1.0, 0.0, 5.0),
        dir: -Vec3::Z,
    };
    assert_eq!(
        r32::hit_cube(&ray, &cube, r32::T_FAR, true).map(|h| h.t),
        Some(4.0)
    );
    assert_eq!(
        r32::hit_cube(&ray, &cube, r32::T_FAR, false).map(|h| h.t),
        None
    );

    // Plane at 5e-7 rad: t = 2e6, which the naive test calls parallel.
    let pl = r32::Plane {
        point: Vec3::ZERO,
        normal: Vec3::Y,
    };
    let ray = ray32(DVec3::Y, at_angle(DVec3::Y, DVec3::X, 5e-7, -1.0));
    assert!(r32::hit_plane(&ray, &pl, r32::T_FAR, true).is_some());
    assert!(r32::hit_plane(&ray, &pl, r32::T_FAR, false).is_none());

    // Shadow rays from a sphere of radius 1 at 1e5: the naive offset is
    // below the hit point's rounding error (ulp(1e5) = 0.008).
    let sph = r32::Sphere {
        center: Vec3::splat(1e5),
        radius: 1.0,
    };
    let (mut robust_acne, mut naive_acne) = (0, 0);
    for i in 0..400 {
        let a = i as f64 * 0.0157;
        let o = DVec3::splat(1e5) + DVec3::new(a.cos() * 0.7, a.sin() * 0.7, 10.0);
        let ray = ray32(o, -DVec3::Z);
        let light = ray32(DVec3::ZERO, DVec3::new(a.cos(), a.sin(), 1.5)).dir;
        for robust in [true, false] {
            let hit = r32::hit_sphere(&ray, &sph, r32::T_FAR, robust).unwrap();
            let origin = r32::offset_ray(hit.point, hit.normal, hit.error_scale, robust);
            let shadow = r32::Ray { origin, dir: light };
            let self_hit = r32::hit_sphere(&shadow, &sph, r32::T_FAR, robust).is_some();
            *(if robust {
                &mut robust_acne
            } else {
                &mut naive_acne
            }) += usize::from(self_hit);
        }
    }
    assert_eq!(robust_acne, 0);
    assert!(
        naive_acne > 20,
        "only {naive_acne} of 400 naive shadow rays hit their sphere"
    );
}
