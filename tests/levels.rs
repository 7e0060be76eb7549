//! Levels from the Tiled editor (`.tmx`, `.tmj`) and ASCII art in scene
//! files: cells, objects, spawn points, and errors that name the file, the
//! layer and the object.

use passo_physics::glam::Vec2;
use passo_physics::{BodyKind, Shape, TileKind};
use passo_scene::{Scene, TileMapRef};
use std::path::PathBuf;

fn assets() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets")
}

fn level_ref(file: &str) -> TileMapRef {
    TileMapRef {
        file: Some(file.to_owned()),
        ascii: None,
        layer: "solid".into(),
        cell: 0.5,
        origin: Vec2::ZERO,
        kind: BodyKind::Static,
        path: None,
        root: None,
    }
}

#[test]
fn the_shipped_tiled_level_builds_with_its_cells_objects_and_spawn() {
    let scene = Scene::load(&assets().join("scenes/platformer.ron")).unwrap();
    let mut built = scene.build().unwrap();
    // The players' spawn points: Tiled (32, 208), (144, 208) and (472,
    // 224) px in a map 240 px tall, 16 px tiles of 0.5 m, y up.
    assert_eq!(
        built.spawns,
        vec![
            ("player".to_owned(), Vec2::new(1.0, 1.0)),
            ("physics player".to_owned(), Vec2::new(4.5, 1.0)),
            ("slopes".to_owned(), Vec2::new(14.75, 0.5))
        ]
    );
    let world = &built.world;
    let named = |name: &str| {
        let id = built
            .bodies
            .iter()
            .find(|b| b.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("{name} is in the scene"))
            .id;
        world.body(id).unwrap()
    };
    let coin = named("coin 1");
    assert!(coin.sensor && coin.kind == BodyKind::Static);
    assert_eq!(coin.shape, Some(Shape::circle(0.125)));
    assert!(named("goal").sensor);
    let lift = named("lift");
    assert_eq!(lift.kind, BodyKind::Kinematic);
    assert_eq!(built.platforms.len(), 1, "the lift follows its path");
    let crate_ = named("crate");
    assert_eq!(crate_.kind, BodyKind::Dynamic);
    assert!(
        (crate_.mass - 2.0 * 0.25).abs() < 1e-6,
        "density 2 × 0.25 m²"
    );
    assert!((crate_.friction - 0.5).abs() < 1e-6);
    // The cells: 197 solid cells merged into far fewer boxes, with ice,
    // bouncy and one-way ones among them.
    let statics: Vec<_> = world
        .bodies()
        .filter(|b| b.kind == BodyKind::Static && !b.sensor)
        .collect();
    assert!(statics.len() < 60, "{} boxes", statics.len());
    assert!(statics.iter().any(|b| b.one_way == Some(Vec2::Y)));
    assert!(
        statics
            .iter()
            .any(|b| (b.friction - TileKind::ICE.friction).abs() < 1e-6)
    );
    assert!(
        statics
            .iter()
            .any(|b| b.restitution == TileKind::BOUNCY.restitution)
    );
    // The crate falls onto the floor (top at 0.5 m) and rests there.
    let crate_id = crate_.id;
    passo_tests::run_scene(&mut built, 180, |_, _| {});
    let y = built.world.body(crate_id).unwrap().position.y;
    assert!((y - 0.75).abs() < 0.01, "the crate rests on the floor: {y}");
}

#[test]
fn the_tmx_and_tmj_forms_of_a_map_give_the_same_level() {
    let scene = assets().join("scenes/platformer.ron").display().to_string();
    let tmx = level_ref("../levels/first.tmx").load(&scene).unwrap();
    let tmj = level_ref("../levels/first.tmj").load(&scene).unwrap();
    assert_eq!(tmx, tmj);
    assert_eq!((tmx.map.width(), tmx.map.height()), (48, 15));
    assert_eq!(tmx.bodies.len(), 8);
    assert_eq!(tmx.chains.len(), 3);
}

/// Every solid cell of the shipped level shows its tile of `blocks.png`
/// (64 × 16 px: solid, ice, bouncy, one-way, 16 px each), from either form
/// of the map.
#[test]
fn each_solid_cell_shows_its_tile_of_the_tileset_image() {
    let scene = assets().join("scenes/platformer.ron").display().to_string();
    for file in ["../levels/first.tmx", "../levels/first.tmj"] {
        let level = level_ref(file).load(&scene).unwrap();
        let art = &level.art;
        assert_eq!(art.images.len(), 1, "{file}");
        assert_eq!(
            art.images[0].canonicalize().unwrap(),
            assets().join("levels/blocks.png").canonicalize().unwrap()
        );
        assert!(art.complete, "{file}");
        let solid = (0..level.map.width())
            .flat_map(|x| (0..level.map.height()).map(move |y| (x, y)))
            .filter(|&(x, y)| level.map.get(x, y).is_some())
            .count();
        assert_eq!(art.tiles.len(), solid, "{file}");
        for tile in &art.tiles {
            assert_eq!(tile.half_extents, Vec2::splat(0.25));
            // The cell under the quad has the kind of the quad's tile:
            // the tile's column of the image is its id.
            let cell = (tile.centre / 0.5 - 0.5).round();
            let kind = level.map.get(cell.x as u32, cell.y as u32).unwrap();
            let column = (tile.uv_min.x * 4.0).round() as usize;
            let kinds = level.map.kinds();
            let expected = match column {
                0 => TileKind::SOLID,
                1 => TileKind::ICE,
                2 => TileKind::BOUNCY,
                _ => TileKind::ONE_WAY,
            };
            assert_eq!(kinds[kind as usize], expected, "{file}: {tile:?}");
            assert_eq!(tile.uv_max - tile.uv_min, Vec2::new(0.25, 1.0));
            assert_eq!(tile.uv_min.y, 0.0);
        }
    }
}

