//! RGBA images read back from the GPU, saved and loaded as PNG.

use crate::RenderError;
use std::path::Path;

/// An 8-bit RGBA image, rows top to bottom, sRGB-encoded like a PNG.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RgbaImage {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// `width * height * 4` bytes.
    pub pixels: Vec<u8>,
}

impl RgbaImage {
    /// The pixel at `(x, y)` (origin top left), or `None` outside (or
    /// beyond `pixels`, should it be shorter than `width * height * 4`).
    pub fn get(&self, x: u32, y: u32) -> Option<[u8; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = (y as usize * self.width as usize + x as usize) * 4;
        self.pixels.get(i..i + 4)?.try_into().ok()
    }

    /// Writes the image as a PNG file.
    pub fn save_png(&self, path: impl AsRef<Path>) -> Result<(), RenderError> {
        let path = path.as_ref();
        let err =
            |e: &dyn std::fmt::Display| RenderError::Image(format!("{}: {e}", path.display()));
        // Checked before the file is made: a picture that cannot be written
        // leaves a picture already there as it was.
        let want = self.width as usize * self.height as usize * 4;
        if self.pixels.len() != want || self.width == 0 || self.height == 0 {
            return Err(err(&format!(
                "a {} × {} picture needs {want} bytes of pixels, it has {}",
                self.width,
                self.height,
                self.pixels.len()
            )));
        }
        let file = std::fs::File::create(path).map_err(|e| err(&e))?;
        let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), self.width, self.height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        let mut writer = encoder.write_header().map_err(|e| err(&e))?;
        writer.write_image_data(&self.pixels).map_err(|e| err(&e))?;
        writer.finish().map_err(|e| err(&e))
    }

    /// Reads an 8-bit RGBA or RGB PNG file.
    pub fn load_png(path: impl AsRef<Path>) -> Result<Self, RenderError> {
        let path = path.as_ref();
        let file = std::fs::File::open(path)
            .map_err(|e| RenderError::Image(format!("{}: {e}", path.display())))?;
        Self::read_png(std::io::BufReader::new(file), &path.display().to_string())
    }

    /// Decodes an 8-bit RGBA or RGB PNG held in memory; `name` names it in
    /// errors.
    pub fn decode_png(bytes: &[u8], name: &str) -> Result<Self, RenderError> {
        Self::read_png(std::io::Cursor::new(bytes), name)
    }

    fn read_png(
        source: impl std::io::BufRead + std::io::Seek,
        name: &str,
    ) -> Result<Self, RenderError> {
        let err = |e: &dyn std::fmt::Display| RenderError::Image(format!("{name}: {e}"));
        let mut decoder = png::Decoder::new(source);
        decoder.set_transformations(png::Transformations::EXPAND);
        let mut reader = decoder.read_info().map_err(|e| err(&e))?;
        let mut buf = vec![
            0;
            reader
                .output_buffer_size()
                .ok_or_else(|| err(&"image too large"))?
        ];
        let info = reader.next_frame(&mut buf).map_err(|e| err(&e))?;
        if info.bit_depth != png::BitDepth::Eight {
            return Err(err(&format!(
                "{:?} bits per channel; 8 expected",
                info.bit_depth
            )));
        }
        let pixels = match info.color_type {
            png::ColorType::Rgba => buf[..info.buffer_size()].to_vec(),
            png::ColorType::Rgb => buf[..info.buffer_size()]
                .chunks_exact(3)
                .flat_map(|c| [c[0], c[1], c[2], 255])
                .collect(),
            other => return Err(err(&format!("{other:?} pixels; RGB or RGBA expected"))),
        };
        Ok(Self {
            width: info.width,
            height: info.height,
            pixels,
        })
    }

    /// Per-pixel difference: the largest channel difference of each pixel.
    /// `None` if the sizes differ.
    pub fn difference(&self, other: &Self) -> Option<Vec<u8>> {
        if (self.width, self.height) != (other.width, other.height) {
            return None;
        }
        Some(
            self.pixels
                .chunks_exact(4)
                .zip(other.pixels.chunks_exact(4))
                .map(|(a, b)| (0..4).map(|i| a[i].abs_diff(b[i])).max().unwrap_or(0))
                .collect(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn get_reads_pixels_and_answers_none_outside_or_past_a_short_buffer() {
        let image = RgbaImage {
            width: 4,
            height: 4,
            pixels: (0..64).collect(),
        };
        assert_eq!(image.get(1, 2), Some([36, 37, 38, 39]));
        assert_eq!(image.get(4, 0), None);
        assert_eq!(image.get(0, 4), None);
        // The fields are public: a buffer shorter than the size says.
        let short = RgbaImage {
            pixels: vec![0; 8],
            ..image
        };
        assert_eq!(short.get(1, 0), Some([0; 4]));
        assert_eq!(short.get(3, 3), None, "it panicked");
    }

    #[test]
    fn a_picture_that_cannot_be_saved_leaves_the_file_there_as_it_was() {
        let dir = std::env::temp_dir().join(format!("passo-png-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("kept.png");
        let good = RgbaImage {
            width: 2,
            height: 2,
            pixels: (0..16).collect(),
        };
        good.save_png(&path).unwrap();
        let short = RgbaImage {
            width: 3,
            ..good.clone()
        };
        let err = short.save_png(&path).unwrap_err().to_string();
        assert!(err.contains("needs 24 bytes of pixels, it has 16"), "{err}");
        assert_eq!(RgbaImage::load_png(&path).unwrap(), good, "emptied before");
        std::fs::remove_dir_all(dir).unwrap();
    }
}
