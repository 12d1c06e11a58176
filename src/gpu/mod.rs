//! The GPU side: device, shader source, buffer packing, the tracer's passes
//! and offscreen rendering with readback. Knows scenes, not windows or UI.

mod buffer;
pub mod compute;
mod context;
mod features;
pub mod fullscreen;
mod id_pass;
pub mod interaction;
mod jobs;
pub mod layout;
mod limits;
mod lines;
mod offscreen;
mod outline;
mod ray_tree;
pub mod shaders;
pub mod shapes;
mod texture;
mod timer;
#[cfg(test)]
mod toy_kind;
mod tracer;
mod view;
mod viewport;

pub use context::{Gpu, GpuError, GpuWaitError, SizeError, TIMER_FEATURES, WAIT_LIMIT};
pub use features::{Features, Rays, ShaderOptions};
pub use id_pass::{FirstHit, IdRenderer};
pub use interaction::{DEFAULT_FRAME_BUDGET_MS, MIN_SCALE};
pub use jobs::{JOB_BUDGET, JobsSince, MeasuredJob, SampleTally};
pub use limits::{BufferLimitError, check_buffers};
pub use lines::{LineOverlay, Segment, project};
pub use offscreen::{
    OffscreenRenderer, RenderError, TexelRead, read_texels, read_texture, render_image,
};
pub use outline::OUTLINE_COLOR;
pub use ray_tree::{GpuRayTree, RayTreeRenderer, TREE_MAX};
pub use shaders::{ShaderError, ShaderSource};
pub use shapes::glue::{DataAccess, data_texture_count};
pub use texture::{OwnedTexture, readback_target, render_target};
pub use timer::{GpuTimer, Timing};
pub use tracer::{
    Accumulator, DEFAULT_MAX_SAMPLES, DEFAULT_MIN_WEIGHT, DEFAULT_RENDER_SAMPLES, FrameTarget,
    PipelineError, Pipelines, SceneBuffers, encode_frame,
};
pub use view::{ColourBar, View, colour_bar};
pub use viewport::{EXPORT_FORMAT, FrameStatus, JobWaker, Refine, Viewport};
