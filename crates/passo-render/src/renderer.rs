//! The renderer: pipelines and buffers for one target format.

use crate::draw_list::{LineInstance, ShapeInstance, SpriteInstance, TextureId};
use crate::{Camera2D, DrawList, Gpu, RenderError, RgbaImage};
use bytemuck::{Pod, Zeroable};
use glam::{DVec2, Vec2};

/// The shape pipeline's WGSL, built in: `crates/passo-render/shaders/`
/// `common.wgsl` then `shapes.wgsl`.
pub const SHAPES_WGSL: &str = concat!(
    include_str!("../shaders/common.wgsl"),
    include_str!("../shaders/shapes.wgsl")
);
/// The line pipeline's WGSL: `common.wgsl` then `lines.wgsl`.
pub const LINES_WGSL: &str = concat!(
    include_str!("../shaders/common.wgsl"),
    include_str!("../shaders/lines.wgsl")
);
/// The sprite pipeline's WGSL: `common.wgsl` then `sprites.wgsl`.
pub const SPRITES_WGSL: &str = concat!(
    include_str!("../shaders/common.wgsl"),
    include_str!("../shaders/sprites.wgsl")
);

/// Per-frame constants, the uniform at `@group(0) @binding(0)`. Mirrors
/// `Globals` in `shaders/common.wgsl` field for field; `tests/shaders.rs` compares
/// the layouts. Public only for that test.
#[doc(hidden)]
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct Globals {
    /// World point at the centre of the target, metres.
    pub centre: [f32; 2],
    /// World to clip space: `clip = (world - centre) * scale`.
    pub scale: [f32; 2],
    /// Metres per pixel.
    pub pixel_size: f32,
    /// 1 when the shader encodes sRGB itself (a `*Unorm` target), else 0.
    pub encode_srgb: u32,
    /// Padding to a 16-byte multiple.
    pub _pad: [f32; 2],
}

/// Draws [`DrawList`]s into texture views of one format.
///
/// ```
/// use passo_render::{AdapterChoice, Camera2D, DrawList, Gpu, OffscreenTarget, Renderer};
/// use passo_render::glam::Vec2;
///
/// // Mesa's software adapter (lavapipe) works on a machine without a GPU.
/// let gpu = Gpu::headless(AdapterChoice::Software)?;
/// let target = OffscreenTarget::new(&gpu, 200, 100);
/// let mut renderer = Renderer::new(&gpu, target.format());
/// let mut list = DrawList::new([0, 0, 0, 255]);
/// list.rect(Vec2::new(-1.0, 0.0), Vec2::new(0.5, 0.5), [40, 200, 90, 255]);
/// // A 4 m × 2 m view: 50 px per metre, (0, 0) at the picture's centre.
/// let camera = Camera2D::fit(Vec2::new(-2.0, -1.0), Vec2::new(2.0, 1.0), target.size());
/// renderer.render(target.view(), target.size(), &camera, &list);
/// let image = target.read(&gpu)?;
/// assert_eq!(image.get(50, 50), Some([40, 200, 90, 255])); // the box, at x = -1 m
/// assert_eq!(image.get(150, 50), Some([0, 0, 0, 255])); // the background
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// Owns its pipelines and buffers. Instance buffers grow to the largest
/// list seen and are reused, so frames that draw no more than before
/// allocate nothing. A list longer than the device's largest buffer
/// (`max_buffer_size`: 4 194 304 shapes or 5 592 405 lines in 256 MiB) draws
/// as many as that holds, in the list's order, and logs a warning.
#[derive(Debug)]
pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    format: wgpu::TextureFormat,
    shapes: wgpu::RenderPipeline,
    lines: wgpu::RenderPipeline,
    sprites: wgpu::RenderPipeline,
    /// The layout of a texture's bind group (`@group(1)` of the sprites).
    texture_layout: wgpu::BindGroupLayout,
    nearest: wgpu::Sampler,
    /// One bind group per texture added, by [`TextureId`].
    textures: Vec<wgpu::BindGroup>,
    sprite_buffer: wgpu::Buffer,
    sprite_capacity: usize,
    /// The frame's sprite instances, gathered for upload.
    sprite_instances: Vec<SpriteInstance>,
    globals: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    shape_buffer: wgpu::Buffer,
    shape_capacity: usize,
    line_buffer: wgpu::Buffer,
    line_capacity: usize,
    /// The lines of the frame cut to the view, when some reach far past it
    /// (see [`lines_in_view`]).
    cut_lines: Vec<LineInstance>,
    /// A list has been longer than the device's largest buffer (warned
    /// once, not every frame).
    over_capacity: bool,
}

