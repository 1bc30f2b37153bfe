//! Headless wgpu context: instance, adapter (real GPUs through Vulkan/Metal/DX12, or Mesa's
//! lavapipe on machines without one), device and queue.

use std::sync::{Arc, Mutex};

use crate::{Error, Result};

/// Set this environment variable (to anything but "0") to make splitsum behave as if no
/// GPU adapter existed: `--backend auto` then uses the CPU backend.
pub const HIDE_GPU_ENV: &str = "SPLITSUM_NO_GPU";

/// Set this environment variable to a kernel name (`brdf_lut`, `equirect_to_cube`,
/// `prefilter_specular`, `irradiance`) to make splitsum destroy its GPU device just before
/// it runs that kernel: a test hook that simulates a device lost in the middle of a job
/// (`--backend auto` must then finish on the CPU, `--backend gpu` fail cleanly).
pub const LOSE_DEVICE_ENV: &str = "SPLITSUM_LOSE_DEVICE_AT";

/// Kernels refused on wgpu's OpenGL backend (`splitsum verify` shows it on Mesa llvmpipe
/// through EGL: they validate and run, but the cube faces they write through per-mip
/// 2D-array storage views come back wrong). The LUT, a plain 2D storage texture, runs.
/// With `--backend auto` the refusal sends these kernels to the CPU backend.
pub const GL_UNSUPPORTED: &[&str] = &[
    "equirect_to_cube",
    "prefilter_specular",
    "prefilter_sheen",
    "irradiance",
];

/// A device and queue with the adapter they came from.
pub struct GpuContext {
    /// The logical device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// What wgpu reports about the adapter.
    pub adapter_info: wgpu::AdapterInfo,
    /// The first error wgpu reported outside an error scope, if any (instead of wgpu's
    /// default handler, which panics).
    uncaptured: Arc<Mutex<Option<String>>>,
    /// Why the device was lost, once it has been (wgpu's device-lost callback).
    lost: Arc<Mutex<Option<String>>>,
    /// The BC6H encoder, its pipeline compiled on first use and kept (compiling it takes a
    /// software adapter over a minute).
    pub(crate) bc6h: crate::gpu::bc6h::CompressorCache,
}

impl std::fmt::Debug for GpuContext {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuContext")
            .field("adapter", &self.adapter_description())
            .finish()
    }
}