/// A tileset image outside the map's folder, or missing, is left out, and
/// so are the quads that show it; the level still loads.
#[test]
fn a_tileset_image_outside_the_folder_or_missing_is_left_out() {
    for source in ["../elsewhere.png", "missing.png"] {
        let map = format!(
            r#"<?xml version="1.0" encoding="UTF-8"?>
<map version="1.10" orientation="orthogonal" renderorder="right-down" width="2" height="1" tilewidth="16" tileheight="16" infinite="0">
 <tileset firstgid="1" name="t" tilewidth="16" tileheight="16" tilecount="2" columns="2">
  <image source="{source}" width="32" height="16"/>
 </tileset>
 <layer id="1" name="solid" width="2" height="1"><data encoding="csv">1,2</data></layer>
</map>"#
        );
        let scene = map_file("art.tmx", &map);
        let dir = PathBuf::from(&scene).parent().unwrap().to_path_buf();
        // The file outside exists: it is refused for where it is.
        std::fs::write(dir.join("../elsewhere.png"), b"not read").unwrap();
        let level = level_ref("art.tmx").load(&scene).unwrap();
        assert_eq!(level.map.rects().len(), 1, "the cells are still there");
        assert!(level.art.images.is_empty(), "{source}: {:?}", level.art);
        assert!(level.art.tiles.is_empty() && !level.art.complete);
    }
}

#[test]
fn an_ascii_tilemap_in_a_scene_file_is_a_level() {
    let text = r#"(
        name: "ascii",
        forces: (gravity: (0, -9.81)),
        collisions: (),
        tilemap: (ascii: "
            #......#
            #..--..#
            ########", cell: 0.5, origin: (-2, 0)),
        bodies: [(shape: Circle(radius: 0.2), position: (-1, 1.2))],
    )"#;
    let mut built = Scene::parse(text, "ascii.ron").unwrap().build().unwrap();
    // Floor, two walls, the ledge; then the ball.
    assert_eq!(built.bodies.len(), 5);
    let ball = built.bodies[4].id;
    for _ in 0..120 {
        built.world.step(1.0 / 60.0);
    }
    let y = built.world.body(ball).unwrap().position.y;
    assert!((y - 0.7).abs() < 0.01, "on the floor (top at 0.5 m): {y}");
}

/// Writes `text` as `name` in a fresh directory; returns the scene path
/// that would sit beside it.
fn map_file(name: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("passo-levels-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join(name), text).unwrap();
    dir.join("scene.ron").display().to_string()
}

fn tmx_with(objects: &str) -> String {
    format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<map version="1.10" orientation="orthogonal" renderorder="right-down" width="2" height="1" tilewidth="16" tileheight="16" infinite="0">
 <layer id="1" name="ground" width="2" height="1"><data encoding="csv">0,0</data></layer>
 <objectgroup id="2" name="things">{objects}</objectgroup>
</map>"#
    )
}

#[test]
fn errors_name_the_file_the_layer_and_the_object() {
    let scene = map_file("a.tmx", &tmx_with(""));
    let err = level_ref("a.tmx").load(&scene).unwrap_err().to_string();
    assert!(
        err.contains("a.tmx") && err.contains("layer `solid`") && err.contains("ground"),
        "{err}"
    );
    let cases = [
        (
            r#"<object id="7" name="rock" class="dynamic" x="0" y="0"><polygon points="0,0 8,0 4,8"/></object>"#,
            "not Dynamic",
        ),
        (
            r#"<object id="7" name="rock" class="platform" x="0" y="0"><polyline points="0,0 8,0"/></object>"#,
            "one-way",
        ),
        (
            r#"<object id="7" name="rock" x="0" y="0"><text>hello</text></object>"#,
            "a text",
        ),
        (
            r#"<object id="7" name="rock" x="0" y="0" width="8" height="8" rotation="30"/>"#,
            "rotated",
        ),
        (
            r#"<object id="7" name="rock" class="boulder" x="0" y="0" width="8" height="8"/>"#,
            "class `boulder`",
        ),
        (
            r#"<object id="7" name="rock" x="0" y="0" width="8" height="4"><ellipse/></object>"#,
            "ellipse",
        ),
        (
            r#"<object id="7" name="rock" x="0" y="0" width="8" height="8"><properties><property name="friction" value="lots"/></properties></object>"#,
            "friction",
        ),
    ];
    for (object, why) in cases {
        let scene = map_file("b.tmx", &tmx_with(object));
        let mut r = level_ref("b.tmx");
        r.layer = "ground".into();
        let err = r.load(&scene).unwrap_err().to_string();
        assert!(
            err.contains("b.tmx")
                && err.contains("layer `things`, object 7 `rock`")
                && err.contains(why),
            "{why}: {err}"
        );
    }
    // A missing file is an error, not a panic.
    let err = level_ref("none.tmx").load(&scene).unwrap_err().to_string();
    assert!(err.contains("none.tmx"), "{err}");
}

