//! The `raysandbox` command line.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use clap::{Parser, Subcommand};

use raysandbox::cli::parse_size;
use raysandbox::gpu::{
    Gpu, GpuWaitError, OffscreenRenderer, RenderError, ShaderOptions, ShaderSource,
};
use raysandbox::reference;
use raysandbox::scene::{NamedOption, Scene, TorusMethod, TriangleTest};

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
    View(ViewArgs),
    /// Validate a scene file and print a one-line summary.
    Check {
        /// The scene file (TOML).
        scene: PathBuf,
    },
    /// Render a scene to a PNG file, on the GPU or with the CPU reference.
    Render(RenderArgs),
    /// Numerical stress suite: GPU (robust and naive) against the reference.
    Stress(raysandbox::stress::StressArgs),
    /// Run your own fragment shader file (WGSL, GLSL Sandbox or Shadertoy
    /// style), reloaded on save, with sliders from its annotations; or
    /// render it headless (--render, --frames). See docs/sandbox.md.
    Shader(raysandbox::sandbox::ShaderArgs),
    /// Benchmark: GPU time against error, specialised against generic
    /// pipelines, and scaling with the number of spheres (BVH on and off).
    Bench(raysandbox::bench::BenchArgs),
}

#[derive(clap::Args, Default)]
struct ViewArgs {
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
    /// Print one line per event (ready, saved, shader-error, ...) on stdout,
    /// for scripts and tests that drive the window.
    #[arg(long, hide = true)]
    print_events: bool,
}

