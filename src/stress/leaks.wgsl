// The watertightness count of `raysandbox stress` (src/stress/leaks.rs,
// docs/accuracy.md, "Triangle meshes: rays through shared edges and
// vertices"): for each ray, whether the shader's own `hit_triangle`
// (shaders/shapes/mesh.wgsl, the test chosen by the TRIANGLE_TEST constant)
// meets any triangle around the point the ray is aimed at: the triangles
// sharing vertex `a` or vertex `b` (an aimed vertex has b = a).

struct LeakRay {
    origin: vec3<f32>,
    a: u32,
    dir: vec3<f32>,
    b: u32,
}

@group(2) @binding(0) var<storage, read> leak_rays: array<LeakRay>;
@group(2) @binding(1) var<storage, read> leak_vertices: array<vec4<f32>>;
@group(2) @binding(2) var<storage, read> leak_triangles: array<vec4<u32>>;
// The triangles around vertex v: star[star_start[v] .. star_start[v + 1]].
@group(2) @binding(3) var<storage, read> star_start: array<u32>;
@group(2) @binding(4) var<storage, read> star: array<u32>;
@group(2) @binding(5) var<storage, read_write> leak_hit: array<u32>;

fn meets_star(ray: Ray, v: u32) -> bool {
    for (var k = star_start[v]; k < star_start[v + 1u]; k++) {
        let t = leak_triangles[star[k]];
        let p0 = leak_vertices[t.x].xyz;
        let p1 = leak_vertices[t.y].xyz;
        let p2 = leak_vertices[t.z].xyz;
        if hit_triangle(ray, p0, p1, p2, T_FAR).hit {
            return true;
        }
    }
    return false;
}

@compute @workgroup_size(64)
fn count_leaks(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&leak_rays) {
        return;
    }
    let r = leak_rays[i];
    let ray = Ray(r.origin, r.dir, 0.0);
    leak_hit[i] = select(0u, 1u, meets_star(ray, r.a) || meets_star(ray, r.b));
}
