// lines.wgsl: the line overlay over the picture (src/gpu/lines.rs): the
// rays of a pixel's tree (docs/ray-tree.md). The CPU projects every point
// with the scene's camera in f64 and sends clip coordinates; this only
// passes them on, and the hardware clips what lies behind the eye.

struct LineVertex {
    @builtin(position) clip: vec4<f32>,
    @location(0) colour: vec4<f32>,
}

@vertex
fn vs_line(@location(0) clip: vec4<f32>, @location(1) colour: vec4<f32>) -> LineVertex {
    return LineVertex(clip, colour);
}

@fragment
fn fs_line(v: LineVertex) -> @location(0) vec4<f32> {
    return v.colour;
}
