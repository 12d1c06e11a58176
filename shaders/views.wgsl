// views.wgsl: ways of looking inside the tracer (docs/views.md): normals,
// depth, object id, barycentrics, cost, steps, bounces and the error against
// the f64 reference, in place of the shaded picture.
//
// VIEW is a pipeline constant (src/gpu/view.rs, `View::number`): 0 is the
// shaded picture, and every counter below is then dead code that the
// driver's compiler removes, as COUNT_RAYS is for the ray counts.
//
// fs_trace writes the view's raw quantity into the accumulation texture
// (`view_quantity`, only for the first sample: a view looks at the ray
// through the pixel centre, so later samples keep it); fs_display maps it
// to a colour (`view_colour`). The CPU reads the raw quantities back for
// the colour bar's range and for the tests against the f64 reference.

override VIEW: u32 = 0u;

const VIEW_SHADED: u32 = 0u;
const VIEW_NORMALS: u32 = 1u;        // shading normal
const VIEW_GEOMETRIC: u32 = 2u;      // geometric normal
const VIEW_DEPTH: u32 = 3u;          // t of the first hit, from the eye
const VIEW_ID: u32 = 4u;             // kind and index of the shape hit
const VIEW_BARYCENTRIC: u32 = 5u;    // triangle weights; a sphere's u, v
const VIEW_NODES: u32 = 6u;          // BVH nodes visited, camera ray
const VIEW_TESTS: u32 = 7u;          // shape and triangle tests, camera ray
const VIEW_NODES_ALL: u32 = 8u;      // BVH nodes visited, all rays of the pixel
const VIEW_TESTS_ALL: u32 = 9u;      // tests, all rays of the pixel
const VIEW_STEPS: u32 = 10u;         // sphere-tracing and root-finding steps, all rays
const VIEW_BOUNCES: u32 = 11u;       // deepest level of the ray tree
const VIEW_SHADOW_RAYS: u32 = 12u;   // shadow rays cast
const VIEW_ERROR: u32 = 13u;         // radiance, then its error against the reference

/// In the error view, `w` of a pixel whose error is not known yet: its
/// quantity is the GPU's radiance, which the CPU compares with the f64
/// reference and replaces with the error (w = 1) as the reference comes in.
const ERROR_PENDING: f32 = 2.0;

/// The counters of the cost, steps and bounces views: BVH nodes visited,
/// shape and triangle tests, steps, deepest ray-tree level.
var<private> view_counts: vec4<f32>;

/// Whether the view counts BVH work (node visits and tests).
fn view_counts_cost() -> bool {
    return VIEW >= VIEW_NODES && VIEW <= VIEW_TESTS_ALL;
}

/// One BVH node's box tested (the scene's BVH or a mesh's).
fn count_node() {
    if view_counts_cost() {
        view_counts.x += 1.0;
    }
}

/// One shape or triangle tested against a ray.
fn count_test() {
    if view_counts_cost() {
        view_counts.y += 1.0;
    }
}

/// One step of sphere tracing, marching or root finding.
fn count_step() {
    if VIEW == VIEW_STEPS {
        view_counts.z += 1.0;
    }
}

/// A ray of the tree at `depth` (0: the camera ray) was traced.
fn count_depth(depth: u32) {
    if VIEW == VIEW_BOUNCES {
        view_counts.w = max(view_counts.w, f32(depth));
    }
}

/// A shadow ray was cast.
fn count_shadow_ray() {
    if VIEW == VIEW_SHADOW_RAYS {
        view_counts.y += 1.0;
    }
}

/// Coordinates a kind's hit noted for the barycentric view (a mesh's
/// triangle weights, which only its hit knows): later shapes replace a hit
/// only when strictly nearer, so when the final hit is of that kind these
/// are its own. `view_coordinates` (generated, src/gpu/shapes/glue.rs)
/// asks the kind hit.
var<private> view_barycentric: vec3<f32>;

fn note_barycentric(b: vec3<f32>) {
    if VIEW == VIEW_BARYCENTRIC {
        view_barycentric = b;
    }
}

