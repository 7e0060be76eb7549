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
    /// `Static` (default) or `Kinematic` (boxes that move together: give
    /// them a `path`, or the same velocity in code; for a part of a level,
    /// not a whole one).
    #[serde(default = "default_kind")]
    pub kind: BodyKind,
    /// A `Kinematic` map's back-and-forth path, as a body's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub path: Option<PlatformPath>,
    /// The folder, relative to the scene file, that every file a Tiled map
    /// names (tilesets, templates) must lie in. Default: the map's own
    /// folder. A map that names a file outside it, or anything but a
    /// regular file (a device, a pipe), is an error: a level from a
    /// stranger reads nothing else on the machine.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub root: Option<String>,
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

/// A kinematic body's motion back and forth between its position and
/// `position + by`: there and back in `period` seconds, easing in and out
/// at each end (no sudden reversal), the same at every frame rate.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlatformPath {
    /// The far end, relative to the body's position, m.
    pub by: Vec2,
    /// Seconds for the way there and back, > 0.
    pub period: f32,
}

impl PlatformPath {
    /// The fastest the body moves along the path, m/s: the eased wave's
    /// steepest slope, `3 |by| / period`.
    pub fn peak_speed(&self) -> f32 {
        3.0 * self.by.length() / self.period
    }

    /// Checks that a world whose kinematic bodies may go at most
    /// `max_speed` can follow the path (a target beyond it is refused each
    /// tick, and the platform would stand still).
    pub(crate) fn check_speed(&self, max_speed: f32) -> Result<(), String> {
        let peak = self.peak_speed();
        if peak <= max_speed {
            return Ok(());
        }
        Err(format!(
            "moves at up to {peak} m/s (3 |by| / period), faster than the scene's max_speed of {max_speed} m/s"
        ))
    }

    /// The offset from the start at `t` seconds: a smoothstep ease of the
    /// triangle wave (arithmetic only, so every platform computes the same
    /// bits).
    pub fn offset(&self, t: f64) -> Vec2 {
        let phase = (t / f64::from(self.period)).rem_euclid(1.0);
        let s = 1.0 - (2.0 * phase - 1.0).abs();
        let eased = s * s * (3.0 - 2.0 * s);
        self.by * eased as f32
    }
}
