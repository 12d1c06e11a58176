//! `raysandbox render`: a scene to a PNG file, on the GPU or with the f64
//! CPU reference.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use super::{Failure, load_scene};
use crate::gpu::{
    Gpu, GpuWaitError, OffscreenRenderer, RenderError, ShaderOptions, ShaderSource, View,
};
use crate::reference;
use crate::scene::{KindOptions, NamedOption};

#[derive(clap::Args)]
pub struct Args {
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
    #[arg(long, default_value_t = crate::gpu::DEFAULT_RENDER_SAMPLES, value_parser = clap::value_parser!(u32).range(1..=65536))]
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
    /// The shape kinds' own flags (`--triangles`, `--torus`).
    #[command(flatten)]
    kinds: KindFlags,
    /// Render the image this many times after one warm-up render and print
    /// the median, fastest and slowest GPU time.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=10000))]
    frames: u32,
    /// What the picture shows: shaded (the Whitted picture), or a view
    /// inside the tracer, of the ray through each pixel's centre
    /// (docs/views.md): normals, geometric, depth, id, barycentric, nodes,
    /// tests, nodes-all, tests-all, steps, bounces, shadow-rays, error
    /// (against the f64 reference, traced at every pixel).
    #[arg(long, default_value = "shaded", value_parser = View::from_name)]
    view: View,
}

