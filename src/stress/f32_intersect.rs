//! The shader's intersection routines (`shaders/shapes/*.wgsl`) and ray
//! offset (`offset_ray` in `shaders/shade.wgsl`) ported line by line to Rust
//! in f32, robust and naive, for the property tests: proptest cannot run on
//! the GPU, and the port lets it search millions of cases on the CPU. The
//! compute-shader test (`tests/wgsl_intersections.rs`) runs the WGSL itself
//! on the same inputs and checks that it agrees with this port and with f64.
//!
//! Keep it in sync with the WGSL: same formulas, same order of operations,
//! same branches; `the_cpu_port_computes_what_the_wgsl_computes` in
//! `tests/wgsl_intersections.rs` fails when the two drift apart. (Rust does not contract `a * b + c` into a fused
//! multiply-add; a GPU may, so results can differ in the last bits.)

use glam::{Mat3, Vec3};

use crate::reference::shapes::cube::naive_slab;
use crate::reference::shapes::sphere::naive_root;

/// The shader's `T_FAR`: no ray parameter is ever larger.
pub const T_FAR: f32 = 1e38;
/// The shader's `GAMMA3`: pbrt-v4's gamma(3) for f32 (eps = 2^-24).
pub const GAMMA3: f32 = 1.788_139_6e-7;
/// The shader's `OFFSET_ULPS`: the offset is this many units of 2^-23 of
/// the scale (see `offset_ray`).
pub const OFFSET_ULPS: f32 = 8.0;
/// The shader's `NAIVE_OFFSET`.
pub const NAIVE_OFFSET: f32 = 1e-3;

/// A ray with unit direction. The shader's `Ray` also carries `t_min`,
/// which is 0 for every ray but a camera ray; the port and the property
/// tests cover that case (`0 < t`), where `t <= ray.t_min` in the WGSL reads
/// `t <= 0.0` here.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    pub origin: Vec3,
    pub dir: Vec3,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    pub center: Vec3,
    pub radius: f32,
}

/// An infinite plane; `normal` is unit length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    pub point: Vec3,
    pub normal: Vec3,
}

/// `center + rotation * local`, local in `[-half_size, half_size]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cube {
    pub center: Vec3,
    pub half_size: Vec3,
    pub rotation: Mat3,
}

/// The shader's `Hit`, without kind and index.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    pub t: f32,
    pub point: Vec3,
    pub normal: Vec3,
    pub error_scale: f32,
}

fn max3(v: Vec3) -> f32 {
    v.x.max(v.y.max(v.z))
}

/// The shader's `foot`: the foot of the perpendicular from `anchor` to the
/// ray, relative to the anchor, and its ray parameter.
pub fn foot(ray: &Ray, anchor: Vec3) -> (Vec3, f32) {
    let f = ray.origin - anchor;
    let s = -f.dot(ray.dir);
    let g0 = f + s * ray.dir;
    (g0 - g0.dot(ray.dir) * ray.dir, s)
}

/// The shader's `major_axis`.
pub fn major_axis(v: Vec3) -> Vec3 {
    let a = v.abs();
    let e = if a.x >= a.y && a.x >= a.z {
        Vec3::X
    } else if a.y >= a.z {
        Vec3::Y
    } else {
        Vec3::Z
    };
    if v.dot(e) >= 0.0 { e } else { -e }
}

/// The shader's `hit_sphere` (robust) or `hit_sphere_naive`.
pub fn hit_sphere(ray: &Ray, s: &Sphere, t_max: f32, robust: bool) -> Option<Hit> {
    if !robust {
        return hit_sphere_naive(ray, s, t_max);
    }
    let d = ray.dir;
    let r = s.radius;
    let f = ray.origin - s.center;
    let b = f.dot(d);
    let g = foot(ray, s.center).0;
    let u = major_axis(f);
    let from_pole = ray.origin - (s.center + r * u);
    let c = from_pole.dot(from_pole) + 2.0 * r * from_pole.dot(u);
    let mut disc = r * r - g.dot(g);
    if b * b + c.abs() < r * r {
        disc = b * b - c;
    }
    if disc < 0.0 || r * r == 0.0 {
        return None;
    }
    let h = disc.sqrt();
    let q = -(b + if b >= 0.0 { 1.0 } else { -1.0 } * h);
    if q == 0.0 {
        return None;
    }
    let t0 = (c / q).min(q);
    let t1 = (c / q).max(q);
    let (mut t, mut along) = (t0, -h);
    if t <= 0.0 {
        t = t1;
        along = h;
    }
    if t <= 0.0 || t >= t_max {
        return None;
    }
    let n = (g + along * d).normalize();
    let ray_scale = max3(ray.origin.abs()) + t;
    let centre_scale = max3(s.center.abs()) + r;
    let mut p = s.center + r * n;
    if ray_scale < centre_scale {
        p = ray.origin + t * d;
    }
    let pole_scale = max3((s.center + r * major_axis(n)).abs());
    let scale = pole_scale.max(ray_scale.min(centre_scale));
    Some(Hit {
        t,
        point: p,
        normal: n,
        error_scale: scale,
    })
}

