// intersect.wgsl: ray-shape intersection (docs/rendering-model.md, "Shapes").
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

/// The unit axis along the largest component of v, with its sign:
/// sign(v_i) e_i (x before y before z on a tie, +1 for 0).
fn major_axis(v: vec3<f32>) -> vec3<f32> {
    let a = abs(v);
    var e = vec3(0.0, 0.0, 1.0);
    if a.x >= a.y && a.x >= a.z {
        e = vec3(1.0, 0.0, 0.0);
    } else if a.y >= a.z {
        e = vec3(0.0, 1.0, 0.0);
    }
    return select(-e, e, dot(v, e) >= 0.0);
}

/// The ray origin moved along the ray to the foot of the perpendicular from
/// `anchor` (a shape's centre or point), relative to the anchor, and the ray
/// parameter of that foot: o + s d = anchor + g, g perpendicular to d. The
/// decomposition behind Hearn and Baker's discriminant, used by every shape:
/// intersecting from the foot keeps the numbers at the size of the shape
/// however far the origin is, and one Gram-Schmidt step removes the error of
/// f + s d along d (~ eps |o - anchor|). t = s + (t from the foot).
struct Foot {
    g: vec3<f32>,
    s: f32,
}

fn foot(ray: Ray, anchor: vec3<f32>) -> Foot {
    let f = ray.origin - anchor;
    let s = -dot(f, ray.dir);
    let g0 = f + s * ray.dir;
    return Foot(g0 - dot(g0, ray.dir) * ray.dir, s);
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
    let r = s.radius;
    let f = ray.origin - s.center;
    let b = dot(f, d);
    let g = foot(ray, s.center).g;
    let u = major_axis(f);
    let from_pole = ray.origin - (s.center + r * u);
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
    let t0 = min(c / q, q);
    let t1 = max(c / q, q);
    var t = t0;
    var along = -h;            // the near root is -b - sqrt(disc)
    if t <= 0.0 {
        t = t1;
        along = h;
    }
    if t <= 0.0 || t >= best.t {
        return best;
    }
    let n = normalize(g + along * d);
    let ray_scale = max3(abs(ray.origin)) + t;
    let centre_scale = max3(abs(s.center)) + r;
    var p = s.center + r * n;
    if ray_scale < centre_scale {
        p = ray.origin + t * d;
    }
    let pole_scale = max3(abs(s.center + r * major_axis(n)));
    let scale = max(pole_scale, min(ray_scale, centre_scale));
    return Hit(t, p, n, KIND_SPHERE, index, scale);
}

/// The lecture's sphere (ROBUST = false): a t^2 + b t + c = 0 with
/// a = d.d, b = 2 f.d, c = f.f - r^2, disc = b^2 - 4 a c and
/// t = (-b -+ sqrt(disc)) / 2a. b^2 and 4ac are nearly equal for a small,
/// far sphere, and their difference loses every digit. The hit point is
/// o + t d, and the normal (p - c) / r, as on the slides.
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
    if t <= 0.0 {
        t = (-b + sqrt(disc)) / (2.0 * a);
    }
    if t <= 0.0 || t >= best.t {
        return best;
    }
    let p = ray.origin + t * ray.dir;
    return Hit(t, p, (p - s.center) / s.radius, KIND_SPHERE, index, 0.0);
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
    if t <= 0.0 || t >= best.t {
        return best;
    }
    var p = ray.origin + t * ray.dir;
    let ft = foot(ray, pl.point);
    let t_foot = -dot(ft.g, pl.normal) / denom;
    if max3(abs(ray.origin)) + t > max3(abs(pl.point)) + abs(t_foot) {
        p = pl.point + (ft.g + t_foot * ray.dir);
    }
    p -= dot(p - pl.point, pl.normal) * pl.normal;
    return Hit(t, p, pl.normal, KIND_PLANE, index, max3(abs(pl.point)));
}

/// The lecture's plane (ROBUST = false): parallel when |n.d| < 1e-6, else
/// t = ((point - o).n) / (n.d) and the hit point o + t d, not re-projected.
fn hit_plane_naive(ray: Ray, pl: Plane, index: u32, best: Hit) -> Hit {
    let denom = dot(pl.normal, ray.dir);
    if abs(denom) < 1e-6 {
        return best;
    }
    let t = dot(pl.point - ray.origin, pl.normal) / denom;
    if t <= 0.0 || t >= best.t {
        return best;
    }
    return Hit(t, ray.origin + t * ray.dir, pl.normal, KIND_PLANE, index, 0.0);
}

