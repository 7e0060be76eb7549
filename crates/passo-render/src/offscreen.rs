//! Rendering to a texture and reading it back.

use crate::{Gpu, RenderError, RgbaImage};

/// A texture to render into, with a buffer to read it back.
///
/// Its format is `Rgba8UnormSrgb`: the renderer writes sRGB-encoded bytes,
/// blended in linear light, exactly what a PNG holds.
#[derive(Debug)]
pub struct OffscreenTarget {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    readback: wgpu::Buffer,
    size: (u32, u32),
    padded_row: u32,
}

/// Texture-to-buffer copies need rows aligned to this many bytes.
const ROW_ALIGN: u32 = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;

impl OffscreenTarget {
    /// A `width` × `height` target (each at least 1 pixel; 0 is raised to 1).
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> Self {
        Self::with_format(gpu, width, height, wgpu::TextureFormat::Rgba8UnormSrgb)
    }

    /// A target of an RGBA8 format: `Rgba8UnormSrgb` or `Rgba8Unorm`.
    pub fn with_format(gpu: &Gpu, width: u32, height: u32, format: wgpu::TextureFormat) -> Self {
        assert!(
            matches!(
                format,
                wgpu::TextureFormat::Rgba8UnormSrgb | wgpu::TextureFormat::Rgba8Unorm
            ),
            "OffscreenTarget reads back RGBA8 formats only, not {format:?}"
        );
        let size = (width.max(1), height.max(1));
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("passo offscreen target"),
            size: wgpu::Extent3d {
                width: size.0,
                height: size.1,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let padded_row = (size.0 * 4).div_ceil(ROW_ALIGN) * ROW_ALIGN;
        let readback = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("passo offscreen readback"),
            size: u64::from(padded_row) * u64::from(size.1),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        Self {
            texture,
            view,
            readback,
            size,
            padded_row,
        }
    }

    /// The view to render into.
    pub fn view(&self) -> &wgpu::TextureView {
        &self.view
    }

    /// Width and height, pixels.
    pub fn size(&self) -> (u32, u32) {
        self.size
    }

    /// The texture format.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.texture.format()
    }

    /// Copies the texture to memory (waiting for the GPU) and strips the
    /// row padding the copy needs.
    pub fn read(&self, gpu: &Gpu) -> Result<RgbaImage, RenderError> {
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("passo readback"),
            });
        encoder.copy_texture_to_buffer(
            self.texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &self.readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(self.padded_row),
                    rows_per_image: Some(self.size.1),
                },
            },
            wgpu::Extent3d {
                width: self.size.0,
                height: self.size.1,
                depth_or_array_layers: 1,
            },
        );
        gpu.queue.submit(Some(encoder.finish()));
        let slice = self.readback.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |result| {
            let _ = tx.send(result);
        });
        gpu.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        rx.recv()
            .map_err(|e| RenderError::Readback(e.to_string()))?
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        let row = (self.size.0 * 4) as usize;
        let mut pixels = Vec::with_capacity(row * self.size.1 as usize);
        {
            let data = slice
                .get_mapped_range()
                .map_err(|e| RenderError::Readback(e.to_string()))?;
            for chunk in data
                .chunks(self.padded_row as usize)
                .take(self.size.1 as usize)
            {
                pixels.extend_from_slice(&chunk[..row]);
            }
        }
        self.readback.unmap();
        Ok(RgbaImage {
            width: self.size.0,
            height: self.size.1,
            pixels,
        })
    }
}