/// The shader's `hit_sphere_naive`: the lecture's quadratic.
pub fn hit_sphere_naive(ray: &Ray, s: &Sphere, t_max: f32) -> Option<Hit> {
    let f = ray.origin - s.center;
    let a = ray.dir.dot(ray.dir);
    let b = 2.0 * f.dot(ray.dir);
    let c = f.dot(f) - s.radius * s.radius;
    let t = naive_root(a, b, c, t_max)?;
    let p = ray.origin + t * ray.dir;
    Some(Hit {
        t,
        point: p,
        normal: (p - s.center) / s.radius,
        error_scale: 0.0,
    })
}

/// The shader's `hit_plane` (robust) or `hit_plane_naive`.
pub fn hit_plane(ray: &Ray, pl: &Plane, t_max: f32, robust: bool) -> Option<Hit> {
    let denom = pl.normal.dot(ray.dir);
    if !robust {
        if denom.abs() < 1e-6 {
            return None;
        }
        let t = (pl.point - ray.origin).dot(pl.normal) / denom;
        if t <= 0.0 || t >= t_max {
            return None;
        }
        return Some(Hit {
            t,
            point: ray.origin + t * ray.dir,
            normal: pl.normal,
            error_scale: 0.0,
        });
    }
    let num = (pl.point - ray.origin).dot(pl.normal);
    // Written as in WGSL: anything but a clear "less than" misses.
    if num.abs() >= denom.abs() * T_FAR || num.is_nan() {
        return None;
    }
    let t = num / denom;
    if t <= 0.0 || t >= t_max {
        return None;
    }
    let mut p = ray.origin + t * ray.dir;
    let (g, _) = foot(ray, pl.point);
    let t_foot = -g.dot(pl.normal) / denom;
    if max3(ray.origin.abs()) + t > max3(pl.point.abs()) + t_foot.abs() {
        p = pl.point + (g + t_foot * ray.dir);
    }
    p -= (p - pl.point).dot(pl.normal) * pl.normal;
    Some(Hit {
        t,
        point: p,
        normal: pl.normal,
        error_scale: max3(pl.point.abs()),
    })
}

/// The shader's `hit_cube` (robust) or `hit_cube_naive`.
pub fn hit_cube(ray: &Ray, cube: &Cube, t_max: f32, robust: bool) -> Option<Hit> {
    if !robust {
        return hit_cube_naive(ray, cube, t_max);
    }
    let to_local = cube.rotation.transpose();
    let h = cube.half_size;
    let mut rel = ray.origin - cube.center;
    let mut s = 0.0;
    if max3(rel.abs()) > 16.0 * max3(h) {
        (rel, s) = foot(ray, cube.center);
    }
    let o = to_local * rel;
    let d = to_local * ray.dir;
    let (mut t_near, mut t_far) = (-T_FAR, T_FAR);
    let (mut near_axis, mut far_axis) = (0, 0);
    for i in 0..3 {
        if d[i].abs() < 1e-20 {
            if o[i].abs() > h[i] {
                return None;
            }
            continue;
        }
        let inv = 1.0 / d[i];
        let ta = (-h[i] - o[i]) * inv;
        let tb = (h[i] - o[i]) * inv;
        let t0 = ta.min(tb);
        let t1 = ta.max(tb);
        let t1_wide = t1 + 2.0 * GAMMA3 * t1.abs();
        if t0 > t_near {
            t_near = t0;
            near_axis = i;
        }
        if t1_wide < t_far {
            t_far = t1_wide;
            far_axis = i;
        }
    }
    if t_near > t_far {
        return None;
    }
    let (mut t_local, mut axis, mut side) = (t_near, near_axis, -1.0);
    if s + t_near <= 0.0 {
        t_local = t_far;
        axis = far_axis;
        side = 1.0;
    }
    let t = s + t_local;
    if t <= 0.0 || t >= t_max {
        return None;
    }
    let sign = side * if d[axis] >= 0.0 { 1.0 } else { -1.0 };
    let mut p_local = o + t_local * d;
    p_local[axis] = sign * h[axis];
    let mut n_local = Vec3::ZERO;
    n_local[axis] = sign;
    Some(Hit {
        t,
        point: cube.center + cube.rotation * p_local,
        normal: cube.rotation * n_local,
        error_scale: max3(cube.center.abs()) + h.length(),
    })
}

