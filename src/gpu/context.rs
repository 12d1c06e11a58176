//! The wgpu device: adapter choice and the errors a user can act on.

/// Adapter, device and queue, shared by everything that draws.
pub struct Gpu {
    pub instance: wgpu::Instance,
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
}

/// The optional features the device is asked for when the adapter has
/// them: timestamp queries, so that the frame timer (`GpuTimer`) can use
/// them.
pub const TIMER_FEATURES: wgpu::Features =
    wgpu::Features::TIMESTAMP_QUERY.union(wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS);

#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    #[error(
        "no usable GPU adapter found ({0}).\n\
         On a machine without a GPU install a software Vulkan driver: on Debian or \
         Ubuntu `apt-get install mesa-vulkan-drivers` (lavapipe). \
         WGPU_BACKEND=vulkan|gl and WGPU_ADAPTER_NAME=... choose an adapter."
    )]
    NoAdapter(String),
    #[error("the adapter \"{adapter}\" refused to create a device: {reason}")]
    NoDevice { adapter: String, reason: String },
}

impl Gpu {
    /// A device for offscreen rendering. Honours `WGPU_BACKEND` and
    /// `WGPU_ADAPTER_NAME`; otherwise tries Vulkan, Metal and DX12 first and
    /// OpenGL only when none of them has an adapter (probing GL through EGL
    /// prints warnings on headless machines, and is rarely the better choice).
    pub fn headless() -> Result<Gpu, GpuError> {
        let options = wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            apply_limit_buckets: false,
        };
        let from_env = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        if wgpu::Backends::from_env().is_some() {
            return Self::with_adapter(wgpu::Instance::new(from_env), &options);
        }
        let with_backends = |backends| {
            let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
            descriptor.backends = backends;
            wgpu::Instance::new(descriptor)
        };
        Self::with_adapter(with_backends(wgpu::Backends::PRIMARY), &options)
            .or_else(|_| Self::with_adapter(with_backends(wgpu::Backends::SECONDARY), &options))
    }

    /// Requests an adapter matching `options` and a device from it.
    pub fn with_adapter(
        instance: wgpu::Instance,
        options: &wgpu::RequestAdapterOptions<'_, '_>,
    ) -> Result<Gpu, GpuError> {
        let adapter = pollster::block_on(instance.request_adapter(options))
            .map_err(|e| GpuError::NoAdapter(e.to_string()))?;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("raysandbox"),
            // Timestamp queries time frames where the adapter has them.
            required_features: adapter.features() & TIMER_FEATURES,
            required_limits: wgpu::Limits::default(),
            ..Default::default()
        }))
        .map_err(|e| GpuError::NoDevice {
            adapter: adapter.get_info().name,
            reason: e.to_string(),
        })?;
        Ok(Gpu {
            instance,
            adapter,
            device,
            queue,
        })
    }

    /// One line naming the adapter, its backend, kind and driver.
    pub fn describe(&self) -> String {
        let info = self.adapter.get_info();
        format!(
            "{} ({:?}, {:?}, driver {} {})",
            info.name, info.backend, info.device_type, info.driver, info.driver_info
        )
    }
}
