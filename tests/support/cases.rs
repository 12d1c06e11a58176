//! Generators of test cases shared by the property tests and the
//! compute-shader test: spheres, planes and boxes of sizes 1e-3 to 1e6 up to
//! 1e3 sizes from the origin, with rays that hit, miss and graze them.

#![allow(dead_code)]

use glam::{DMat3, DVec3, Vec3};
use proptest::prelude::*;

use raysandbox::stress::f32_intersect as r32;

pub fn unit(v: [f64; 3]) -> DVec3 {
    let v = DVec3::from(v);
    if v.length() < 1e-3 {
        DVec3::Y
    } else {
        v.normalize()
    }
}

/// Rounds to f32 and back.
pub fn r(v: DVec3) -> DVec3 {
    v.as_vec3().as_dvec3()
}

pub fn finite3(v: Vec3) -> bool {
    v.is_finite()
}

/// A direction at angle `theta` from the plane with unit normal `n`, on the
/// side `side` (+1 along n, -1 against it), heading along `tangent`.
pub fn at_angle(n: DVec3, tangent: DVec3, theta: f64, side: f64) -> DVec3 {
    // A tangent nearly along n would leave a projection too short to be
    // perpendicular to n to 1e-6; use any perpendicular then.
    let mut t = tangent - tangent.dot(n) * n;
    if t.length() < 0.1 * tangent.length() {
        t = n.any_orthonormal_vector();
    }
    let t = t - t.dot(n) * n;
    (theta.cos() * t.normalize() + side * theta.sin() * n).normalize()
}

/// Scene size, distance of the scene from the origin (in sizes) and where.
pub fn placement() -> impl Strategy<Value = (f64, DVec3)> {
    (
        -3.0..6.0f64,
        -1.0..3.0f64,
        prop::array::uniform3(-1.0..1.0f64),
    )
        .prop_map(|(size, away, dir)| {
            let s = 10f64.powf(size);
            (s, unit(dir) * s * 10f64.powf(away))
        })
}

/// The case of a sphere: centre, radius, ray origin, ray direction, in f64.
#[derive(Debug, Clone)]
pub struct SphereCase {
    pub centre: DVec3,
    pub radius: f64,
    pub origin: DVec3,
    pub dir: DVec3,
}

pub fn sphere_case() -> impl Strategy<Value = SphereCase> {
    (
        placement(),
        -1.5..1.0f64,
        prop::array::uniform3(-1.0..1.0f64),
        -0.5..4.0f64,
        prop::array::uniform3(-1.0..1.0f64),
        0.0..1.6f64,
    )
        .prop_map(|((s, at), radius, from, dist, aim, miss)| {
            let radius = s * 10f64.powf(radius);
            let centre = at;
            let origin = centre + unit(from) * radius * 10f64.powf(dist);
            let target = centre + unit(aim) * radius * miss;
            SphereCase {
                centre,
                radius,
                origin,
                dir: (target - origin).normalize(),
            }
        })
}

/// An f32 ray as the shader makes it: rounded origin, direction normalised
/// in f32.
pub fn ray32(o: DVec3, d: DVec3) -> r32::Ray {
    r32::Ray {
        origin: o.as_vec3(),
        dir: d.as_vec3().normalize(),
    }
}

pub fn ray64(o: DVec3, d: DVec3) -> raysandbox::reference::ray::Ray {
    raysandbox::reference::ray::Ray { origin: o, dir: d }
}

/// A plane case: the plane, and a ray from `height` above it (on `side`)
/// coming down at `theta` radians.
#[derive(Debug, Clone)]
pub struct PlaneCase {
    pub point: DVec3,
    pub normal: DVec3,
    pub origin: DVec3,
    pub dir: DVec3,
    pub theta: f64,
    pub side: f64,
}

pub fn plane_case() -> impl Strategy<Value = PlaneCase> {
    (
        placement(),
        prop::array::uniform3(-1.0..1.0f64),
        prop::array::uniform3(-10.0..10.0f64),
        -3.0..1.0f64,
        prop::array::uniform3(-1.0..1.0f64),
        -6.0..0.19f64,
        prop::bool::ANY,
    )
        .prop_map(|((s, at), normal, along, height, tangent, theta, up)| {
            let normal = unit(normal);
            let side = if up { 1.0 } else { -1.0 };
            let along = DVec3::from(along) * s;
            let along = along - along.dot(normal) * normal;
            let origin = at + along + side * s * 10f64.powf(height) * normal;
            let theta = 10f64.powf(theta);
            PlaneCase {
                point: at,
                normal,
                origin,
                dir: at_angle(normal, unit(tangent), theta, -side),
                theta,
                side,
            }
        })
}

/// A box case: centre, half edges, rotation, and a ray from outside aimed
/// at a point of `[-1.3, 1.3]` times the half edges.
#[derive(Debug, Clone)]
pub struct BoxCase {
    pub centre: DVec3,
    pub half: DVec3,
    pub rotation: DMat3,
    pub origin: DVec3,
    pub dir: DVec3,
}

pub fn rotation(kind: u8, angles: [f64; 3]) -> DMat3 {
    let a = match kind {
        // None: every direction component in the box frame is as given.
        0 => DVec3::ZERO,
        // Multiples of 90 degrees: 6e-17 where a 0 belongs.
        1 => DVec3::from(angles.map(|x| (x * 2.0).round() * 90.0)),
        _ => DVec3::from(angles.map(|x| x * 180.0)),
    };
    let r = a * (std::f64::consts::PI / 180.0);
    DMat3::from_rotation_z(r.z) * DMat3::from_rotation_y(r.y) * DMat3::from_rotation_x(r.x)
}

pub fn box_case() -> impl Strategy<Value = BoxCase> {
    (
        placement(),
        prop::array::uniform3(-1.0..0.5f64),
        0u8..3,
        prop::array::uniform3(-1.0..1.0f64),
        prop::array::uniform3(-1.0..1.0f64),
        0.3..3.0f64,
        prop::array::uniform3(-1.3..1.3f64),
    )
        .prop_map(|((s, at), half, kind, angles, from, dist, aim)| {
            let half = DVec3::from(half.map(|h| s * 10f64.powf(h)));
            let rotation = rotation(kind, angles);
            let origin = at + unit(from) * half.length() * 10f64.powf(dist);
            let target = at + rotation * (DVec3::from(aim) * half);
            BoxCase {
                centre: at,
                half,
                rotation,
                origin,
                dir: (target - origin).normalize(),
            }
        })
}

pub fn cube32(case: &BoxCase) -> r32::Cube {
    r32::Cube {
        center: case.centre.as_vec3(),
        half_size: case.half.as_vec3(),
        rotation: case.rotation.as_mat3(),
    }
}

pub fn cube64(case: &BoxCase) -> raysandbox::reference::shapes::cube::Cube {
    raysandbox::reference::shapes::cube::Cube::new(case.centre, 2.0 * case.half, case.rotation)
}
