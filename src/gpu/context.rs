//! The wgpu device: adapter choice, its limits, waiting for it, and the
//! errors a user can act on.

use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

use super::shapes::glue::data_texture_count;
use super::tracer::ACCUM_FORMAT;

/// Adapter, device and queue, shared by everything that draws. A clone
/// shares them (the viewer's worker traces a pixel's ray tree with one).
#[derive(Clone)]
pub struct Gpu {
    pub instance: wgpu::Instance,
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    /// Why the device was lost, once it is (set by wgpu's device-lost
    /// callback: a driver reset, `Device::destroy`, ...).
    lost: Arc<Mutex<Option<String>>>,
    /// Called once the device is lost (see [`Gpu::wake_on_loss`]).
    wake: Arc<Mutex<Option<Waker>>>,
}

/// What wakes a program's event loop when its device is lost.
type Waker = Box<dyn Fn() + Send>;

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
         Ubuntu `apt-get install mesa-vulkan-drivers libvulkan1` (lavapipe). \
         WGPU_BACKEND=vulkan|gl and WGPU_ADAPTER_NAME=... choose an adapter."
    )]
    NoAdapter(String),
    #[error("the adapter \"{adapter}\" refused to create a device: {reason}")]
    NoDevice { adapter: String, reason: String },
}

/// An image size the device cannot render: a zero side, or a side beyond the
/// largest 2D texture it allows (8192 pixels on lavapipe with the limits the
/// device is created with).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "an image of {width}x{height} pixels is not possible on this GPU: each side must be from 1 \
     to {max} pixels (its largest texture, max_texture_dimension_2d); choose a smaller size"
)]
pub struct SizeError {
    pub width: u32,
    pub height: u32,
    pub max: u32,
}

/// The GPU did not finish the submitted work: too slow (e.g. a shader that
/// loops for too long), or the device was lost on the way.
#[derive(Debug, thiserror::Error)]
pub enum GpuWaitError {
    #[error(
        "the GPU did not finish a frame within {} s: is a shader running too long?",
        .0.as_secs()
    )]
    Timeout(Duration),
    #[error("the GPU failed while finishing a frame (device lost?): {0}")]
    Lost(String),
}

/// How long one submission may keep the GPU busy before [`Gpu::wait`] gives
/// up. The renderers submit a few samples per pixel at a time; on lavapipe
/// with two cores a batch of the heaviest bundled scene at the largest size
/// (8192 x 8192) takes a few minutes, so a user's shader that is still
/// running after ten is taken to be stuck.
pub const WAIT_LIMIT: Duration = Duration::from_secs(600);

/// Storage buffers asked for per shader stage where the adapter has them.
/// WebGPU's default allows 8; lavapipe and desktop GPUs offer far more. The
/// tracer binds none (its globals and arrays are data textures,
/// `gpu::shapes::glue`); this is headroom for other shaders.
pub const STORAGE_BUFFERS_NEEDED: u32 = 16;

