//! The subcommands of the `raysandbox` binary, one module each with its
//! clap `Args` and its `run`, as [`crate::stress`] and [`crate::bench`]
//! are: `view`, `render`, `check`, `shader` and `ray-tree`. `src/main.rs` only parses
//! the command line, calls the chosen `run` and turns a [`Failure`] into
//! the exit status.

pub mod check;
pub mod ray_tree;
pub mod render;
pub mod shader;
pub mod view;

use std::path::Path;

use crate::bench::BenchError;
use crate::sandbox::SandboxError;
use crate::scene::Scene;
use crate::stress::StressError;

/// Why a subcommand failed; it sets the exit status.
pub enum Failure {
    /// The user's input (a bad file, bad arguments): exit status 2.
    Input(String),
    /// The machine (no GPU, an unwritable output): exit status 1.
    Runtime(String),
}

impl From<StressError> for Failure {
    fn from(e: StressError) -> Self {
        match e {
            StressError::Input(m) => Failure::Input(m),
            StressError::Runtime(m) => Failure::Runtime(m),
        }
    }
}

impl From<BenchError> for Failure {
    fn from(e: BenchError) -> Self {
        match e {
            BenchError::NoGpu(m) | BenchError::Failed(m) => Failure::Runtime(m),
        }
    }
}

impl From<SandboxError> for Failure {
    fn from(e: SandboxError) -> Self {
        match e {
            SandboxError::Input(m) => Failure::Input(m),
            SandboxError::Runtime(m) => Failure::Runtime(m),
        }
    }
}

/// The scene file at `path`; an error names the file, key and line.
fn load_scene(path: &Path) -> Result<Scene, Failure> {
    Scene::load(path).map_err(|e| Failure::Input(e.to_string()))
}
