// shapes/mesh.wgsl: the triangle mesh (docs/rendering-model.md, "Triangle meshes").
//
// A shape kind's WGSL: its struct, twin of src/gpu/shapes/mesh.rs (the layout
// test checks it), and `hit_mesh(ray, shape, index, best) -> Hit`. The
// buffers `meshes` and `mesh_data`, KIND_MESH, HAS_MESHES and the loops that
// call hit_mesh are generated from the registry (src/gpu/shapes/glue.rs).
//
// A mesh's triangles live in its own coordinates, in a BVH of their own
// (src/bvh.rs, built once per loaded file): the ray is taken into those
// coordinates (t does not change, the direction is not unit length there),
// so moving a mesh only changes this struct.

/// A placed mesh. `mesh_data` (a texture, read by `mesh_data_at`, see
/// src/gpu/shapes/glue.rs) holds, from `node_start`, its BVH nodes (two
/// vec4 each: min.xyz and `first`, max.xyz and `count`, floats as bits);
/// from `tri_start`, its triangles in leaf order (three vec4: p0, p1, p2);
/// from `normal_start` (smooth meshes only), their vertex normals (three
/// vec4 each, in the same order).
///
/// What the walk reads comes first, in four texels: a texel fetch is the
/// walk's price on lavapipe (docs/performance.md, "Fewer fetches per
/// mesh"), so `to_local` is stored by columns, a start offset beside each.
struct Mesh {
    to_local_x: vec3<f32>,        // to_local = inverse of R diag(scale), by columns
    node_start: u32,
    to_local_y: vec3<f32>,
    tri_start: u32,
    to_local_z: vec3<f32>,
    normal_start: u32,
    origin: vec3<f32>,            // `translate`, relative to the frame origin
    error_scale: f32,
    to_world: mat3x3<f32>,        // R diag(scale)
    material: u32,
}

/// Mesh coordinates from world ones (relative to the mesh's origin).
fn mesh_to_local(m: Mesh) -> mat3x3<f32> {
    return mat3x3(m.to_local_x, m.to_local_y, m.to_local_z);
}

/// Which ray-triangle test (src/scene/shapes/mesh.rs, `TriangleTest`):
/// 0 Cramer's rule, 1 Moeller-Trumbore, 2 watertight.
override TRIANGLE_TEST: u32 = 2u;

/// A ray-triangle hit: `t` and the weights of the three vertices.
struct TriangleHit {
    hit: bool,
    t: f32,
    b: vec3<f32>,
}

fn data_vec3(i: u32) -> vec3<f32> {
    return bitcast<vec3<f32>>(mesh_data_at(i).xyz);
}

/// A hit if every weight is >= 0 and t_min < t < t_max.
fn triangle_hit(t: f32, b: vec3<f32>, ray: Ray, t_max: f32) -> TriangleHit {
    let ok = all(b >= vec3(0.0)) && t > ray.t_min && t < t_max;
    return TriangleHit(ok, t, b);
}

/// Cramer's rule with signed volumes: the system
/// [-d e1 e2] (t, b1, b2) = s, s = o - p0, each unknown the ratio of two
/// determinants a.(b x c) (Shirley and Marschner, "Fundamentals of Computer
/// Graphics", 4.4.2). D = 0: the ray is parallel to the plane.
fn hit_cramer(ray: Ray, p0: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>, t_max: f32) -> TriangleHit {
    let e1 = p1 - p0;
    let e2 = p2 - p0;
    let s = ray.origin - p0;
    let d = -ray.dir;
    let volume = dot(d, cross(e1, e2));
    if volume == 0.0 {
        return TriangleHit(false, 0.0, vec3(0.0));
    }
    let t = dot(s, cross(e1, e2)) / volume;
    let b1 = dot(d, cross(s, e2)) / volume;
    let b2 = dot(d, cross(e1, s)) / volume;
    return triangle_hit(t, vec3(1.0 - b1 - b2, b1, b2), ray, t_max);
}

