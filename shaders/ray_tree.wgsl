// ray_tree.wgsl: a pixel's ray tree (docs/ray-tree.md). The debug pass
// `fs_ray_tree` traces the ray through one pixel's centre and writes every
// ray of its Whitted tree into a small target that the CPU reads back
// (src/gpu/ray_tree.rs) and sets beside the f64 reference's tree.
//
// RAY_TREE is a pipeline constant: only the debug pass has it true. The
// trace loop of shade.wgsl calls the tree_* functions below at each ray,
// hit and shadow ray; in every other pipeline their bodies are `if false`
// and the driver's compiler removes them, as it does the views' counters.

override RAY_TREE: bool = false;

/// The rays kept: a larger tree is cut here (the counts say how many
/// rays there were). The pass traces the tree once per ray kept and row,
/// so this bounds its time too.
const TREE_MAX: u32 = 256u;

// The kinds of ray: `reference::RayKind` in this order.
const TREE_CAMERA: u32 = 0u;
const TREE_REFLECTED: u32 = 1u;
const TREE_REFRACTED: u32 = 2u;
const TREE_TOTAL_INTERNAL: u32 = 3u;
const TREE_SHADOW: u32 = 4u;
const TREE_NONE: u32 = 0xffffffffu;

/// One ray, as `reference::TreeRay` describes it (the CPU reads this
/// layout: src/gpu/ray_tree.rs, `GpuNode`).
struct TreeNode {
    kind: u32,
    depth: u32,
    parent: u32,         // TREE_NONE for the camera ray
    shape_kind: u32,     // KIND_NONE on a miss; a shadow ray: 1 if blocked
    origin: vec3<f32>,   // relative to the frame origin (scene.wgsl)
    shape_index: u32,    // a shadow ray: its light
    dir: vec3<f32>,
    t: f32,              // distance to the hit (-1 on a miss); a shadow ray: to its light
    normal: vec3<f32>,   // shading normal facing the ray
    fresnel: f32,
    throughput: vec3<f32>,
    wr: f32,
    contribution: vec3<f32>,
    wt: f32,
}

/// Where the camera ray goes through, in pixels (xy).
@group(2) @binding(0) var<uniform> tree_pixel: vec4<f32>;

// The pass draws a TREE_MAX x TREE_ROWS target: the invocation at (x, y)
// traces the whole tree, keeps ray number x (`tree_capture`) in
// `tree_node` and writes its row y. One kept ray, not an array of them:
// lavapipe had not compiled the pipeline that kept them all in a private
// array after ten minutes, while tracing the tree a few hundred times over
// costs microseconds. And the render target, not a storage buffer: on
// lavapipe (Mesa 22.3) the fragment shader's stores to one never arrived.
var<private> tree_capture: u32;
var<private> tree_node: TreeNode;
/// Rays begun so far (the next ray's number).
var<private> tree_count: u32;
/// The ray being shaded: its number, depth and throughput.
var<private> tree_current: u32 = TREE_NONE;
var<private> tree_current_depth: u32;
var<private> tree_current_throughput: vec3<f32>;
/// For each entry of trace()'s stack: the ray that pushed it, and its kind.
/// Entry TREE_HELD is the child that trace() holds outside the stack.
var<private> tree_slot_parent: array<u32, STACK_SIZE + 1>;
var<private> tree_slot_kind: array<u32, STACK_SIZE + 1>;
const TREE_HELD: u32 = STACK_SIZE;

/// A ray of `kind` was pushed into stack entry `slot` by the current ray.
fn tree_pending(slot: u32, kind: u32) {
    if RAY_TREE {
        tree_slot_parent[slot] = tree_current;
        tree_slot_kind[slot] = kind;
    }
}

/// The kind of a reflected ray: total internal reflection where glass
/// (`transparent`) is met from inside with F = 1.
fn tree_reflected_kind(fresnel: f32, inside: bool, transparent: bool) -> u32 {
    return select(TREE_REFLECTED, TREE_TOTAL_INTERNAL, transparent && inside && fresnel >= 1.0);
}

