//! # passo-scene
//!
//! Scene files for Passo. A scene is a RON file that says which bodies exist
//! and which physics they need: force models, collisions, integrator, fixed
//! rate. The demo, the command line and the tests all load scenes the same
//! way, and the world a scene builds runs only the stages it declares.
//!
//! ```
//! let text = r#"(
//!     name: "Drop",
//!     forces: (gravity: (0, -9.81)),
//!     bodies: [(position: (0, 10), mass: 2)],
//! )"#;
//! let scene = passo_scene::Scene::parse(text, "drop.ron").unwrap();
//! let mut built = scene.build().unwrap();
//! built.world.step(1.0 / scene.file.rate_hz as f32);
//! assert_eq!(built.world.len(), 1);
//! ```
//!
//! Every field, its unit and its default are listed in the guide's scene format chapter (`docs/guide/src/scene-format.md`).
#![warn(missing_docs)]
#![forbid(unsafe_code)]

mod art;
mod build;
mod error;
mod format;
mod generate;
mod level;
mod files;
mod limits;
mod map_ref;
mod save;
mod tiled_file;
mod validate;

pub use art::{LevelArt, TileSprite};
pub use build::{BuiltScene, KINEMATIC_COLOUR, Platform, SceneBody};
pub use error::SceneError;
pub use files::embed_files;
pub use format::{
    BodySpec, Camera, Colour, Forces, Generator, JointSpec, JointSpecKind, MAX_BODIES,
    MAX_SCENE_JOINTS, Material, SceneFile,
};
pub use level::Level;
pub use limits::{
    MAX_FILE_BYTES, MAX_JSON_VALUES, MAX_MAP_BYTES, MAX_OBJECTS, MAX_TILE_DATA_BYTES,
    MAX_TILESET_TILES, MAX_XML_DEPTH, read_at_most,
};
pub use map_ref::{PlatformPath, TileMapRef};
pub use save::scene_from_world;

use std::path::Path;

/// A parsed and validated scene file.
///
/// ```
/// use passo_scene::Scene;
///
/// let text = r#"(
///     name: "Crates",
///     forces: (gravity: (0, -9.81)),
///     collisions: (),
///     bodies: [
///         (kind: Static, position: (0, -0.5), shape: Box(half_extents: (5, 0.5))),
///         (position: (0, 2), mass: 2, shape: Box(half_extents: (0.25, 0.25))),
///     ],
/// )"#;
/// let scene = Scene::parse(text, "crates.ron").unwrap();
/// let mut built = scene.build().unwrap();
/// let dt = (1.0 / scene.file.rate_hz) as f32; // 60 Hz unless the file says
/// for _ in 0..120 {
///     built.step(dt); // steers the path platforms, steps, counts the tick
/// }
/// let top = built.world.bodies().map(|b| b.position.y).fold(f32::MIN, f32::max);
/// assert!((top - 0.25).abs() < 0.006, "the crate rests on the ground, at {top}");
///
/// // A mistake is an error naming the line and the field.
/// let error = Scene::parse("(name: \"x\", bodies: [(mass: -1)])", "bad.ron").unwrap_err();
/// assert!(error.to_string().contains("mass"), "{error}");
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// What the file says, defaults filled in.
    pub file: SceneFile,
    /// Where it came from (a path or a name), for messages.
    pub source: String,
}

impl Scene {
    /// Parses and validates scene text. `source` names it in error messages.
    pub fn parse(text: &str, source: &str) -> Result<Self, SceneError> {
        let file = format::parse(text, source)?;
        file.validate(source)?;
        Ok(Self {
            file,
            source: source.to_owned(),
        })
    }

    /// Reads, parses and validates a scene file.
    pub fn load(path: &Path) -> Result<Self, SceneError> {
        let source = path.display().to_string();
        let text = limits::read_text(path).map_err(|e| SceneError::Io {
            source_name: source.clone(),
            message: e.to_string(),
        })?;
        Self::parse(&text, &source)
    }

    /// Builds the physics world the scene describes.
    pub fn build(&self) -> Result<BuiltScene, SceneError> {
        build::build(&self.file, &self.source)
    }

    /// The scene as RON text (pretty-printed).
    pub fn to_ron(&self) -> String {
        format::to_ron(&self.file)
    }
}