/// Moeller and Trumbore, "Fast, Minimum Storage Ray/Triangle Intersection"
/// (JGT 1997): the same determinants as scalar triple products sharing
/// p = d x e2 and q = s x e1, with early exits.
fn hit_moller_trumbore(ray: Ray, p0: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>, t_max: f32) -> TriangleHit {
    let miss = TriangleHit(false, 0.0, vec3(0.0));
    let e1 = p1 - p0;
    let e2 = p2 - p0;
    let p = cross(ray.dir, e2);
    let det = dot(e1, p);
    if det == 0.0 {
        return miss;
    }
    let inv = 1.0 / det;
    let s = ray.origin - p0;
    let b1 = dot(s, p) * inv;
    if b1 < 0.0 || b1 > 1.0 {
        return miss;
    }
    let q = cross(s, e1);
    let b2 = dot(ray.dir, q) * inv;
    if b2 < 0.0 || b1 + b2 > 1.0 {
        return miss;
    }
    return triangle_hit(dot(e2, q) * inv, vec3(1.0 - b1 - b2, b1, b2), ray, t_max);
}

/// Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection" (JCGT
/// 2013), as in pbrt-v4: translate the vertices to the ray origin, permute
/// the axes so that z is the direction's largest component, shear so the
/// ray runs along +z; the hit is then decided by the signs of three 2D edge
/// functions, which two triangles sharing an edge compute from the same
/// numbers: a ray through the edge is inside at least one of them.
fn hit_watertight(ray: Ray, q0: vec3<f32>, q1: vec3<f32>, q2: vec3<f32>, t_max: f32) -> TriangleHit {
    let miss = TriangleHit(false, 0.0, vec3(0.0));
    let ad = abs(ray.dir);
    var kz = 2u;
    if ad.x > ad.y && ad.x > ad.z {
        kz = 0u;
    } else if ad.y > ad.z {
        kz = 1u;
    }
    let kx = (kz + 1u) % 3u;
    let ky = (kx + 1u) % 3u;
    let d = vec3(ray.dir[kx], ray.dir[ky], ray.dir[kz]);
    let r0 = q0 - ray.origin;
    let r1 = q1 - ray.origin;
    let r2 = q2 - ray.origin;
    var a = vec3(r0[kx], r0[ky], r0[kz]);
    var b = vec3(r1[kx], r1[ky], r1[kz]);
    var c = vec3(r2[kx], r2[ky], r2[kz]);
    let sx = -d.x / d.z;
    let sy = -d.y / d.z;
    let sz = 1.0 / d.z;
    a = vec3(a.x + sx * a.z, a.y + sy * a.z, a.z);
    b = vec3(b.x + sx * b.z, b.y + sy * b.z, b.z);
    c = vec3(c.x + sx * c.z, c.y + sy * c.z, c.z);
    let e0 = b.x * c.y - b.y * c.x;
    let e1 = c.x * a.y - c.y * a.x;
    let e2 = a.x * b.y - a.y * b.x;
    if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
        return miss;
    }
    let det = e0 + e1 + e2;
    if det == 0.0 {
        return miss;
    }
    let t_scaled = e0 * a.z * sz + e1 * b.z * sz + e2 * c.z * sz;
    return triangle_hit(t_scaled / det, vec3(e0, e1, e2) / det, ray, t_max);
}

fn hit_triangle(ray: Ray, p0: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>, t_max: f32) -> TriangleHit {
    if TRIANGLE_TEST == 0u {
        return hit_cramer(ray, p0, p1, p2, t_max);
    }
    if TRIANGLE_TEST == 1u {
        return hit_moller_trumbore(ray, p0, p1, p2, t_max);
    }
    return hit_watertight(ray, p0, p1, p2, t_max);
}

