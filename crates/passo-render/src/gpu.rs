//! Choosing an adapter and opening a device.

use std::fmt;

/// Which adapter to render with.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AdapterChoice {
    /// The system's preferred adapter (a GPU if there is one).
    #[default]
    Default,
    /// The software fallback (Mesa's lavapipe on Linux): slower, but
    /// present on machines without a GPU and the same everywhere, which is
    /// what tests and CI want.
    Software,
}

impl AdapterChoice {
    /// `PASSO_ADAPTER=software` or `PASSO_ADAPTER=default`; `default`
    /// when unset. `WGPU_BACKEND=vulkan|gl` still picks the backend.
    pub fn from_env() -> Result<Self, RenderError> {
        match std::env::var("PASSO_ADAPTER").as_deref() {
            Err(_) | Ok("") | Ok("default") => Ok(Self::Default),
            Ok("software") => Ok(Self::Software),
            Ok(other) => Err(RenderError::BadAdapterChoice(other.to_owned())),
        }
    }
}

/// Why rendering could not start or finish.
#[derive(Debug)]
pub enum RenderError {
    /// No adapter matched: no GPU driver and no software driver.
    NoAdapter(String),
    /// The adapter refused to open a device.
    Device(String),
    /// `PASSO_ADAPTER` had a value other than `software` or `default`.
    BadAdapterChoice(String),
    /// Reading the picture back from the GPU failed.
    Readback(String),
    /// Writing or reading a PNG file failed.
    Image(String),
}

impl fmt::Display for RenderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoAdapter(detail) => write!(
                f,
                "no graphics adapter found ({detail}). To render without a GPU install Mesa's \
                 software Vulkan driver and the Vulkan loader: \
                 `sudo apt-get install mesa-vulkan-drivers libvulkan1` (Debian/Ubuntu)"
            ),
            Self::Device(detail) => write!(f, "the graphics adapter refused a device: {detail}"),
            Self::BadAdapterChoice(value) => write!(
                f,
                "PASSO_ADAPTER must be `software` or `default`, got `{value}`"
            ),
            Self::Readback(detail) => write!(f, "reading the picture back failed: {detail}"),
            Self::Image(detail) => write!(f, "image file: {detail}"),
        }
    }
}

impl std::error::Error for RenderError {}

/// An instance, an adapter, and a device with its queue.
#[derive(Clone, Debug)]
pub struct Gpu {
    /// The wgpu instance (needed to make window surfaces).
    pub instance: wgpu::Instance,
    /// The chosen adapter.
    pub adapter: wgpu::Adapter,
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
}

impl Gpu {
    /// Opens a device for off-screen rendering (no window, no display).
    /// Blocks until it is open: in a browser, where nothing may block, it
    /// returns an error; use [`open`](Self::open) there.
    pub fn headless(choice: AdapterChoice) -> Result<Self, RenderError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        Self::with_instance(instance, choice, None)
    }

    /// Opens a device on `instance` that can present to `surface`, if given.
    /// Blocks until it is open; in a browser, where nothing may block, use
    /// [`open`](Self::open).
    pub fn with_instance(
        instance: wgpu::Instance,
        choice: AdapterChoice,
        surface: Option<&wgpu::Surface<'_>>,
    ) -> Result<Self, RenderError> {
        #[cfg(not(target_arch = "wasm32"))]
        return pollster::block_on(Self::open(instance, choice, surface));
        #[cfg(target_arch = "wasm32")]
        {
            let _ = (instance, choice, surface);
            Err(RenderError::NoAdapter(
                "a browser cannot wait for a GPU: open it with `Gpu::open(..).await`".into(),
            ))
        }
    }

    /// Opens a device on `instance` that can present to `surface`, if
    /// given, without blocking. A WebGL2 adapter gets WebGL2's limits.
    pub async fn open(
        instance: wgpu::Instance,
        choice: AdapterChoice,
        surface: Option<&wgpu::Surface<'_>>,
    ) -> Result<Self, RenderError> {
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::default(),
                force_fallback_adapter: choice == AdapterChoice::Software,
                compatible_surface: surface,
                ..Default::default()
            })
            .await
            .map_err(|e| RenderError::NoAdapter(e.to_string()))?;
        let info = adapter.get_info();
        log::info!(
            "adapter: {} ({:?}, {:?} backend, driver {} {})",
            info.name,
            info.device_type,
            info.backend,
            info.driver,
            info.driver_info
        );
        let limits = if info.backend == wgpu::Backend::Gl {
            wgpu::Limits::downlevel_webgl2_defaults()
        } else {
            wgpu::Limits::downlevel_defaults()
        };
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("passo device"),
                required_limits: limits.using_resolution(adapter.limits()),
                ..Default::default()
            })
            .await
            .map_err(|e| RenderError::Device(e.to_string()))?;
        Ok(Self {
            instance,
            adapter,
            device,
            queue,
        })
    }

    /// A one-line description of the adapter, for logs and reports.
    pub fn adapter_summary(&self) -> String {
        let info = self.adapter.get_info();
        format!("{} ({:?}, {:?})", info.name, info.device_type, info.backend)
    }
}
