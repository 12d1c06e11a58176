// intersect.wgsl: ray-shape intersection (spec section 2).
//
// Every routine accepts only 0 < t < t_max and reports the outward geometric
// normal. WGSL makes no promise about inf and NaN, so no routine may form
// them: divisions are guarded by explicit branches.

/// Largest ray parameter we ever use; finite, so comparisons stay defined.
const T_FAR: f32 = 1e30;

/// pbrt-v4's gamma(3) = 3 eps / (1 - 3 eps) with eps = 2^-24: the relative
/// error bound of three f32 operations, used to widen the far slab bound.
const GAMMA3: f32 = 1.7881396e-7;

/// true: the robust routines below; false: the lecture's textbook versions
/// (naive quadratic, plain slab test, fixed offset), to show the difference.
override ROBUST: bool = true;

const KIND_NONE: u32 = 0u;
const KIND_SPHERE: u32 = 1u;
const KIND_PLANE: u32 = 2u;
const KIND_CUBE: u32 = 3u;

/// A surface hit: where, which way the surface faces, and what it is.
struct Hit {
    t: f32,
    point: vec3<f32>,
    normal: vec3<f32>,       // outward geometric normal, unit length
    kind: u32,               // KIND_*, KIND_NONE = missed everything
    index: u32,              // index into the array of that kind
    error_scale: f32,        // magnitude of the shape's numbers, sizes offset_ray
}

fn no_hit(t_max: f32) -> Hit {
    return Hit(t_max, vec3(0.0), vec3(0.0), KIND_NONE, 0u, 0.0);
}

fn max3(v: vec3<f32>) -> f32 {
    return max(v.x, max(v.y, v.z));
}

/// Sphere, with the two precision fixes of Ray Tracing Gems ch. 7:
/// the discriminant as r^2 - |f - (f.d) d|^2 (Hearn and Baker), which does not
/// cancel catastrophically when the sphere is small and far away, and the
/// roots as q and c / q with q = -(b + sign(b) sqrt(disc)) (Press et al.,
/// Numerical Recipes 5.6), which never subtracts two nearly equal numbers.
/// The hit point is re-projected onto the sphere.
fn hit_sphere(ray: Ray, s: Sphere, index: u32, best: Hit) -> Hit {
    let f = ray.origin - s.center;
    let b = dot(f, ray.dir);
    let g = f - b * ray.dir;
    let r = s.radius;
    let disc = r * r - dot(g, g);
    if disc < 0.0 {
        return best;
    }
    let lf = length(f);
    let c = (lf - r) * (lf + r);
    let q = -(b + select(-1.0, 1.0, b >= 0.0) * sqrt(disc));
    if q == 0.0 {
        return best;
    }
    let t0 = min(c / q, q);
    let t1 = max(c / q, q);
    var t = t0;
    if t <= 0.0 {
        t = t1;
    }
    if t <= 0.0 || t >= best.t {
        return best;
    }
    // Re-project onto the surface: o + t d is off by the rounding of t
    // times |d|, which grows with the distance travelled.
    let n = normalize(ray.origin + t * ray.dir - s.center);
    return Hit(t, s.center + r * n, n, KIND_SPHERE, index, max3(abs(s.center)) + r);
}

/// Infinite plane: t = ((point - o).n) / (d.n). A ray (numerically) parallel
/// to the plane misses; the test |num| < |denom| * T_FAR rejects it without
/// ever dividing by zero. The hit point is re-projected onto the plane.
fn hit_plane(ray: Ray, pl: Plane, index: u32, best: Hit) -> Hit {
    let denom = dot(pl.normal, ray.dir);
    let num = dot(pl.point - ray.origin, pl.normal);
    if !(abs(num) < abs(denom) * T_FAR) {
        return best;
    }
    let t = num / denom;
    if t <= 0.0 || t >= best.t {
        return best;
    }
    var p = ray.origin + t * ray.dir;
    p -= dot(p - pl.point, pl.normal) * pl.normal;
    return Hit(t, p, pl.normal, KIND_PLANE, index, max3(abs(pl.point)));
}

