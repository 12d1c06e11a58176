//! GPU time of a stretch of commands, from timestamp queries where the
//! adapter has them: around several passes where timestamps may be written
//! inside an encoder (`TIMESTAMP_QUERY_INSIDE_ENCODERS`, native drivers),
//! or at the start and end of one render pass (`TIMESTAMP_QUERY` alone,
//! which WebGPU in the browser has too).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
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
    /// One word, for the viewer's `ready` event.
    pub fn name(self) -> &'static str {
        match self {
            Timing::GpuTimestamps => "timestamps",
            Timing::SubmitToDone => "wall",
        }
    }

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
    /// A [`Self::read_later`] is under way: `readback` is mapped or about
    /// to be, and a command that copies into it would make its whole
    /// submission invalid (WebGPU drops it: a job's pixels never drawn).
    reading: Arc<AtomicBool>,
}

impl GpuTimer {
    /// For [`Self::begin`] and [`Self::end`] around several passes; `None`
    /// when the device lacks timestamp queries inside encoders.
    pub fn new(gpu: &Gpu) -> Option<GpuTimer> {
        gpu.device
            .features()
            .contains(TIMER_FEATURES)
            .then(|| Self::made(gpu))
    }

    /// For one render pass ([`Self::pass_writes`]); `None` when the device
    /// lacks timestamp queries. The browser has these: there a job's time
    /// is its pass's own, not the queue's wait for the frames before it.
    pub fn for_passes(gpu: &Gpu) -> Option<GpuTimer> {
        gpu.device
            .features()
            .contains(wgpu::Features::TIMESTAMP_QUERY)
            .then(|| Self::made(gpu))
    }

    fn made(gpu: &Gpu) -> GpuTimer {
        let size = 2 * wgpu::QUERY_SIZE as u64;
        let buffer = |label, usage| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        GpuTimer {
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
            reading: Arc::new(AtomicBool::new(false)),
        }
    }

    /// Timestamps at the start and the end of a render pass; then
    /// [`Self::resolve`] after the pass.
    pub fn pass_writes(&self) -> wgpu::RenderPassTimestampWrites<'_> {
        wgpu::RenderPassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        }
    }

    /// Marks the start of the timed commands.
    pub fn begin(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.write_timestamp(&self.queries, 0);
    }

    /// Marks their end and copies the timestamps where [`Self::read`] finds them.
    pub fn end(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.write_timestamp(&self.queries, 1);
        self.resolve(encoder);
    }

    /// Copies the two timestamps where [`Self::read`] and
    /// [`Self::read_later`] find them.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.queries, 0..2, &self.resolved, 0);
        encoder.copy_buffer_to_buffer(&self.resolved, 0, &self.readback, 0, self.resolved.size());
    }

    /// The time between the two marks of the last submitted frame; waits
    /// for the GPU to finish it.
    pub fn read(&self, gpu: &Gpu) -> Option<Duration> {
        let slice = self.readback.slice(..);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        gpu.device.poll(wgpu::PollType::wait_indefinitely()).ok()?;
        Self::take_time(&self.readback, self.period)
    }

    /// The same without waiting (the browser cannot): `done` gets the time
    /// once the GPU has finished the frame and the buffer is mapped, `None`
    /// if it could not be read. Until then the timer is
    /// [`Self::reading`]: time nothing else with it.
    pub fn read_later(&self, done: impl FnOnce(Option<Duration>) + wgpu::WasmNotSend + 'static) {
        let (readback, period) = (self.readback.clone(), self.period);
        let reading = Arc::clone(&self.reading);
        reading.store(true, Ordering::Release);
        self.readback
            .slice(..)
            .map_async(wgpu::MapMode::Read, move |mapped| {
                let time = mapped
                    .ok()
                    .and_then(|()| Self::take_time(&readback, period));
                reading.store(false, Ordering::Release);
                done(time);
            });
    }

    /// Whether a [`Self::read_later`] has not delivered its time yet: a
    /// pass timed now could not have its timestamps copied back.
    pub fn reading(&self) -> bool {
        self.reading.load(Ordering::Acquire)
    }

    /// Reads the mapped timestamps and unmaps the buffer.
    fn take_time(readback: &wgpu::Buffer, period: f64) -> Option<Duration> {
        let ticks = {
            let data = readback.slice(..).get_mapped_range().ok()?;
            let stamps: &[u64] = bytemuck::cast_slice(&data);
            stamps[1].saturating_sub(stamps[0])
        };
        readback.unmap();
        Some(Duration::from_nanos((ticks as f64 * period) as u64))
    }
}
