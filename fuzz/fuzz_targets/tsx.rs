//! Tiled `.tsx` tilesets, named by a small valid map.
#![no_main]

#[path = "common.rs"]
mod common;

use libfuzzer_sys::fuzz_target;

const MAP: &[u8] = br#"<?xml version="1.0" encoding="UTF-8"?>
<map version="1.10" orientation="orthogonal" renderorder="right-down" width="2" height="1" tilewidth="16" tileheight="16" infinite="0">
 <tileset firstgid="1" source="set.tsx"/>
 <layer id="1" name="solid" width="2" height="1"><data encoding="csv">1,2</data></layer>
</map>"#;

fuzz_target!(|data: &[u8]| common::load_level(&[("map.tmx", MAP), ("set.tsx", data)], "map.tmx"));