#[test]
fn a_scene_tilemap_needs_exactly_one_source() {
    for text in [
        r#"(name: "x", tilemap: ())"#,
        r##"(name: "x", tilemap: (file: "a.tmx", ascii: "#"))"##,
        r##"(name: "x", tilemap: (ascii: "#", cell: 0))"##,
        r##"(name: "x", tilemap: (ascii: "#", kind: Dynamic))"##,
    ] {
        let err = Scene::parse(text, "t.ron").unwrap_err().to_string();
        assert!(err.contains("tilemap"), "{err}");
    }
}

#[test]
fn malformed_maps_are_errors_not_panics() {
    // A .tmx whose layer has fewer tiles than the map has cells.
    let short = r#"<?xml version="1.0" encoding="UTF-8"?>
<map version="1.10" orientation="orthogonal" renderorder="right-down" width="4" height="2" tilewidth="16" tileheight="16" infinite="0">
 <layer id="1" name="solid" width="4" height="2"><data encoding="csv">1,1,1</data></layer>
</map>"#;
    let scene = map_file("short.tmx", short);
    let err = level_ref("short.tmx").load(&scene).unwrap_err().to_string();
    // Counted before the `tiled` crate reads the layer (it panicked inside,
    // and its message was printed, before the error).
    assert!(
        err.contains("short.tmx") && err.contains("a layer of 8 cells whose data holds 3 tiles"),
        "{err}"
    );
    // A layer that says it is larger than its data, so that a cell of the
    // map falls past the data; compressed and plain base64 data counted too.
    let huge = short.replace(
        r#"width="4" height="2"><data"#,
        r#"width="65536" height="65536"><data"#,
    );
    let ids: Vec<u8> = [1u32; 7].iter().flat_map(|id| id.to_le_bytes()).collect();
    let zlib = tmx_4x2(&format!(
        r#"<data encoding="base64" compression="zlib">{}</data>"#,
        zlib_base64(&ids)
    ));
    use base64::Engine;
    let plain = tmx_4x2(&format!(
        r#"<data encoding="base64">{}</data>"#,
        base64::engine::general_purpose::STANDARD.encode(&ids)
    ));
    for (name, text, tiles) in [
        ("huge.tmx", huge, 3),
        ("zlib.tmx", zlib, 7),
        ("plain.tmx", plain, 7),
    ] {
        let err = level_ref(name)
            .load(&map_file(name, &text))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains(name) && err.contains(&format!("holds {tiles} tiles")),
            "{err}"
        );
    }
    // A .tmj whose data does not match its size.
    let tmj = r#"{"orientation": "orthogonal", "width": 4, "height": 2, "tilewidth": 16, "tileheight": 16,
        "tilesets": [], "layers": [{"type": "tilelayer", "name": "solid", "data": [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]}]}"#;
    let scene = map_file("long.tmj", tmj);
    let err = level_ref("long.tmj").load(&scene).unwrap_err().to_string();
    assert!(
        err.contains("long.tmj") && err.contains("10 tiles"),
        "{err}"
    );
    // An object with a path of period 0 is checked as a scene body is.
    let object = r#"<object id="3" name="lift" class="kinematic" x="0" y="0" width="16" height="8"><properties><property name="period" type="float" value="0"/></properties></object>"#;
    let scene = map_file("c.tmx", &tmx_with(object));
    let mut r = level_ref("c.tmx");
    r.layer = "ground".into();
    let err = r.load(&scene).unwrap_err().to_string();
    assert!(
        err.contains("object 3 `lift`") && err.contains("period"),
        "{err}"
    );
}

/// `bytes` zlib-compressed and base64-encoded, as Tiled writes a layer.
fn zlib_base64(bytes: &[u8]) -> String {
    use base64::Engine;
    use std::io::Write;
    let mut e = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::fast());
    e.write_all(bytes).unwrap();
    base64::engine::general_purpose::STANDARD.encode(e.finish().unwrap())
}

/// A 4 × 2 map whose `solid` layer has `data`, with a one-tile tileset.
fn tmx_4x2(data: &str) -> String {
    format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<map version="1.10" orientation="orthogonal" renderorder="right-down" width="4" height="2" tilewidth="16" tileheight="16" infinite="0">
 <tileset firstgid="1" name="t" tilewidth="16" tileheight="16" tilecount="1" columns="1"/>
 <layer id="1" name="solid" width="4" height="2">{data}</layer>
</map>"#
    )
}

/// [`tmx_4x2`] with a CSV layer, naming the tilesets `tilesets` (files)
/// instead of its own.
fn tmx_4x2_naming(tilesets: &str) -> String {
    tmx_4x2(r#"<data encoding="csv">1,0,0,1,1,1,1,1</data>"#).replace(
        r#"<tileset firstgid="1" name="t" tilewidth="16" tileheight="16" tilecount="1" columns="1"/>"#,
        tilesets,
    )
}

