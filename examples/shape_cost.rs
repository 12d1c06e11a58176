//! What a scene's tori, implicit surfaces and Julia sets cost against
//! spheres in their place (`raysandbox::bench::spheres_in_place`), by the
//! CPU time this process spends per frame (on lavapipe the GPU is our own
//! threads, and a loaded machine does not stretch CPU time as it stretches
//! wall-clock time), for several variants of the shaders at once, each
//! against its sphere twin drawn by the same shaders: the renders take turns
//! frame by frame, each ratio is per turn, and the median and every ratio
//! are printed (docs/performance.md,
//! "The torus against its sphere").
//!
//!     cargo run --release --example shape_cost -- SCENE FRAMES WIDTH HEIGHT VARIANT...
//!
//! A VARIANT is a torus method (`TorusMethod`: bisection, newton,
//! closed-form), optionally `@DIR` to read the WGSL from the folder DIR
//! instead of the built-in shaders (a copy of `shaders/` with one change).

use std::path::Path;
use std::time::Duration;

use raysandbox::bench::{median, process_cpu_time, spheres_in_place};
use raysandbox::gpu::{Gpu, OffscreenRenderer, ShaderOptions, ShaderSource};
use raysandbox::scene::{NamedOption, Scene, TorusMethod};

type Failure = Box<dyn std::error::Error>;

fn main() -> Result<(), Failure> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [scene, frames, width, height, variants @ ..] = &args[..] else {
        return Err("usage: shape_cost SCENE FRAMES WIDTH HEIGHT VARIANT...".into());
    };
    let scene = Scene::load(Path::new(scene))?;
    let frames: usize = frames.parse()?;
    if frames == 0 {
        return Err("FRAMES must be at least 1".into());
    }
    let size: (u32, u32) = (width.parse()?, height.parse()?);
    let gpu = Gpu::headless()?;
    let spheres = spheres_in_place(&scene);
    // Per variant: its sphere twin (the same shaders), then the scene.
    let mut renderers = Vec::new();
    for variant in variants {
        let (method, dir) = match variant.split_once('@') {
            Some((method, dir)) => (method, Some(Path::new(dir))),
            None => (variant.as_str(), None),
        };
        let method = TorusMethod::from_name(method)?;
        renderers.push(renderer(&gpu, &spheres, method, dir, size)?);
        renderers.push(renderer(&gpu, &scene, method, dir, size)?);
    }
    let mut times = vec![Vec::new(); renderers.len()];
    for r in renderers.iter_mut() {
        r.render(&gpu, 1)?;
    }
    for _ in 0..frames {
        for (r, t) in renderers.iter_mut().zip(&mut times) {
            let before = cpu_time()?;
            r.render(&gpu, 1)?;
            t.push((cpu_time()? - before).as_secs_f64() * 1e3);
        }
    }
    for (variant, pair) in variants.iter().zip(times.chunks(2)) {
        let ratios: Vec<f64> = pair[1].iter().zip(&pair[0]).map(|(a, s)| a / s).collect();
        let listed: Vec<String> = ratios.iter().map(|r| format!("{r:.2}")).collect();
        println!(
            "{variant:>28}: CPU {:7.1} ms, spheres {:7.1} ms (medians), ratio {:.3} (median of {})",
            median(pair[1].iter().copied()),
            median(pair[0].iter().copied()),
            median(ratios.iter().copied()),
            listed.join(", ")
        );
    }
    Ok(())
}

fn renderer(
    gpu: &Gpu,
    scene: &Scene,
    torus: TorusMethod,
    shaders: Option<&Path>,
    (width, height): (u32, u32),
) -> Result<OffscreenRenderer, Failure> {
    let source = match shaders {
        Some(dir) => ShaderSource::from_dir(dir)?,
        None => ShaderSource::embedded(),
    };
    let mut options = ShaderOptions::for_scene(scene);
    options.kinds.tori = torus;
    Ok(OffscreenRenderer::new(
        gpu, &source, &options, scene, width, height,
    )?)
}

fn cpu_time() -> Result<Duration, Failure> {
    process_cpu_time().ok_or_else(|| "no /proc/self/task/*/schedstat on this system".into())
}