/// Box: the slab test (Williams et al. 2005) in the box's own frame. From an
/// origin far from the box (more than 16 half edges away) the test starts at
/// the foot of the perpendicular from the centre (see `foot`), so that the
/// far origin is not rotated into the box frame as a large, rounded vector;
/// from nearby it starts at the origin itself, where a face lying in a plane
/// gets exactly the plane's t (a box resting on the floor). An axis the ray runs parallel to is decided by a branch (inside the slab or
/// a miss), never by 0 * inf. The far bound is widened by 2 gamma(3) of its
/// size as in pbrt-v4 (t_far *= 1 + 2 gamma(3), written for either sign), so
/// rounding cannot make a ray slip between two faces at an edge. A ray
/// starting inside hits the face where it leaves. The hit point is
/// re-projected onto the face (its local coordinate on the face's axis set to
/// exactly +-h), so its error does not grow with the distance travelled.
fn hit_cube(ray: Ray, cube: Cube, index: u32, best: Hit) -> Hit {
    if !ROBUST {
        return hit_cube_naive(ray, cube, index, best);
    }
    let to_local = transpose(cube.rotation);
    let h = cube.half_size;
    var rel = ray.origin - cube.center;
    var s = 0.0;               // ray parameter of the point the test starts at
    if max3(abs(rel)) > 16.0 * max3(h) {
        let ft = foot(ray, cube.center);
        rel = ft.g;
        s = ft.s;
    }
    let o = to_local * rel;
    let d = to_local * ray.dir;
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
        let t1 = max(ta, tb);
        let t1_wide = t1 + 2.0 * GAMMA3 * abs(t1);
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
        return best;
    }
    // From the start of the test to the ray origin's parameter: t = s + t_local.
    var t_local = t_near;
    var axis = near_axis;
    var side = -1.0;           // the entry face faces against the ray
    if s + t_near <= 0.0 {
        t_local = t_far;
        axis = far_axis;
        side = 1.0;            // the exit face faces along it
    }
    let t = s + t_local;
    if t <= 0.0 || t >= best.t {
        return best;
    }
    let sign = side * select(-1.0, 1.0, d[axis] >= 0.0);
    var p_local = o + t_local * d;
    p_local[axis] = sign * h[axis];
    var n_local = vec3(0.0);
    n_local[axis] = sign;
    let p = cube.center + cube.rotation * p_local;
    let scale = max3(abs(cube.center)) + length(h);
    return Hit(t, p, cube.rotation * n_local, KIND_CUBE, index, scale);
}

/// The plain slab test (ROBUST = false), as usually taught: inv = 1 / d_i,
/// the entry and exit of each slab, no special case for d_i = 0 (1 / 0 and
/// 0 * inf are left to the hardware, which WGSL does not pin down), no
/// widening of the far bound, and the hit point o + t d, not re-projected.
fn hit_cube_naive(ray: Ray, cube: Cube, index: u32, best: Hit) -> Hit {
    let to_local = transpose(cube.rotation);
    let o = to_local * (ray.origin - cube.center);
    let d = to_local * ray.dir;
    let h = cube.half_size;
    let inv = 1.0 / d;
    let ta = (-h - o) * inv;
    let tb = (h - o) * inv;
    let lo = min(ta, tb);
    let hi = max(ta, tb);
    var t_near = lo.x;
    var near_axis = 0u;
    if lo.y > t_near {
        t_near = lo.y;
        near_axis = 1u;
    }
    if lo.z > t_near {
        t_near = lo.z;
        near_axis = 2u;
    }
    var t_far = hi.x;
    var far_axis = 0u;
    if hi.y < t_far {
        t_far = hi.y;
        far_axis = 1u;
    }
    if hi.z < t_far {
        t_far = hi.z;
        far_axis = 2u;
    }
    if t_near > t_far {
        return best;
    }
    var t = t_near;
    var axis = near_axis;
    var side = -1.0;
    if t_near <= 0.0 {
        t = t_far;
        axis = far_axis;
        side = 1.0;
    }
    if t <= 0.0 || t >= best.t {
        return best;
    }
    var n_local = vec3(0.0);
    n_local[axis] = side * sign(d[axis]);
    let p = ray.origin + t * ray.dir;
    return Hit(t, p, cube.rotation * n_local, KIND_CUBE, index, 0.0);
}