#[derive(clap::Args)]
struct RenderArgs {
    /// The scene file (TOML).
    scene: PathBuf,
    /// Output PNG file.
    #[arg(short, long)]
    output: PathBuf,
    #[arg(long, default_value_t = 1280, value_parser = clap::value_parser!(u32).range(1..=16384))]
    width: u32,
    #[arg(long, default_value_t = 720, value_parser = clap::value_parser!(u32).range(1..=16384))]
    height: u32,
    /// Samples per pixel (the R4 sequence, see docs/implementation.md); the
    /// default is chosen from `raysandbox bench` (docs/performance.md).
    #[arg(long, default_value_t = raysandbox::gpu::DEFAULT_RENDER_SAMPLES, value_parser = clap::value_parser!(u32).range(1..=65536))]
    spp: u32,
    /// Render with the f64 CPU reference instead of the GPU.
    #[arg(long)]
    reference: bool,
    /// Read the WGSL from this folder instead of the embedded copy.
    #[arg(long)]
    shaders: Option<PathBuf>,
    /// The GPU pipeline: compiled for the scene's features only, or with
    /// every feature (the same source either way).
    #[arg(long, value_enum, default_value_t = PipelineKind::Specialized)]
    pipeline: PipelineKind,
    /// on: the bounded shapes (every kind but planes) go through the
    /// bounding volume hierarchy where it pays (a specialised pipeline uses
    /// it from 128 of them, the generic one always); off: a loop over every
    /// shape.
    #[arg(long, value_enum, default_value_t = Switch::On)]
    bvh: Switch,
    /// The ray-triangle test of meshes: cramer (Cramer's rule),
    /// moller-trumbore, or watertight (Woop, Benthin and Wald).
    #[arg(long, default_value = "watertight", value_parser = TriangleTest::from_name)]
    triangles: TriangleTest,
    /// How the GPU solves a torus's quartic: bisection, newton (the
    /// slope's zeros in closed form, Newton steps kept inside the bracket),
    /// or closed-form (the quartic's own roots in closed form, one Newton
    /// step).
    #[arg(long, default_value = "newton", value_parser = TorusMethod::from_name)]
    torus: TorusMethod,
    /// Render the image this many times after one warm-up render and print
    /// the median, fastest and slowest GPU time.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=10000))]
    frames: u32,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum PipelineKind {
    Specialized,
    Generic,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum Switch {
    On,
    Off,
}

/// A failure the user caused (bad file, bad arguments): exit status 2.
struct InputError(String);

/// A failure of the machine (no GPU, unwritable output): exit status 1.
struct RuntimeError(String);

enum Failure {
    Input(InputError),
    Runtime(RuntimeError),
}

impl From<InputError> for Failure {
    fn from(e: InputError) -> Self {
        Failure::Input(e)
    }
}

impl From<RuntimeError> for Failure {
    fn from(e: RuntimeError) -> Self {
        Failure::Runtime(e)
    }
}

fn main() -> ExitCode {
    give_wayland_clients_a_runtime_dir();
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).init();
    let cli = Cli::parse();
    let result = match cli.command.unwrap_or(Command::View(ViewArgs::default())) {
        Command::View(args) => view(args),
        Command::Check { scene } => check(&scene),
        Command::Render(args) => render(&args),
        Command::Stress(args) => raysandbox::stress::run(&args).map_err(|e| match e {
            raysandbox::stress::StressError::Input(m) => Failure::Input(InputError(m)),
            raysandbox::stress::StressError::Runtime(m) => Failure::Runtime(RuntimeError(m)),
        }),
        Command::Shader(args) => shader(&args),
        Command::Bench(args) => raysandbox::bench::run(&args).map_err(|e| match e {
            raysandbox::bench::BenchError::NoGpu(m) => Failure::Runtime(RuntimeError(m)),
            raysandbox::bench::BenchError::Failed(m) => Failure::Runtime(RuntimeError(m)),
        }),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Input(InputError(message))) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
        Err(Failure::Runtime(RuntimeError(message))) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}

/// A renderer that could not be made: a bad shader or image size is the
/// user's input (exit status 2), anything else the machine's.
fn render_failure(e: RenderError) -> Failure {
    if e.is_input() {
        InputError(e.to_string()).into()
    } else {
        RuntimeError(e.to_string()).into()
    }
}

/// The GPU did not deliver the image.
fn gpu_failure(e: GpuWaitError) -> Failure {
    RuntimeError(e.to_string()).into()
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

fn load_scene(path: &Path) -> Result<Scene, InputError> {
    Scene::load(path).map_err(|e| InputError(e.to_string()))
}

fn view(args: ViewArgs) -> Result<(), Failure> {
    use raysandbox::app::{ViewerError, ViewerOptions, run};
    let options = ViewerOptions {
        scene: args.scene,
        shaders: args.shaders,
        size: args.size,
        max_samples: args.max_samples,
        print_events: args.print_events,
    };
    run(options).map_err(|e| match e {
        ViewerError::Scene(_) | ViewerError::Shader(_) | ViewerError::Size(_) => {
            InputError(e.to_string()).into()
        }
        ViewerError::NoDisplay(_) | ViewerError::NoGpu(_) => RuntimeError(e.to_string()).into(),
    })
}

/// `raysandbox shader`: headless renders are the sandbox's, the window is
/// the app's.
fn shader(args: &raysandbox::sandbox::ShaderArgs) -> Result<(), Failure> {
    use raysandbox::sandbox::{self, SandboxError};
    let result = if args.is_headless() {
        sandbox::run_headless(args)
    } else {
        raysandbox::app::run_sandbox(args)
    };
    result.map_err(|e| match e {
        SandboxError::Input(m) => Failure::Input(InputError(m)),
        SandboxError::Runtime(m) => Failure::Runtime(RuntimeError(m)),
    })
}

fn check(path: &Path) -> Result<(), Failure> {
    let scene = load_scene(path)?;
    println!("{}: ok: {}", path.display(), scene.summary());
    Ok(())
}

fn render(args: &RenderArgs) -> Result<(), Failure> {
    let scene = load_scene(&args.scene)?;
    let start = Instant::now();
    let image = if args.reference {
        println!(
            "renderer: f64 CPU reference, {} threads",
            rayon::current_num_threads()
        );
        let options = reference::ReferenceOptions {
            triangles: args.triangles,
            ..Default::default()
        };
        let prepared = reference::PreparedScene::with_options(&scene, &options);
        reference::render_prepared_rgba8(&prepared, args.width, args.height, args.spp)
    } else {
        let source = match &args.shaders {
            Some(dir) => ShaderSource::from_dir(dir).map_err(|e| InputError(e.to_string()))?,
            None => ShaderSource::embedded(),
        };
        // A broken shader is the user's input: report it before asking for a GPU.
        source.validate().map_err(|e| InputError(e.to_string()))?;
        let gpu = Gpu::headless().map_err(|e| RuntimeError(e.to_string()))?;
        println!("adapter: {}", gpu.describe());
        let mut options = match args.pipeline {
            PipelineKind::Specialized => ShaderOptions::for_scene(&scene),
            PipelineKind::Generic => ShaderOptions::generic(&scene),
        };
        if args.bvh == Switch::Off {
            options.features.bvh = false;
        }
        options.triangles = args.triangles;
        options.torus = args.torus;
        let mut renderer =
            OffscreenRenderer::new(&gpu, &source, &options, &scene, args.width, args.height)
                .map_err(render_failure)?;
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        let first = renderer.render(&gpu, args.spp).map_err(gpu_failure)?;
        println!(
            "GPU time ({}): {:.1} ms",
            renderer.timing().describe(),
            ms(first)
        );
        if args.frames > 1 {
            let mut times: Vec<Duration> = (0..args.frames)
                .map(|_| renderer.render(&gpu, args.spp))
                .collect::<Result<_, _>>()
                .map_err(gpu_failure)?;
            times.sort();
            println!(
                "{} frames after warm-up: median {:.2} ms, fastest {:.2} ms, slowest {:.2} ms",
                times.len(),
                ms(times[times.len() / 2]),
                ms(times[0]),
                ms(times[times.len() - 1]),
            );
        }
        renderer.read_image(&gpu).map_err(gpu_failure)?
    };
    println!(
        "rendered {}x{} at {} spp in {:.1} ms",
        args.width,
        args.height,
        args.spp,
        start.elapsed().as_secs_f64() * 1e3
    );
    image
        .save(&args.output)
        .map_err(|e| RuntimeError(format!("{}: {e}", args.output.display())))?;
    println!("wrote {}", args.output.display());
    Ok(())
}