/// Numbers a new ray and keeps it if it is the one captured.
fn tree_add(kind: u32, depth: u32, parent: u32, ray: Ray, throughput: vec3<f32>) -> u32 {
    let i = tree_count;
    tree_count += 1u;
    if i == tree_capture {
        // The camera ray starts at t_min (camera.wgsl): back to the eye.
        let origin = ray.origin + ray.t_min * ray.dir;
        tree_node = TreeNode(kind, depth, parent, KIND_NONE, origin, 0u, ray.dir, 0.0,
            vec3(0.0), 0.0, throughput, 0.0, vec3(0.0), 0.0);
    }
    return i;
}

/// Whether the current ray is the one captured.
fn tree_at_current() -> bool {
    return RAY_TREE && tree_current == tree_capture;
}

/// The ray in stack entry `slot` is popped and traced.
fn tree_begin(slot: u32, ray: Ray, depth: u32, throughput: vec3<f32>) {
    if RAY_TREE {
        tree_current = tree_add(tree_slot_kind[slot], depth, tree_slot_parent[slot], ray, throughput);
        tree_current_depth = depth;
        tree_current_throughput = throughput;
    }
}

/// The current ray hit nothing; it adds `contribution` (the background).
fn tree_missed(contribution: vec3<f32>) {
    if tree_at_current() {
        tree_node.t = -1.0;
        tree_node.contribution = contribution;
    }
}

/// The current ray hit `hit`; `ns` is the shading normal facing it.
fn tree_hit(hit: Hit, ray: Ray, ns: vec3<f32>) {
    if tree_at_current() {
        tree_node.shape_kind = hit.kind;
        tree_node.shape_index = hit.index;
        tree_node.t = hit.t - ray.t_min;
        tree_node.normal = ns;
    }
}

/// A shadow ray of the current ray to light `light`, `dist` away.
fn tree_shadow(light: u32, origin: vec3<f32>, dir: vec3<f32>, dist: f32, blocked: bool) {
    if RAY_TREE {
        let throughput = tree_current_throughput;
        let i = tree_add(TREE_SHADOW, tree_current_depth, tree_current, Ray(origin, dir, 0.0), throughput);
        if i == tree_capture {
            tree_node.shape_kind = select(0u, 1u, blocked);
            tree_node.shape_index = light;
            tree_node.t = dist;
        }
    }
}

/// Light `light` adds `term` at the current ray's hit: the contribution of
/// its shadow ray, the last ray numbered, if that is the one captured.
fn tree_light(light: u32, term: vec3<f32>) {
    if RAY_TREE && tree_count == tree_capture + 1u && tree_node.kind == TREE_SHADOW
        && tree_node.parent == tree_current && tree_node.shape_index == light {
        tree_node.contribution = tree_current_throughput * term;
    }
}

/// The current ray's local light and how the rest divides.
fn tree_split(local: vec3<f32>, fresnel: f32, wr: f32, wt: f32) {
    if tree_at_current() {
        tree_node.contribution = tree_current_throughput * local;
        tree_node.fresnel = fresnel;
        tree_node.wr = wr;
        tree_node.wt = wt;
    }
}

/// Rows of the debug pass's target: the six of a `TreeNode`, then the
/// counts.
const TREE_ROWS: u32 = 7u;

/// The debug pass into an Rgba32Uint target TREE_MAX x TREE_ROWS: at
/// (x, y < 6), row y of ray number x of the tree of the ray through
/// `tree_pixel` and the lens centre, as the bits of `TreeNode`; at (0, 6)
/// the rays kept and the rays traced.
@fragment
fn fs_ray_tree(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<u32> {
    tree_capture = u32(frag.x);
    _ = trace(camera_ray(tree_pixel.xy, vec2(0.0)));
    let n = tree_node;
    switch u32(frag.y) {
        case 0u: { return vec4(n.kind, n.depth, n.parent, n.shape_kind); }
        case 1u: { return vec4(bitcast<vec3<u32>>(n.origin), n.shape_index); }
        case 2u: { return vec4(bitcast<vec3<u32>>(n.dir), bitcast<u32>(n.t)); }
        case 3u: { return vec4(bitcast<vec3<u32>>(n.normal), bitcast<u32>(n.fresnel)); }
        case 4u: { return vec4(bitcast<vec3<u32>>(n.throughput), bitcast<u32>(n.wr)); }
        case 5u: { return vec4(bitcast<vec3<u32>>(n.contribution), bitcast<u32>(n.wt)); }
        default: { return vec4(min(tree_count, TREE_MAX), tree_count, 0u, 0u); }
    }
}
