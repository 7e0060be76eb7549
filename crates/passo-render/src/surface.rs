//! A window surface: configure, resize, acquire, with the rules every
//! window needs in one place.

use crate::{Gpu, RenderError};

/// A window's surface and its configuration.
///
/// - [`resize`](Self::resize) ignores 0×0 (a minimised window): nothing is
///   configured or drawn until the window has a size again.
/// - [`acquire`](Self::acquire) handles every outcome of asking for the next
///   frame: `Lost` and `Outdated` reconfigure here and skip the frame,
///   `Timeout` and `Occluded` skip it, a validation error is logged. It never
///   panics; a skipped frame is simply not drawn.
#[derive(Debug)]
pub struct WindowSurface {
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    /// False while the window is 0×0.
    configured: bool,
    /// The last frame was suboptimal: reconfigure before the next one.
    stale: bool,
}

impl WindowSurface {
    /// Configures `surface` for a window of `size` pixels, preferring an
    /// sRGB format.
    pub fn new(
        gpu: &Gpu,
        surface: wgpu::Surface<'static>,
        size: (u32, u32),
    ) -> Result<Self, RenderError> {
        let caps = surface.get_capabilities(&gpu.adapter);
        let format = caps
            .formats
            .iter()
            .copied()
            .find(wgpu::TextureFormat::is_srgb)
            .or_else(|| caps.formats.first().copied())
            .ok_or_else(|| {
                RenderError::Device(
                    "the window surface offers no pixel format (under Xvfb use a 24-bit screen: \
                     -screen 0 1280x800x24)"
                        .into(),
                )
            })?;
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            width: size.0.max(1),
            height: size.1.max(1),
            present_mode: wgpu::PresentMode::Fifo,
            desired_maximum_frame_latency: 2,
            alpha_mode: caps
                .alpha_modes
                .first()
                .copied()
                .unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: vec![],
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        let mut this = Self {
            surface,
            config,
            configured: false,
            stale: false,
        };
        this.resize(&gpu.device, size);
        Ok(this)
    }

    /// The surface's pixel format (build the [`Renderer`](crate::Renderer) for it).
    pub fn format(&self) -> wgpu::TextureFormat {
        self.config.format
    }

    /// The configured size, pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.config.width, self.config.height)
    }

    /// Whether the window has a drawable size (not minimised).
    pub fn is_drawable(&self) -> bool {
        self.configured
    }

    /// Follows the window's new size. A 0×0 size (minimised) is ignored:
    /// the surface keeps its old configuration and frames are skipped until
    /// a real size arrives.
    pub fn resize(&mut self, device: &wgpu::Device, size: (u32, u32)) {
        if size.0 == 0 || size.1 == 0 {
            self.configured = false;
            return;
        }
        self.config.width = size.0;
        self.config.height = size.1;
        self.surface.configure(device, &self.config);
        self.configured = true;
        self.stale = false;
    }

    /// The next frame to draw into, or `None` to skip this frame.
    pub fn acquire(&mut self, device: &wgpu::Device) -> Option<wgpu::SurfaceTexture> {
        if !self.configured {
            return None;
        }
        if self.stale {
            self.resize(device, self.size());
        }
        match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame) => Some(frame),
            wgpu::CurrentSurfaceTexture::Suboptimal(frame) => {
                self.stale = true;
                Some(frame)
            }
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => None,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                log::info!("surface outdated or lost: reconfiguring");
                self.resize(device, self.size());
                None
            }
            wgpu::CurrentSurfaceTexture::Validation => {
                log::error!("surface validation error while acquiring a frame; skipping it");
                None
            }
        }
    }
}
