//! Reading map files of the Tiled editor into what Passo uses of them
//! ([`RawMap`]): `.tmx` through the `tiled` crate, `.tmj` as JSON (the
//! crate reads no JSON maps). Only the wanted tile layer's tiles are read;
//! a layer whose tiles do not match the map's size, or a map larger than a
//! tile map may be, is an error, never a panic.

use crate::error::SceneError;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// A property value, as both formats give it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Value {
    Bool(bool),
    Number(f32),
    Text(String),
}

pub(crate) type Properties = Vec<(String, Value)>;

/// A tile of the solid layer: its class and properties, and how it looks.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct RawTile {
    pub class: String,
    pub properties: Properties,
    pub art: Option<RawArt>,
}

/// How a tile looks: a rectangle of an image, in pixels.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct RawArt {
    /// The image file, as the map names it, joined to the map's folder.
    pub image: PathBuf,
    /// The image's width and height, pixels, as the tileset gives them.
    pub image_size: (u32, u32),
    /// `[x, y, width, height]` of the tile in the image, pixels from its
    /// top-left corner.
    pub rect: [u32; 4],
}

/// A `.tmj` tileset: its first global id, its listed tiles sorted by local
/// id, and its image.
type TmjSet = (u32, Vec<(u32, RawTile)>, Option<SetImage>);

/// A `.tmj` tileset's image and how its tiles are laid out in it.
struct SetImage {
    image: PathBuf,
    image_size: (u32, u32),
    columns: u32,
    tile_size: (u32, u32),
    margin: u32,
    spacing: u32,
}

/// Where tile `id` of a tileset of `columns` columns lies in its image.
pub(crate) fn tile_rect(
    id: u32,
    columns: u32,
    size: (u32, u32),
    margin: u32,
    spacing: u32,
) -> [u32; 4] {
    let columns = columns.max(1);
    let (col, row) = (id % columns, id / columns);
    [
        margin.saturating_add(col.saturating_mul(size.0.saturating_add(spacing))),
        margin.saturating_add(row.saturating_mul(size.1.saturating_add(spacing))),
        size.0,
        size.1,
    ]
}

#[derive(Clone, Debug, PartialEq)]
pub(crate) enum RawShape {
    Rect(f32, f32),
    Ellipse(f32, f32),
    Point,
    /// A closed outline: its points relative to the object's position,
    /// pixels.
    Polygon(Vec<(f32, f32)>),
    /// An open line through its points, relative to the object's position.
    Polyline(Vec<(f32, f32)>),
    /// A shape Passo has no body for (text, capsule).
    Other(&'static str),
}

#[derive(Clone, Debug, PartialEq)]
pub(crate) struct RawObject {
    pub layer: String,
    pub id: u32,
    pub name: String,
    pub class: String,
    pub x: f32,
    pub y: f32,
    pub rotation: f32,
    pub shape: RawShape,
    pub properties: Properties,
}

/// A map in neither format's types: what Passo reads of it.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct RawMap {
    pub width: u32,
    pub height: u32,
    pub tile_width: f32,
    pub tile_height: f32,
    /// The distinct tiles the wanted layer shows, each read once however
    /// many cells show it (a tile's properties are not copied per cell).
    pub tiles: Vec<RawTile>,
    /// Every tile layer: its name and, cell by cell, row by row from the
    /// top, the index in `tiles` of the tile there (only the wanted
    /// layer's cells are read).
    pub tile_layers: Vec<(String, Vec<Option<u32>>)>,
    pub objects: Vec<RawObject>,
}

/// The distinct tiles of a layer by a key of the file's (a tileset and a
/// tile id, or a global id), each read once into [`RawMap::tiles`].
struct Palette<K>(BTreeMap<K, u32>);

impl<K: Ord> Palette<K> {
    fn new() -> Self {
        Self(BTreeMap::new())
    }

    /// The index in `tiles` of the tile `key`, read by `read` the first time.
    fn index(&mut self, key: K, tiles: &mut Vec<RawTile>, read: impl FnOnce() -> RawTile) -> u32 {
        *self.0.entry(key).or_insert_with(|| {
            tiles.push(read());
            (tiles.len() - 1) as u32
        })
    }
}