/// The shader's `hit_cube_naive`: the plain slab test.
pub fn hit_cube_naive(ray: &Ray, cube: &Cube, t_max: f32) -> Option<Hit> {
    let to_local = cube.rotation.transpose();
    let o = to_local * (ray.origin - cube.center);
    let d = to_local * ray.dir;
    let (t, axis, n) = naive_slab(o.to_array(), d.to_array(), cube.half_size.to_array(), t_max)?;
    let mut n_local = Vec3::ZERO;
    n_local[axis] = n;
    Some(Hit {
        t,
        point: ray.origin + t * ray.dir,
        normal: cube.rotation * n_local,
        error_scale: 0.0,
    })
}

/// The shader's `offset_ray`: `p + k 2^-23 max(|p|_max, error_scale, 1/32) n`
/// with k = [`OFFSET_ULPS`], or the fixed textbook offset.
pub fn offset_ray(p: Vec3, n: Vec3, error_scale: f32, robust: bool) -> Vec3 {
    if !robust {
        return p + NAIVE_OFFSET * n;
    }
    let scale = max3(p.abs()).max(error_scale.max(1.0 / 32.0));
    p + (OFFSET_ULPS * f32::EPSILON * scale) * n
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f32; 3], d: [f32; 3]) -> Ray {
        Ray {
            origin: Vec3::from(o),
            dir: Vec3::from(d).normalize(),
        }
    }

    #[test]
    fn the_constants_are_the_shaders() {
        let intersect = include_str!("../../shaders/intersect.wgsl");
        let shade = include_str!("../../shaders/shade.wgsl");
        assert!(intersect.contains("const T_FAR: f32 = 1e38;"));
        assert!(intersect.contains("const GAMMA3: f32 = 1.7881396e-7;"));
        assert!(shade.contains(&format!(
            "const OFFSET_ULPS: f32 = {OFFSET_ULPS:.1} * 1.1920929e-7;"
        )));
        assert!(shade.contains("const NAIVE_OFFSET: f32 = 1e-3;"));
        assert_eq!(
            GAMMA3,
            3.0 * f32::EPSILON / 2.0 / (1.0 - 3.0 * f32::EPSILON / 2.0)
        );
    }

    #[test]
    fn sphere_box_and_plane_by_hand() {
        let s = Sphere {
            center: Vec3::new(0.0, 0.0, -5.0),
            radius: 1.0,
        };
        for robust in [true, false] {
            let hit = hit_sphere(&ray([0.0; 3], [0.0, 0.0, -1.0]), &s, T_FAR, robust).unwrap();
            assert_eq!(hit.t, 4.0);
            assert_eq!(hit.normal, Vec3::Z);
            let pl = Plane {
                point: Vec3::new(0.0, -1.0, 0.0),
                normal: Vec3::Y,
            };
            let hit = hit_plane(&ray([0.0; 3], [0.0, -1.0, 0.0]), &pl, T_FAR, robust).unwrap();
            assert_eq!((hit.t, hit.point), (1.0, -Vec3::Y));
            let cube = Cube {
                center: Vec3::new(0.0, 0.0, -5.0),
                half_size: Vec3::splat(0.5),
                rotation: Mat3::IDENTITY,
            };
            let hit = hit_cube(
                &ray([0.2, 0.1, 0.0], [0.0, 0.0, -1.0]),
                &cube,
                T_FAR,
                robust,
            );
            assert_eq!(hit.unwrap().t, 4.5);
        }
    }

    #[test]
    fn naive_slab_makes_nan_where_robust_branches() {
        // Origin on the slab plane x = -h, direction along it: 0 * inf.
        let cube = Cube {
            center: Vec3::ZERO,
            half_size: Vec3::splat(1.0),
            rotation: Mat3::IDENTITY,
        };
        let r = ray([-1.0, 0.0, 5.0], [0.0, 0.0, -1.0]);
        let robust = hit_cube(&r, &cube, T_FAR, true).unwrap();
        assert_eq!((robust.t, robust.normal), (4.0, Vec3::Z));
        // IEEE: (-1 - -1) * inf = NaN for the x slab; min/max skip it here,
        // but whether a GPU does is up to the driver.
        let inv_x = 1.0 / r.dir.x;
        assert!(((-1.0 - r.origin.x) * inv_x).is_nan());
    }
}
