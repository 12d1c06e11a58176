//! The `raysandbox` command line.

use std::path::Path;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use raysandbox::commands::{self, Failure};
use raysandbox::{bench, stress};

#[derive(Parser)]
#[command(
    name = "raysandbox",
    version,
    about = "Whitted ray tracing for the lecture: a WGSL shader on wgpu and an f64 CPU reference"
)]
struct Cli {
    /// Without a command: the viewer on the built-in Whitted scene.
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Open the interactive viewer (the default without a command).
    View(commands::view::Args),
    /// Validate a scene file and print a one-line summary.
    Check(commands::check::Args),
    /// Render a scene to a PNG file, on the GPU or with the CPU reference.
    Render(commands::render::Args),
    /// Print one pixel's Whitted ray tree, from the f64 reference and from
    /// the GPU, side by side (docs/ray-tree.md).
    RayTree(commands::ray_tree::Args),
    /// Numerical stress suite: GPU (robust and naive) against the reference.
    Stress(stress::StressArgs),
    /// Run your own fragment shader file (WGSL, GLSL Sandbox or Shadertoy
    /// style), reloaded on save, with sliders from its annotations; or
    /// render it headless (--render, --frames). See docs/sandbox.md.
    Shader(commands::shader::Args),
    /// Benchmark: GPU time against error, specialised against generic
    /// pipelines, and scaling with the number of spheres (BVH on and off).
    Bench(bench::BenchArgs),
}

fn main() -> ExitCode {
    give_wayland_clients_a_runtime_dir();
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).init();
    let cli = Cli::parse();
    let result = match cli.command {
        None => commands::view::run(&commands::view::Args::default()),
        Some(Command::View(args)) => commands::view::run(&args),
        Some(Command::Check(args)) => commands::check::run(&args),
        Some(Command::Render(args)) => commands::render::run(&args),
        Some(Command::RayTree(args)) => commands::ray_tree::run(&args),
        Some(Command::Stress(args)) => stress::run(&args).map_err(Failure::from),
        Some(Command::Shader(args)) => commands::shader::run(&args),
        Some(Command::Bench(args)) => bench::run(&args).map_err(Failure::from),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Input(message)) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
        Err(Failure::Runtime(message)) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}

/// Without `XDG_RUNTIME_DIR` every program that may talk to Wayland prints
/// "error: XDG_RUNTIME_DIR is invalid or not set in the environment." Here
/// that is Mesa's Vulkan device-selection layer: wgpu enables the Wayland
/// surface extension on every Linux instance, so the layer asks libwayland
/// for a compositor's display, twice, even in a headless render. The
/// variable is only missing where no Wayland session runs (containers, CI,
/// ssh), so a private directory of our own is set, as the XDG base
/// directory rules advise when the session provides none. A directory that
/// cannot be made private leaves the environment as it is.
fn give_wayland_clients_a_runtime_dir() {
    use std::os::unix::fs::{DirBuilderExt, MetadataExt, PermissionsExt};
    if std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|d| Path::new(&d).is_absolute()) {
        return;
    }
    let Ok(uid) = std::fs::metadata("/proc/self").map(|m| m.uid()) else {
        return;
    };
    let dir = std::env::temp_dir().join(format!("raysandbox-runtime-{uid}"));
    let _ = std::fs::DirBuilder::new().mode(0o700).create(&dir);
    let private = std::fs::symlink_metadata(&dir)
        .is_ok_and(|m| m.is_dir() && m.uid() == uid && m.permissions().mode() & 0o077 == 0);
    if private {
        // SAFETY: the first statement of `main`, before any other thread
        // exists that could read the environment at the same time.
        unsafe { std::env::set_var("XDG_RUNTIME_DIR", &dir) };
    }
}
