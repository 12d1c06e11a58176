//! `raysandbox ray-tree`: a pixel's Whitted ray tree (docs/ray-tree.md) as
//! text, the f64 reference's and the GPU's side by side with their
//! difference.

use std::path::PathBuf;

use super::{Failure, load_scene};
use crate::gpu::{Gpu, RayTreeRenderer, ShaderOptions, ShaderSource};
use crate::reference;

#[derive(clap::Args)]
pub struct Args {
    /// The scene file (TOML).
    scene: PathBuf,
    /// The pixel, `X,Y` from the top left corner.
    #[arg(long, value_parser = parse_pixel)]
    pixel: (u32, u32),
    /// The image size the pixel is in.
    #[arg(long, default_value = "1280x720", value_parser = crate::cli::parse_size)]
    size: (u32, u32),
    /// Read the WGSL from this folder instead of the embedded copy.
    #[arg(long)]
    shaders: Option<PathBuf>,
}

/// Parses `X,Y`.
fn parse_pixel(text: &str) -> Result<(u32, u32), String> {
    let parse = |s: &str| {
        s.trim()
            .parse::<u32>()
            .map_err(|_| format!("expected X,Y in pixels, got {text:?}"))
    };
    let (x, y) = text
        .split_once(',')
        .ok_or_else(|| format!("expected X,Y in pixels, got {text:?}"))?;
    Ok((parse(x)?, parse(y)?))
}

pub fn run(args: &Args) -> Result<(), Failure> {
    let scene = load_scene(&args.scene)?;
    let (width, height) = args.size;
    let (x, y) = args.pixel;
    if x >= width || y >= height {
        return Err(Failure::Input(format!(
            "--pixel {x},{y} is outside the {width}x{height} image"
        )));
    }
    let prepared = reference::PreparedScene::new(&scene);
    let expected = reference::ray_tree(&prepared, width, height, x, y);
    let source = ShaderSource::checked(args.shaders.as_deref())
        .map_err(|e| Failure::Input(e.to_string()))?;
    let gpu = Gpu::headless().map_err(|e| Failure::Runtime(e.to_string()))?;
    println!("adapter: {}", gpu.describe());
    let renderer = RayTreeRenderer::new(&gpu, &source, &ShaderOptions::for_scene(&scene))
        .map_err(|e| Failure::Input(e.to_string()))?;
    let traced = renderer
        .trace(&gpu, &scene, (width, height), (x, y))
        .map_err(|e| Failure::Runtime(e.to_string()))?;
    println!("pixel {x},{y} of {width}x{height}: reference (f64), gpu (f32) and |difference|");
    print!(
        "{}",
        reference::describe_trees(&expected, Some(&traced.tree))
    );
    if traced.total > traced.tree.rays.len() {
        println!(
            "the GPU traced {} rays and kept the first {}",
            traced.total,
            traced.tree.rays.len()
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::parse_pixel;

    #[test]
    fn pixels_parse_and_bad_ones_are_named() {
        assert_eq!(parse_pixel("12, 7"), Ok((12, 7)));
        assert_eq!(
            parse_pixel("12"),
            Err("expected X,Y in pixels, got \"12\"".to_string())
        );
        assert!(parse_pixel("-1,3").is_err());
    }
}