/// The default limits, with as many storage buffers per stage as the
/// scene's shape kinds need (when the adapter has them; otherwise device
/// creation names the limit), storage textures enough for the tracer's
/// data textures on a CPU adapter that has them (`DataAccess::for_device`
/// reads them as storage textures then; the gain was measured on lavapipe
/// only, so a GPU keeps sampled ones), and buffers as large as the adapter
/// allows, so that a large mesh fits wherever the GPU can hold it (the
/// defaults stop at 128 MiB per storage binding).
fn required_limits(adapter: &wgpu::Adapter) -> wgpu::Limits {
    let offered = adapter.limits();
    let defaults = wgpu::Limits::default();
    let storage_textures = if adapter.get_info().device_type == wgpu::DeviceType::Cpu {
        data_texture_count()
    } else {
        defaults.max_storage_textures_per_shader_stage
    };
    wgpu::Limits {
        max_storage_buffers_per_shader_stage: STORAGE_BUFFERS_NEEDED
            .min(offered.max_storage_buffers_per_shader_stage)
            .max(8),
        max_storage_textures_per_shader_stage: storage_textures
            .min(offered.max_storage_textures_per_shader_stage)
            .max(defaults.max_storage_textures_per_shader_stage),
        max_storage_buffer_binding_size: offered
            .max_storage_buffer_binding_size
            .max(defaults.max_storage_buffer_binding_size),
        max_buffer_size: offered.max_buffer_size.max(defaults.max_buffer_size),
        ..defaults
    }
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
        pollster::block_on(Self::request(instance, options))
    }

    /// As [`Gpu::with_adapter`], without blocking: the browser answers these
    /// requests only once control returns to its event loop (docs/web.md).
    pub async fn request(
        instance: wgpu::Instance,
        options: &wgpu::RequestAdapterOptions<'_, '_>,
    ) -> Result<Gpu, GpuError> {
        let adapter = instance
            .request_adapter(options)
            .await
            .map_err(|e| GpuError::NoAdapter(e.to_string()))?;
        let accumulates = adapter
            .get_texture_format_features(ACCUM_FORMAT)
            .allowed_usages
            .contains(wgpu::TextureUsages::RENDER_ATTACHMENT);
        if !accumulates {
            let info = adapter.get_info();
            return Err(GpuError::NoAdapter(format!(
                "{} ({:?}) cannot render into {ACCUM_FORMAT:?} textures, which hold the \
                 running sum of samples",
                info.name, info.backend
            )));
        }
        Self::request_with_limits(instance, adapter, |_| ()).await
    }

    /// A device from `adapter` with the limits this program asks for,
    /// changed by `adjust`: tests use it to play a GPU with smaller limits.
    pub async fn request_with_limits(
        instance: wgpu::Instance,
        adapter: wgpu::Adapter,
        adjust: impl FnOnce(&mut wgpu::Limits),
    ) -> Result<Gpu, GpuError> {
        let mut limits = required_limits(&adapter);
        adjust(&mut limits);
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("raysandbox"),
                // Timestamp queries time frames where the adapter has them.
                // Float32 filtering: the sandbox's multipass buffers are
                // rgba32float where it is there (docs/sandbox.md, "Multipass").
                required_features: adapter.features()
                    & (TIMER_FEATURES | wgpu::Features::FLOAT32_FILTERABLE),
                required_limits: limits,
                ..Default::default()
            })
            .await
            .map_err(|e| GpuError::NoDevice {
                adapter: adapter.get_info().name,
                reason: e.to_string(),
            })?;
        let lost = Arc::new(Mutex::new(None));
        let wake: Arc<Mutex<Option<Waker>>> = Arc::new(Mutex::new(None));
        let (lost_in_callback, wake_in_callback) = (lost.clone(), wake.clone());
        device.set_device_lost_callback(move |reason, message| {
            log::error!("the GPU device was lost ({reason:?}): {message}");
            *lost_in_callback
                .lock()
                .unwrap_or_else(PoisonError::into_inner) = Some(lost_message(reason, &message));
            if let Some(wake) = &*wake_in_callback
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
            {
                wake();
            }
        });
        // wgpu's default handler panics. What reaches it is either a bug of
        // this program or the fallout of a lost device, which the viewer
        // recovers from: logged, so that the window stays up.
        device.on_uncaptured_error(Arc::new(|error| log::error!("GPU error: {error}")));
        Ok(Gpu {
            instance,
            adapter,
            device,
            queue,
            lost,
            wake,
        })
    }

    /// Calls `wake` when the device is lost (at once if it already is): a
    /// program that draws only when something changes (the web page at
    /// rest) learns of the loss without drawing first (docs/web.md, "A lost
    /// GPU device").
    pub fn wake_on_loss(&self, wake: impl Fn() + Send + 'static) {
        if self.lost().is_some() {
            wake();
        }
        *self.wake.lock().unwrap_or_else(PoisonError::into_inner) = Some(Box::new(wake));
    }

    /// Why the device was lost, if it was: everything made from it is
    /// useless, and a new [`Gpu`] must replace it. Polls the device without
    /// waiting first: wgpu reports a loss from its polling.
    pub fn lost(&self) -> Option<String> {
        // An error here is the loss itself, or a timeout that cannot
        // happen without waiting.
        let _ = self.device.poll(wgpu::PollType::Poll);
        self.lost
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .clone()
    }

    /// Whether an image of `width` x `height` pixels can be rendered on this
    /// device: both sides from 1 to its largest texture size.
    pub fn check_size(&self, (width, height): (u32, u32)) -> Result<(), SizeError> {
        let max = self.device.limits().max_texture_dimension_2d;
        if (1..=max).contains(&width) && (1..=max).contains(&height) {
            Ok(())
        } else {
            Err(SizeError { width, height, max })
        }
    }

    /// Waits until the GPU has finished everything submitted so far (and the
    /// callbacks of finished buffer mappings have run), for at most
    /// [`WAIT_LIMIT`].
    pub fn wait(&self) -> Result<(), GpuWaitError> {
        self.device
            .poll(wgpu::PollType::Wait {
                submission_index: None,
                timeout: Some(WAIT_LIMIT),
            })
            .map(drop)
            .map_err(|e| match e {
                wgpu::PollError::Timeout => GpuWaitError::Timeout(WAIT_LIMIT),
                other => GpuWaitError::Lost(other.to_string()),
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

/// What a lost device's reason and message say, for a user.
fn lost_message(reason: wgpu::DeviceLostReason, message: &str) -> String {
    let why = match reason {
        wgpu::DeviceLostReason::Destroyed => "it was destroyed",
        wgpu::DeviceLostReason::Unknown => "the driver reset it or failed",
    };
    if message.is_empty() {
        why.to_string()
    } else {
        format!("{why}: {message}")
    }
}
