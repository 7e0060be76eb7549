//! What to draw: shapes and lines as plain instance data.

use bytemuck::{Pod, Zeroable};
use glam::Vec2;
use std::mem::offset_of;

/// [`ShapeInstance::kind`] of a circle.
pub const SHAPE_CIRCLE: u32 = 0;
/// [`ShapeInstance::kind`] of an axis-aligned box.
pub const SHAPE_BOX: u32 = 1;
/// [`ShapeInstance::kind`] of a capsule: its half-circles' radius is the
/// smaller half extent.
pub const SHAPE_CAPSULE: u32 = 2;

/// One circle, box or capsule, as the GPU reads it. Mirrors `Instance` in
/// `crates/passo-render/shaders/shapes.wgsl` field for field (`tests/shaders.rs` compares them).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ShapeInstance {
    /// Centre, metres.
    pub centre: [f32; 2],
    /// Half extents, metres (a circle's radius in `x`; a capsule's whole
    /// box).
    pub half_extents: [f32; 2],
    /// Fill colour: linear RGB, straight alpha.
    pub fill: [f32; 4],
    /// Outline colour: linear RGB, straight alpha.
    pub outline: [f32; 4],
    /// [`SHAPE_CIRCLE`], [`SHAPE_BOX`] or [`SHAPE_CAPSULE`].
    pub kind: u32,
    /// Padding to a 16-byte multiple.
    pub _pad: [u32; 3],
}

impl ShapeInstance {
    /// The vertex attributes of the instance buffer (offsets written out
    /// from the struct, not packed by a macro).
    const ATTRIBUTES: [wgpu::VertexAttribute; 5] = [
        attribute(0, offset_of!(Self, centre), wgpu::VertexFormat::Float32x2),
        attribute(
            1,
            offset_of!(Self, half_extents),
            wgpu::VertexFormat::Float32x2,
        ),
        attribute(2, offset_of!(Self, fill), wgpu::VertexFormat::Float32x4),
        attribute(3, offset_of!(Self, outline), wgpu::VertexFormat::Float32x4),
        attribute(4, offset_of!(Self, kind), wgpu::VertexFormat::Uint32),
    ];

    /// The layout of a buffer of instances, one per drawn quad, as the
    /// shape pipeline reads it.
    pub const LAYOUT: wgpu::VertexBufferLayout<'static> =
        instance_layout::<Self>(&Self::ATTRIBUTES);
}

/// One line segment, as the GPU reads it. Mirrors `Instance` in
/// `crates/passo-render/shaders/lines.wgsl` field for field (`tests/shaders.rs` compares them).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct LineInstance {
    /// Start point, metres.
    pub start: [f32; 2],
    /// End point, metres.
    pub end: [f32; 2],
    /// Colour: linear RGB, straight alpha.
    pub colour: [f32; 4],
    /// Full width, pixels.
    pub width: f32,
    /// Padding to a 16-byte multiple.
    pub _pad: [f32; 3],
}

impl LineInstance {
    /// The vertex attributes of the instance buffer.
    const ATTRIBUTES: [wgpu::VertexAttribute; 4] = [
        attribute(0, offset_of!(Self, start), wgpu::VertexFormat::Float32x2),
        attribute(1, offset_of!(Self, end), wgpu::VertexFormat::Float32x2),
        attribute(2, offset_of!(Self, colour), wgpu::VertexFormat::Float32x4),
        attribute(3, offset_of!(Self, width), wgpu::VertexFormat::Float32),
    ];

    /// The layout of a buffer of instances, one per drawn quad, as the line
    /// pipeline reads it.
    pub const LAYOUT: wgpu::VertexBufferLayout<'static> =
        instance_layout::<Self>(&Self::ATTRIBUTES);
}

/// One textured quad, as the GPU reads it. Mirrors `Instance` in
/// `crates/passo-render/shaders/sprites.wgsl` field for field
/// (`tests/shaders.rs` compares them).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct SpriteInstance {
    /// Centre, metres.
    pub centre: [f32; 2],
    /// Half extents, metres.
    pub half_extents: [f32; 2],
    /// The texture rectangle's top-left corner, 0 to 1 across the image
    /// (v runs down its rows).
    pub uv_min: [f32; 2],
    /// Its bottom-right corner.
    pub uv_max: [f32; 2],
}

impl SpriteInstance {
    /// The vertex attributes of the instance buffer.
    const ATTRIBUTES: [wgpu::VertexAttribute; 4] = [
        attribute(0, offset_of!(Self, centre), wgpu::VertexFormat::Float32x2),
        attribute(
            1,
            offset_of!(Self, half_extents),
            wgpu::VertexFormat::Float32x2,
        ),
        attribute(2, offset_of!(Self, uv_min), wgpu::VertexFormat::Float32x2),
        attribute(3, offset_of!(Self, uv_max), wgpu::VertexFormat::Float32x2),
    ];

