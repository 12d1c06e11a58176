// intersect.wgsl: ray-shape intersection (docs/rendering-model.md, "Shapes").
//
// Every routine accepts only ray.t_min < t < t_max (t_min is 0 but for
// camera rays, which start on the focus plane and reach back to the eye) and
// reports the outward geometric normal. WGSL makes no promise about inf and
// NaN, so no routine may form them: divisions are guarded by explicit
// branches.

/// Largest ray parameter we ever use; finite, so comparisons stay defined.
const T_FAR: f32 = 1e38;

/// pbrt-v4's gamma(3) = 3 eps / (1 - 3 eps) with eps = 2^-24: the relative
/// error bound of three f32 operations, used to widen the far slab bound.
const GAMMA3: f32 = 1.7881396e-7;

/// true: the robust routines below; false: the lecture's textbook versions
/// (naive quadratic, plain slab test, fixed offset), to show the difference.
override ROBUST: bool = true;

const KIND_NONE: u32 = 0u;   // the other KIND_* numbers are generated

/// A surface hit: where, which way the surface faces, and what it is.
struct Hit {
    t: f32,
    point: vec3<f32>,
    normal: vec3<f32>,       // outward geometric normal, unit length
    kind: u32,               // KIND_*, KIND_NONE = missed everything
    index: u32,              // index into the array of that kind
    error_scale: f32,        // magnitude of the shape's numbers, sizes offset_ray
    shading: vec3<f32>,      // outward shading normal: `normal`, or a smooth mesh's interpolated one
}

fn no_hit(t_max: f32) -> Hit {
    return Hit(t_max, vec3(0.0), vec3(0.0), KIND_NONE, 0u, 0.0, vec3(0.0));
}