impl Renderer {
    /// A renderer for targets of `format`. With a `*Srgb` format the
    /// hardware encodes colours and blends in linear light; with a `*Unorm`
    /// format the shaders encode sRGB themselves, so both give the same
    /// picture.
    ///
    /// # Panics
    /// If `format` is not a colour format the device blends (wgpu refuses
    /// the pipeline): use a surface's format or an 8-bit RGBA or BGRA one.
    pub fn new(gpu: &Gpu, format: wgpu::TextureFormat) -> Self {
        let device = &gpu.device;
        let globals = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("passo globals"),
            size: std::mem::size_of::<Globals>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("passo globals layout"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("passo globals bind group"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: globals.as_entire_binding(),
            }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("passo pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let texture_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("passo texture layout"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
            ],
        });
        let sprite_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("passo sprite pipeline layout"),
            bind_group_layouts: &[Some(&layout), Some(&texture_layout)],
            immediate_size: 0,
        });
        let pipeline = |label: &str,
                        source: &str,
                        pipeline_layout: &wgpu::PipelineLayout,
                        instances: wgpu::VertexBufferLayout<'static>| {
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_main"),
                    compilation_options: Default::default(),
                    buffers: &[Some(instances)],
                },
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: None,
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs_main"),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format,
                        blend: Some(wgpu::BlendState::ALPHA_BLENDING),
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let shapes = pipeline(
            "passo shapes",
            SHAPES_WGSL,
            &pipeline_layout,
            ShapeInstance::LAYOUT,
        );
        let lines = pipeline(
            "passo lines",
            LINES_WGSL,
            &pipeline_layout,
            LineInstance::LAYOUT,
        );
        let sprites = pipeline(
            "passo sprites",
            SPRITES_WGSL,
            &sprite_layout,
            SpriteInstance::LAYOUT,
        );
        // Nearest texels: tiles of pixel art stay sharp at any zoom.
        let nearest = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("passo nearest sampler"),
            ..Default::default()
        });
        let shape_buffer = instance_buffer(device, "passo shape instances", 256 * 64);
        let line_buffer = instance_buffer(device, "passo line instances", 256 * 48);
        Self {
            device: device.clone(),
            queue: gpu.queue.clone(),
            format,
            shapes,
            lines,
            sprites,
            texture_layout,
            nearest,
            textures: Vec::new(),
            sprite_buffer: instance_buffer(device, "passo sprite instances", 256 * 32),
            sprite_capacity: 256,
            sprite_instances: Vec::new(),
            globals,
            bind_group,
            shape_buffer,
            shape_capacity: 256,
            line_buffer,
            line_capacity: 256,
            cut_lines: Vec::new(),
            over_capacity: false,
        }
    }

    /// The target format the pipelines were built for.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.format
    }

    /// Uploads `image` (8-bit sRGB RGBA, as [`RgbaImage::load_png`]
    /// reads a PNG) as a texture that [`DrawList::sprite`] can show parts
    /// of: a tileset image. Textures live as long as the renderer.
    ///
    /// # Errors
    /// [`RenderError::Image`] for an empty image, one whose pixels do not
    /// match its size, or one larger than the device's largest texture.
    pub fn add_texture(&mut self, image: &RgbaImage) -> Result<TextureId, RenderError> {
        let (w, h) = (image.width, image.height);
        let most = self.device.limits().max_texture_dimension_2d;
        if w == 0 || h == 0 || w > most || h > most {
            return Err(RenderError::Image(format!(
                "a {w} × {h} texture: each side must be 1 to {most} pixels"
            )));
        }
        if image.pixels.len() != w as usize * h as usize * 4 {
            return Err(RenderError::Image(format!(
                "a {w} × {h} texture needs {} bytes of pixels, it has {}",
                w as usize * h as usize * 4,
                image.pixels.len()
            )));
        }
        let size = wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        };
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("passo sprite texture"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            // sRGB: sampling gives linear light, as the shapes' colours are.
            format: wgpu::TextureFormat::Rgba8UnormSrgb,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        self.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            &image.pixels,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * w),
                rows_per_image: Some(h),
            },
            size,
        );
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("passo sprite texture bind group"),
            layout: &self.texture_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Sampler(&self.nearest),
                },
            ],
        });
        let id = TextureId(u32::try_from(self.textures.len()).unwrap_or(u32::MAX));
        self.textures.push(group);
        Ok(id)
    }

    /// Draws `list` into `view` (of `size` pixels) and submits the work.
    pub fn render(
        &mut self,
        view: &wgpu::TextureView,
        size: (u32, u32),
        camera: &Camera2D,
        list: &DrawList,
    ) {
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("passo frame"),
            });
        self.encode(&mut encoder, view, size, camera, list);
        self.queue.submit(Some(encoder.finish()));
    }

    /// Records the drawing of `list` into `encoder`, clearing `view` first,
    /// so a caller can add its own passes (a user interface) before
    /// submitting. Uploads go through the queue: encode one list per
    /// submission. A zero-sized target draws nothing; a camera that is not
    /// [usable](Camera2D::is_usable) (a NaN centre, a zero height) draws
    /// the background alone.
    pub fn encode(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        view: &wgpu::TextureView,
        size: (u32, u32),
        camera: &Camera2D,
        list: &DrawList,
    ) {
        if size.0 == 0 || size.1 == 0 {
            return;
        }
        let (centre, scale) = camera.clip_transform(size);
        let globals = Globals {
            centre: centre.to_array(),
            scale: scale.to_array(),
            pixel_size: camera.pixel_size(size),
            encode_srgb: u32::from(!self.format.is_srgb()),
            _pad: [0.0; 2],
        };
        self.queue
            .write_buffer(&self.globals, 0, bytemuck::bytes_of(&globals));
        // Sprites of a texture this renderer does not hold are left out.
        let known = self.textures.len();
        self.sprite_instances.clear();
        self.sprite_instances.extend(
            list.sprites
                .iter()
                .filter(|s| (s.texture.0 as usize) < known)
                .map(|s| s.instance),
        );
        let sprites = upload(
            &self.device,
            &self.queue,
            &mut self.sprite_buffer,
            &mut self.sprite_capacity,
            "passo sprite instances",
            &self.sprite_instances,
        );
        let shapes = upload(
            &self.device,
            &self.queue,
            &mut self.shape_buffer,
            &mut self.shape_capacity,
            "passo shape instances",
            &list.shapes,
        );
        let in_view = lines_in_view(&list.lines, centre, scale, size, &mut self.cut_lines);
        let lines = upload(
            &self.device,
            &self.queue,
            &mut self.line_buffer,
            &mut self.line_capacity,
            "passo line instances",
            in_view,
        );
        let cut = shapes as usize != list.shapes.len() || lines as usize != in_view.len();
        if cut && !std::mem::replace(&mut self.over_capacity, true) {
            log::warn!(
                "{} shapes and {} lines to draw, the device's largest buffer holds {shapes} and \
                 {lines}: drawing those (said once)",
                list.shapes.len(),
                list.lines.len()
            );
        }
        let [r, g, b, a] = list.clear_colour.map(f64::from);
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("passo bodies"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(clear_colour(self.format, [r, g, b, a])),
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        if !camera.is_usable() {
            return;
        }
        pass.set_bind_group(0, &self.bind_group, &[]);
        if let Some(clip) = list.clip {
            // Cut to the target itself too: a scissor past it is a wgpu
            // validation panic, and `size` is the caller's word for it.
            let target = view.texture().size();
            let bound = (size.0.min(target.width), size.1.min(target.height));
            let Some([x, y, w, h]) = within(clip, bound) else {
                return; // nothing of the target is left to draw on
            };
            pass.set_scissor_rect(x, y, w, h);
        }
        if sprites > 0 {
            pass.set_pipeline(&self.sprites);
            pass.set_vertex_buffer(0, self.sprite_buffer.slice(..));
            // One draw per run of sprites of the same texture, in order.
            let mut textures = list
                .sprites
                .iter()
                .map(|s| s.texture)
                .filter(|t| (t.0 as usize) < known)
                .take(sprites as usize)
                .peekable();
            let mut start = 0u32;
            while let Some(texture) = textures.next() {
                let mut end = start + 1;
                while textures.next_if_eq(&texture).is_some() {
                    end += 1;
                }
                pass.set_bind_group(1, &self.textures[texture.0 as usize], &[]);
                pass.draw(0..6, start..end);
                start = end;
            }
        }
        if shapes > 0 {
            pass.set_pipeline(&self.shapes);
            pass.set_vertex_buffer(0, self.shape_buffer.slice(..));
            pass.draw(0..6, 0..shapes);
        }
        if lines > 0 {
            pass.set_pipeline(&self.lines);
            pass.set_vertex_buffer(0, self.line_buffer.slice(..));
            pass.draw(0..6, 0..lines);
        }
    }
}

