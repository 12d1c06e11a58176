//! What the device can hold: a scene whose arrays exceed the largest
//! storage buffer is refused before any buffer is made, with the limit
//! named (docs/reliability.md, "The GPU's limits and a lost device").

use super::layout::PackedScene;

/// A scene whose data does not fit in the device's storage buffers: one of
/// its arrays (a mesh's triangles, the BVH, ...) is larger than one binding
/// may be.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "the scene needs {} for its {what} in one GPU buffer, but this GPU allows at most {} per \
     buffer ({limit} = {allowed} bytes): use fewer or smaller shapes (e.g. a mesh with fewer \
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

/// Checks every array of `packed` against `limits`: the smaller of the
/// largest storage binding and the largest buffer.
pub fn check_buffers(limits: &wgpu::Limits, packed: &PackedScene) -> Result<(), BufferLimitError> {
    let (limit, allowed) = if limits.max_buffer_size < limits.max_storage_buffer_binding_size {
        ("max_buffer_size", limits.max_buffer_size)
    } else {
        (
            "max_storage_buffer_binding_size",
            limits.max_storage_buffer_binding_size,
        )
    };
    match packed
        .arrays()
        .into_iter()
        .find(|(_, bytes)| *bytes > allowed)
    {
        Some((what, bytes)) => Err(BufferLimitError {
            what,
            bytes,
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
