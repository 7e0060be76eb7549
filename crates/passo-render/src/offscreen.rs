//! Rendering to a texture and reading it back.

use crate::{Gpu, RenderError, RgbaImage};

/// A texture to render into and read back.
///
/// Its format is `Rgba8UnormSrgb`: the renderer writes sRGB-encoded bytes,
/// blended in linear light, exactly what a PNG holds.
#[derive(Debug)]
pub struct OffscreenTarget {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    size: (u32, u32),
}

/// Texture-to-buffer copies need rows aligned to this many bytes.
const ROW_ALIGN: u32 = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;

impl OffscreenTarget {
    /// A `width` × `height` target: each side at least 1 pixel and at most
    /// the device's largest texture (`max_texture_dimension_2d`, 8192 or
    /// more); 0 is raised to 1 and a larger side lowered to that, so
    /// [`size`](Self::size) is the size made.
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
        let max = gpu.device.limits().max_texture_dimension_2d;
        let size = (width.clamp(1, max), height.clamp(1, max));
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
        Self {
            texture,
            view,
            size,
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

    /// Copies the texture to memory (waiting for the GPU).
    pub fn read(&self, gpu: &Gpu) -> Result<RgbaImage, RenderError> {
        read_texture(gpu, &self.texture)
    }
}

/// Copies an RGBA8 or BGRA8 texture (with `COPY_SRC` usage) to memory,
/// waiting for the GPU: strips the 256-byte row padding the copy needs and
/// swaps BGRA to RGBA. Used for off-screen targets and window screenshots.
/// A texture larger than the device's largest buffer (`max_buffer_size`,
/// 256 MiB on lavapipe: an 8 193 × 8 193 target) is read in bands of rows.
pub fn read_texture(gpu: &Gpu, texture: &wgpu::Texture) -> Result<RgbaImage, RenderError> {
    use wgpu::TextureFormat as F;
    // What the copy needs, checked here: wgpu panics on either.
    if texture.sample_count() != 1 {
        return Err(RenderError::Readback(format!(
            "cannot read back a multisampled texture ({} samples): resolve it first",
            texture.sample_count()
        )));
    }
    if !texture.usage().contains(wgpu::TextureUsages::COPY_SRC) {
        return Err(RenderError::Readback(
            "cannot read back a texture without COPY_SRC usage".into(),
        ));
    }
    let bgra = match texture.format() {
        F::Rgba8Unorm | F::Rgba8UnormSrgb => false,
        F::Bgra8Unorm | F::Bgra8UnormSrgb => true,
        other => {
            return Err(RenderError::Readback(format!(
                "cannot read back {other:?} textures (RGBA8 or BGRA8 only)"
            )));
        }
    };
    let (width, height) = (texture.width(), texture.height());
    let padded_row = (width * 4).div_ceil(ROW_ALIGN) * ROW_ALIGN;
    let band = rows_per_band(padded_row, height, gpu.device.limits().max_buffer_size);
    let mut pixels = Vec::with_capacity((width * 4) as usize * height as usize);
    for first in (0..height).step_by(band as usize) {
        read_rows(
            gpu,
            texture,
            first..(first + band).min(height),
            padded_row,
            &mut pixels,
        )?;
    }
    if bgra {
        for p in pixels.chunks_exact_mut(4) {
            p.swap(0, 2);
        }
    }
    Ok(RgbaImage {
        width,
        height,
        pixels,
    })
}

/// How many rows of `padded_row` bytes one read-back buffer holds: all
/// `height` if they fit in `max_buffer_size` bytes, else as many as fit
/// (at least one).
fn rows_per_band(padded_row: u32, height: u32, max_buffer_size: u64) -> u32 {
    let fit = max_buffer_size / u64::from(padded_row.max(1));
    u32::try_from(fit)
        .unwrap_or(u32::MAX)
        .clamp(1, height.max(1))
}

/// Copies the texture's `rows` to memory through one buffer, appending
/// them without their padding to `pixels`.
fn read_rows(
    gpu: &Gpu,
    texture: &wgpu::Texture,
    rows: std::ops::Range<u32>,
    padded_row: u32,
    pixels: &mut Vec<u8>,
) -> Result<(), RenderError> {
    let (width, height) = (texture.width(), rows.end - rows.start);
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("passo readback"),
        size: u64::from(padded_row) * u64::from(height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("passo readback"),
        });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            origin: wgpu::Origin3d {
                x: 0,
                y: rows.start,
                z: 0,
            },
            ..texture.as_image_copy()
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded_row),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    gpu.queue.submit(Some(encoder.finish()));
    let slice = buffer.slice(..);
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
    let row = (width * 4) as usize;
    {
        let data = slice
            .get_mapped_range()
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        for chunk in data.chunks(padded_row as usize).take(height as usize) {
            pixels.extend_from_slice(&chunk[..row]);
        }
    }
    buffer.unmap();
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::rows_per_band;

    #[test]
    fn bands_hold_as_many_rows_as_the_largest_buffer_does() {
        // 16 384 pixels a row (64 KiB), 256 MiB buffers: 4 096 rows a band.
        assert_eq!(rows_per_band(65_536, 4_200, 256 << 20), 4_096);
        assert_eq!(rows_per_band(65_536, 100, 256 << 20), 100, "all in one");
        assert_eq!(rows_per_band(65_536, 4_200, 1_000), 1, "at least a row");
        assert_eq!(rows_per_band(256, 0, 256 << 20), 1);
        assert_eq!(rows_per_band(256, 10, u64::MAX), 10);
    }
}