/// The nearest triangle of the mesh through its BVH, nearer than best.t.
fn hit_mesh(ray: Ray, m: Mesh, index: u32, best: Hit) -> Hit {
    let to_local = mesh_to_local(m);
    let local = Ray(to_local * (ray.origin - m.origin), to_local * ray.dir, ray.t_min);
    let inv_d = select(1.0 / local.dir, vec3(0.0), abs(local.dir) < vec3(1e-20));
    var t_best = best.t;
    var found = false;
    var tri = 0u;
    var weights = vec3(0.0);
    var vertices = array<vec3<f32>, 3>();
    var stack: array<u32, BVH_STACK>;
    stack[0] = 0u;
    var top = 1u;
    // Aila and Laine's "while-while" traversal (docs/performance.md, "What
    // each change bought"): the inner loop only descends, until this ray
    // holds a leaf its box test keeps (or has nothing left); the leaf's
    // triangles are tested after it. Rays run side by side in SIMD lanes
    // wait in the inner loop until every one holds a leaf, and then test
    // their leaves together, instead of paying for both branches in every
    // step. Every loop tests its end last: lavapipe leaves a loop only
    // when no lane is left in it, and these loops written to test first
    // cost 6% more instructions per pixel (docs/performance.md, "The fixed
    // price per pixel"). The stack is never empty where a loop starts.
    loop {
        var first = 0u;
        var count = 0u;
        loop {
            top -= 1u;
            let at = m.node_start + 2u * stack[top];
            let lo = mesh_data_at(at);
            let hi = mesh_data_at(at + 1u);
            count_node();
            if hit_box(bitcast<vec3<f32>>(lo.xyz), bitcast<vec3<f32>>(hi.xyz), local, inv_d, t_best) {
                if hi.w == 0u {
                    let e = bitcast<vec3<f32>>(hi.xyz) - bitcast<vec3<f32>>(lo.xyz);
                    top = push_children(&stack, top, lo.w, e, local.dir);
                } else {
                    first = lo.w;
                    count = hi.w;
                }
            }
            if top == 0u || count != 0u {
                break;
            }
        }
        if count > 0u {
            var k = first;
            loop {
                let v = m.tri_start + 3u * k;
                let p = array(data_vec3(v), data_vec3(v + 1u), data_vec3(v + 2u));
                count_test();
                let h = hit_triangle(local, p[0], p[1], p[2], t_best);
                if h.hit {
                    t_best = h.t;
                    found = true;
                    tri = k;
                    weights = h.b;
                    vertices = p;
                }
                k++;
                if k >= first + count {
                    break;
                }
            }
        }
        if top == 0u {
            break;
        }
    }
    if !found {
        return best;
    }
    note_barycentric(weights);
    // The nearest triangle's vertices were kept from the walk, and normals
    // go to world coordinates by the transpose of to_local: three texel
    // fetches fewer each (docs/performance.md, "Fewer fetches per mesh").
    let normal_to_world = transpose(to_local);
    let p0 = vertices[0];
    let n = normalize(normal_to_world * cross(vertices[1] - p0, vertices[2] - p0));
    var shading = n;
    if m.normal_start != 0u {
        let w = m.normal_start + 3u * tri;
        let local_n = weights.x * data_vec3(w) + weights.y * data_vec3(w + 1u) + weights.z * data_vec3(w + 2u);
        let s = normal_to_world * local_n;
        if dot(s, s) > 0.0 {
            shading = normalize(s);
        }
    }
    // The point from the weights, as the reference computes it: on the
    // triangle up to the rounding of the vertices, whatever t's error.
    let local_p = weights.x * p0 + weights.y * vertices[1] + weights.z * vertices[2];
    let p = m.origin + m.to_world * local_p;
    return Hit(t_best, p, n, KIND_MESH, index, m.error_scale, shading);
}

/// The barycentric view on a mesh (docs/views.md): the weights of the
/// nearest triangle, which hit_mesh noted.
fn view_coordinates_mesh(hit: Hit) -> vec3<f32> {
    return view_barycentric;
}
