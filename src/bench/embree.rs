//! Intel Embree 3 through the small C file `src/bench/embree.c` (built by
//! build.rs with the `embree` feature): one mesh, single rays by
//! `rtcIntersect1`, on two threads, as the anchor of `bench --throughput`.

use std::ffi::c_void;

unsafe extern "C" {
    fn rs_embree_new(
        vertices: *const f32,
        vertex_count: usize,
        indices: *const u32,
        triangle_count: usize,
    ) -> *mut c_void;
    fn rs_embree_trace(scene: *const c_void, rays: *const f32, count: usize, hits: *mut u8);
    fn rs_embree_free(scene: *mut c_void);
}

/// A committed Embree scene of one triangle mesh.
pub struct Embree(*mut c_void);

// Embree's committed scenes may be traced from any number of threads at
// once (rtcIntersect1 only reads the scene).
unsafe impl Sync for Embree {}

/// The threads the trace is split over: the machine's two cores, as
/// lavapipe uses them.
const THREADS: usize = 2;

impl Embree {
    pub fn new(vertices: &[[f32; 3]], triangles: &[[u32; 3]]) -> Result<Embree, String> {
        // SAFETY: the pointers and counts describe the two slices, which
        // Embree copies into buffers of its own before returning.
        let scene = unsafe {
            rs_embree_new(
                vertices.as_ptr().cast(),
                vertices.len(),
                triangles.as_ptr().cast(),
                triangles.len(),
            )
        };
        if scene.is_null() {
            return Err("Embree could not build the scene".into());
        }
        Ok(Embree(scene))
    }

    /// Whether each ray (origin, direction) hits the mesh, the rays split
    /// into [`THREADS`] contiguous parts traced at the same time.
    pub fn trace(&self, rays: &[[f32; 6]]) -> Vec<bool> {
        let mut hits = vec![0u8; rays.len()];
        let part = rays.len().div_ceil(THREADS).max(1);
        std::thread::scope(|s| {
            for (r, h) in rays.chunks(part).zip(hits.chunks_mut(part)) {
                s.spawn(move || {
                    // SAFETY: `r` and `h` have the same length, the scene
                    // lives as long as `self`.
                    unsafe { rs_embree_trace(self.0, r.as_ptr().cast(), r.len(), h.as_mut_ptr()) }
                });
            }
        });
        hits.into_iter().map(|h| h != 0).collect()
    }
}

impl Drop for Embree {
    fn drop(&mut self) {
        // SAFETY: made by rs_embree_new, freed once.
        unsafe { rs_embree_free(self.0) }
    }
}
