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

/// Deepest BVH level (src/bvh.rs MAX_DEPTH) + 1: the traversal stack.
const BVH_STACK: u32 = 31u;

/// The nearest sphere or box hit through the BVH, nearer than best.t. With
/// `any`, stops at the first hit (shadow rays need no more). The root's box
/// holds every bounded shape, so a ray that misses it leaves at once.
fn hit_bounded_bvh(ray: Ray, best_in: Hit, any: bool) -> Hit {
    var best = best_in;
    if globals.bvh_node_count == 0u {
        return best;
    }
    let inv_d = select(1.0 / ray.dir, vec3(0.0), abs(ray.dir) < vec3(1e-20));
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
            top = min(top + 2u, BVH_STACK - 1u);
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
