//! `raysandbox check`: validates a scene file and prints a one-line
//! summary.

use std::path::PathBuf;

use super::{Failure, load_scene};

#[derive(clap::Args)]
pub struct Args {
    /// The scene file (TOML).
    scene: PathBuf,
}

pub fn run(args: &Args) -> Result<(), Failure> {
    let scene = load_scene(&args.scene)?;
    println!("{}: ok: {}", args.scene.display(), scene.summary());
    Ok(())
}
