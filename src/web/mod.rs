//! The browser page (docs/web.md): the GPU tracer drawing a scene into the
//! page's canvas through WebGPU ([`canvas`], built for `wasm32` only), and
//! the scene carried in the page's address ([`link`]), which the native
//! program and the tests can write too.

#[cfg(target_arch = "wasm32")]
mod canvas;
pub mod link;
#[cfg(target_arch = "wasm32")]
mod page;