#[test]
fn a_compressed_layer_reads_as_its_csv_form() {
    let csv = tmx_4x2(r#"<data encoding="csv">1,0,0,1,1,1,1,1</data>"#);
    // Global tile ids as little-endian u32s.
    let ids: Vec<u8> = [1u32, 0, 0, 1, 1, 1, 1, 1]
        .iter()
        .flat_map(|id| id.to_le_bytes())
        .collect();
    let zlib = tmx_4x2(&format!(
        r#"<data encoding="base64" compression="zlib">{}</data>"#,
        zlib_base64(&ids)
    ));
    let from_csv = level_ref("csv.tmx")
        .load(&map_file("csv.tmx", &csv))
        .unwrap();
    let from_zlib = level_ref("z.tmx").load(&map_file("z.tmx", &zlib)).unwrap();
    assert_eq!(from_csv, from_zlib);
    let map = &from_csv.map;
    let filled = (0..2)
        .flat_map(|y| (0..4).map(move |x| (x, y)))
        .filter(|&(x, y)| map.get(x, y).is_some())
        .count();
    assert_eq!(filled, 6);
}

#[test]
fn maps_that_would_exhaust_the_machine_are_errors() {
    // Group layers nested 100 000 deep (1.5 MB): the `tiled` crate reads
    // them recursively and would overflow the stack.
    let deep = tmx_4x2(r#"<data encoding="csv">1,0,0,1,1,1,1,1</data>"#).replace(
        "</map>",
        &("<group>".repeat(100_000) + &"</group>".repeat(100_000) + "</map>"),
    );
    let err = level_ref("deep.tmx")
        .load(&map_file("deep.tmx", &deep))
        .unwrap_err()
        .to_string();
    assert!(err.contains("deep.tmx") && err.contains("64 deep"), "{err}");
    // A layer of 300 MiB of zeros, compressed to about 2 MB.
    let zeros = zlib_base64(&vec![0u8; 300 << 20]);
    let bomb = tmx_4x2(&format!(
        r#"<data encoding="base64" compression="zlib">{zeros}</data>"#
    ));
    let err = level_ref("bomb.tmx")
        .load(&map_file("bomb.tmx", &bomb))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("bomb.tmx") && err.contains("more than 256 MiB"),
        "{err}"
    );
    // The same checks hold for a tileset file the map names.
    let tileset = format!(
        r#"<?xml version="1.0"?><tileset name="t" tilewidth="16" tileheight="16" tilecount="1" columns="1">{}{}</tileset>"#,
        "<x>".repeat(100),
        "</x>".repeat(100)
    );
    let scene = map_file("deep_set.tsx", &tileset);
    let map = tmx_4x2_naming(r#"<tileset firstgid="1" source="deep_set.tsx"/>"#);
    let dir = std::path::Path::new(&scene).parent().unwrap();
    std::fs::write(dir.join("uses_set.tmx"), map).unwrap();
    let err = level_ref("uses_set.tmx")
        .load(&scene)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("deep_set.tsx") && err.contains("64 deep"),
        "{err}"
    );
}

#[test]
fn a_tile_with_thousands_of_properties_painted_everywhere_is_read_once() {
    // One ice tile with 4 000 properties over all 512 × 512 cells: each
    // cell used to get its own copy of them (about 60 GB here; 450 MB for
    // 64 × 64 cells and 1 000 properties).
    let (side, junk) = (512usize, 4000);
    let names: Vec<String> = (0..junk).map(|i| format!("p{i}")).collect();
    let tmx_props: String = names
        .iter()
        .map(|n| format!(r#"<property name="{n}" type="int" value="1"/>"#))
        .collect();
    let cells = vec!["1"; side * side].join(",");
    let tmx = format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<map version="1.10" orientation="orthogonal" renderorder="right-down" width="{side}" height="{side}" tilewidth="16" tileheight="16" infinite="0">
 <tileset firstgid="1" name="t" tilewidth="16" tileheight="16" tilecount="1" columns="1">
  <tile id="0" type="ice"><properties><property name="friction" type="float" value="0.05"/>{tmx_props}</properties></tile>
 </tileset>
 <layer id="1" name="solid" width="{side}" height="{side}"><data encoding="csv">{cells}</data></layer>
</map>"#
    );
    let json_props: Vec<String> = names
        .iter()
        .map(|n| format!(r#"{{"name":"{n}","type":"int","value":1}}"#))
        .collect();
    let tmj = format!(
        r#"{{"orientation":"orthogonal","infinite":false,"width":{side},"height":{side},"tilewidth":16,"tileheight":16,
  "tilesets":[{{"firstgid":1,"name":"t","tiles":[{{"id":0,"class":"ice","properties":[{{"name":"friction","type":"float","value":0.05}},{}]}}]}}],
  "layers":[{{"type":"tilelayer","name":"solid","width":{side},"height":{side},"data":[{cells}]}}]}}"#,
        json_props.join(",")
    );
    let from_tmx = level_ref("many.tmx")
        .load(&map_file("many.tmx", &tmx))
        .unwrap();
    let from_tmj = level_ref("many.tmj")
        .load(&map_file("many.tmj", &tmj))
        .unwrap();
    assert_eq!(from_tmx, from_tmj);
    let map = &from_tmx.map;
    let side = side as u32;
    assert_eq!((map.width(), map.height()), (side, side));
    for (x, y) in [
        (0, 0),
        (side - 1, 0),
        (0, side - 1),
        (side - 1, side - 1),
        (300, 200),
    ] {
        let kind = map.kinds()[usize::from(map.get(x, y).expect("every cell is filled"))];
        assert_eq!(
            kind.friction, 0.05,
            "the tile's own property, at ({x}, {y})"
        );
    }
}

#[test]
fn a_level_counts_against_the_scenes_body_limit() {
    // A checkerboard of 1 500 × 1 500 cells: 1 125 000 one-cell boxes.
    let row = |odd: usize| -> String {
        (0..1500)
            .map(|x| {
                if (x + odd).is_multiple_of(2) {
                    '#'
                } else {
                    '.'
                }
            })
            .collect()
    };
    let ascii: Vec<String> = (0..1500).map(|y| row(y % 2)).collect();
    let text = format!(
        "(name: \"board\", collisions: (), tilemap: (ascii: \"{}\"))",
        ascii.join("\n")
    );
    let err = Scene::parse(&text, "board.ron")
        .unwrap()
        .build()
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("tilemap") && err.contains("makes 1125000 bodies") && err.contains("1000000"),
        "{err}"
    );
}