    /// The layout of a buffer of instances, one per drawn quad, as the
    /// sprite pipeline reads it.
    pub const LAYOUT: wgpu::VertexBufferLayout<'static> =
        instance_layout::<Self>(&Self::ATTRIBUTES);
}

/// A texture the renderer holds, from [`Renderer::add_texture`](crate::Renderer::add_texture).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TextureId(pub(crate) u32);

/// A sprite in a [`DrawList`]: which texture, and where.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sprite {
    /// The texture it shows part of.
    pub texture: TextureId,
    /// Where, and which part.
    pub instance: SpriteInstance,
}

/// A buffer of `T`s read once per instance.
const fn instance_layout<T>(
    attributes: &'static [wgpu::VertexAttribute],
) -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: size_of::<T>() as u64,
        step_mode: wgpu::VertexStepMode::Instance,
        attributes,
    }
}

const fn attribute(
    location: u32,
    offset: usize,
    format: wgpu::VertexFormat,
) -> wgpu::VertexAttribute {
    wgpu::VertexAttribute {
        format,
        offset: offset as u64,
        shader_location: location,
    }
}

/// The sRGB transfer function undone: an 8-bit sRGB channel as linear light.
pub fn srgb_to_linear(c: u8) -> f32 {
    let c = f32::from(c) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// An 8-bit sRGB colour with straight alpha as linear RGBA floats.
fn linear(srgba: [u8; 4]) -> [f32; 4] {
    [
        srgb_to_linear(srgba[0]),
        srgb_to_linear(srgba[1]),
        srgb_to_linear(srgba[2]),
        f32::from(srgba[3]) / 255.0,
    ]
}

/// A darker shade of the same colour for outlines.
fn outline_of(fill: [f32; 4]) -> [f32; 4] {
    [fill[0] * 0.35, fill[1] * 0.35, fill[2] * 0.35, fill[3]]
}

/// Everything one frame draws: a clear colour, sprites (drawn first, in
/// order: tiles behind everything), shapes (over them, in order) and lines
/// (over both). Colours are given as 8-bit sRGB with
/// straight alpha, as in scene files; the list stores linear light.
///
/// Keep one list and [`clear`](Self::clear) it each frame: its buffers keep
/// their capacity, so a frame with no more instances than before allocates
/// nothing.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DrawList {
    /// Background, linear RGBA.
    pub clear_colour: [f32; 4],
    /// Textured quads: tiles.
    pub sprites: Vec<Sprite>,
    /// Circles, boxes and capsules.
    pub shapes: Vec<ShapeInstance>,
    /// Line segments.
    pub lines: Vec<LineInstance>,
    /// Where the shapes and lines may draw, in pixels from the target's
    /// top-left corner (`[x, y, width, height]`), or `None` for the whole
    /// target. It is cut to the size given to
    /// [`Renderer::encode`](crate::Renderer::encode), which must be the
    /// target's. The background still fills the whole target. A window
    /// whose user interface covers part of it (a side panel) clips the
    /// scene to the rest: nothing shows through a panel drawn without a
    /// fill, which on a software adapter saves filling its every pixel
    /// again.
    pub clip: Option<[u32; 4]>,
}

impl DrawList {
    /// An empty list with an sRGB background colour.
    pub fn new(background: [u8; 4]) -> Self {
        Self {
            clear_colour: linear(background),
            sprites: Vec::new(),
            shapes: Vec::new(),
            lines: Vec::new(),
            clip: None,
        }
    }

    /// Empties the list, keeping its capacity, sets the background and
    /// draws on the whole target again (no [`clip`](Self::clip)).
    pub fn clear(&mut self, background: [u8; 4]) {
        self.clear_colour = linear(background);
        self.sprites.clear();
        self.shapes.clear();
        self.lines.clear();
        self.clip = None;
    }

    /// A quad centred on `centre` showing the rectangle from `uv_min` to
    /// `uv_max` of `texture` (0 to 1 across the image, v down its rows):
    /// a tile of a tileset image. Colours come from the texture as they
    /// are; texels with alpha 0 are not drawn.
    pub fn sprite(
        &mut self,
        texture: TextureId,
        centre: Vec2,
        half_extents: Vec2,
        uv_min: Vec2,
        uv_max: Vec2,
    ) {
        self.sprites.push(Sprite {
            texture,
            instance: SpriteInstance {
                centre: centre.to_array(),
                half_extents: half_extents.to_array(),
                uv_min: uv_min.to_array(),
                uv_max: uv_max.to_array(),
            },
        });
    }

    /// A filled circle with a darker outline.
    pub fn circle(&mut self, centre: Vec2, radius: f32, srgba: [u8; 4]) {
        self.shape(SHAPE_CIRCLE, centre, Vec2::splat(radius), srgba);
    }

