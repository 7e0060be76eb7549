//! The web demo reads its levels from the files built into the program
//! (`passo::scenes::LEVEL_FILES`, handed to `passo_scene::embed_files`),
//! having no disk. Done natively here, in a test binary of its own (the
//! embedding is for the whole process): the platformer's Tiled level and
//! its tileset image come from memory, and nothing else can be read.

use passo::scenes::LEVEL_FILES;
use std::path::Path;

#[test]
fn the_platformer_builds_from_embedded_files_and_nothing_else_is_read() {
    // From disk first, for the reference.
    let from_disk = passo::scenes::load("platformer").unwrap().build().unwrap();
    assert!(passo_scene::embed_files(LEVEL_FILES));
    assert!(!passo_scene::embed_files(LEVEL_FILES), "once only");

    let scene = passo::scenes::load("platformer").unwrap();
    let built = scene.build().unwrap();
    assert!(
        !built.cell_bodies.is_empty(),
        "the level's tiles became bodies"
    );
    assert_eq!(built.cell_bodies.len(), from_disk.cell_bodies.len());
    assert_eq!(built.world.state_hash(), from_disk.world.state_hash());
    // The tileset's image, by the path the level names it.
    assert_eq!(built.art.images.len(), from_disk.art.images.len());
    assert!(built.art.complete && !built.art.images.is_empty());
    for path in &built.art.images {
        let bytes = passo_scene::read_at_most(path, 1 << 20).unwrap();
        assert_eq!(&bytes[1..4], b"PNG", "{}", path.display());
    }
    // A file on the disk but not embedded is not read.
    let here = Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml");
    assert!(here.is_file());
    let refused = passo_scene::read_at_most(&here, 1 << 20).unwrap_err();
    assert!(
        refused
            .to_string()
            .contains("not among the program's files"),
        "{refused}"
    );
}