pub(crate) fn read_tmx(path: &Path, wanted_layer: &str, root: &Path) -> Result<RawMap, SceneError> {
    let shown = path.display().to_string();
    // Every file the map names (tilesets, templates) is read through the
    // same checks, out of one budget for them all, from inside `root` alone.
    let budget = crate::limits::MapBudget::new(root);
    let map = tiled::Loader::with_reader(|p: &Path| budget.read_tiled_xml(p))
        .load_tmx_map(path)
        .map_err(|e| SceneError::Io {
            source_name: shown.clone(),
            message: e.to_string(),
        })?;
    if map.orientation != tiled::Orientation::Orthogonal || map.infinite() {
        return Err(SceneError::Invalid {
            source_name: shown,
            field: "map".into(),
            message: "must be orthogonal and finite".into(),
        });
    }
    if map.width as usize * map.height as usize > passo_physics::MAX_TILE_CELLS {
        return Err(SceneError::Invalid {
            source_name: shown,
            field: "map".into(),
            message: format!(
                "{} × {} tiles is more than a tile map may have (4096 × 4096)",
                map.width, map.height
            ),
        });
    }
    let mut raw = RawMap {
        width: map.width,
        height: map.height,
        tile_width: map.tile_width as f32,
        tile_height: map.tile_height as f32,
        ..RawMap::default()
    };
    // The `tiled` crate indexes a layer's tiles without checking that the
    // file gave as many as the map has cells: a short layer would panic
    // inside it, so that becomes an error here.
    let read = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        collect_tmx_layers(&map, map.layers(), wanted_layer, &mut raw)
    }));
    if read.is_err() {
        return Err(SceneError::Invalid {
            source_name: shown,
            field: format!("layer `{wanted_layer}`"),
            message: "has fewer tiles than the map has cells".into(),
        });
    }
    Ok(raw)
}

fn collect_tmx_layers<'m>(
    map: &'m tiled::Map,
    layers: impl Iterator<Item = tiled::Layer<'m>>,
    wanted: &str,
    raw: &mut RawMap,
) {
    for layer in layers {
        let name = layer.name.clone();
        match layer.layer_type() {
            tiled::LayerType::Tiles(_) if name != wanted => {
                raw.tile_layers.push((name, Vec::new()))
            }
            tiled::LayerType::Tiles(tiles) => {
                let mut palette = Palette::new();
                let mut cells = Vec::with_capacity(map.width as usize * map.height as usize);
                for y in 0..map.height as i32 {
                    for x in 0..map.width as i32 {
                        cells.push(tiles.get_tile(x, y).map(|t| {
                            let key = (t.tileset_index(), t.id());
                            palette.index(key, &mut raw.tiles, || {
                                let art = tmx_art(t.get_tileset(), t.id(), t.get_tile());
                                match t.get_tile() {
                                    Some(tile) => RawTile {
                                        class: tile.user_type.clone(),
                                        properties: tmx_properties(&tile.properties),
                                        art,
                                    },
                                    None => RawTile {
                                        art,
                                        ..RawTile::default()
                                    },
                                }
                            })
                        }));
                    }
                }
                raw.tile_layers.push((name, cells));
            }
            tiled::LayerType::Objects(objects) => {
                for object in objects.objects() {
                    #[allow(deprecated)]
                    let shape = match &object.shape {
                        tiled::ObjectShape::Rect { width, height } => {
                            RawShape::Rect(*width, *height)
                        }
                        tiled::ObjectShape::Ellipse { width, height } => {
                            RawShape::Ellipse(*width, *height)
                        }
                        tiled::ObjectShape::Point(..) => RawShape::Point,
                        tiled::ObjectShape::Polygon { points } => RawShape::Polygon(points.clone()),
                        tiled::ObjectShape::Polyline { points } => {
                            RawShape::Polyline(points.clone())
                        }
                        tiled::ObjectShape::Capsule { .. } => RawShape::Other("a capsule"),
                        tiled::ObjectShape::Text { .. } => RawShape::Other("a text"),
                    };
                    // A tile object is placed by its bottom-left corner.
                    let tile_height = match (&object.shape, object.tile_data()) {
                        (tiled::ObjectShape::Rect { height, .. }, Some(_)) => *height,
                        _ => 0.0,
                    };
                    raw.objects.push(RawObject {
                        layer: name.clone(),
                        id: object.id(),
                        name: object.name.clone(),
                        class: object.user_type.clone(),
                        x: object.x,
                        y: object.y - tile_height,
                        rotation: object.rotation,
                        shape,
                        properties: tmx_properties(&object.properties),
                    });
                }
            }
            tiled::LayerType::Group(group) => collect_tmx_layers(map, group.layers(), wanted, raw),
            tiled::LayerType::Image(_) => {}
        }
    }
}

