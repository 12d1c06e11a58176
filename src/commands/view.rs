//! `raysandbox view`: the interactive viewer, the default without a
//! command.

use std::path::PathBuf;

use super::Failure;
use crate::app::{ViewerError, ViewerOptions};
use crate::cli::parse_size;
use crate::gpu::View;
use crate::scene::NamedOption;

#[derive(clap::Args, Default)]
pub struct Args {
    /// The scene file (TOML); without it, the built-in Whitted scene.
    scene: Option<PathBuf>,
    /// The WGSL folder to use and watch (default: ./shaders if it exists,
    /// else the shaders built into the binary).
    #[arg(long)]
    shaders: Option<PathBuf>,
    /// Initial window size in pixels, e.g. 1280x720.
    #[arg(long, value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Progressive refinement limit in samples per pixel.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=65536))]
    max_samples: Option<u32>,
    /// What the picture shows at first (docs/views.md): shaded, or a view
    /// inside the tracer, as `render --view`; `V` cycles on from it.
    #[arg(long, default_value = "shaded", value_parser = View::from_name)]
    view: View,
    /// Print one line per event (ready, saved, shader-error, ...) on stdout,
    /// for scripts and tests that drive the window.
    #[arg(long, hide = true)]
    print_events: bool,
}

pub fn run(args: &Args) -> Result<(), Failure> {
    let options = ViewerOptions {
        scene: args.scene.clone(),
        shaders: args.shaders.clone(),
        size: args.size,
        max_samples: args.max_samples,
        view: args.view,
        print_events: args.print_events,
    };
    crate::app::run(options).map_err(|e| match e {
        ViewerError::Scene(_) | ViewerError::Shader(_) | ViewerError::Size(_) => {
            Failure::Input(e.to_string())
        }
        ViewerError::NoDisplay(_) | ViewerError::NoGpu(_) => Failure::Runtime(e.to_string()),
    })
}
