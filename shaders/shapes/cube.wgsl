// shapes/cube.wgsl: the rotated box (docs/rendering-model.md, "Shapes").
//
// A shape kind's WGSL: its struct, twin of src/gpu/shapes/cube.rs (the layout
// test checks it), and `hit_cube(ray, shape, index, best) -> Hit`, the
// nearest hit with ray.t_min < t < best.t or `best`. The buffer, the
// KIND_CUBE number, the HAS_CUBES flag and the loops that call hit_cube are
// generated from the registry (src/gpu/shapes/glue.rs).

/// A box: world = center + rotation * local, local in [-half_size, half_size].
struct Cube {
    center: vec3<f32>,
    material: u32,
    rotation: mat3x3<f32>,   // Rz Ry Rx, columns are the box's local axes in the world
    half_size: vec3<f32>,
}

/// The slab test of hit_cube so far: the entry and exit parameters and
/// their axes; `missed` once the ray runs parallel to a slab outside it.
struct CubeSpan {
    t_near: f32,
    t_far: f32,
    near_axis: u32,
    far_axis: u32,
    missed: bool,
}

/// One axis of hit_cube's slab test. hit_cube calls it once per axis rather
/// than looping over the axes: lavapipe does not unroll shader loops, as
/// for hit_box's `slab` (docs/performance.md, "Work moved out of loops").
fn cube_slab(span: CubeSpan, o: f32, d: f32, h: f32, axis: u32) -> CubeSpan {
    var next = span;
    if abs(d) < 1e-20 {
        next.missed = next.missed || abs(o) > h;
        return next;
    }
    let inv = 1.0 / d;
    let ta = (-h - o) * inv;
    let tb = (h - o) * inv;
    let t0 = min(ta, tb);
    let t1 = max(ta, tb);
    let t1_wide = t1 + 2.0 * GAMMA3 * abs(t1);
    if t0 > next.t_near {
        next.t_near = t0;
        next.near_axis = axis;
    }
    if t1_wide < next.t_far {
        next.t_far = t1_wide;
        next.far_axis = axis;
    }
    return next;
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
    var span = CubeSpan(-T_FAR, T_FAR, 0u, 0u, false);
    span = cube_slab(span, o.x, d.x, h.x, 0u);
    span = cube_slab(span, o.y, d.y, h.y, 1u);
    span = cube_slab(span, o.z, d.z, h.z, 2u);
    if span.missed || span.t_near > span.t_far {
        return best;
    }
    let t_near = span.t_near;
    let t_far = span.t_far;
    // From the start of the test to the ray origin's parameter: t = s + t_local.
    var t_local = t_near;
    var axis = span.near_axis;
    var side = -1.0;           // the entry face faces against the ray
    if s + t_near <= ray.t_min {
        t_local = t_far;
        axis = span.far_axis;
        side = 1.0;            // the exit face faces along it
    }
    let t = s + t_local;
    if t <= ray.t_min || t >= best.t {
        return best;
    }
    let sign = side * select(-1.0, 1.0, d[axis] >= 0.0);
    var p_local = o + t_local * d;
    p_local[axis] = sign * h[axis];
    var n_local = vec3(0.0);
    n_local[axis] = sign;
    let p = cube.center + cube.rotation * p_local;
    let scale = max3(abs(cube.center)) + scaled_length(h);
    return surface_hit(t, p, cube.rotation * n_local, KIND_CUBE, index, scale);
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
    if t_near <= ray.t_min {
        t = t_far;
        axis = far_axis;
        side = 1.0;
    }
    if t <= ray.t_min || t >= best.t {
        return best;
    }
    var n_local = vec3(0.0);
    n_local[axis] = side * sign(d[axis]);
    let p = ray.origin + t * ray.dir;
    return surface_hit(t, p, cube.rotation * n_local, KIND_CUBE, index, 0.0);
}
