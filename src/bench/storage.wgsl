// The storage comparison of `raysandbox bench --meshes` (src/bench/storage.rs,
// docs/performance.md, "Storage"): each ray is tested against a block of
// triangles with the shader's own `hit_triangle` (shaders/shapes/mesh.wgsl),
// the triangles read either as the renderer stores them (three vertices per
// triangle, in BVH leaf order) or through an index triple into a shared
// vertex array. The result is the nearest hit: t's bits and the triangle.

struct StorageRay {
    origin: vec3<f32>,
    first: u32,
    dir: vec3<f32>,
    count: u32,
}

/// false: `leaf_triangles`, three vec4 per triangle; true: `tri_indices`
/// into `shared_vertices`. A pipeline constant, so each pipeline keeps
/// only its own reads.
override INDEXED: bool = false;

@group(2) @binding(0) var<storage, read> storage_rays: array<StorageRay>;
@group(2) @binding(1) var<storage, read> leaf_triangles: array<vec4<f32>>;
@group(2) @binding(2) var<storage, read> tri_indices: array<vec4<u32>>;
@group(2) @binding(3) var<storage, read> shared_vertices: array<vec4<f32>>;
@group(2) @binding(4) var<storage, read_write> storage_hits: array<vec2<u32>>;

@compute @workgroup_size(64)
fn nearest_in_block(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&storage_rays) {
        return;
    }
    let r = storage_rays[i];
    let ray = Ray(r.origin, r.dir, 0.0);
    var t_best = T_FAR;
    var nearest = 0xffffffffu;
    for (var k = r.first; k < r.first + r.count; k++) {
        var p0: vec3<f32>;
        var p1: vec3<f32>;
        var p2: vec3<f32>;
        if INDEXED {
            let v = tri_indices[k];
            p0 = shared_vertices[v.x].xyz;
            p1 = shared_vertices[v.y].xyz;
            p2 = shared_vertices[v.z].xyz;
        } else {
            p0 = leaf_triangles[3u * k].xyz;
            p1 = leaf_triangles[3u * k + 1u].xyz;
            p2 = leaf_triangles[3u * k + 2u].xyz;
        }
        let h = hit_triangle(ray, p0, p1, p2, t_best);
        if h.hit {
            t_best = h.t;
            nearest = k;
        }
    }
    storage_hits[i] = vec2(bitcast<u32>(t_best), nearest);
}
