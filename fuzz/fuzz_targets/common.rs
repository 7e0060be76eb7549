//! What the targets share: a level file written where the loader reads it.

use passo_scene::TileMapRef;
use std::path::PathBuf;

/// A folder of this process's own for the level files.
pub fn folder() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("passo-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    dir
}

/// Writes `files` into the folder and loads the map `map` as a scene next
/// to them would; the result is dropped, errors included: a target only
/// looks for panics, aborts, leaks and time-outs.
pub fn load_level(files: &[(&str, &[u8])], map: &str) {
    let dir = folder();
    for (name, bytes) in files {
        std::fs::write(dir.join(name), bytes).expect("writing a level file");
    }
    let level = TileMapRef {
        file: Some(map.to_owned()),
        ascii: None,
        layer: "solid".into(),
        cell: 0.5,
        origin: Default::default(),
        kind: passo_physics::BodyKind::Static,
        path: None,
        root: None,
    };
    let scene = dir.join("scene.ron").display().to_string();
    let _ = level.load(&scene);
}