/// Whether the ray meets the box for some 0 <= t < t_max: the slab test
/// with the same care as hit_cube (a parallel axis decided by a branch, the
/// far bound widened by 1 + 2 gamma(3)). `inv_d` is 1 / d, 0 where |d_i| is
/// below 1e-20 (those components are not used).
fn hit_box(lo: vec3<f32>, hi: vec3<f32>, ray: Ray, inv_d: vec3<f32>, t_max: f32) -> bool {
    var near = 0.0;
    var far = t_max;
    for (var i = 0u; i < 3u; i++) {
        if abs(ray.dir[i]) < 1e-20 {
            if ray.origin[i] < lo[i] || ray.origin[i] > hi[i] {
                return false;
            }
            continue;
        }
        let ta = (lo[i] - ray.origin[i]) * inv_d[i];
        let tb = (hi[i] - ray.origin[i]) * inv_d[i];
        near = max(near, min(ta, tb));
        far = min(far, max(ta, tb) * (1.0 + 2.0 * GAMMA3));
    }
    return near <= far;
}

/// The nearest sphere or box hit through the BVH, nearer than best.t. With
/// `any`, stops at the first hit (shadow rays need no more). The root's box
/// holds every bounded shape, so a ray that misses it leaves at once.
fn hit_bounded_bvh(ray: Ray, best_in: Hit, any: bool) -> Hit {
    var best = best_in;
    if globals.bvh_node_count == 0u {
        return best;
    }
    let inv_d = select(1.0 / ray.dir, vec3(0.0), abs(ray.dir) < vec3(1e-20));
    // BVH_STACK (generated from src/bvh.rs) is enough for the deepest tree.
    var stack: array<u32, BVH_STACK>;
    stack[0] = 0u;
    var top = 1u;
    while top > 0u {
        top -= 1u;
        let node = bvh_nodes[stack[top]];
        if !hit_box(node.bounds_min, node.bounds_max, ray, inv_d, best.t) {
            continue;
        }
        if node.count == 0u {
            // Visit the nearer child first: push it last.
            let e = node.bounds_max - node.bounds_min;
            var axis = 2u;
            if e.x >= e.y && e.x >= e.z {
                axis = 0u;
            } else if e.y >= e.z {
                axis = 1u;
            }
            let near_first = ray.dir[axis] >= 0.0;
            stack[top] = select(node.first, node.first + 1u, near_first);
            stack[top + 1u] = select(node.first + 1u, node.first, near_first);
            top = min(top + 2u, BVH_STACK);
            continue;
        }
        for (var i = node.first; i < node.first + node.count; i++) {
            let shape = bvh_shapes[i];
            if (shape & CUBE_BIT) != 0u {
                if HAS_CUBES {
                    best = hit_cube(ray, cubes[shape & ~CUBE_BIT], shape & ~CUBE_BIT, best);
                }
            } else if HAS_SPHERES {
                best = hit_sphere(ray, spheres[shape], shape, best);
            }
        }
        if any && best.kind != KIND_NONE {
            return best;
        }
    }
    return best;
}

/// The nearest sphere or box hit by looping over all of them (USE_BVH =
/// false: the lecture's loop, and the baseline of the BVH's speed-up).
fn hit_bounded_loop(ray: Ray, best_in: Hit, any: bool) -> Hit {
    var best = best_in;
    if HAS_SPHERES {
        for (var i = 0u; i < globals.sphere_count; i++) {
            best = hit_sphere(ray, spheres[i], i, best);
            if any && best.kind != KIND_NONE {
                return best;
            }
        }
    }
    if HAS_CUBES {
        for (var i = 0u; i < globals.cube_count; i++) {
            best = hit_cube(ray, cubes[i], i, best);
            if any && best.kind != KIND_NONE {
                return best;
            }
        }
    }
    return best;
}

/// The nearest hit with 0 < t < best.t over planes and bounded shapes; with
/// `any`, any hit will do.
fn hit_shapes(ray: Ray, best_in: Hit, any: bool) -> Hit {
    var best = best_in;
    if HAS_PLANES {
        for (var i = 0u; i < globals.plane_count; i++) {
            best = hit_plane(ray, planes[i], i, best);
            if any && best.kind != KIND_NONE {
                return best;
            }
        }
    }
    if HAS_SPHERES || HAS_CUBES {
        if USE_BVH {
            best = hit_bounded_bvh(ray, best, any);
        } else {
            best = hit_bounded_loop(ray, best, any);
        }
    }
    return best;
}

/// The nearest hit over the whole scene with 0 < t < t_max.
fn hit_scene(ray: Ray, t_max: f32) -> Hit {
    return hit_shapes(ray, no_hit(t_max), false);
}

/// Whether anything blocks the segment 0 < t < t_max (shadow rays): stops at
/// the first blocker, since any blocker casts the whole shadow.
fn occluded(ray: Ray, t_max: f32) -> bool {
    return hit_shapes(ray, no_hit(t_max), true).kind != KIND_NONE;
}
