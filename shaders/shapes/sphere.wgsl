// shapes/sphere.wgsl: the sphere (docs/rendering-model.md, "Shapes").
//
// A shape kind's WGSL: its struct, twin of src/gpu/shapes/sphere.rs (the layout
// test checks it), and `hit_sphere(ray, shape, index, best) -> Hit`, the
// nearest hit with ray.t_min < t < best.t or `best`. The buffer, the
// KIND_SPHERE number, the HAS_SPHERES flag and the loops that call hit_sphere are
// generated from the registry (src/gpu/shapes/glue.rs).

struct Sphere {
    center: vec3<f32>,
    radius: f32,
    material: u32,
}

/// Sphere, with the two precision fixes of Ray Tracing Gems ch. 7
/// (Haines, Guenther and Akenine-Moeller, "Precision Improvements for
/// Ray/Sphere Intersection"): the discriminant as r^2 - |g|^2 with
/// g = f - (f.d) d, f = o - c (Hearn and Baker), which does not cancel
/// catastrophically when the sphere is small and far away, and the roots as
/// q and c / q with q = -(b + sign(b) sqrt(disc)) (Press et al., Numerical
/// Recipes 5.6), which never subtracts two nearly equal numbers.
///
/// Refinements of ours (docs/accuracy.md), for scenes whose numbers are
/// large:
/// - g is perpendicular to d: one Gram-Schmidt step, g -= (g.d) d, removes
///   its rounding error along d (~ eps |f|, large for a far sphere);
/// - the constant term c = |f|^2 - r^2 is formed as (f - r u).(f + r u) =
///   |s|^2 + 2 r (s.u), with u the major axis of f and s = o - (centre + r u)
///   the ray origin relative to the sphere's pole nearest to it. On a huge
///   ground sphere (centre y = -1e5, pole at y = 0) f = o - centre is rounded
///   to ~0.008, which Press's (|f| - r)(|f| + r) turns into an error of the
///   origin's height, and so of t, of that size; s keeps the origin's height
///   exact;
/// - with c that accurate the textbook discriminant b^2 - c has the error
///   eps (b^2 + |c|), against eps r^2 for r^2 - |g|^2: near a huge sphere
///   (its horizon, where the hit is nearly tangent) the smaller is used;
/// - the normal is normalize(g -+ sqrt(disc) d) (the foot of the
///   perpendicular from the centre, then along the ray: f + t d for the near
///   and the far root), so no world coordinate as large as the distance
///   travelled enters it; the hit point is o + t d when those numbers are
///   smaller than the centre's (the ground sphere seen from nearby), else
///   the re-projection centre + r n (a small sphere seen from far away).
/// `error_scale` is the size of the numbers the point and a later test of
/// a ray from it against this sphere involve (see offset_ray).
fn hit_sphere(ray: Ray, s: Sphere, index: u32, best: Hit) -> Hit {
    if !ROBUST {
        return hit_sphere_naive(ray, s, index, best);
    }
    let d = ray.dir;
    let world_f = ray.origin - s.center;
    // The squares below overflow an f32 for lengths past 2^63 (a radius of
    // 1e30) and vanish below 2^-63: such a sphere is intersected in units of
    // a power of two near its numbers, which scales exactly, and t is
    // scaled back (docs/reliability.md, "Extreme scenes on the GPU").
    let k = unit_scale(max(s.radius, max3(abs(world_f))));
    let r = s.radius * k;
    let f = world_f * k;
    let b = dot(f, d);
    let g = foot(ray, s.center).g * k;
    let u = major_axis(f);
    let from_pole = (ray.origin - (s.center + s.radius * u)) * k;
    let c = dot(from_pole, from_pole) + 2.0 * r * dot(from_pole, u);
    // The two forms of the discriminant and their rounding errors:
    // r^2 - |g|^2 ~ eps r^2, b^2 - c ~ eps (b^2 + |c|). The first wins for
    // a sphere small against its distance, the second near a huge sphere,
    // e.g. at the horizon of a ground sphere, where eps r^2 would move the
    // hit point's height by eps r / 2.
    var disc = r * r - dot(g, g);
    if b * b + abs(c) < r * r {
        disc = b * b - c;
    }
    if disc < 0.0 || r * r == 0.0 {
        return best;
    }
    let h = sqrt(disc);
    let q = -(b + select(-1.0, 1.0, b >= 0.0) * h);
    if q == 0.0 {
        return best;
    }
    let t0 = min(c / q, q) / k;
    let t1 = max(c / q, q) / k;
    var t = t0;
    var along = -h;            // the near root is -b - sqrt(disc)
    if t <= ray.t_min {
        t = t1;
        along = h;
    }
    if t <= ray.t_min || t >= best.t {
        return best;
    }
    let n = normalize(g + along * d);
    let ray_scale = max3(abs(ray.origin)) + abs(t);
    // In world units again.
    let centre_scale = max3(abs(s.center)) + s.radius;
    var p = s.center + s.radius * n;
    if ray_scale < centre_scale {
        p = ray.origin + t * d;
    }
    let pole_scale = max3(abs(s.center + s.radius * major_axis(n)));
    let scale = max(pole_scale, min(ray_scale, centre_scale));
    return surface_hit(t, p, n, KIND_SPHERE, index, scale);
}

/// 1, or for a length x outside [2^-40, 2^40] the power of two 2^-e that
/// brings it to [1, 2) (e its binary exponent, read from the bits: exact).
fn unit_scale(x: f32) -> f32 {
    let e = (bitcast<u32>(x) >> 23u) & 0xffu;
    if e >= 87u && e <= 167u {
        return 1.0;
    }
    return bitcast<f32>((254u - clamp(e, 1u, 253u)) << 23u);
}

/// The lecture's sphere (ROBUST = false): a t^2 + b t + c = 0 with
/// a = d.d, b = 2 f.d, c = f.f - r^2, disc = b^2 - 4 a c and
/// t = (-b -+ sqrt(disc)) / 2a. b^2 and 4ac are nearly equal for a small,
/// far sphere, and their difference loses every digit. The hit point is
/// o + t d, and the normal (p - c) / r (docs/rendering-model.md, "Shapes").
fn hit_sphere_naive(ray: Ray, s: Sphere, index: u32, best: Hit) -> Hit {
    let f = ray.origin - s.center;
    let a = dot(ray.dir, ray.dir);
    let b = 2.0 * dot(f, ray.dir);
    let c = dot(f, f) - s.radius * s.radius;
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return best;
    }
    var t = (-b - sqrt(disc)) / (2.0 * a);
    if t <= ray.t_min {
        t = (-b + sqrt(disc)) / (2.0 * a);
    }
    if t <= ray.t_min || t >= best.t {
        return best;
    }
    let p = ray.origin + t * ray.dir;
    return surface_hit(t, p, (p - s.center) / s.radius, KIND_SPHERE, index, 0.0);
}

/// The barycentric view on a sphere (docs/views.md): its (u, v) =
/// (longitude / 2 pi, colatitude / pi) of the outward normal about +y, as
/// `reference::shapes::sphere::uv`.
fn view_coordinates_sphere(hit: Hit) -> vec3<f32> {
    let n = hit.normal;
    let pi = 3.14159265358979;
    let u = 0.5 + atan2(n.z, n.x) / (2.0 * pi);
    let v = acos(clamp(n.y, -1.0, 1.0)) / pi;
    return vec3(u, v, 0.0);
}
