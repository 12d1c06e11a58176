//! The browser page (docs/web.md): the GPU tracer drawing a scene into the
//! page's canvas through WebGPU ([`canvas`], built for `wasm32` only), the
//! scene and shader editors ([`editor`], [`workbench`]) and the sandbox in
//! the page ([`sandbox_page`]), and the scene or shader carried in the
//! page's address ([`link`]), which the native program and the tests can
//! write too, the bundled mesh scenes' models the page fetches
//! ([`shape_files`]), and the images dropped on it for a multipass shader's
//! texture channels ([`dropped_images`]).

#[cfg(target_arch = "wasm32")]
mod canvas;
#[cfg(target_arch = "wasm32")]
mod drop;
pub mod dropped_images;
#[cfg(target_arch = "wasm32")]
mod editor;
pub mod link;
#[cfg(target_arch = "wasm32")]
mod multipass_page;
#[cfg(target_arch = "wasm32")]
mod page;
#[cfg(target_arch = "wasm32")]
mod panel_width;
#[cfg(target_arch = "wasm32")]
mod sandbox_page;
pub mod shape_files;
#[cfg(target_arch = "wasm32")]
mod split;
#[cfg(target_arch = "wasm32")]
mod workbench;