/// The flags the shape kinds declare (`Choices::FLAG`, gathered by
/// `KindOptions::flags`), each with the value given, which chooses that
/// kind's options in place of the scene's.
#[derive(Clone, Default)]
struct KindFlags(Vec<(&'static str, String)>);

impl clap::FromArgMatches for KindFlags {
    fn from_arg_matches(matches: &clap::ArgMatches) -> Result<Self, clap::Error> {
        let given = KindOptions::flags().into_iter().filter_map(|(flag, _)| {
            let value = matches.get_one::<String>(flag)?;
            Some((flag, value.clone()))
        });
        Ok(KindFlags(given.collect()))
    }

    fn update_from_arg_matches(&mut self, matches: &clap::ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(matches)?;
        Ok(())
    }
}

impl clap::Args for KindFlags {
    fn augment_args(command: clap::Command) -> clap::Command {
        KindOptions::flags()
            .into_iter()
            .fold(command, |command, (flag, help)| {
                // The value is checked as the kind reads it, so a wrong name
                // is reported with the names there are.
                let check = move |value: &str| {
                    KindOptions::default()
                        .set_named(flag, value)
                        .map(|()| value.to_owned())
                };
                command.arg(
                    clap::Arg::new(flag)
                        .long(flag)
                        .help(help)
                        .value_parser(check),
                )
            })
    }

    fn augment_args_for_update(command: clap::Command) -> clap::Command {
        Self::augment_args(command)
    }
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

/// A renderer that could not be made: a bad shader or image size is the
/// user's input (exit status 2), anything else the machine's.
fn render_failure(e: RenderError) -> Failure {
    if e.is_input() {
        Failure::Input(e.to_string())
    } else {
        Failure::Runtime(e.to_string())
    }
}

impl Args {
    /// What `scene` asks of its kinds, with the methods chosen on the
    /// command line in place of its own.
    fn kinds(&self, scene: &crate::scene::Scene) -> KindOptions {
        let mut kinds = KindOptions::of(scene);
        for (flag, value) in &self.kinds.0 {
            // Checked by clap's value parser already.
            let _ = kinds.set_named(flag, value);
        }
        kinds
    }

    /// The f64 reference of `scene`, with the kinds' methods chosen on the
    /// command line.
    fn prepared(&self, scene: &crate::scene::Scene) -> reference::PreparedScene {
        let options = reference::ReferenceOptions {
            kinds: self.kinds(scene),
            ..reference::ReferenceOptions::of(scene)
        };
        reference::PreparedScene::with_options(scene, &options)
    }
}

/// The error view of a rendered `renderer`: the f64 reference traced at
/// every pixel centre (docs/views.md, "The error view"), the errors (in
/// levels, or FLIP per pixel for `error-flip`) shown in place of the GPU's
/// radiance. Returns their colour bar.
fn show_error(
    gpu: &Gpu,
    renderer: &mut OffscreenRenderer,
    scene: &crate::scene::Scene,
    args: &Args,
) -> Result<Option<crate::gpu::ColourBar>, Failure> {
    let start = Instant::now();
    let prepared = args.prepared(scene);
    let image = reference::ErrorImage::traced(&prepared, args.width, args.height);
    println!(
        "reference: f64 at every pixel centre, {} threads, {:.1} ms",
        rayon::current_num_threads(),
        start.elapsed().as_secs_f64() * 1e3
    );
    let gpu_radiance = renderer.read_sums(gpu).map_err(gpu_failure)?;
    let (flip, flip_mean) =
        crate::stress::metrics::flip_quantities(&image.rgba8(), &image.gpu_rgba8(&gpu_radiance));
    println!("FLIP of the GPU's picture against the reference's (mean): {flip_mean:.4}");
    let (shown, range) = if args.view == View::ErrorFlip {
        (flip, Some(crate::stress::metrics::FLIP_RANGE))
    } else {
        (image.quantities(&gpu_radiance), None)
    };
    renderer
        .show_quantities(gpu, &shown, range)
        .map_err(gpu_failure)
}

/// The GPU did not deliver the image.
fn gpu_failure(e: GpuWaitError) -> Failure {
    Failure::Runtime(e.to_string())
}

pub fn run(args: &Args) -> Result<(), Failure> {
    let scene = load_scene(&args.scene)?;
    let start = Instant::now();
    if args.reference && args.view != View::Shaded {
        return Err(Failure::Input(
            "--view: the reference renders the shaded picture only (docs/views.md)".into(),
        ));
    }
    // A view looks at the ray through the pixel centre: one sample is all.
    let spp = if args.view == View::Shaded {
        args.spp
    } else {
        1
    };
    let image = if args.reference {
        println!(
            "renderer: f64 CPU reference, {} threads",
            rayon::current_num_threads()
        );
        let prepared = args.prepared(&scene);
        reference::render_prepared_rgba8(&prepared, args.width, args.height, spp)
    } else {
        let source = ShaderSource::checked(args.shaders.as_deref())
            .map_err(|e| Failure::Input(e.to_string()))?;
        let gpu = Gpu::headless().map_err(|e| Failure::Runtime(e.to_string()))?;
        println!("adapter: {}", gpu.describe());
        let mut options = match args.pipeline {
            PipelineKind::Specialized => ShaderOptions::for_scene(&scene),
            PipelineKind::Generic => ShaderOptions::generic(&scene),
        };
        if args.bvh == Switch::Off {
            options.features.bvh = false;
        }
        options.kinds = args.kinds(&scene);
        options.view = args.view.traced();
        let mut renderer =
            OffscreenRenderer::new(&gpu, &source, &options, &scene, args.width, args.height)
                .map_err(render_failure)?;
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        let first = renderer.render(&gpu, spp).map_err(gpu_failure)?;
        println!(
            "GPU time ({}): {:.1} ms",
            renderer.timing().describe(),
            ms(first)
        );
        if args.frames > 1 {
            let mut times = Vec::new();
            let mut cpu_times = Vec::new();
            for _ in 0..args.frames {
                let before = crate::bench::process_cpu_time();
                times.push(renderer.render(&gpu, spp).map_err(gpu_failure)?);
                if let (Some(a), Some(b)) = (before, crate::bench::process_cpu_time()) {
                    cpu_times.push(b.saturating_sub(a));
                }
            }
            times.sort();
            println!(
                "{} frames after warm-up: median {:.2} ms, fastest {:.2} ms, slowest {:.2} ms",
                times.len(),
                ms(times[times.len() / 2]),
                ms(times[0]),
                ms(times[times.len() - 1]),
            );
            // On lavapipe the GPU is this process's threads: their CPU time
            // is the frame's work, which a loaded machine does not stretch
            // (docs/performance.md, "Where the time goes").
            if cpu_times.len() == times.len() {
                println!(
                    "CPU time per frame: median {:.2} ms",
                    ms(crate::bench::median(cpu_times))
                );
            }
        }
        if args.view.is_error() {
            let bar = show_error(&gpu, &mut renderer, &scene, args)?;
            println!("view {}", args.view.legend(bar));
        } else if args.view != View::Shaded {
            let bar = renderer.fit_colour_bar(&gpu).map_err(gpu_failure)?;
            println!("view {}", args.view.legend(bar));
        }
        renderer.read_image(&gpu).map_err(gpu_failure)?
    };
    println!(
        "rendered {}x{} at {} spp in {:.1} ms",
        args.width,
        args.height,
        spp,
        start.elapsed().as_secs_f64() * 1e3
    );
    image
        .save(&args.output)
        .map_err(|e| Failure::Runtime(format!("{}: {e}", args.output.display())))?;
    println!("wrote {}", args.output.display());
    Ok(())
}