/// How tile `id` of `set` looks: its rectangle of the tileset's image, or
/// the tile's own image in an image-collection tileset.
fn tmx_art(set: &tiled::Tileset, id: u32, tile: Option<tiled::Tile<'_>>) -> Option<RawArt> {
    let size = |image: &tiled::Image| {
        let w = u32::try_from(image.width).ok().filter(|&w| w > 0)?;
        let h = u32::try_from(image.height).ok().filter(|&h| h > 0)?;
        Some((w, h))
    };
    if let Some(image) = &set.image {
        return Some(RawArt {
            image: image.source.clone(),
            image_size: size(image)?,
            rect: tile_rect(
                id,
                set.columns,
                (set.tile_width, set.tile_height),
                set.margin,
                set.spacing,
            ),
        });
    }
    let image = tile?.image.clone()?;
    let image_size = size(&image)?;
    Some(RawArt {
        image: image.source,
        image_size,
        rect: [0, 0, image_size.0, image_size.1],
    })
}

fn tmx_properties(properties: &tiled::Properties) -> Properties {
    let mut out: Properties = properties
        .iter()
        .filter_map(|(name, value)| {
            let value = match value {
                tiled::PropertyValue::BoolValue(b) => Value::Bool(*b),
                tiled::PropertyValue::FloatValue(f) => Value::Number(*f),
                tiled::PropertyValue::IntValue(i) => Value::Number(*i as f32),
                tiled::PropertyValue::StringValue(s) => Value::Text(s.clone()),
                _ => return None,
            };
            Some((name.clone(), value))
        })
        .collect();
    // A hash map's order is not the file's: sort, so errors come out the
    // same every run.
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// Reads a map saved as JSON (`.tmj`): the same model as a `.tmx`, with
/// tilesets embedded or in `.tsj` files beside it.
pub(crate) fn read_tmj(path: &Path, wanted_layer: &str, root: &Path) -> Result<RawMap, SceneError> {
    use serde_json::Value as Json;
    let shown = path.display().to_string();
    let fail = |message: String| SceneError::Invalid {
        source_name: shown.clone(),
        field: "map".into(),
        message,
    };
    // The map and its tilesets are read out of one budget, from inside
    // `root` alone.
    let budget = crate::limits::MapBudget::new(root);
    let read = |p: &Path| -> Result<Json, SceneError> {
        let text = budget.read_json(p).map_err(|e| SceneError::Io {
            source_name: p.display().to_string(),
            message: e.to_string(),
        })?;
        serde_json::from_str(&text).map_err(|e| SceneError::Syntax {
            source_name: p.display().to_string(),
            line: e.line(),
            column: e.column(),
            field: None,
            message: e.to_string(),
        })
    };
    let json = read(path)?;
    let number = |v: &Json, key: &str| v.get(key).and_then(Json::as_f64);
    let text = |v: &Json, key: &str| v.get(key).and_then(Json::as_str).unwrap_or("").to_owned();
    if text(&json, "orientation") != "orthogonal" || json.get("infinite") == Some(&Json::Bool(true))
    {
        return Err(fail("must be orthogonal and finite".into()));
    }
    // Sizes and ids are whole numbers, as Tiled writes them and as the
    // `.tmx` reader requires: 1.5 is refused, not read as 1.
    let dimension = |key: &str| {
        number(&json, key)
            .filter(|n| *n >= 1.0 && *n <= 65_536.0 && n.fract() == 0.0)
            .ok_or_else(|| fail(format!("`{key}` must be a whole number in [1, 65536]")))
    };
    let mut raw = RawMap {
        width: dimension("width")? as u32,
        height: dimension("height")? as u32,
        tile_width: dimension("tilewidth")? as f32,
        tile_height: dimension("tileheight")? as f32,
        ..RawMap::default()
    };
    if raw.width as usize * raw.height as usize > passo_physics::MAX_TILE_CELLS {
        return Err(fail(format!(
            "{} × {} tiles is more than a tile map may have (4096 × 4096)",
            raw.width, raw.height
        )));
    }
    // Tiles by global id.
    let mut sets: Vec<TmjSet> = Vec::new();
    for set in json
        .get("tilesets")
        .and_then(Json::as_array)
        .into_iter()
        .flatten()
    {
        let first = match set.get("firstgid") {
            None => 1,
            Some(v) => v
                .as_u64()
                .filter(|&n| (1..=u64::from(u32::MAX)).contains(&n))
                .ok_or_else(|| {
                    fail(format!(
                        "a tileset's `firstgid` must be a whole number from 1, not {v}"
                    ))
                })? as u32,
        };
        // Images are named relative to the file that names them.
        let map_dir = path.parent().unwrap_or(Path::new(""));
        let (set, dir) = match set.get("source").and_then(Json::as_str) {
            Some(source) => {
                let file = map_dir.join(source);
                let dir = file.parent().unwrap_or(Path::new("")).to_path_buf();
                (read(&file)?, dir)
            }
            None => (set.clone(), map_dir.to_path_buf()),
        };
        let whole = |v: &Json, key: &str| {
            v.get(key)
                .and_then(Json::as_u64)
                .and_then(|n| u32::try_from(n).ok())
        };
        let image_of = |v: &Json| -> Option<(PathBuf, (u32, u32))> {
            let file = v.get("image").and_then(Json::as_str)?;
            let w = whole(v, "imagewidth").filter(|&w| w > 0)?;
            let h = whole(v, "imageheight").filter(|&h| h > 0)?;
            Some((dir.join(file), (w, h)))
        };
        let set_image = image_of(&set).map(|(image, image_size)| SetImage {
            image,
            image_size,
            columns: whole(&set, "columns").unwrap_or(1),
            tile_size: (
                whole(&set, "tilewidth").unwrap_or(0),
                whole(&set, "tileheight").unwrap_or(0),
            ),
            margin: whole(&set, "margin").unwrap_or(0),
            spacing: whole(&set, "spacing").unwrap_or(0),
        });
        let mut tiles: Vec<(u32, RawTile)> = set
            .get("tiles")
            .and_then(Json::as_array)
            .into_iter()
            .flatten()
            .map(|t| {
                let class = t.get("class").or_else(|| t.get("type"));
                let id = number(t, "id").unwrap_or(0.0) as u32;
                // A tile of an image collection has its own image.
                let art = image_of(t).map(|(image, image_size)| RawArt {
                    image,
                    image_size,
                    rect: [0, 0, image_size.0, image_size.1],
                });
                let tile = RawTile {
                    class: class.and_then(Json::as_str).unwrap_or("").to_owned(),
                    properties: json_properties(t),
                    art,
                };
                (id, tile)
            })
            .collect();
        // Stable: of two entries for one id, the first is found, as a
        // search from the front found it.
        tiles.sort_by_key(|t| t.0);
        sets.push((first, tiles, set_image));
    }
    sets.sort_by_key(|s| s.0);
    // A binary search of the set's tiles: a linear one for each distinct
    // tile of the layer took hours for 640 × 640 distinct tiles against
    // 200 000 in the set.
    let tile_of = |gid: u32| {
        let set = sets.iter().rev().find(|s| s.0 <= gid)?;
        let local = gid - set.0;
        let at = set.1.partition_point(|t| t.0 < local);
        let mut tile = set
            .1
            .get(at)
            .filter(|t| t.0 == local)
            .map(|t| t.1.clone())
            .unwrap_or_default();
        // A tile of the set's image, unless it has an image of its own.
        if tile.art.is_none()
            && let Some(i) = &set.2
        {
            tile.art = Some(RawArt {
                image: i.image.clone(),
                image_size: i.image_size,
                rect: tile_rect(local, i.columns, i.tile_size, i.margin, i.spacing),
            });
        }
        Some(tile)
    };
    fn layers(json: &Json) -> Vec<&Json> {
        let mut out = Vec::new();
        for layer in json
            .get("layers")
            .and_then(Json::as_array)
            .into_iter()
            .flatten()
        {
            if layer.get("type").and_then(Json::as_str) == Some("group") {
                out.extend(layers(layer));
            } else {
                out.push(layer);
            }
        }
        out
    }
    for layer in layers(&json) {
        let name = text(layer, "name");
        match layer.get("type").and_then(Json::as_str) {
            Some("tilelayer") => {
                if name != wanted_layer {
                    raw.tile_layers.push((name, Vec::new()));
                    continue;
                }
                let Some(data) = layer.get("data").and_then(Json::as_array) else {
                    return Err(fail(format!(
                        "layer `{name}`: tile data must be a CSV array (Tiled: layer format CSV)"
                    )));
                };
                if data.len() != raw.width as usize * raw.height as usize {
                    return Err(fail(format!(
                        "layer `{name}` has {} tiles for a map of {} × {} cells",
                        data.len(),
                        raw.width,
                        raw.height
                    )));
                }
                // Each cell is a global tile id, a whole number from 0 (empty)
                // to 2^32 - 1, as the `.tmx` reader requires; anything else
                // is refused rather than read as an empty cell. The top bits
                // of an id are flip flags.
                let mut gids = Vec::with_capacity(data.len());
                for (k, v) in data.iter().enumerate() {
                    let gid = v.as_u64().filter(|&n| n <= u64::from(u32::MAX)).ok_or_else(|| {
                        fail(format!(
                            "layer `{name}`: cell {k} holds {v}: a tile id is a whole number from 0"
                        ))
                    })?;
                    gids.push(gid as u32 & 0x1FFF_FFFF);
                }
                let mut palette = Palette::new();
                let cells = gids
                    .into_iter()
                    .map(|gid| {
                        (gid != 0).then(|| {
                            let read = || tile_of(gid).unwrap_or_default();
                            palette.index(gid, &mut raw.tiles, read)
                        })
                    })
                    .collect();
                raw.tile_layers.push((name, cells));
            }
            Some("objectgroup") => {
                for object in layer
                    .get("objects")
                    .and_then(Json::as_array)
                    .into_iter()
                    .flatten()
                {
                    let flag = |key: &str| object.get(key) == Some(&Json::Bool(true));
                    let (w, h) = (
                        number(object, "width").unwrap_or(0.0) as f32,
                        number(object, "height").unwrap_or(0.0) as f32,
                    );
                    let shape = if flag("point") {
                        RawShape::Point
                    } else if flag("ellipse") {
                        RawShape::Ellipse(w, h)
                    } else if let Some(points) = object.get("polygon") {
                        json_points(points).map_or(
                            RawShape::Other("a polygon with bad points"),
                            RawShape::Polygon,
                        )
                    } else if let Some(points) = object.get("polyline") {
                        json_points(points).map_or(
                            RawShape::Other("a polyline with bad points"),
                            RawShape::Polyline,
                        )
                    } else if object.get("text").is_some() {
                        RawShape::Other("a text")
                    } else if flag("capsule") {
                        RawShape::Other("a capsule")
                    } else {
                        RawShape::Rect(w, h)
                    };
                    let class = object.get("class").or_else(|| object.get("type"));
                    raw.objects.push(RawObject {
                        layer: name.clone(),
                        id: number(object, "id").unwrap_or(0.0) as u32,
                        name: text(object, "name"),
                        class: class.and_then(Json::as_str).unwrap_or("").to_owned(),
                        x: number(object, "x").unwrap_or(0.0) as f32,
                        // A tile object is placed by its bottom-left corner.
                        y: number(object, "y").unwrap_or(0.0) as f32
                            - if object.get("gid").is_some() { h } else { 0.0 },
                        rotation: number(object, "rotation").unwrap_or(0.0) as f32,
                        shape,
                        properties: json_properties(object),
                    });
                }
            }
            _ => {}
        }
    }
    Ok(raw)
}

fn json_properties(v: &serde_json::Value) -> Properties {
    use serde_json::Value as Json;
    let mut out: Properties = v
        .get("properties")
        .and_then(Json::as_array)
        .into_iter()
        .flatten()
        .filter_map(|p| {
            let name = p.get("name")?.as_str()?.to_owned();
            let value = match p.get("value")? {
                Json::Bool(b) => Value::Bool(*b),
                Json::Number(n) => Value::Number(n.as_f64()? as f32),
                Json::String(s) => Value::Text(s.clone()),
                _ => return None,
            };
            Some((name, value))
        })
        .collect();
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// The points of a `.tmj` polygon or polyline: `[{"x": .., "y": ..}, ...]`;
/// `None` if any is not a pair of numbers.
fn json_points(value: &serde_json::Value) -> Option<Vec<(f32, f32)>> {
    let coordinate = |p: &serde_json::Value, key: &str| p.get(key)?.as_f64().map(|v| v as f32);
    value
        .as_array()?
        .iter()
        .map(|p| Some((coordinate(p, "x")?, coordinate(p, "y")?)))
        .collect()
}
