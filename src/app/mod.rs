//! The interactive viewer: the ray-traced scene, the egui scene editor on
//! top, the orbit camera and selection ([`viewer`], the same in the window
//! program and in the web page), and, natively, the window with hot reload
//! of shaders, scene and mesh files, and the sandbox window. The app owns
//! the [`Document`](document::Document) and tells the GPU viewport what
//! changed; drawing is done by `gpu` (the image) and egui-wgpu (the UI).

// The page does not use everything yet (files, mesh dialogs, the sandbox
// clock's controls): no warnings for those in the wasm build.
#![cfg_attr(target_arch = "wasm32", allow(dead_code))]

pub mod camera_model;
mod controls;
pub(crate) mod document;
mod error_view;
pub(crate) mod help;
pub(crate) mod layout;
mod orbit;
mod overlay;
pub(crate) mod panel;
pub(crate) mod pipelines;
pub(crate) mod ray_tree;
mod shape_files;
pub(crate) mod shell;
mod status;
pub(crate) mod ui;
pub mod viewer;

// What only the window program has (docs/web.md, "Differences from the
// native program"): windows of its own, files watched, dialogs, threads.
#[cfg(not(target_arch = "wasm32"))]
mod memory;
#[cfg(not(target_arch = "wasm32"))]
mod sandbox_window;
#[cfg(not(target_arch = "wasm32"))]
mod watch;
#[cfg(not(target_arch = "wasm32"))]
mod window;
#[cfg(not(target_arch = "wasm32"))]
pub use {
    sandbox_window::run_sandbox,
    window::{ViewerError, ViewerOptions, run},
};
