//! Runs a WGSL compute kernel over arrays of inputs and reads its results
//! back: the harness of the WGSL-against-CPU tests (`tests/expr.rs`,
//! `tests/wgsl_intersections.rs`) and of the GPU leak count of
//! `raysandbox stress` (docs/accuracy.md, "Triangle meshes: rays through
//! shared edges and vertices").

use std::time::{Duration, Instant};

use super::buffer;
use super::{Gpu, ShaderSource};

/// One kernel: `entry` of `source` with its override `constants`; the
/// inputs are bound at bindings `0..n` of bind group `group` and the
/// results right after them, one invocation per case in workgroups of 64.
pub struct Kernel<'a> {
    pub label: &'a str,
    pub source: &'a ShaderSource,
    pub entry: &'a str,
    pub constants: &'a [(&'a str, f64)],
    pub group: u32,
}

impl Kernel<'_> {
    /// Runs the kernel over `cases` (binding 0) and returns `results`
    /// values of `R` (binding 1). Panics on an invalid source: for tests.
    pub fn run<C: bytemuck::Pod, R: bytemuck::Pod>(
        &self,
        gpu: &Gpu,
        cases: &[C],
        results: usize,
    ) -> Vec<R> {
        self.run_with(gpu, &[bytemuck::cast_slice(cases)], cases.len(), results)
            .unwrap_or_else(|e| panic!("{e}"))
    }

    /// Runs `invocations` invocations with `inputs` bound in order from
    /// binding 0 and returns `results` values of `R`, bound after them.
    /// Fails with a message if the source does not validate.
    pub fn run_with<R: bytemuck::Pod>(
        &self,
        gpu: &Gpu,
        inputs: &[&[u8]],
        invocations: usize,
        results: usize,
    ) -> Result<Vec<R>, String> {
        let prepared = self.prepare(gpu, inputs, results * std::mem::size_of::<R>())?;
        prepared.dispatch(gpu, invocations)?;
        prepared.read(gpu)
    }

    /// Compiles the kernel and uploads `inputs` (bindings `0..n`) with a
    /// results buffer of `result_bytes` after them, so that the kernel can
    /// be dispatched and timed many times without compiling or uploading
    /// again (`raysandbox bench --meshes`, "Storage").
    pub fn prepare(
        &self,
        gpu: &Gpu,
        inputs: &[&[u8]],
        result_bytes: usize,
    ) -> Result<Prepared, String> {
        self.source.validate().map_err(|e| e.to_string())?;
        let device = &gpu.device;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(self.label),
            source: wgpu::ShaderSource::Wgsl(self.source.text().into()),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(self.label),
            layout: None,
            module: &module,
            entry_point: Some(self.entry),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: self.constants,
                ..Default::default()
            },
            cache: None,
        });
        let buffers: Vec<wgpu::Buffer> = inputs
            .iter()
            .map(|bytes| {
                buffer::with_contents(device, "kernel input", bytes, wgpu::BufferUsages::STORAGE)
            })
            .collect();
        let size = result_bytes as u64;
        let output = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("results"),
            size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let entries: Vec<wgpu::BindGroupEntry> = buffers
            .iter()
            .chain([&output])
            .enumerate()
            .map(|(binding, buffer)| wgpu::BindGroupEntry {
                binding: binding as u32,
                resource: buffer.as_entire_binding(),
            })
            .collect();
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(self.group),
            entries: &entries,
        });
        Ok(Prepared {
            pipeline,
            bind_group,
            group: self.group,
            output,
            size,
        })
    }
}

/// A compiled kernel with its buffers bound (see [`Kernel::prepare`]).
pub struct Prepared {
    pipeline: wgpu::ComputePipeline,
    bind_group: wgpu::BindGroup,
    group: u32,
    output: wgpu::Buffer,
    size: u64,
}

impl Prepared {
    /// Runs `invocations` invocations in workgroups of 64 and waits for
    /// them: returns the wall-clock time from submission to completion.
    pub fn dispatch(&self, gpu: &Gpu, invocations: usize) -> Result<Duration, String> {
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(self.group, &self.bind_group, &[]);
            pass.dispatch_workgroups((invocations as u32).div_ceil(64), 1, 1);
        }
        let start = Instant::now();
        gpu.queue.submit([encoder.finish()]);
        gpu.wait().map_err(|e| e.to_string())?;
        Ok(start.elapsed())
    }

    /// The results of the last dispatch, as values of `R`.
    pub fn read<R: bytemuck::Pod>(&self, gpu: &Gpu) -> Result<Vec<R>, String> {
        let readback = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: self.size,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&self.output, 0, &readback, 0, self.size);
        gpu.queue.submit([encoder.finish()]);
        let slice = readback.slice(..);
        let (sender, mapped) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |result| {
            let _ = sender.send(result);
        });
        gpu.wait().map_err(|e| e.to_string())?;
        mapped
            .try_recv()
            .map_err(|_| "the results were never mapped".to_string())?
            .map_err(|e| e.to_string())?;
        let data = slice.get_mapped_range().map_err(|e| e.to_string())?;
        Ok(bytemuck::cast_slice(&data).to_vec())
    }
}

/// `source` with a compute kernel's WGSL (`name`, `text`) appended: the
/// kernel calls the shader's own functions (`hit_triangle`, ...).
pub fn with_kernel(source: &ShaderSource, name: &str, text: &str) -> ShaderSource {
    ShaderSource::from_parts(
        source
            .parts()
            .map(|(name, text)| (name.to_string(), text.to_string()))
            .chain([(name.to_string(), text.to_string())]),
    )
}
