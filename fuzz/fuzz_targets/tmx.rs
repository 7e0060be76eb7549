//! Tiled `.tmx` maps, loaded as a scene's tile map.
#![no_main]

#[path = "common.rs"]
mod common;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| common::load_level(&[("map.tmx", data)], "map.tmx"));
