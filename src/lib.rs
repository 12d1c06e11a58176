//! raysandbox: a Whitted ray tracer for teaching, as a WGSL shader on wgpu and
//! as an f64 CPU reference that measures how far the GPU is from exact.

pub mod app;
pub mod bench;
pub mod bvh;
pub mod cli;
pub mod compare;
pub mod expr;
pub mod files;
pub mod gpu;
pub mod reference;
pub mod sandbox;
pub mod scene;
pub mod stress;