#[test]
fn odd_tile_sizes_and_far_spawn_points_are_errors() {
    // The map `text` saved as `name`, read with its `ground` layer solid.
    let load = |name: &str, text: &str| {
        let mut r = level_ref(name);
        r.layer = "ground".into();
        r.load(&map_file(name, text))
    };
    let zero_wide = tmx_with("").replace(r#"tilewidth="16""#, r#"tilewidth="0""#);
    let err = load("zero.tmx", &zero_wide).unwrap_err().to_string();
    assert!(
        err.contains("zero.tmx") && err.contains("at least 1 px"),
        "{err}"
    );
    let far = r#"<object id="7" name="p1" x="1e39" y="0"><point/></object>"#;
    let err = load("far.tmx", &tmx_with(far)).unwrap_err().to_string();
    assert!(
        err.contains("object 7 `p1`") && err.contains("beyond the world's coordinates"),
        "{err}"
    );
    // A spawn point where the world reaches is kept.
    let near = r#"<object id="7" name="p1" x="16" y="0"><point/></object>"#;
    let level = load("near.tmx", &tmx_with(near)).unwrap();
    assert_eq!(level.spawns, vec![("p1".to_owned(), Vec2::new(0.5, 0.5))]);
}

#[test]
fn a_platform_path_faster_than_the_world_allows_is_an_error() {
    let scene = |by: f32, period: f32| {
        format!(
            "(name: \"lift\", collisions: (), max_speed: 50, bodies: [(kind: Kinematic, shape: Box(half_extents: (1, 0.2)), position: (0, 0), path: (by: ({by}, 0), period: {period}))])"
        )
    };
    // Peak speed 3 × 10 / 0.5 = 60 m/s: refused when the file is read.
    let err = Scene::parse(&scene(10.0, 0.5), "lift.ron")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("bodies[0].path") && err.contains("60 m/s") && err.contains("50 m/s"),
        "{err}"
    );
    // 3 × 10 / 0.6 = 50 m/s: followed to the far end.
    let mut built = Scene::parse(&scene(10.0, 0.6), "lift.ron")
        .unwrap()
        .build()
        .unwrap();
    let lift = built.platforms[0].id;
    let mut far: f32 = 0.0;
    for _ in 0..36 {
        built.step(1.0 / 60.0);
        far = far.max(built.world.body(lift).unwrap().position.x);
    }
    assert!((far - 10.0).abs() < 1e-3, "{far}");
    assert_eq!(built.world.stats().rejected_inputs, 0);
}

#[test]
fn a_tile_object_is_placed_by_its_bottom_left_corner() {
    // Tiled places an object made from a tile by its bottom-left corner:
    // this one (16 × 16 px, y = 16 px) fills the top tile row of a map two
    // rows tall, so its centre is 1.5 tiles up: 0.75 m.
    let tmj = r#"{"orientation": "orthogonal", "width": 2, "height": 2, "tilewidth": 16, "tileheight": 16,
        "tilesets": [{"firstgid": 1, "tiles": []}],
        "layers": [{"type": "tilelayer", "name": "solid", "data": [0, 0, 0, 0]},
                   {"type": "objectgroup", "name": "things", "objects": [
                       {"id": 1, "name": "block", "gid": 1, "x": 0, "y": 16, "width": 16, "height": 16}]}]}"#;
    let scene = map_file("tile.tmj", tmj);
    let level = level_ref("tile.tmj").load(&scene).unwrap();
    assert_eq!(level.bodies[0].position, Vec2::new(0.25, 0.75));
}

#[test]
fn a_kinematic_map_on_a_path_carries_a_rider_standing_on_a_joint() {
    // A moving bridge of solid and bouncy cells (so several boxes, all of
    // friction 0.6), on a path
    // 2 m to the right and back in 4 s; a box rides it standing on the
    // joint of two of its boxes.
    let text = r###"(
        name: "bridge",
        forces: (gravity: (0, -9.81)),
        collisions: (),
        tilemap: (ascii: "##^^##^^##", cell: 0.5, kind: Kinematic, path: (by: (2, 0), period: 4)),
        bodies: [(name: "rider", shape: Box(half_extents: (0.2, 0.2)), position: (1.0, 0.7))],
    )"###;
    let mut built = Scene::parse(text, "bridge.ron").unwrap().build().unwrap();
    assert_eq!(
        built.platforms.len(),
        5,
        "every box of the map follows the path"
    );
    let rider = built.body_named("rider").unwrap();
    let mut fastest_drop = 0.0f32;
    let start = built.world.body(rider).unwrap().position;
    passo_tests::run_scene(&mut built, 120, |tick, world| {
        if tick > 30 {
            fastest_drop = fastest_drop.max(-world.body(rider).unwrap().velocity.y);
        }
    });
    // After 2 s the bridge is at its far end: the rider came along.
    let moved = built.world.body(rider).unwrap().position - start;
    assert!((moved.x - 2.0).abs() < 0.05, "carried {moved}");
    assert!(
        fastest_drop < 1e-3,
        "no bump at the joints: {fastest_drop} m/s down"
    );
    let err = Scene::parse(
        r##"(name: "x", tilemap: (ascii: "#", path: (by: (1, 0), period: 2)))"##,
        "t.ron",
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("tilemap.path"), "{err}");
}

