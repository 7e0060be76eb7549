//! # passo-render
//!
//! A wgpu renderer for 2D physics: bodies as instanced, anti-aliased circles
//! and boxes with outlines, and debug lines and arrows (velocities, forces,
//! contact normals). One [`Renderer`] draws into any texture view of the
//! format it was made for: a window surface ([`WindowSurface`]) and an
//! off-screen texture ([`OffscreenTarget`]) are just two places to draw.
//!
//! It takes plain data ([`DrawList`]), so it knows nothing about physics;
//! the `passo` app turns a world into a draw list. Off-screen rendering runs
//! on any adapter, including Mesa's software Vulkan driver (lavapipe) on
//! machines without a GPU:
//!
//! ```
//! use passo_render::{AdapterChoice, Camera2D, DrawList, Gpu, OffscreenTarget, Renderer};
//! use glam::Vec2;
//!
//! let gpu = Gpu::headless(AdapterChoice::Software)?;
//! let target = OffscreenTarget::new(&gpu, 320, 240);
//! let mut renderer = Renderer::new(&gpu, target.format());
//! let mut list = DrawList::new([20, 22, 28, 255]);
//! list.circle(Vec2::new(0.0, 1.0), 0.5, [228, 108, 58, 255]);
//! list.arrow(Vec2::ZERO, Vec2::new(2.0, 0.0), 2.0, [255, 255, 255, 255]);
//! let camera = Camera2D::fit(Vec2::new(-4.0, -3.0), Vec2::new(4.0, 3.0), target.size());
//! renderer.render(target.view(), target.size(), &camera, &list);
//! let image = target.read(&gpu)?;
//! // 40 px per metre: the circle at (0, 1) m is centred on pixel (160, 80).
//! assert_eq!(image.get(160, 80), Some([228, 108, 58, 255]));
//! image.save_png(std::env::temp_dir().join("passo-picture.png"))?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]
#![warn(unreachable_pub)]
#![forbid(unsafe_code)]

mod camera;
mod draw_list;
mod gpu;
mod image;
mod offscreen;
mod renderer;
mod surface;

pub use camera::Camera2D;
pub use draw_list::{
    DrawList, LineInstance, SHAPE_BOX, SHAPE_CAPSULE, SHAPE_CIRCLE, ShapeInstance, Sprite,
    SpriteInstance, TextureId, srgb_to_linear,
};
/// The maths types the draw list and camera take (`glam::Vec2`), re-exported
/// so a game uses the same version.
pub use glam;
pub use gpu::{AdapterChoice, Gpu, RenderError};
pub use image::RgbaImage;
pub use offscreen::{OffscreenTarget, read_texture};
#[doc(hidden)]
pub use renderer::Globals;
pub use renderer::{LINES_WGSL, Renderer, SHAPES_WGSL, SPRITES_WGSL};
pub use surface::WindowSurface;
pub use wgpu;