    /// A filled axis-aligned box with a darker outline.
    pub fn rect(&mut self, centre: Vec2, half_extents: Vec2, srgba: [u8; 4]) {
        self.shape(SHAPE_BOX, centre, half_extents, srgba);
    }

    /// A filled capsule filling the box of `half_extents` about `centre`,
    /// upright if it is taller than wide, with a darker outline: its
    /// half-circles' radius is the smaller half extent.
    pub fn capsule(&mut self, centre: Vec2, half_extents: Vec2, srgba: [u8; 4]) {
        self.shape(SHAPE_CAPSULE, centre, half_extents, srgba);
    }

    fn shape(&mut self, kind: u32, centre: Vec2, half_extents: Vec2, srgba: [u8; 4]) {
        let fill = linear(srgba);
        self.shapes.push(ShapeInstance {
            centre: centre.to_array(),
            half_extents: half_extents.to_array(),
            fill,
            outline: outline_of(fill),
            kind,
            _pad: [0; 3],
        });
    }

    /// A line segment `width` pixels wide.
    pub fn line(&mut self, start: Vec2, end: Vec2, width: f32, srgba: [u8; 4]) {
        self.lines.push(LineInstance {
            start: start.to_array(),
            end: end.to_array(),
            colour: linear(srgba),
            width,
            _pad: [0.0; 3],
        });
    }

    /// An arrow from `from` to `to`: a shaft and a two-stroke head whose
    /// size follows the arrow's length (a quarter of it, at most 0.5 m).
    pub fn arrow(&mut self, from: Vec2, to: Vec2, width: f32, srgba: [u8; 4]) {
        self.line(from, to, width, srgba);
        let d = to - from;
        let len = d.length();
        if len <= 0.0 {
            return;
        }
        let head = (len * 0.25).min(0.5);
        let back = -d / len * head;
        let side = back.perp() * 0.5;
        self.line(to, to + back + side, width, srgba);
        self.line(to, to + back - side, width, srgba);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn instance_layouts_match_the_wgsl_structs() {
        assert_eq!(std::mem::size_of::<ShapeInstance>(), 64);
        let offsets: Vec<u64> = ShapeInstance::ATTRIBUTES.iter().map(|a| a.offset).collect();
        assert_eq!(offsets, [0, 8, 16, 32, 48]);
        assert_eq!(std::mem::size_of::<LineInstance>(), 48);
        let offsets: Vec<u64> = LineInstance::ATTRIBUTES.iter().map(|a| a.offset).collect();
        assert_eq!(offsets, [0, 8, 16, 32]);
        assert_eq!(std::mem::size_of::<SpriteInstance>(), 32);
        let offsets: Vec<u64> = SpriteInstance::ATTRIBUTES
            .iter()
            .map(|a| a.offset)
            .collect();
        assert_eq!(offsets, [0, 8, 16, 24]);
    }

    #[test]
    fn srgb_decodes_to_linear_light() {
        assert_eq!(srgb_to_linear(0), 0.0);
        assert_eq!(srgb_to_linear(255), 1.0);
        // Mid grey 188 is about half the light of white.
        assert!((srgb_to_linear(188) - 0.5029).abs() < 1e-3);
        assert!((srgb_to_linear(10) - 10.0 / 255.0 / 12.92).abs() < 1e-7);
    }

    #[test]
    fn clearing_keeps_capacity_so_frames_do_not_allocate() {
        let mut list = DrawList::new([0, 0, 0, 255]);
        for i in 0..100 {
            list.circle(Vec2::splat(i as f32), 1.0, [255; 4]);
            list.arrow(Vec2::ZERO, Vec2::X, 1.0, [255; 4]);
        }
        let (shapes, lines) = (list.shapes.capacity(), list.lines.capacity());
        list.clear([1, 2, 3, 255]);
        assert!(list.shapes.is_empty() && list.lines.is_empty());
        assert_eq!(
            (list.shapes.capacity(), list.lines.capacity()),
            (shapes, lines)
        );
        assert_eq!(list.lines.len(), 0);
    }

    #[test]
    fn an_arrow_is_a_shaft_and_two_head_strokes() {
        let mut list = DrawList::new([0; 4]);
        list.arrow(Vec2::ZERO, Vec2::new(4.0, 0.0), 2.0, [255; 4]);
        assert_eq!(list.lines.len(), 3);
        assert_eq!(list.lines[1].start, [4.0, 0.0]);
        assert_eq!(list.lines[1].end, [3.5, -0.25]);
        assert_eq!(list.lines[2].end, [3.5, 0.25]);
        list.arrow(Vec2::ONE, Vec2::ONE, 2.0, [255; 4]);
        assert_eq!(list.lines.len(), 4, "a zero-length arrow has no head");
    }
}
