//! Files dropped on the page's canvas (docs/web.md, "Dropping files"): the
//! browser's `dragover` and `drop` events, each dropped file read whole
//! (`File.arrayBuffer()`) and handed to the page's event loop with its name.
//! What a file becomes depends on its extension ([`Dropped::of`]), as when
//! a file is dropped on the native window.

use std::rc::Rc;

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;
use wasm_bindgen_futures::JsFuture;

use crate::scene::{NewShape, ShapeKind};

/// A dropped file, read.
pub struct DroppedFile {
    pub name: String,
    pub bytes: Vec<u8>,
}

/// What a dropped file is for, told by its extension.
pub enum Dropped {
    /// A scene's TOML text: it replaces the scene.
    Scene(String),
    /// A file a shape is made from (an OBJ or PLY model), the shape added
    /// to the scene in front of the camera.
    Shape(NewShape),
    /// A sandbox shader (WGSL, or GLSL in GLSL Sandbox or Shadertoy style).
    Shader(String),
    /// A PNG or JPEG image, for a multipass shader's texture channels.
    Image(Box<image::RgbaImage>),
}

impl Dropped {
    /// The file `name` with its `bytes`, as what it is for; an error names
    /// the file (and the line, for a model that cannot be read).
    pub fn of(name: &str, bytes: Vec<u8>) -> Result<Dropped, String> {
        let text = |bytes| String::from_utf8(bytes).map_err(|_| format!("{name}: not UTF-8 text"));
        if let Some(kind) = ShapeKind::for_file(std::path::Path::new(name)) {
            return NewShape::from_bytes(kind, name, &bytes).map(Dropped::Shape);
        }
        let extension = name.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase());
        match extension.as_deref() {
            Some("toml") => text(bytes).map(Dropped::Scene),
            // A Shadertoy JSON export is a multipass shader (docs/web.md).
            Some("wgsl" | "glsl" | "frag" | "json") => text(bytes).map(Dropped::Shader),
            // Read as `--channel0` reads a file (docs/sandbox.md, "Textures").
            Some("png" | "jpg" | "jpeg") => image::load_from_memory(&bytes)
                .map(|image| Dropped::Image(Box::new(image.to_rgba8())))
                .map_err(|e| format!("{name}: cannot read the image: {e}")),
            _ => Err(format!(
                "{name}: the page opens scenes (.toml), models (.obj, .ply), shaders \
                 (.wgsl, .glsl, .frag, and Shadertoy's .json) and images for a multipass \
                 shader's channels (.png, .jpg)"
            )),
        }
    }
}

/// Lets files be dropped on `targets` (the canvas, and the message box
/// over it); `dropped` gets each one once read. The listeners live as
/// long as the page.
pub fn listen(
    targets: &[web_sys::EventTarget],
    dropped: impl Fn(Result<DroppedFile, String>) + 'static,
) -> Result<(), String> {
    // The browser opens a file dropped on the page unless `dragover` says
    // that the canvas takes it.
    let over = Closure::<dyn FnMut(web_sys::DragEvent)>::new(|event: web_sys::DragEvent| {
        event.prevent_default();
        if let Some(transfer) = event.data_transfer() {
            transfer.set_drop_effect("copy");
        }
    });
    let dropped = Rc::new(dropped);
    let drop = Closure::<dyn FnMut(web_sys::DragEvent)>::new(move |event: web_sys::DragEvent| {
        event.prevent_default();
        let Some(files) = event.data_transfer().and_then(|t| t.files()) else {
            return;
        };
        for file in (0..files.length()).filter_map(|i| files.get(i)) {
            let dropped = dropped.clone();
            wasm_bindgen_futures::spawn_local(async move { dropped(read(file).await) });
        }
    });
    for target in targets {
        for (kind, listener) in [("dragover", &over), ("drop", &drop)] {
            target
                .add_event_listener_with_callback(kind, listener.as_ref().unchecked_ref())
                .map_err(|e| format!("cannot listen to {kind} on the canvas: {e:?}"))?;
        }
    }
    over.forget();
    drop.forget();
    Ok(())
}

/// The whole content of a dropped file.
async fn read(file: web_sys::File) -> Result<DroppedFile, String> {
    let name = file.name();
    let buffer = JsFuture::from(file.array_buffer())
        .await
        .map_err(|e| format!("{name}: cannot be read: {e:?}"))?;
    Ok(DroppedFile {
        name,
        bytes: js_sys::Uint8Array::new(&buffer).to_vec(),
    })
}