#[test]
fn a_map_and_the_files_it_names_are_bounded_together() {
    // One 40 MB tileset named twice, spelled two ways (the `tiled` crate
    // caches by the path as written): 80 MB read for a map of 1 kB.
    let dir_of = |scene: &str| std::path::Path::new(scene).parent().unwrap().to_owned();
    let big = format!(
        r#"<?xml version="1.0"?><tileset name="t" tilewidth="16" tileheight="16" tilecount="1" columns="1"><!-- {} --></tileset>"#,
        "x".repeat(40 << 20)
    );
    let scene = map_file("big.tsx", &big);
    let dir = dir_of(&scene);
    std::fs::create_dir_all(dir.join("d")).unwrap();
    let map = tmx_4x2_naming(
        r#"<tileset firstgid="1" source="big.tsx"/><tileset firstgid="2" source="d/../big.tsx"/>"#,
    );
    std::fs::write(dir.join("twice.tmx"), map).unwrap();
    let err = level_ref("twice.tmx").load(&scene).unwrap_err().to_string();
    assert!(
        err.contains("big.tsx") && err.contains("64 MiB together"),
        "{err}"
    );
    // A .tmj of 18 million empty objects (54 MB; parsed, they took 3.6 GB
    // and more) is refused before it is parsed.
    let objects = format!(
        r#"{{"orientation": "orthogonal", "width": 1, "height": 1, "tilewidth": 16, "tileheight": 16,
        "layers": [{{"type": "tilelayer", "name": "solid", "data": [0]}},
        {{"type": "objectgroup", "name": "o", "objects": [{}{{}}]}}]}}"#,
        "{},".repeat(18_000_000)
    );
    let scene = map_file("objects.tmj", &objects);
    let err = level_ref("objects.tmj")
        .load(&scene)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("objects.tmj") && err.contains("JSON values"),
        "{err}"
    );
}

#[test]
fn a_tmj_tileset_listing_its_tiles_out_of_order_gives_each_cell_its_tile() {
    // Tiles are looked up by a binary search of the set sorted by id (a
    // search from the front for each distinct tile took hours on a map of
    // 640 × 640 distinct tiles against a set of 200 000).
    let tmj = r#"{"orientation": "orthogonal", "width": 4, "height": 1, "tilewidth": 16, "tileheight": 16,
        "tilesets": [{"firstgid": 1, "tiles": [
            {"id": 3, "class": "ice"}, {"id": 0, "class": "solid"}, {"id": 2, "class": "bouncy"}]}],
        "layers": [{"type": "tilelayer", "name": "solid", "data": [4, 1, 3, 2]}]}"#;
    let scene = map_file("order.tmj", tmj);
    let level = level_ref("order.tmj").load(&scene).unwrap();
    let map = &level.map;
    let kind = |x| map.kinds()[map.get(x, 0).unwrap() as usize];
    assert_eq!(kind(0), TileKind::ICE);
    assert_eq!(kind(1), TileKind::SOLID);
    assert_eq!(kind(2), TileKind::BOUNCY);
    // Id 1 is not listed: a plain solid tile.
    assert_eq!(kind(3), TileKind::SOLID);
}