/// A hit whose shading normal is its geometric normal.
fn surface_hit(t: f32, p: vec3<f32>, n: vec3<f32>, kind: u32, index: u32, error_scale: f32) -> Hit {
    return Hit(t, p, n, kind, index, error_scale, n);
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

/// Whether the ray meets the box for some t_min <= t < t_max: the slab test
/// with the same care as hit_cube (a parallel axis decided by a branch, the
/// far bound widened by 1 + 2 gamma(3)). `inv_d` is 1 / d, 0 where |d_i| is
/// below 1e-20 (those components are not used). The three axes are written
/// out, not looped over: lavapipe does not unroll shader loops, and the loop
/// with its indexed components cost 10% of the instructions of a frame of
/// the teapot (docs/performance.md, "The fixed price per pixel").
fn hit_box(lo: vec3<f32>, hi: vec3<f32>, ray: Ray, inv_d: vec3<f32>, t_max: f32) -> bool {
    var span = vec2(ray.t_min, t_max);
    span = slab(lo.x, hi.x, ray.origin.x, ray.dir.x, inv_d.x, span);
    span = slab(lo.y, hi.y, ray.origin.y, ray.dir.y, inv_d.y, span);
    span = slab(lo.z, hi.z, ray.origin.z, ray.dir.z, inv_d.z, span);
    return span.x <= span.y;
}

/// One axis of hit_box: the parameter span (near, far) narrowed to the slab
/// lo <= origin + t dir <= hi, or an empty span (near > far) when the ray
/// runs parallel to the slab outside it.
fn slab(lo: f32, hi: f32, origin: f32, dir: f32, inv_d: f32, span: vec2<f32>) -> vec2<f32> {
    if abs(dir) < 1e-20 {
        if origin < lo || origin > hi {
            return vec2(1.0, 0.0);
        }
        return span;
    }
    let ta = (lo - origin) * inv_d;
    let tb = (hi - origin) * inv_d;
    return vec2(max(span.x, min(ta, tb)), min(span.y, max(ta, tb) * (1.0 + 2.0 * GAMMA3)));
}

/// Pushes an inner BVH node's children, `first` and `first + 1` (split
/// along the longest axis of the node's box, of extent `e`), onto a
/// traversal's stack above `top`: the nearer along `dir` last, so that it
/// is visited first. Returns the new top.
fn push_children(stack: ptr<function, array<u32, BVH_STACK>>, top: u32, first: u32, e: vec3<f32>, dir: vec3<f32>) -> u32 {
    var axis = 2u;
    if e.x >= e.y && e.x >= e.z {
        axis = 0u;
    } else if e.y >= e.z {
        axis = 1u;
    }
    let near_first = dir[axis] >= 0.0;
    (*stack)[top] = select(first, first + 1u, near_first);
    (*stack)[top + 1u] = select(first + 1u, first, near_first);
    return min(top + 2u, BVH_STACK);
}

/// Narrows a bracket [a, b] of a sign change of g (g(a) < 0 when
/// `a_negative`) to the half that keeps it, g being `g_x` at x in [a, b].
fn narrow_bracket(a: ptr<function, f32>, b: ptr<function, f32>, x: f32, g_x: f32, a_negative: bool) {
    if (g_x < 0.0) == a_negative {
        *a = x;
    } else {
        *b = x;
    }
}

/// The nearest hit of a bounded shape (every kind but planes) through the
/// BVH, nearer than best.t. With `any`, stops at the first hit (shadow rays
/// need no more). The root's box holds every bounded shape, so a ray that
/// misses it leaves at once.
fn hit_bounded_bvh(ray: Ray, best_in: Hit, any: bool) -> Hit {
    var best = best_in;
    if globals().bvh_node_count == 0u {
        return best;
    }
    let inv_d = select(1.0 / ray.dir, vec3(0.0), abs(ray.dir) < vec3(1e-20));
    // BVH_STACK (generated from src/bvh.rs) is enough for the deepest tree.
    var stack: array<u32, BVH_STACK>;
    stack[0] = 0u;
    var top = 1u;
    // The "while-while" traversal of shaders/shapes/mesh.wgsl: descend to
    // a leaf, then test its shapes outside the descending loop.
    loop {
        var leaf = BvhNode();
        while top > 0u && leaf.count == 0u {
            top -= 1u;
            let node = load_bvh_node(stack[top]);
            count_node();
            if !hit_box(node.bounds_min, node.bounds_max, ray, inv_d, best.t) {
                continue;
            }
            if node.count == 0u {
                top = push_children(&stack, top, node.first, node.bounds_max - node.bounds_min, ray.dir);
                continue;
            }
            leaf = node;
        }
        if leaf.count == 0u {
            break;
        }
        for (var i = leaf.first; i < leaf.first + leaf.count; i++) {
            let shape = bvh_shape(i);
            count_test();
            best = hit_bounded(shape >> KIND_SHIFT, shape & INDEX_MASK, ray, best, any);
        }
        if any && best.kind != KIND_NONE {
            break;
        }
    }
    return best;
}

/// The nearest hit with 0 < t < best.t over unbounded shapes (planes, in a
/// loop) and bounded ones (the BVH, or a loop: hit_unbounded_loop,
/// hit_bounded_loop and hit_bounded are generated, src/gpu/shapes/glue.rs); with
/// `any`, any hit will do.
fn hit_shapes(ray: Ray, best_in: Hit, any: bool) -> Hit {
    var best = hit_unbounded_loop(ray, best_in, any);
    if any && best.kind != KIND_NONE {
        return best;
    }
    if USE_BVH {
        best = hit_bounded_bvh(ray, best, any);
    } else {
        best = hit_bounded_loop(ray, best, any);
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

/// A ray in a placed shape's local coordinates (the user functions and
/// Julia sets; docs/implementation.md, "Implicit surfaces"; the torus,
/// symmetric about its axis, needs no local frame): local points q + u d,
/// measured from the foot of the perpendicular from the shape's centre,
/// world parameter t = s + scale u.
struct LocalRay {
    q: vec3<f32>,
    d: vec3<f32>,
    s: f32,
    scale: f32,
}

/// world = center + scale * rotation * local.
fn local_ray(ray: Ray, center: vec3<f32>, scale: f32, rotation: mat3x3<f32>) -> LocalRay {
    let f = foot(ray, center);
    let inverse = transpose(rotation);
    return LocalRay(inverse * f.g / scale, inverse * ray.dir, f.s, scale);
}

/// The local parameter of world parameter t.
fn local_u(l: LocalRay, t: f32) -> f32 {
    return (t - l.s) / l.scale;
}

/// The hit at local parameter u with the local (not necessarily unit)
/// normal n, or `best` when u is not inside ray.t_min < t < best.t. A normal
/// that is zero or not finite falls back to -d.
fn placed_hit(ray: Ray, best: Hit, l: LocalRay, u: f32, n: vec3<f32>, center: vec3<f32>, rotation: mat3x3<f32>, kind: u32, index: u32, error_scale: f32) -> Hit {
    let t = l.s + l.scale * u;
    if !(t > ray.t_min && t < best.t) {
        return best;
    }
    let world_n = rotation * n;
    let len = length(world_n);
    var normal = -ray.dir;
    if len > 1e-30 && len < 1e30 {
        normal = world_n / len;
    }
    let p = center + l.scale * (rotation * (l.q + u * l.d));
    return surface_hit(t, p, normal, kind, index, error_scale);
}
