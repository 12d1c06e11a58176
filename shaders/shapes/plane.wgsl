// shapes/plane.wgsl: the infinite, two-sided plane (docs/rendering-model.md, "Shapes").
//
// A shape kind's WGSL: its struct, twin of src/gpu/shapes/plane.rs (the layout
// test checks it), and `hit_plane(ray, shape, index, best) -> Hit`, the
// nearest hit with ray.t_min < t < best.t or `best`. The buffer, the
// KIND_PLANE number, the HAS_PLANES flag and the loops that call hit_plane are
// generated from the registry (src/gpu/shapes/glue.rs).

/// An infinite two-sided plane; `normal` is unit length.
struct Plane {
    point: vec3<f32>,
    material: u32,
    normal: vec3<f32>,
}

/// Infinite plane: t = ((point - o).n) / (d.n). A ray (numerically)
/// parallel to the plane misses; the test |num| < |denom| * T_FAR rejects it
/// without ever dividing by zero. The hit point is o + t d or, when that
/// involves larger numbers (a plane seen from far away), point + q with q
/// computed from the foot of the perpendicular from `point` (see `foot`);
/// either is then re-projected onto the plane. (t itself stays the plain
/// quotient: a box face lying in the plane computes the very same number,
/// so the two tie exactly and the plane wins in both renderers.)
fn hit_plane(ray: Ray, pl: Plane, index: u32, best: Hit) -> Hit {
    if !ROBUST {
        return hit_plane_naive(ray, pl, index, best);
    }
    let denom = dot(pl.normal, ray.dir);
    let num = dot(pl.point - ray.origin, pl.normal);
    if !(abs(num) < abs(denom) * T_FAR) {
        return best;
    }
    let t = num / denom;
    if t <= ray.t_min || t >= best.t {
        return best;
    }
    var p = ray.origin + t * ray.dir;
    let ft = foot(ray, pl.point);
    let t_foot = -dot(ft.g, pl.normal) / denom;
    if max3(abs(ray.origin)) + abs(t) > max3(abs(pl.point)) + abs(t_foot) {
        p = pl.point + (ft.g + t_foot * ray.dir);
    }
    p -= dot(p - pl.point, pl.normal) * pl.normal;
    return surface_hit(t, p, pl.normal, KIND_PLANE, index, max3(abs(pl.point)));
}

/// The lecture's plane (ROBUST = false): parallel when |n.d| < 1e-6, else
/// t = ((point - o).n) / (n.d) and the hit point o + t d, not re-projected.
fn hit_plane_naive(ray: Ray, pl: Plane, index: u32, best: Hit) -> Hit {
    let denom = dot(pl.normal, ray.dir);
    if abs(denom) < 1e-6 {
        return best;
    }
    let t = dot(pl.point - ray.origin, pl.normal) / denom;
    if t <= ray.t_min || t >= best.t {
        return best;
    }
    return surface_hit(t, ray.origin + t * ray.dir, pl.normal, KIND_PLANE, index, 0.0);
}
