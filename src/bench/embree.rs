//! Intel Embree 3 through the small C file `src/bench/embree.c` (built by
//! build.rs with the `embree` feature): one mesh, single rays by
//! `rtcIntersect1`, on two threads, as the anchor of `bench --throughput`.

use std::ffi::c_void;
use std::time::Duration;

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
    /// into [`THREADS`] contiguous parts traced at the same time, and the
    /// CPU time the threads spent.
    pub fn trace(&self, rays: &[[f32; 6]]) -> (Vec<bool>, Duration) {
        let mut hits = vec![0u8; rays.len()];
        let part = rays.len().div_ceil(THREADS).max(1);
        let cpu = std::thread::scope(|s| {
            let threads: Vec<_> = rays
                .chunks(part)
                .zip(hits.chunks_mut(part))
                .map(|(r, h)| {
                    s.spawn(move || {
                        let start = thread_cpu_time();
                        // SAFETY: `r` and `h` have the same length, the
                        // scene lives as long as `self`.
                        unsafe {
                            rs_embree_trace(self.0, r.as_ptr().cast(), r.len(), h.as_mut_ptr())
                        }
                        thread_cpu_time().saturating_sub(start)
                    })
                })
                .collect();
            threads
                .into_iter()
                .map(|t| t.join().expect("an Embree thread panicked"))
                .sum()
        });
        (hits.into_iter().map(|h| h != 0).collect(), cpu)
    }
}

/// The CPU time of the calling thread.
fn thread_cpu_time() -> Duration {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: a valid timespec to write into; this clock exists on Linux.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
    Duration::new(t.tv_sec as u64, t.tv_nsec as u32)
}

impl Drop for Embree {
    fn drop(&mut self) {
        // SAFETY: made by rs_embree_new, freed once.
        unsafe { rs_embree_free(self.0) }
    }
}