/// The lines to draw: `lines` itself when each lies within two views of
/// the target's centre, else copies in `cut` with every line that reaches
/// past that cut to it, and those wholly outside left out.
///
/// `f32` cannot place a long line in a small view: one from -10^9 to
/// 10^9 m seen 20 m wide puts its quad's corners at 10^8 times the view,
/// where the rasteriser loses the line and the fragment shader's distance
/// to it is off by tens of metres. The cut is made in `f64` from the
/// exact endpoints, so the new ones are as exact as any point near the
/// view. The box is two views wide each way (clip coordinates within
/// +-2, as the shape shader clamps) plus the line's pad, so the new ends,
/// caps and all, stay out of sight.
fn lines_in_view<'a>(
    lines: &'a [LineInstance],
    centre: Vec2,
    scale: Vec2,
    size: (u32, u32),
    cut: &'a mut Vec<LineInstance>,
) -> &'a [LineInstance] {
    let view = ClipBox::new(centre, scale, size);
    if lines.iter().all(|l| view.holds(l)) {
        return lines;
    }
    cut.clear();
    cut.extend(lines.iter().filter_map(|l| view.cut(l)));
    cut
}

/// The box of clip coordinates a line must lie in to be drawn as it is.
struct ClipBox {
    centre: DVec2,
    scale: DVec2,
    /// Clip units per pixel, the larger of the two axes.
    per_pixel: f64,
}

