// main.wgsl: the two full-screen passes.
//
// 1. `fs_trace` traces `sample_count` samples per pixel and adds their linear
//    radiance to the running sum of earlier passes (progressive refinement).
// 2. `fs_display` turns the sum into the output colour (docs/rendering-model.md, "Output").

/// One triangle that covers the whole viewport; no vertex buffer needed.
@vertex
fn vs_fullscreen(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4(uv * 2.0 - 1.0, 0.0, 1.0);
}

/// The radiance sum of the earlier passes (ignored when sample_start = 0).
@group(1) @binding(0) var accumulated: texture_2d<f32>;

@fragment
fn fs_trace(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    if VIEW != VIEW_SHADED {
        return view_trace(frag.xy);
    }
    let pixel = vec2<f32>(floor(frag.xy));
    var sum = vec3(0.0);
    // The end is tested after each sample, not before: on llvmpipe the
    // loop that tests first made every frame measured slower
    // (docs/performance.md, "The torus against its sphere").
    var k = 0u;
    if globals().sample_count > 0u {
        loop {
            let s = sample_r4(globals().sample_start + k);
            sum += trace(camera_ray(pixel + s.xy, concentric_disk(s.zw)));
            continuing {
                k++;
                break if k >= globals().sample_count;
            }
        }
    }
    if COUNT_RAYS {
        // The counting variant sums its counts over the passes, as the
        // others sum radiance.
        var counts = ray_counts;
        if globals().sample_start > 0u {
            counts += textureLoad(accumulated, vec2<i32>(frag.xy), 0);
        }
        return counts;
    }
    if globals().sample_start > 0u {
        sum += textureLoad(accumulated, vec2<i32>(frag.xy), 0).rgb;
    }
    return vec4(sum, 1.0);
}

/// Set to false when the render target is an *Srgb format that encodes by
/// itself (the viewer's window surface).
override ENCODE_SRGB: bool = true;

/// True where x is neither inf nor NaN (all exponent bits set), read from the
/// bits because float comparisons with NaN may be optimised away.
fn is_finite(x: vec3<f32>) -> vec3<bool> {
    return (bitcast<vec3<u32>>(x) & vec3(0x7f800000u)) != vec3(0x7f800000u);
}

/// The sRGB transfer function of docs/rendering-model.md, "Output", for c in [0, 1].
fn srgb_encode(c: vec3<f32>) -> vec3<f32> {
    let low = 12.92 * c;
    let high = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
    return select(high, low, c < vec3(0.0031308));
}

@fragment
fn fs_display(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    // The image may be traced at a lower resolution than it is shown
    // (resolution scale): each output pixel shows the traced pixel under it.
    let scale = vec2<f32>(globals().resolution) / vec2<f32>(globals().output_size);
    let texel = min(vec2<u32>(frag.xy * scale), globals().resolution - 1u);
    if VIEW != VIEW_SHADED {
        // A view's colours are display values: the sRGB target's own
        // encoding is undone in advance.
        let c = view_colour(textureLoad(accumulated, texel, 0));
        return vec4(select(srgb_decode(c), c, ENCODE_SRGB), 1.0);
    }
    let total = f32(max(globals().sample_start + globals().sample_count, 1u));
    let radiance = textureLoad(accumulated, texel, 0).rgb / total;
    // WGSL gives no guarantee for inf and NaN (clamp may pass them through),
    // so a non-finite sum is caught from its bits and shown as magenta: a
    // numerical failure must be visible, never a quiet black pixel.
    if any(!is_finite(radiance)) {
        return vec4(1.0, 0.0, 1.0, 1.0);
    }
    let c = clamp(globals().exposure * radiance, vec3(0.0), vec3(1.0));
    if !ENCODE_SRGB {
        return vec4(c, 1.0);
    }
    // Round to the nearest 8-bit level here, so the unorm conversion of the
    // target is exact whatever rounding the hardware uses.
    return vec4(round(srgb_encode(c) * 255.0) / 255.0, 1.0);
}

/// The id/depth pass (accuracy measurements, `raysandbox stress`): for the
/// ray through the pixel centre and the lens centre, what it hits first:
/// (kind, index, bits of t, 1), kind = KIND_NONE where it hits nothing; t is
/// counted from the eye (the camera ray's own t starts at t_min there).
/// Rendered into an Rgba32Uint target; the reference computes the same with
/// `reference::pick`, and the two are compared pixel by pixel.
@fragment
fn fs_id(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<u32> {
    let pixel = vec2<f32>(floor(frag.xy)) + vec2(0.5);
    let ray = camera_ray(pixel, vec2(0.0));
    let hit = hit_scene(ray, T_FAR);
    return vec4(hit.kind, hit.index, bitcast<u32>(hit.t - ray.t_min), 1u);
}