/// The view's raw quantity for the ray through the pixel centre: w = 1
/// where it means something (a hit; always for counters), 0 elsewhere.
/// The CPU twin is `reference::views`.
fn view_quantity(pixel: vec2<f32>) -> vec4<f32> {
    let ray = camera_ray(pixel + vec2(0.5), vec2(0.0));
    if VIEW == VIEW_ERROR {
        return vec4(trace(ray), ERROR_PENDING);
    }
    if VIEW >= VIEW_NODES_ALL {
        // Counters over the whole ray tree of the pixel.
        _ = trace(ray);
        switch VIEW {
            case VIEW_NODES_ALL: { return vec4(view_counts.x, 0.0, 0.0, 1.0); }
            case VIEW_TESTS_ALL: { return vec4(view_counts.y, 0.0, 0.0, 1.0); }
            case VIEW_STEPS: { return vec4(view_counts.z, 0.0, 0.0, 1.0); }
            case VIEW_BOUNCES: { return vec4(view_counts.w, 0.0, 0.0, 1.0); }
            default: { return vec4(view_counts.y, 0.0, 0.0, 1.0); }
        }
    }
    let hit = hit_scene(ray, T_FAR);
    if VIEW == VIEW_NODES {
        return vec4(view_counts.x, 0.0, 0.0, 1.0);
    }
    if VIEW == VIEW_TESTS {
        return vec4(view_counts.y, 0.0, 0.0, 1.0);
    }
    if hit.kind == KIND_NONE {
        return vec4(0.0);
    }
    switch VIEW {
        case VIEW_NORMALS: { return vec4(hit.shading, 1.0); }
        case VIEW_GEOMETRIC: { return vec4(hit.normal, 1.0); }
        case VIEW_DEPTH: { return vec4(hit.t - ray.t_min, 0.0, 0.0, 1.0); }
        case VIEW_ID: { return vec4(f32(hit.kind), f32(hit.index), 0.0, 1.0); }
        default: { return vec4(view_coordinates(hit), 1.0); }
    }
}


/// What fs_trace writes in a view: the quantity for the first sample, the
/// texture's own value after (the pixel centre's ray does not change).
fn view_trace(frag: vec2<f32>) -> vec4<f32> {
    if globals().sample_start > 0u {
        return textureLoad(accumulated, vec2<i32>(frag), 0);
    }
    return view_quantity(floor(frag));
}

/// A scalar view's heat map: blue (the low end of the range) through cyan,
/// green and yellow to red (the high end).
fn heat(x: f32) -> vec3<f32> {
    let s = clamp(x, 0.0, 1.0) * 4.0;
    let r = clamp(s - 2.0, 0.0, 1.0);
    let g = clamp(s, 0.0, 1.0) - clamp(s - 3.0, 0.0, 1.0);
    let b = 1.0 - clamp(s - 1.0, 0.0, 1.0);
    return vec3(r, g, b);
}

/// A stable false colour for a shape: a hash of its kind and index.
fn id_colour(kind: u32, index: u32) -> vec3<f32> {
    var h = (kind * 0x9e3779b9u) ^ ((index + 1u) * 0x85ebca6bu);
    h ^= h >> 15u;
    h *= 0x2c1b3c6du;
    h ^= h >> 12u;
    let c = vec3<f32>(vec3(h & 0xffu, (h >> 8u) & 0xffu, (h >> 16u) & 0xffu)) / 255.0;
    return 0.25 + 0.75 * c;
}

/// The colour (display-encoded, as shown) of a view's quantity `q`;
/// background pixels (q.w = 0) are dark grey.
fn view_colour(q: vec4<f32>) -> vec3<f32> {
    if q.w == 0.0 {
        return vec3(0.1);
    }
    if VIEW == VIEW_ERROR && q.w == ERROR_PENDING {
        // The GPU's picture, dimmed, until the reference reaches the pixel.
        return 0.35 * srgb_encode(clamp(globals().exposure * q.xyz, vec3(0.0), vec3(1.0)));
    }
    switch VIEW {
        case VIEW_NORMALS, VIEW_GEOMETRIC: { return clamp(0.5 * q.xyz + 0.5, vec3(0.0), vec3(1.0)); }
        case VIEW_ID: { return id_colour(u32(q.x), u32(q.y)); }
        case VIEW_BARYCENTRIC: { return clamp(q.xyz, vec3(0.0), vec3(1.0)); }
        default: {
            let lo = globals().view_range.x;
            let span = globals().view_range.y - lo;
            return heat(select(0.0, (q.x - lo) / span, span > 0.0));
        }
    }
}
