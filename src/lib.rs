//! raysandbox: a Whitted ray tracer for teaching, as a WGSL shader on wgpu and
//! as an f64 CPU reference that measures how far the GPU is from exact.
//!
//! The same crate builds for the browser (`wasm32`, docs/web.md): there the
//! page in [`web`] replaces the command line, the window and the
//! measurements, which need files, threads and a terminal; it shows the
//! viewer's core ([`app::viewer`]) in the page's canvas.

pub mod app;
#[cfg(not(target_arch = "wasm32"))]
pub mod bench;
pub mod bvh;
pub mod cli;
#[cfg(not(target_arch = "wasm32"))]
pub mod commands;
pub mod compare;
pub mod expr;
pub mod files;
pub mod gpu;
pub mod reference;
pub mod sandbox;
pub mod scene;
pub mod shader_params;
#[cfg(not(target_arch = "wasm32"))]
pub mod stress;
pub mod web;
