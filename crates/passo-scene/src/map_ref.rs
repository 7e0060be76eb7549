//! The `tilemap` field of a scene file: where its level on a grid comes
//! from (read by `level`).

use passo_physics::BodyKind;
use passo_physics::glam::Vec2;
use serde::{Deserialize, Serialize};

/// A scene's level on a grid: a Tiled map file or ASCII art.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TileMapRef {
    /// A Tiled map, `.tmx` or `.tmj`, relative to the scene file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// Or the map drawn as text, the first line the top row: `#` solid,
    /// `-` one-way, `~` ice, `^` bouncy, `.` or a space empty.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ascii: Option<String>,
    /// The Tiled tile layer whose tiles are solid. Default `"solid"`.
    #[serde(default = "default_layer")]
    pub layer: String,
    /// Size of one tile, metres, > 0. Default 1.
    #[serde(default = "default_cell")]
    pub cell: f32,
    /// Where the map's lower-left corner goes, metres. Default (0, 0).
    #[serde(default)]
    pub origin: Vec2,
    /// `Static` (default) or `Kinematic` (boxes the game moves: give each
    /// the same velocity; for a few boxes, not a whole level).
    #[serde(default = "default_kind")]
    pub kind: BodyKind,
}

fn default_layer() -> String {
    "solid".to_owned()
}
fn default_cell() -> f32 {
    1.0
}
fn default_kind() -> BodyKind {
    BodyKind::Static
}