impl ClipBox {
    fn new(centre: Vec2, scale: Vec2, size: (u32, u32)) -> Self {
        Self {
            centre: centre.as_dvec2(),
            scale: scale.as_dvec2(),
            per_pixel: 2.0 / f64::from(size.0.min(size.1).max(1)),
        }
    }

    /// Half the box's side for `line`: two views plus the quad's pad (as
    /// `lines.wgsl` grows it) past each end.
    fn half_side(&self, line: &LineInstance) -> f64 {
        2.0 + (0.5 * f64::from(line.width.max(0.0)) + 1.5) * self.per_pixel
    }

    fn clip(&self, p: [f32; 2]) -> DVec2 {
        (Vec2::from(p).as_dvec2() - self.centre) * self.scale
    }

    /// Both ends inside the box, or an end not finite (left to the GPU).
    fn holds(&self, line: &LineInstance) -> bool {
        let half = self.half_side(line);
        let inside = |p: DVec2| p.abs().max_element() <= half || !p.is_finite();
        inside(self.clip(line.start)) && inside(self.clip(line.end))
    }

    /// `line` cut to the box (Liang-Barsky), or `None` if it misses it.
    fn cut(&self, line: &LineInstance) -> Option<LineInstance> {
        if self.holds(line) {
            return Some(*line);
        }
        let half = self.half_side(line);
        let (a, b) = (self.clip(line.start), self.clip(line.end));
        if !(a.is_finite() && b.is_finite()) {
            return Some(*line);
        }
        let d = b - a;
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for (p, q) in [
            (-d.x, a.x + half),
            (d.x, half - a.x),
            (-d.y, a.y + half),
            (d.y, half - a.y),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else if p < 0.0 {
                t0 = t0.max(q / p);
            } else {
                t1 = t1.min(q / p);
            }
        }
        if t0 > t1 {
            return None;
        }
        let (start, end) = (
            Vec2::from(line.start).as_dvec2(),
            Vec2::from(line.end).as_dvec2(),
        );
        let at = |t: f64| (start + (end - start) * t).as_vec2().to_array();
        Some(LineInstance {
            start: at(t0),
            end: at(t1),
            ..*line
        })
    }
}

/// `[x, y, width, height]` cut to a target of `size` pixels (a scissor
/// rectangle must lie inside it), or `None` if nothing is left.
fn within([x, y, w, h]: [u32; 4], size: (u32, u32)) -> Option<[u32; 4]> {
    let (x, y) = (x.min(size.0), y.min(size.1));
    let (w, h) = (w.min(size.0 - x), h.min(size.1 - y));
    (w > 0 && h > 0).then_some([x, y, w, h])
}

/// The clear colour for a target: linear for `*Srgb` formats (the hardware
/// encodes), sRGB-encoded for `*Unorm` ones.
fn clear_colour(format: wgpu::TextureFormat, linear: [f64; 4]) -> wgpu::Color {
    let encode = |c: f64| {
        if format.is_srgb() {
            c
        } else if c <= 0.0031308 {
            c * 12.92
        } else {
            1.055 * c.powf(1.0 / 2.4) - 0.055
        }
    };
    wgpu::Color {
        r: encode(linear[0]),
        g: encode(linear[1]),
        b: encode(linear[2]),
        a: linear[3],
    }
}

