//! How a level looks: the tiles of its tilesets' images, cell by cell.
//! Passo reads no image; a game draws these.

use passo_physics::glam::Vec2;
use std::path::PathBuf;

/// How a level's solid cells look: a rectangle of a tileset image for each
/// cell whose tile has one. Empty for ASCII maps. Passo reads no image: a
/// game loads [`images`](Self::images) itself (as PNG, for
/// `passo_render::RgbaImage::load_png`) and draws each of
/// [`tiles`](Self::tiles) as a textured quad.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LevelArt {
    /// The image files the tiles show, each a regular file inside the
    /// map's folder (or the scene's `root`): an image elsewhere, or
    /// missing, is left out, and its tiles with it.
    pub images: Vec<PathBuf>,
    /// One quad per solid cell that has an image.
    pub tiles: Vec<TileSprite>,
    /// Every solid cell has a quad in [`tiles`](Self::tiles), so a game
    /// can draw the quads instead of the level's boxes.
    pub complete: bool,
}

/// One cell's quad: where, and which part of which image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TileSprite {
    /// The cell's centre, metres.
    pub centre: Vec2,
    /// Half the cell's size, metres.
    pub half_extents: Vec2,
    /// The index of its image in [`LevelArt::images`].
    pub image: usize,
    /// The top-left corner of its rectangle of the image, 0 to 1 (v runs
    /// down the image's rows).
    pub uv_min: Vec2,
    /// The bottom-right corner.
    pub uv_max: Vec2,
}