#[test]
fn a_tmj_is_as_strict_about_numbers_as_a_tmx() {
    let map = |width: &str, firstgid: &str, cell: &str| {
        format!(
            r#"{{"orientation": "orthogonal", "width": {width}, "height": 1, "tilewidth": 16, "tileheight": 16,
            "tilesets": [{{"firstgid": {firstgid}, "tilecount": 1, "tiles": []}}],
            "layers": [{{"type": "tilelayer", "name": "solid", "data": [1, {cell}]}}]}}"#
        )
    };
    let load = |name: &str, text: &str| level_ref(name).load(&map_file(name, text));
    // A well-formed map loads: 2 cells, both solid.
    assert!(load("good.tmj", &map("2", "1", "1")).is_ok());
    // Tile data that is not a tile id is refused, naming the cell.
    for cell in ["-1", "2.5", "\"x\"", "null", "true", "4294967296"] {
        let err = load("cell.tmj", &map("2", "1", cell))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("cell.tmj") && err.contains("cell 1") && err.contains(cell),
            "{cell}: {err}"
        );
    }
    for firstgid in ["0", "-1", "1.5", "\"1\""] {
        let err = load("gid.tmj", &map("2", firstgid, "1"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("firstgid"), "{firstgid}: {err}");
    }
    let err = load("wide.tmj", &map("2.5", "1", "1"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("`width` must be a whole number"), "{err}");
}

/// A map reads only regular files inside its own folder, or inside the
/// folder its scene names as `root`: a map naming `../../…`, `/dev/zero` or
/// a pipe was opened, and a pipe blocked the load.
#[test]
fn a_map_reads_only_regular_files_inside_its_folder() {
    let set = r#"<?xml version="1.0"?><tileset name="t" tilewidth="16" tileheight="16" tilecount="1" columns="1"/>"#;
    // levels/ holds the maps; shared/ beside it a tileset.
    let scene = map_file("scene.ron", "");
    let dir = std::path::Path::new(&scene).parent().unwrap().to_owned();
    for sub in ["levels", "shared"] {
        std::fs::create_dir_all(dir.join(sub)).unwrap();
    }
    std::fs::write(dir.join("shared/set.tsx"), set).unwrap();
    std::fs::write(dir.join("levels/set.tsx"), set).unwrap();
    let fifo = dir.join("levels/pipe.tsx");
    let _ = std::fs::remove_file(&fifo);
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo");
    let naming = |name: &str, source: &str| {
        let map = tmx_4x2_naming(&format!(r#"<tileset firstgid="1" source="{source}"/>"#));
        std::fs::write(dir.join("levels").join(name), map).unwrap();
        format!("levels/{name}")
    };
    // Beside the map: read.
    let file = naming("inside.tmx", "set.tsx");
    assert!(level_ref(&file).load(&scene).is_ok());
    // Outside its folder, a device, a pipe: refused, naming what and why.
    let cases = [
        ("up.tmx", "../shared/set.tsx", "outside the map's folder"),
        (
            "far.tmx",
            "../../../../../../../etc/hostname",
            "outside the map's folder",
        ),
        ("zero.tmx", "/dev/zero", "not a regular file"),
        ("pipe.tmx", "pipe.tsx", "not a regular file"),
    ];
    for (name, source, why) in cases {
        let file = naming(name, source);
        let err = level_ref(&file).load(&scene).unwrap_err().to_string();
        assert!(err.contains(name) && err.contains(why), "{source}: {err}");
    }
    // A scene that names their common folder as the root reads ../shared.
    let file = naming("up.tmx", "../shared/set.tsx");
    let mut r = level_ref(&file);
    r.root = Some(".".into());
    assert!(r.load(&scene).is_ok(), "{:?}", r.load(&scene));
}

/// What the `tiled` crate builds before any check of Passo's could run is
/// bounded before it gets the file: an infinite map's chunks (one 67
/// million tiles wide took 5.8 GB), a tileset's tile count (4 294 967 295
/// aborted the process asking for 1.7 TB), a chunk at x = 2^31 - 1 (an
/// overflow panic inside the crate) and millions of objects (2.2 GB for
/// six million `<object/>`, 1.3 GB for eight million `{}` in a `.tmj`).
#[test]
fn a_map_cannot_make_the_tiled_crate_build_without_bound() {
    let csv = r#"<data encoding="csv">1,0,0,1,1,1,1,1</data>"#;
    let load = |name: &str, text: &str| {
        level_ref(name)
            .load(&map_file(name, text))
            .unwrap_err()
            .to_string()
    };
    let infinite = tmx_4x2(r#"<data encoding="csv"><chunk x="0" y="0" width="4" height="2">1,0,0,1,1,1,1,1</chunk></data>"#)
        .replace(r#"infinite="0""#, r#"infinite="1""#);
    let err = load("infinite.tmx", &infinite);
    assert!(
        err.contains("infinite.tmx") && err.contains("an infinite map"),
        "{err}"
    );
    let chunk = tmx_4x2(
        r#"<data encoding="csv"><chunk x="2147483647" y="0" width="2" height="1">1,1</chunk></data>"#,
    );
    let err = load("chunk.tmx", &chunk);
    assert!(err.contains("has a chunk"), "{err}");
    for (count, image) in [
        ("4294967295", ""),
        (
            "30000000",
            r#"<image source="t.png" width="16" height="16"/>"#,
        ),
        ("65537", ""),
    ] {
        let set = format!(
            r#"<tileset firstgid="1" name="t" tilewidth="16" tileheight="16" tilecount="{count}" columns="1">{image}</tileset>"#
        );
        let inline = tmx_4x2(csv).replace(
            r#"<tileset firstgid="1" name="t" tilewidth="16" tileheight="16" tilecount="1" columns="1"/>"#,
            &set,
        );
        let err = load("count.tmx", &inline);
        assert!(
            err.contains(&format!("a tileset of {count} tiles")),
            "{count}: {err}"
        );
        // The same tileset in its own file.
        let scene = map_file("count.tsx", &format!(r#"<?xml version="1.0"?>{set}"#));
        let dir = std::path::Path::new(&scene).parent().unwrap().to_owned();
        let map = tmx_4x2_naming(r#"<tileset firstgid="1" source="count.tsx"/>"#);
        std::fs::write(dir.join("external.tmx"), map).unwrap();
        let err = level_ref("external.tmx")
            .load(&scene)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("count.tsx") && err.contains(count),
            "{count}: {err}"
        );
    }
    // The most tiles a tileset may have still loads.
    let most = tmx_4x2(csv).replace(r#"tilecount="1""#, r#"tilecount="65536""#);
    assert!(
        level_ref("most.tmx")
            .load(&map_file("most.tmx", &most))
            .is_ok()
    );
    // Objects past the bound, in both formats.
    let many = r#"<object id="1" x="0" y="0"/>"#.repeat(262_145);
    let err = load("objects.tmx", &tmx_with(&many));
    assert!(err.contains("more than 262144 objects"), "{err}");
    let braces = vec!["{}"; 262_145].join(",");
    let tmj = format!(
        r#"{{"orientation": "orthogonal", "width": 2, "height": 1, "tilewidth": 16, "tileheight": 16,
        "tilesets": [], "layers": [{{"type": "tilelayer", "name": "solid", "data": [0, 0]}},
        {{"type": "objectgroup", "name": "things", "objects": [{braces}]}}]}}"#
    );
    let err = load("braces.tmj", &tmj);
    assert!(err.contains("more than 262144 objects"), "{err}");
}

/// Maps the `tmx` fuzz target found: a layer's CSV cut by an element
/// (`tmx_short_first_section.tmx`), and cut by a `<layer>` tag, which must
/// not change the size the data is held to (`tmx_layer_inside_data.tmx`).
/// The `tiled` crate, which reads the text up to the element alone,
/// indexed past the tiles it had. Each is refused before the crate reads
/// it, with no panic (a panic, even caught, aborts a fuzzer, and prints in
/// a game).
#[test]
fn a_layer_whose_text_an_element_cuts_short_is_refused_without_a_panic() {
    for found in ["tmx_short_first_section.tmx", "tmx_layer_inside_data.tmx"] {
        let bytes = std::fs::read(
            PathBuf::from(env!("CARGO_MANIFEST_DIR"))
                .join("fuzz_found")
                .join(found),
        )
        .unwrap();
        let scene = map_file(found, &String::from_utf8_lossy(&bytes));
        let hook = std::panic::take_hook();
        let panicked = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let flag = panicked.clone();
        std::panic::set_hook(Box::new(move |_| {
            flag.store(true, std::sync::atomic::Ordering::SeqCst)
        }));
        let result = level_ref(found).load(&scene);
        std::panic::set_hook(hook);
        let err = result.unwrap_err().to_string();
        assert!(err.contains("cells whose data holds"), "{found}: {err}");
        assert!(
            !panicked.load(std::sync::atomic::Ordering::SeqCst),
            "{found}: a panic was caught on the way"
        );
    }
}

#[test]
fn polygons_and_polylines_in_tiled_become_chains_solid_on_the_right_side() {
    // A polyline drawn left to right (ground: solid below), and a
    // triangle drawn either way round (solid inside): the same in .tmx
    // and .tmj. 16 px tiles of 0.5 m; the map is 8 tiles tall (4 m).
    let tmx = |polygon: &str| {
        format!(
            r#"<?xml version="1.0" encoding="UTF-8"?>
<map version="1.10" orientation="orthogonal" renderorder="right-down" width="16" height="8" tilewidth="16" tileheight="16" infinite="0">
 <layer id="1" name="solid" width="16" height="8"><data encoding="csv">{}</data></layer>
 <objectgroup id="2" name="things">
  <object id="1" name="hill" x="0" y="96"><polyline points="0,0 64,0 128,-32 256,-32"/></object>
  <object id="2" name="rock" x="160" y="32"><polygon points="{polygon}"/></object>
 </objectgroup>
</map>"#,
            vec!["0"; 16 * 8].join(",")
        )
    };
    let tmj = r#"{"orientation": "orthogonal", "width": 16, "height": 8, "tilewidth": 16, "tileheight": 16,
        "tilesets": [],
        "layers": [{"type": "tilelayer", "name": "solid", "data": [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
            0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
            0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
            0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
            0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]},
                   {"type": "objectgroup", "name": "things", "objects": [
                       {"id": 1, "name": "hill", "x": 0, "y": 96, "polyline": [{"x": 0, "y": 0}, {"x": 64, "y": 0}, {"x": 128, "y": -32}, {"x": 256, "y": -32}]},
                       {"id": 2, "name": "rock", "x": 160, "y": 32, "polygon": [{"x": 0, "y": 0}, {"x": 32, "y": 0}, {"x": 16, "y": 16}]}]}]}"#;
    let mut levels = Vec::new();
    for (name, text) in [
        ("a.tmx", tmx("0,0 32,0 16,16")),
        ("b.tmx", tmx("0,0 16,16 32,0")),
        ("c.tmj", tmj.to_owned()),
    ] {
        let scene = map_file(name, &text);
        levels.push(level_ref(name).load(&scene).unwrap());
    }
    for level in &levels {
        assert_eq!(level.chains.len(), 2);
        let hill = &level.chains[0];
        assert!(!hill.closed && hill.name.as_deref() == Some("hill"));
        // 96 px down a 128 px map is 1 m up; 32 px is 0.5 m.
        assert_eq!(
            hill.points,
            [
                Vec2::new(0.0, 1.0),
                Vec2::new(2.0, 1.0),
                Vec2::new(4.0, 2.0),
                Vec2::new(8.0, 2.0)
            ]
        );
        // Clockwise however it was drawn: solid inside.
        let rock = &level.chains[1].points;
        let twice_area: f32 = (0..3).map(|i| rock[i].perp_dot(rock[(i + 1) % 3])).sum();
        assert!(level.chains[1].closed && twice_area < 0.0, "{rock:?}");
    }
    // In a scene, a ball dropped on the slope's top rests there.
    let scene_text = r#"(name: "Hill", collisions: (), forces: (gravity: (0, -9.81)),
        tilemap: (file: "a.tmx", layer: "solid", cell: 0.5),
        bodies: [(name: "ball", shape: Circle(radius: 0.25), position: (6, 3))])"#;
    let path = map_file("a.tmx", &tmx("0,0 32,0 16,16"));
    let scene = passo_scene::Scene::parse(scene_text, &path).unwrap();
    let mut built = scene.build().unwrap();
    for _ in 0..120 {
        built.step(1.0 / 60.0);
    }
    let ball = built.world.body(built.body_named("ball").unwrap()).unwrap();
    assert!((ball.position.y - 2.25).abs() < 0.006, "{ball:?}");
}
