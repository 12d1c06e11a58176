//! Shared by the integration tests: the GPU, and where the scenes are.
//! Each test binary compiles this module and uses only part of it.
#![allow(dead_code)]

pub mod xwindow;

use std::path::{Path, PathBuf};

use raysandbox::gpu::Gpu;

/// The GPU device, or `None` (with a loud message) on a developer machine
/// without one. In CI (`CI=true`) a missing adapter fails the test instead:
/// the GPU tests must run there, on lavapipe.
pub fn gpu() -> Option<Gpu> {
    match Gpu::headless() {
        Ok(gpu) => {
            eprintln!("adapter: {}", gpu.describe());
            Some(gpu)
        }
        Err(e) if std::env::var("CI").is_ok_and(|v| v == "true") => {
            panic!("CI=true and no GPU adapter: {e}")
        }
        Err(e) => {
            eprintln!(
                "!!! SKIPPING GPU TEST: no adapter ({e}). Run scripts/test to install lavapipe."
            );
            None
        }
    }
}

/// The project's folder of bundled scenes.
pub fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes")
}

/// Every `*.toml` directly in `dir`, sorted by name.
pub fn toml_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files
}

/// Copies a folder with its subfolders (the shader folder has `shapes/`).
pub fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let path = entry.unwrap().path();
        let target = to.join(path.file_name().unwrap());
        if path.is_dir() {
            copy_dir(&path, &target);
        } else {
            std::fs::copy(&path, &target).unwrap();
        }
    }
}
