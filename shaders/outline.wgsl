// outline.wgsl: the viewer's outline around the selected shape
// (docs/implementation.md, "Selection outline").
//
// The id pass (`fs_id` in main.wgsl) writes, per traced pixel, which shape
// its primary ray hits first. `fs_outline` draws over the displayed image:
// a pixel outside the selected shape's silhouette within `radius` output
// pixels of it takes the outline colour, the ring just past that band is
// black; every other pixel is left as it is (discarded). Whatever shape kind is selected, the test is the same: its
// (kind, index) in the id image.

/// Which shape is outlined, and how. Mirrored by `gpu::outline::Selection`.
struct Selection {
    kind: u32,               // KIND_* of the selected shape; KIND_NONE = nothing
    index: u32,              // its index in that kind's array
    radius: u32,             // outline width in output pixels
    _pad: u32,
    color: vec4<f32>,        // sRGB-encoded, as stored in an 8-bit unorm target
}

// Group 1 as the tracer's, but past its binding 0 (`accumulated`), so that
// both live in one module.
@group(1) @binding(1) var first_hits: texture_2d<u32>;
@group(1) @binding(2) var<uniform> selection: Selection;

/// Whether the traced pixel under output pixel `p` shows the selected shape.
/// The id image may be smaller than the output (resolution scale), as the
/// accumulated image of `fs_display` is.
fn shows_selected(p: vec2<i32>) -> bool {
    let size = vec2<i32>(textureDimensions(first_hits));
    let scale = vec2<f32>(size) / vec2<f32>(globals().output_size);
    let texel = clamp(vec2<i32>(vec2<f32>(p) * scale), vec2(0), size - 1);
    let id = textureLoad(first_hits, texel, 0);
    return id.x == selection.kind && id.y == selection.index;
}

@fragment
fn fs_outline(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(floor(frag.xy));
    if selection.kind == KIND_NONE || shows_selected(p) {
        discard;
    }
    // The squared distance to the nearest pixel of the silhouette, looked
    // for one pixel past the band: that last ring is drawn dark, so the
    // band stands out on light and dark surroundings alike.
    let r = i32(selection.radius);
    let reach = (r + 1) * (r + 1);
    var nearest = reach + 1;
    for (var dy = -r - 1; dy <= r + 1; dy++) {
        for (var dx = -r - 1; dx <= r + 1; dx++) {
            let d = dx * dx + dy * dy;
            if d < nearest && shows_selected(p + vec2(dx, dy)) {
                nearest = d;
            }
        }
    }
    if nearest > reach {
        discard;
    }
    let color = select(vec4(0.0, 0.0, 0.0, 1.0), selection.color, nearest <= r * r);
    if ENCODE_SRGB {
        return color;
    }
    // An *Srgb target encodes by itself: hand it the linear colour.
    return vec4(srgb_decode(color.rgb), color.a);
}

/// The inverse of `srgb_encode` (docs/rendering-model.md, "Output").
fn srgb_decode(c: vec3<f32>) -> vec3<f32> {
    let low = c / 12.92;
    let high = pow((c + 0.055) / 1.055, vec3(2.4));
    return select(high, low, c <= vec3(0.04045));
}
