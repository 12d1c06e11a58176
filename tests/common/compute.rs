//! Runs a WGSL compute kernel over an array of test cases and reads its
//! results back: the harness the WGSL-against-CPU tests share.

use raysandbox::gpu::{Gpu, ShaderSource};
use wgpu::util::DeviceExt;

/// One kernel run: `entry` of `source` with its override `constants`, the
/// cases bound at `binding 0` and the results at `binding 1` of bind group
/// `group`, one invocation per case in workgroups of 64.
pub struct Kernel<'a> {
    pub label: &'a str,
    pub source: &'a ShaderSource,
    pub entry: &'a str,
    pub constants: &'a [(&'a str, f64)],
    pub group: u32,
}

impl Kernel<'_> {
    /// Runs the kernel over `cases` and returns `results` values of `R`.
    pub fn run<C: bytemuck::Pod, R: bytemuck::Pod>(
        &self,
        gpu: &Gpu,
        cases: &[C],
        results: usize,
    ) -> Vec<R> {
        self.source.validate().unwrap_or_else(|e| panic!("{e}"));
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
        let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("cases"),
            contents: bytemuck::cast_slice(cases),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let size = (results * std::mem::size_of::<R>()) as u64;
        let output = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("results"),
            size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(self.group),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: input.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: output.as_entire_binding(),
                },
            ],
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(self.group, &bind_group, &[]);
            pass.dispatch_workgroups((cases.len() as u32).div_ceil(64), 1, 1);
        }
        encoder.copy_buffer_to_buffer(&output, 0, &readback, 0, size);
        gpu.queue.submit([encoder.finish()]);
        let slice = readback.slice(..);
        slice.map_async(wgpu::MapMode::Read, |r| r.expect("map"));
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .expect("waiting for the GPU");
        let data = slice.get_mapped_range().expect("mapped");
        bytemuck::cast_slice(&data).to_vec()
    }
}
