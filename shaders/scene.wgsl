// scene.wgsl: the scene as the GPU sees it.
//
// Every struct here has a twin in src/gpu/layout.rs (`#[repr(C)]`, bytemuck);
// a unit test checks that sizes and field offsets agree. Vectors are vec3 with
// a scalar packed into the fourth slot, so no field hides implicit padding.
//
// Positions (camera_from, camera_to, centres, points, lights, BVH boxes) are relative
// to a frame origin, the camera target, subtracted in f64 on the CPU before
// rounding (docs/implementation.md, "Camera-relative coordinates"): the
// numbers stay at the size of what the camera sees wherever that is.

/// Camera, render settings and counts: one uniform buffer, written on every change.
struct Globals {
    camera_from: vec3<f32>,  // camera `from`, relative to the frame origin (`from` is reserved)
    film_height: f32,        // h = 2 tan(fov / 2), the film height at unit distance
    camera_to: vec3<f32>,    // camera `to`, relative (0 until the viewer pans)
    aperture: f32,           // lens radius, 0 = pinhole
    u: vec3<f32>,            // the camera's basis, computed once in f64 on the CPU
    focus_distance: f32,
    v: vec3<f32>,
    target_distance: f32,    // |from - to|
    w: vec3<f32>,
    min_weight: f32,
    background: vec3<f32>,
    exposure: f32,
    ambient: vec3<f32>,
    max_depth: u32,
    resolution: vec2<u32>,   // image size in pixels
    sample_start: u32,       // index of the first sample this pass adds
    sample_count: u32,       // samples per pixel added by this pass
    light_count: u32,
    bvh_node_count: u32,     // 0: no bounded shapes (every kind but planes)
    output_size: vec2<u32>,  // size of the display target (may exceed `resolution`)
    view_range: vec2<f32>,   // a scalar view's colour bar: quantity at blue, at red (views.wgsl)
    _view_pad: vec2<u32>,
}

struct Material {
    color: vec3<f32>,
    diffuse: f32,
    checker_color: vec3<f32>,
    checker_size: f32,       // 0 = no checker
    checker_phase: vec3<f32>, // (frame origin / checker_size) mod 2, see albedo_at
    specular: f32,
    shininess: f32,
    mirror: f32,
    transparency: f32,
    ior: f32,
}

/// A node of the bounding volume hierarchy over the bounded shapes (every
/// kind but planes; built on the CPU, src/bvh.rs): an inner node (count = 0)
/// has its children at `first` and `first + 1`; a leaf holds `count` entries
/// of `bvh_shapes` from `first`. The box is rounded outwards, so it holds its shapes.
struct BvhNode {
    bounds_min: vec3<f32>,
    first: u32,
    bounds_max: vec3<f32>,
    count: u32,
}

/// An entry of `bvh_shapes`: the shape's KIND_* number in the bits from
/// KIND_SHIFT up, its index in that kind's array below.
const KIND_SHIFT: u32 = 24u;
const INDEX_MASK: u32 = 0xffffffu;

struct Light {
    position: vec3<f32>,
    _pad: u32,
    radiance: vec3<f32>,     // color * intensity
    _pad1: u32,
}

// The globals live in an `Rgba32Uint` data texture (binding 0, generated
// with its loader `load_globals`, src/gpu/shapes/glue.rs), read where used:
// `globals().max_depth` fetches the texel that holds it, at the index all
// lanes share, which costs little. Not a private copy made once per pixel:
// llvmpipe keeps a `var<private>` struct in memory, and its reads cost the
// mirror cube 27% of its instructions (docs/performance.md, "The globals
// read where used"). Not a uniform buffer: lavapipe compiles a new variant
// of a pipeline for every new set of uniform values its branches read, and
// keeps each one (2.7 MB a frame at 640 x 360) as long as the pipeline
// lives (docs/reliability.md, "Memory under live editing"). Not a storage
// buffer: llvmpipe reads one in a fragment shader one lane at a time, even
// at an index all lanes share, which made the camera ray alone cost as much
// as all the output passes (docs/performance.md, "What each change bought").
fn globals() -> Globals {
    return load_globals(0u);
}
// Bindings 1 to 5, generated (src/gpu/shapes/glue.rs): the arrays
// `materials`, `lights`, `bvh_nodes`, `bvh_shapes` and `shape_counts`
// (how many shapes of each kind, by KIND_* number), each an `Rgba32Uint`
// data texture, read as load_material(i), load_light(i), load_bvh_node(i),
// bvh_shape(i) and shape_count(kind): llvmpipe reads a storage buffer one
// lane at a time, a texture with one gather (docs/performance.md, "Where
// the time goes").
// Bindings 6 and up: one array per shape kind (`spheres`, `planes`, ...,
// read as load_sphere(i), ...), generated with the kinds' KIND_* numbers
// and HAS_* flags from the registry; their structs are in shaders/shapes/.

// What the scene uses, as pipeline-overridable constants (src/gpu/features.rs):
// the pipeline for a scene is compiled with false for what it does not use,
// and the compiler drops the code behind those flags. The defaults (all
// true) make the generic pipeline, which draws any scene.
override HAS_LIGHTS: bool = true;        // shading by lights, shadow rays
override HAS_MIRRORS: bool = true;       // materials with mirror > 0
override HAS_TRANSPARENCY: bool = true;  // materials with transparency > 0
override HAS_CHECKER: bool = true;
override HAS_LENS: bool = true;          // aperture > 0
override USE_BVH: bool = true;           // bounded shapes through the BVH
// The lecture switches of `[render]` (docs/rendering-model.md, "Lecture
// switches"), compiled in as the features are: off, the rays they trace
// cost nothing; flipped in the viewer, a new pipeline is built.
override SHADOWS: bool = true;           // shadow rays
override REFLECTION: bool = true;        // reflected rays
override REFRACTION: bool = true;        // refracted rays
