//! GPU time of a stretch of commands, from timestamp queries where the
//! adapter has them (`TIMESTAMP_QUERY` and `TIMESTAMP_QUERY_INSIDE_ENCODERS`).

use std::time::Duration;

use super::context::{Gpu, TIMER_FEATURES};

/// How a frame time was measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Timing {
    /// GPU timestamps written before and after the frame's commands.
    GpuTimestamps,
    /// Wall time from submission until the GPU reported the work done.
    SubmitToDone,
}

impl Timing {
    pub fn describe(self) -> &'static str {
        match self {
            Timing::GpuTimestamps => "GPU timestamps",
            Timing::SubmitToDone => "submit to done, wall time",
        }
    }
}

/// Two timestamps around the commands of one frame, and where they are read.
pub struct GpuTimer {
    queries: wgpu::QuerySet,
    resolved: wgpu::Buffer,
    readback: wgpu::Buffer,
    /// Nanoseconds per timestamp tick.
    period: f64,
}

impl GpuTimer {
    /// `None` when the device lacks timestamp queries inside encoders.
    pub fn new(gpu: &Gpu) -> Option<GpuTimer> {
        if !gpu.device.features().contains(TIMER_FEATURES) {
            return None;
        }
        let size = 2 * wgpu::QUERY_SIZE as u64;
        let buffer = |label, usage| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        Some(GpuTimer {
            queries: gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("frame timer"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            }),
            resolved: buffer(
                "timestamps",
                wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            ),
            readback: buffer(
                "timestamps readback",
                wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            ),
            period: f64::from(gpu.queue.get_timestamp_period()),
        })
    }

    /// Marks the start of the timed commands.
    pub fn begin(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.write_timestamp(&self.queries, 0);
    }

    /// Marks their end and copies the timestamps where [`Self::read`] finds them.
    pub fn end(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.write_timestamp(&self.queries, 1);
        encoder.resolve_query_set(&self.queries, 0..2, &self.resolved, 0);
        encoder.copy_buffer_to_buffer(&self.resolved, 0, &self.readback, 0, self.resolved.size());
    }

    /// The time between the two marks of the last submitted frame; waits
    /// for the GPU to finish it.
    pub fn read(&self, gpu: &Gpu) -> Option<Duration> {
        let slice = self.readback.slice(..);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        gpu.device.poll(wgpu::PollType::wait_indefinitely()).ok()?;
        let ticks = {
            let data = slice.get_mapped_range().ok()?;
            let stamps: &[u64] = bytemuck::cast_slice(&data);
            stamps[1].saturating_sub(stamps[0])
        };
        self.readback.unmap();
        Some(Duration::from_nanos((ticks as f64 * self.period) as u64))
    }
}
