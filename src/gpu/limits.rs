//! What the device can hold: a scene whose arrays exceed the largest
//! storage buffer is refused before any buffer is made, with the limit
//! named (docs/reliability.md, "The GPU's limits and a lost device").

use super::layout::PackedScene;
use super::shapes::glue::DATA_TEXTURE_WIDTH;

/// A scene whose data does not fit in the device's buffers: one of its
/// arrays (a mesh's triangles, the BVH, ...) is larger than one storage
/// binding or data texture may be.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "the scene needs {} for its {what} in one GPU buffer, but this GPU allows at most {} there \
     ({limit}: {allowed} bytes): use fewer or smaller shapes (e.g. a mesh with fewer \
     triangles)",
    readable_size(*.bytes), readable_size(*.allowed)
)]
pub struct BufferLimitError {
    /// What the array holds ("mesh triangles", "BVH nodes").
    pub what: String,
    pub bytes: u64,
    /// The name of the wgpu limit exceeded.
    pub limit: &'static str,
    pub allowed: u64,
}

/// Checks every array of `packed` against `limits`: a storage buffer
/// against the smaller of the largest storage binding and the largest
/// buffer, a data texture against the rows a texture may have.
pub fn check_buffers(limits: &wgpu::Limits, packed: &PackedScene) -> Result<(), BufferLimitError> {
    let buffer = if limits.max_buffer_size < limits.max_storage_buffer_binding_size {
        ("max_buffer_size", limits.max_buffer_size)
    } else {
        (
            "max_storage_buffer_binding_size",
            limits.max_storage_buffer_binding_size,
        )
    };
    let texture_row = u64::from(DATA_TEXTURE_WIDTH) * 16;
    let texture = (
        "max_texture_dimension_2d",
        texture_row * u64::from(limits.max_texture_dimension_2d),
    );
    match packed.arrays().into_iter().find_map(|array| {
        let (limit, allowed) = if array.texture { texture } else { buffer };
        (array.bytes > allowed).then_some((array, limit, allowed))
    }) {
        Some((array, limit, allowed)) => Err(BufferLimitError {
            what: array.what,
            bytes: array.bytes,
            limit,
            allowed,
        }),
        None => Ok(()),
    }
}

/// `bytes` in KiB, MiB or GiB, with one decimal.
fn readable_size(bytes: u64) -> String {
    let units = ["KiB", "MiB", "GiB"];
    let mut size = bytes as f64 / 1024.0;
    let mut unit = 0;
    while size >= 1024.0 && unit + 1 < units.len() {
        size /= 1024.0;
        unit += 1;
    }
    format!("{size:.1} {}", units[unit])
}