/// Box: the slab test (Williams et al. 2005) in the box's own frame. An axis
/// the ray runs parallel to is decided by a branch (inside the slab or a
/// miss), never by 0 * inf. The far bound is widened by 1 + 2 gamma(3) as in
/// pbrt-v4, so rounding cannot make a ray slip between two faces at an edge.
/// A ray starting inside hits the face where it leaves. The hit point is
/// re-projected onto the face (its local coordinate on the face's axis set to
/// exactly +-h), so its error does not grow with the distance travelled.
fn hit_cube(ray: Ray, cube: Cube, index: u32, best: Hit) -> Hit {
    let to_local = transpose(cube.rotation);
    let o = to_local * (ray.origin - cube.center);
    let d = to_local * ray.dir;
    let h = cube.half_size;
    var t_near = -T_FAR;
    var t_far = T_FAR;
    var near_axis = 0u;
    var far_axis = 0u;
    for (var i = 0u; i < 3u; i++) {
        if abs(d[i]) < 1e-20 {
            if abs(o[i]) > h[i] {
                return best;
            }
            continue;
        }
        let inv = 1.0 / d[i];
        let ta = (-h[i] - o[i]) * inv;
        let tb = (h[i] - o[i]) * inv;
        let t0 = min(ta, tb);
        let t1 = max(ta, tb) * (1.0 + 2.0 * GAMMA3);
        if t0 > t_near {
            t_near = t0;
            near_axis = i;
        }
        if t1 < t_far {
            t_far = t1;
            far_axis = i;
        }
    }
    if t_near > t_far {
        return best;
    }
    var t = t_near;
    var axis = near_axis;
    var side = -1.0;           // the entry face faces against the ray
    if t_near <= 0.0 {
        t = t_far;
        axis = far_axis;
        side = 1.0;            // the exit face faces along it
    }
    if t <= 0.0 || t >= best.t {
        return best;
    }
    let sign = side * select(-1.0, 1.0, d[axis] >= 0.0);
    var p_local = o + t * d;
    p_local[axis] = sign * h[axis];
    var n_local = vec3(0.0);
    n_local[axis] = sign;
    let p = cube.center + cube.rotation * p_local;
    let scale = max3(abs(cube.center)) + length(h);
    return Hit(t, p, cube.rotation * n_local, KIND_CUBE, index, scale);
}

/// The nearest hit over the whole scene with 0 < t < t_max.
fn hit_scene(ray: Ray, t_max: f32) -> Hit {
    var best = no_hit(t_max);
    for (var i = 0u; i < globals.sphere_count; i++) {
        best = hit_sphere(ray, spheres[i], i, best);
    }
    for (var i = 0u; i < globals.plane_count; i++) {
        best = hit_plane(ray, planes[i], i, best);
    }
    for (var i = 0u; i < globals.cube_count; i++) {
        best = hit_cube(ray, cubes[i], i, best);
    }
    return best;
}

/// Whether anything blocks the segment 0 < t < t_max (shadow rays): stops at
/// the first blocker, since any blocker casts the whole shadow.
fn occluded(ray: Ray, t_max: f32) -> bool {
    let none = no_hit(t_max);
    for (var i = 0u; i < globals.sphere_count; i++) {
        if hit_sphere(ray, spheres[i], i, none).kind != KIND_NONE {
            return true;
        }
    }
    for (var i = 0u; i < globals.plane_count; i++) {
        if hit_plane(ray, planes[i], i, none).kind != KIND_NONE {
            return true;
        }
    }
    for (var i = 0u; i < globals.cube_count; i++) {
        if hit_cube(ray, cubes[i], i, none).kind != KIND_NONE {
            return true;
        }
    }
    return false;
}
