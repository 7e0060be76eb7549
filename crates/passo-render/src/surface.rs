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
    /// The format to draw the scene in: the sRGB view of the surface when
    /// it has one.
    srgb_view: Option<wgpu::TextureFormat>,
    /// False while the window is 0×0.
    configured: bool,
    /// The last frame was suboptimal: reconfigure before the next one.
    stale: bool,
}

impl WindowSurface {
    /// Configures `surface` for a window of `size` pixels. With `capture`,
    /// frames can also be copied out ([`read_texture`](crate::read_texture))
    /// for screenshots, if the surface allows it.
    ///
    /// The surface gets a plain (`*Unorm`) format, which user-interface
    /// libraries such as egui expect, plus an sRGB view format where the
    /// adapter allows views of another format: draw the scene through
    /// [`scene_view`](Self::scene_view) in [`scene_format`](Self::scene_format)
    /// for blending in linear light. Without such views the scene is drawn
    /// in the plain format and the renderer encodes sRGB itself.
    pub fn new(
        gpu: &Gpu,
        surface: wgpu::Surface<'static>,
        size: (u32, u32),
        capture: bool,
    ) -> Result<Self, RenderError> {
        let caps = surface.get_capabilities(&gpu.adapter);
        let mut usage = wgpu::TextureUsages::RENDER_ATTACHMENT;
        if capture && caps.usages.contains(wgpu::TextureUsages::COPY_SRC) {
            usage |= wgpu::TextureUsages::COPY_SRC;
        }
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| !f.is_srgb())
            .or_else(|| caps.formats.first().copied())
            .ok_or_else(|| {
                RenderError::Device(
                    "the window surface offers no pixel format (under Xvfb use a 24-bit screen: \
                     -screen 0 1280x800x24)"
                        .into(),
                )
            })?;
        let can_view = gpu
            .adapter
            .get_downlevel_capabilities()
            .flags
            .contains(wgpu::DownlevelFlags::SURFACE_VIEW_FORMATS);
        let srgb = format.add_srgb_suffix();
        let srgb_view = (can_view && srgb != format).then_some(srgb);
        let config = wgpu::SurfaceConfiguration {
            usage,
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
            view_formats: srgb_view.into_iter().collect(),
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        let mut this = Self {
            surface,
            config,
            srgb_view,
            configured: false,
            stale: false,
        };
        this.resize(&gpu.device, size);
        Ok(this)
    }

    /// The surface's pixel format (for a user interface drawn on top).
    pub fn format(&self) -> wgpu::TextureFormat {
        self.config.format
    }

    /// The format to build the scene's [`Renderer`](crate::Renderer) for.
    pub fn scene_format(&self) -> wgpu::TextureFormat {
        self.srgb_view.unwrap_or(self.config.format)
    }

    /// A view of `frame` in [`scene_format`](Self::scene_format).
    pub fn scene_view(&self, frame: &wgpu::SurfaceTexture) -> wgpu::TextureView {
        frame.texture.create_view(&wgpu::TextureViewDescriptor {
            format: Some(self.scene_format()),
            ..Default::default()
        })
    }

    /// Whether frames can be copied out for screenshots.
    pub fn can_capture(&self) -> bool {
        self.config.usage.contains(wgpu::TextureUsages::COPY_SRC)
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
    /// a real size arrives. A side larger than the device's largest texture
    /// (`max_texture_dimension_2d`) is lowered to it (the compositor
    /// stretches the picture).
    pub fn resize(&mut self, device: &wgpu::Device, size: (u32, u32)) {
        if size.0 == 0 || size.1 == 0 {
            self.configured = false;
            return;
        }
        let max = device.limits().max_texture_dimension_2d;
        self.config.width = size.0.min(max);
        self.config.height = size.1.min(max);
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