impl GpuContext {
    /// Finds an adapter (preferring a high-performance one; `WGPU_BACKEND` restricts the
    /// backends) and creates a device with the adapter's own limits.
    pub fn new() -> Result<Self> {
        if std::env::var(HIDE_GPU_ENV).is_ok_and(|v| v != "0") {
            return Err(Error::NoAdapter {
                reason: format!("{HIDE_GPU_ENV} is set"),
            });
        }
        // Without WGPU_BACKEND, the primary backends (Vulkan, Metal, DX12) are searched
        // first and OpenGL only when they have no adapter: starting the GL backend (EGL)
        // costs ~0.04 CPU-s of every run, and GL runs fewer kernels (GL_UNSUPPORTED).
        let request = |backends: Option<wgpu::Backends>| {
            let mut desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
            if let Some(b) = backends {
                desc.backends = b;
            }
            let instance = wgpu::Instance::new(desc);
            pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                force_fallback_adapter: false,
                compatible_surface: None,
                apply_limit_buckets: false,
            }))
        };
        let adapter = match wgpu::Backends::from_env() {
            Some(_) => request(None),
            None => request(Some(wgpu::Backends::PRIMARY))
                .or_else(|_| request(Some(wgpu::Backends::SECONDARY))),
        }
        .map_err(|e| Error::NoAdapter {
            reason: e.to_string(),
        })?;
        Self::from_adapter(&adapter)
    }

    /// A device on `adapter` with the adapter's own limits and, where the adapter has it,
    /// filtering of 32-bit float textures (what the viewer's forward pass samples with;
    /// `view::gpu`), its errors and loss recorded (instead of wgpu's default handler,
    /// which panics).
    pub fn from_adapter(adapter: &wgpu::Adapter) -> Result<Self> {
        let adapter_info = adapter.get_info();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("splitsum"),
            required_features: adapter.features() & wgpu::Features::FLOAT32_FILTERABLE,
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| Error::Gpu {
            stage: format!("creating a device on {}", adapter_info.name),
            message: e.to_string(),
        })?;
        let uncaptured = Arc::new(Mutex::new(None::<String>));
        let sink = uncaptured.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            if let Ok(mut slot) = sink.lock() {
                slot.get_or_insert_with(|| e.to_string());
            }
        }));
        let lost = Arc::new(Mutex::new(None::<String>));
        let sink = lost.clone();
        device.set_device_lost_callback(move |reason, message| {
            if let Ok(mut slot) = sink.lock() {
                let why = match reason {
                    wgpu::DeviceLostReason::Destroyed => "it was destroyed",
                    wgpu::DeviceLostReason::Unknown => "driver error or reset",
                };
                let detail = if message.is_empty() {
                    String::new()
                } else {
                    format!(": {message}")
                };
                slot.get_or_insert_with(|| format!("the GPU device was lost ({why}){detail}"));
            }
        });
        Ok(GpuContext {
            device,
            queue,
            adapter_info,
            uncaptured,
            lost,
            bc6h: Default::default(),
        })
    }

    /// "name (backend, device type)", for `-v` output and manifests.
    pub fn adapter_description(&self) -> String {
        let i = &self.adapter_info;
        format!("{} ({:?}, {:?})", i.name, i.backend, i.device_type)
    }

    /// Why the device was lost, if it has been.
    pub fn lost_reason(&self) -> Option<String> {
        self.lost.lock().ok().and_then(|s| s.clone())
    }

    /// Runs one kernel: honours [`LOSE_DEVICE_ENV`], then turns any error the kernel
    /// returned or wgpu reported outside an error scope into [`Error::Gpu`] for
    /// `kernel`, naming a device loss as such (the raw wgpu error after a loss is a
    /// confusing "invalid pipeline" validation message).
    pub fn run_kernel<T>(
        &self,
        kernel: &str,
        f: impl FnOnce(&wgpu::Device, &wgpu::Queue) -> Result<T>,
    ) -> Result<T> {
        if self.adapter_info.backend == wgpu::Backend::Gl && GL_UNSUPPORTED.contains(&kernel) {
            return Err(Error::Gpu {
                stage: kernel.to_string(),
                message: format!(
                    "the OpenGL adapter {} cannot run it: on wgpu's GL backend the kernels \
                     that write cube faces through 2D-array storage views return wrong \
                     results; install a Vulkan driver (Linux: mesa-vulkan-drivers) or use \
                     --backend cpu",
                    self.adapter_description()
                ),
            });
        }
        if std::env::var(LOSE_DEVICE_ENV).is_ok_and(|v| v == kernel) {
            self.device.destroy();
        }
        let result = f(&self.device, &self.queue);
        let result = result.and_then(|v| self.take_uncaptured_error(kernel).map(|()| v));
        if result.is_err() {
            // Device-lost callbacks run from poll; let a pending one report.
            let _ = self.device.poll(wgpu::PollType::Poll);
        }
        match (result, self.lost_reason()) {
            (Err(Error::Gpu { .. }), Some(lost)) => Err(Error::Gpu {
                stage: kernel.to_string(),
                message: lost,
            }),
            (result, _) => result,
        }
    }

    /// Returns the first error wgpu reported outside an error scope since the last call.
    pub fn take_uncaptured_error(&self, stage: &str) -> Result<()> {
        let taken = self.uncaptured.lock().ok().and_then(|mut s| s.take());
        match taken {
            Some(message) => Err(Error::Gpu {
                stage: stage.to_string(),
                message,
            }),
            None => Ok(()),
        }
    }
}
