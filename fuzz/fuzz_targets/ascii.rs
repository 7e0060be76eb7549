//! ASCII tile maps, as a scene's `ascii` field gives them.
#![no_main]

use libfuzzer_sys::fuzz_target;
use passo_physics::TileMap;
use passo_physics::glam::Vec2;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = TileMap::from_ascii(text, Vec2::splat(0.5), Vec2::ZERO);
    }
});