fn instance_buffer(device: &wgpu::Device, label: &str, bytes: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: bytes as u64,
        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// Writes instances to `buffer`, first growing it (see [`fitting`]), and
/// returns how many it holds for drawing: all of `items`, or as many as
/// the device's largest buffer holds.
fn upload<T: Pod>(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    buffer: &mut wgpu::Buffer,
    capacity: &mut usize,
    label: &str,
    items: &[T],
) -> u32 {
    if items.is_empty() {
        return 0;
    }
    let size = std::mem::size_of::<T>();
    let (grown, drawn) = fitting(
        items.len(),
        *capacity,
        device.limits().max_buffer_size,
        size,
    );
    if grown != *capacity {
        *capacity = grown;
        *buffer = instance_buffer(device, label, grown * size);
    }
    queue.write_buffer(buffer, 0, bytemuck::cast_slice(&items[..drawn]));
    // A buffer of u64 bytes holds far fewer than u32::MAX instances of a
    // few dozen bytes on any device; saturate anyway.
    u32::try_from(drawn).unwrap_or(u32::MAX)
}

/// For `len` instances of `size` bytes in a buffer of `capacity`: the
/// capacity to have (grown to the next power of two, at most what a buffer
/// of `max_bytes` holds) and how many instances fit in it.
fn fitting(len: usize, capacity: usize, max_bytes: u64, size: usize) -> (usize, usize) {
    let most = usize::try_from(max_bytes / size as u64).unwrap_or(usize::MAX);
    let capacity = if len > capacity {
        len.checked_next_power_of_two()
            .unwrap_or(usize::MAX)
            .min(most)
    } else {
        capacity
    };
    (capacity, len.min(capacity))
}

#[cfg(test)]
mod tests {
    use super::{LineInstance, Vec2, fitting, lines_in_view};

    #[test]
    fn instances_past_the_devices_largest_buffer_are_not_drawn() {
        // 64-byte shapes, a 256 MiB buffer: 4 194 304 fit.
        let max = 256 << 20;
        assert_eq!(fitting(10, 256, max, 64), (256, 10));
        assert_eq!(fitting(300, 256, max, 64), (512, 300));
        assert_eq!(fitting(4_194_304, 256, max, 64), (4_194_304, 4_194_304));
        // Six million lines of 48 bytes: 8 388 608 rounded up would need
        // 402 MB; the buffer stops at 5 592 405 and that many are drawn.
        assert_eq!(fitting(6_000_000, 256, max, 48), (5_592_405, 5_592_405));
        // A list that shrinks keeps the buffer.
        assert_eq!(fitting(100, 5_592_405, max, 48), (5_592_405, 100));
    }

    fn line(start: [f32; 2], end: [f32; 2]) -> LineInstance {
        LineInstance {
            start,
            end,
            colour: [1.0; 4],
            width: 2.0,
            _pad: [0.0; 3],
        }
    }

    #[test]
    fn lines_past_two_views_are_cut_to_them_and_lines_outside_left_out() {
        // A 100 x 100 pixel view of 10 x 10 m about (5, 0): clip x = (x - 5)
        // / 5. Two views each way plus the pad (1 + 1.5 pixels, 0.05 clip
        // units): x from -5.25 to 15.25, y from -10.25 to 10.25 m.
        let (centre, scale, size) = (Vec2::new(5.0, 0.0), Vec2::splat(0.2), (100, 100));
        let mut cut = Vec::new();
        let near = [
            line([0.0, 0.0], [10.0, 3.0]),
            line([-5.0, 9.0], [15.0, -9.0]),
        ];
        let same = lines_in_view(&near, centre, scale, size, &mut cut);
        assert_eq!(same.as_ptr(), near.as_ptr(), "nothing cut, nothing copied");
        let far = [
            near[0],
            line([-1e9, 1.0], [1e9, 1.0]),
            line([-1e9, 11.0], [1e9, 11.0]),
            line([5.0, -1e9], [5.0, -1e9 + 1.0]),
            line([f32::NAN, 0.0], [1e9, 0.0]),
        ];
        let drawn = lines_in_view(&far, centre, scale, size, &mut cut).to_vec();
        assert_eq!(drawn.len(), 3, "the two lines wholly outside are left out");
        assert_eq!(drawn[0], near[0]);
        let across = drawn[1];
        assert_eq!(across.start, [-5.25, 1.0]);
        assert_eq!(across.end, [15.25, 1.0]);
        assert_eq!(
            (across.colour, across.width),
            (near[0].colour, near[0].width)
        );
        assert!(drawn[2].start[0].is_nan(), "a NaN end is left to the GPU");
    }
}
