//! Levels on a grid: a scene's `tilemap`, read from a map made in the
//! Tiled editor (`.tmx` through the `tiled` crate, `.tmj` as JSON) or drawn
//! as ASCII art.
//!
//! From a Tiled map Passo reads:
//! - the tile layer named by `layer` (default `solid`): every tile in it is
//!   a solid cell. A tile's class in its tileset (`ice`, `bouncy`,
//!   `one_way`; anything else is plain ground) and its custom properties
//!   `friction`, `restitution` and `one_way` (bool) give the cell's kind;
//! - every object layer: rectangles become boxes, ellipses (as wide as they
//!   are tall) circles, points spawn points. An object's class (or its
//!   `kind` property) is its body kind: `Static` (the default), `Dynamic`,
//!   `Kinematic`, `Sensor` (also `coin`, `goal`, `trigger`), `OneWay`
//!   (also `platform`), or `Spawn`. Its custom properties `friction`,
//!   `restitution`, `density`, `mass`, `sensor`, `one_way`, `bullet`,
//!   `vx`, `vy` (velocity, m/s), `path_x`, `path_y` and `period` (a
//!   kinematic body's back-and-forth path) set those fields; other
//!   properties are the game's own and are left alone.
//!
//! One tile is `cell` metres; Tiled's y axis points down, Passo's up, so
//! the map's bottom-left corner lands on `origin`.

use crate::error::SceneError;
use crate::format::{BodySpec, Colour};
use crate::map_ref::{PlatformPath, TileMapRef};
use passo_physics::glam::Vec2;
use passo_physics::{BodyKind, Shape, TileKind, TileMap};
use std::path::{Path, PathBuf};

/// A level read from a map: its cells, and the bodies and spawn points of
/// its object layers.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    /// The solid cells.
    pub map: TileMap,
    /// Bodies from object layers, named after their objects.
    pub bodies: Vec<BodySpec>,
    /// Spawn points by name (an unnamed one is `"spawn"`), metres.
    pub spawns: Vec<(String, Vec2)>,
}

impl TileMapRef {
    /// Reads the level; `scene` is the scene file's path or name (a map
    /// file is looked for beside it).
    pub fn load(&self, scene: &str) -> Result<Level, SceneError> {
        let invalid = |source: &str, field: String, message: String| SceneError::Invalid {
            source_name: source.to_owned(),
            field,
            message,
        };
        if let Some(text) = &self.ascii {
            let map = TileMap::from_ascii(text, Vec2::splat(self.cell), self.origin)
                .map_err(|e| invalid(scene, "tilemap.ascii".into(), e.to_string()))?;
            return Ok(Level {
                map,
                bodies: Vec::new(),
                spawns: Vec::new(),
            });
        }
        let Some(file) = &self.file else {
            return Err(invalid(
                scene,
                "tilemap".into(),
                "needs a `file` or `ascii`".into(),
            ));
        };
        let path = beside(scene, file);
        let shown = path.display().to_string();
        let raw = match path.extension().and_then(|e| e.to_str()) {
            Some("tmj") | Some("json") => read_tmj(&path, &self.layer)?,
            _ => read_tmx(&path, &self.layer)?,
        };
        raw.into_level(self, &shown)
    }
}

/// `file` relative to the directory of `scene`.
fn beside(scene: &str, file: &str) -> PathBuf {
    let dir = Path::new(scene).parent().unwrap_or(Path::new(""));
    dir.join(file)
}

/// A property value, as both formats give it.
#[derive(Clone, Debug, PartialEq)]
enum Value {
    Bool(bool),
    Number(f32),
    Text(String),
}

type Properties = Vec<(String, Value)>;

/// A tile of the solid layer: its class and properties.
#[derive(Clone, Debug, Default, PartialEq)]
struct RawTile {
    class: String,
    properties: Properties,
}

#[derive(Clone, Debug, PartialEq)]
enum RawShape {
    Rect(f32, f32),
    Ellipse(f32, f32),
    Point,
    /// A shape Passo has no body for (polygon, polyline, text, capsule).
    Other(&'static str),
}

#[derive(Clone, Debug, PartialEq)]
struct RawObject {
    layer: String,
    id: u32,
    name: String,
    class: String,
    x: f32,
    y: f32,
    rotation: f32,
    shape: RawShape,
    properties: Properties,
}

/// A map in neither format's types: what Passo reads of it.
#[derive(Clone, Debug, Default, PartialEq)]
struct RawMap {
    width: u32,
    height: u32,
    tile_width: f32,
    tile_height: f32,
    /// Every tile layer: its name and tiles, row by row from the top.
    tile_layers: Vec<(String, Vec<Option<RawTile>>)>,
    objects: Vec<RawObject>,
}

fn read_tmx(path: &Path, wanted_layer: &str) -> Result<RawMap, SceneError> {
    let shown = path.display().to_string();
    let map = tiled::Loader::new()
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
                let cells = (0..map.height as i32)
                    .flat_map(|y| (0..map.width as i32).map(move |x| (x, y)))
                    .map(|(x, y)| {
                        tiles.get_tile(x, y).map(|t| match t.get_tile() {
                            Some(tile) => RawTile {
                                class: tile.user_type.clone(),
                                properties: tmx_properties(&tile.properties),
                            },
                            None => RawTile::default(),
                        })
                    })
                    .collect();
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
                        tiled::ObjectShape::Polygon { .. } => RawShape::Other("a polygon"),
                        tiled::ObjectShape::Polyline { .. } => RawShape::Other("a polyline"),
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
fn read_tmj(path: &Path, wanted_layer: &str) -> Result<RawMap, SceneError> {
    use serde_json::Value as Json;
    let shown = path.display().to_string();
    let fail = |message: String| SceneError::Invalid {
        source_name: shown.clone(),
        field: "map".into(),
        message,
    };
    let read = |p: &Path| -> Result<Json, SceneError> {
        let text = std::fs::read_to_string(p).map_err(|e| SceneError::Io {
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
    let dimension = |key: &str| {
        number(&json, key)
            .filter(|n| *n >= 1.0 && *n <= 65_536.0)
            .ok_or_else(|| fail(format!("`{key}` must be a number in [1, 65536]")))
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
    // Tiles by global id: (first gid, tiles of the set by local id).
    let mut sets: Vec<(u32, Vec<(u32, RawTile)>)> = Vec::new();
    for set in json
        .get("tilesets")
        .and_then(Json::as_array)
        .into_iter()
        .flatten()
    {
        let first = number(set, "firstgid").unwrap_or(1.0) as u32;
        let set = match set.get("source").and_then(Json::as_str) {
            Some(source) => read(&path.parent().unwrap_or(Path::new("")).join(source))?,
            None => set.clone(),
        };
        let tiles = set
            .get("tiles")
            .and_then(Json::as_array)
            .into_iter()
            .flatten()
            .map(|t| {
                let class = t.get("class").or_else(|| t.get("type"));
                let tile = RawTile {
                    class: class.and_then(Json::as_str).unwrap_or("").to_owned(),
                    properties: json_properties(t),
                };
                (number(t, "id").unwrap_or(0.0) as u32, tile)
            })
            .collect();
        sets.push((first, tiles));
    }
    sets.sort_by_key(|s| s.0);
    let tile_of = |gid: u32| {
        let set = sets.iter().rev().find(|s| s.0 <= gid)?;
        let local = gid - set.0;
        Some(
            set.1
                .iter()
                .find(|t| t.0 == local)
                .map(|t| t.1.clone())
                .unwrap_or_default(),
        )
    };
    fn layers(json: &Json) -> Vec<Json> {
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
                out.push(layer.clone());
            }
        }
        out
    }
    for layer in layers(&json) {
        let name = text(&layer, "name");
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
                // The top bits of a global id are flip flags.
                let cells = data
                    .iter()
                    .map(|v| v.as_u64().unwrap_or(0) as u32 & 0x1FFF_FFFF)
                    .map(|gid| (gid != 0).then(|| tile_of(gid).unwrap_or_default()))
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
                    } else if object.get("polygon").is_some() {
                        RawShape::Other("a polygon")
                    } else if object.get("polyline").is_some() {
                        RawShape::Other("a polyline")
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

/// What a property says, for reading fields.
struct Props<'a>(&'a Properties);

impl Props<'_> {
    fn get(&self, name: &str) -> Option<&Value> {
        self.0.iter().find(|(n, _)| n == name).map(|(_, v)| v)
    }

    fn number(&self, name: &str) -> Result<Option<f32>, String> {
        match self.get(name) {
            None => Ok(None),
            Some(Value::Number(n)) => Ok(Some(*n)),
            Some(_) => Err(format!("property `{name}` must be a number")),
        }
    }

    fn flag(&self, name: &str) -> Result<Option<bool>, String> {
        match self.get(name) {
            None => Ok(None),
            Some(Value::Bool(b)) => Ok(Some(*b)),
            Some(_) => Err(format!("property `{name}` must be a bool")),
        }
    }

    fn text(&self, name: &str) -> Result<Option<&str>, String> {
        match self.get(name) {
            None => Ok(None),
            Some(Value::Text(s)) => Ok(Some(s)),
            Some(_) => Err(format!("property `{name}` must be a string")),
        }
    }
}

/// A tile's kind from its class and properties.
fn tile_kind(tile: &RawTile) -> Result<TileKind, String> {
    let mut kind = match tile.class.to_ascii_lowercase().as_str() {
        "ice" => TileKind::ICE,
        "bouncy" => TileKind::BOUNCY,
        "one_way" | "oneway" | "platform" => TileKind::ONE_WAY,
        _ => TileKind::SOLID,
    };
    let props = Props(&tile.properties);
    if let Some(f) = props.number("friction")? {
        kind.friction = f;
    }
    if let Some(e) = props.number("restitution")? {
        kind.restitution = e;
    }
    if let Some(one_way) = props.flag("one_way")? {
        kind.one_way = one_way.then_some(Vec2::Y);
    }
    Ok(kind)
}

/// What an object's class (or `kind` property) makes of it.
enum ObjectRole {
    Body(BodyKind, bool, bool),
    Spawn,
}

fn role(class: &str) -> Result<ObjectRole, String> {
    Ok(match class.to_ascii_lowercase().as_str() {
        "" | "static" | "solid" => ObjectRole::Body(BodyKind::Static, false, false),
        "dynamic" => ObjectRole::Body(BodyKind::Dynamic, false, false),
        "kinematic" => ObjectRole::Body(BodyKind::Kinematic, false, false),
        "sensor" | "coin" | "goal" | "trigger" => ObjectRole::Body(BodyKind::Static, true, false),
        "oneway" | "one_way" | "platform" => ObjectRole::Body(BodyKind::Static, false, true),
        "spawn" => ObjectRole::Spawn,
        other => {
            return Err(format!(
                "class `{other}` is not one Passo knows: Static, Dynamic, Kinematic, Sensor (coin, goal, trigger), OneWay (platform) or Spawn"
            ));
        }
    })
}

impl RawMap {
    fn into_level(self, wanted: &TileMapRef, shown: &str) -> Result<Level, SceneError> {
        let invalid = |field: String, message: String| SceneError::Invalid {
            source_name: shown.to_owned(),
            field,
            message,
        };
        let Some((_, cells)) = self.tile_layers.iter().find(|(n, _)| *n == wanted.layer) else {
            let names: Vec<&str> = self.tile_layers.iter().map(|(n, _)| n.as_str()).collect();
            return Err(invalid(
                format!("layer `{}`", wanted.layer),
                format!("there is no such tile layer (the map has {names:?})"),
            ));
        };
        let cell = Vec2::splat(wanted.cell);
        let mut map = TileMap::new(self.width, self.height, cell, wanted.origin)
            .map_err(|e| invalid("map".into(), e.to_string()))?;
        let layer_field = format!("layer `{}`", wanted.layer);
        let mut kinds: Vec<TileKind> = Vec::new();
        for (i, tile) in cells.iter().enumerate() {
            let Some(tile) = tile else { continue };
            let (x, row) = (i as u32 % self.width, i as u32 / self.width);
            let at = || format!("{layer_field}, tile ({x}, {row})");
            let kind = tile_kind(tile).map_err(|m| invalid(at(), m))?;
            let k = match kinds.iter().position(|k| *k == kind) {
                Some(k) => k as u8,
                None => {
                    let k = map
                        .add_kind(kind)
                        .map_err(|e| invalid(at(), e.to_string()))?;
                    kinds.push(kind);
                    k
                }
            };
            // Tiled's rows run from the top.
            map.set(x, self.height - 1 - row, Some(k))
                .map_err(|e| invalid(at(), e.to_string()))?;
        }
        // Pixels to metres: one tile is `cell` metres, y up.
        let scale = Vec2::new(
            wanted.cell / self.tile_width,
            wanted.cell / self.tile_height,
        );
        let top = self.height as f32 * self.tile_height;
        let to_world = |x: f32, y: f32| wanted.origin + Vec2::new(x, top - y) * scale;
        let mut level = Level {
            map,
            bodies: Vec::new(),
            spawns: Vec::new(),
        };
        let mut checked = 0;
        for object in &self.objects {
            let what = if object.name.is_empty() {
                format!("layer `{}`, object {}", object.layer, object.id)
            } else {
                format!(
                    "layer `{}`, object {} `{}`",
                    object.layer, object.id, object.name
                )
            };
            object
                .read(&to_world, scale, &mut level)
                .map_err(|m| invalid(what.clone(), m))?;
            if let Some(spec) = level.bodies.last().filter(|_| level.bodies.len() > checked) {
                crate::format::check_body(spec, shown, &what)?;
            }
            checked = level.bodies.len();
        }
        Ok(level)
    }
}

impl RawObject {
    fn read(
        &self,
        to_world: &dyn Fn(f32, f32) -> Vec2,
        scale: Vec2,
        level: &mut Level,
    ) -> Result<(), String> {
        let props = Props(&self.properties);
        let class = props.text("kind")?.unwrap_or(&self.class);
        let role = role(class)?;
        let name = (!self.name.is_empty()).then(|| self.name.clone());
        if matches!(self.shape, RawShape::Point) || matches!(role, ObjectRole::Spawn) {
            let at = match self.shape {
                RawShape::Rect(w, h) | RawShape::Ellipse(w, h) => {
                    to_world(self.x + w / 2.0, self.y + h / 2.0)
                }
                _ => to_world(self.x, self.y),
            };
            level
                .spawns
                .push((name.unwrap_or_else(|| "spawn".to_owned()), at));
            return Ok(());
        }
        let ObjectRole::Body(kind, sensor, one_way) = role else {
            unreachable!("spawns returned above")
        };
        if self.rotation != 0.0 {
            return Err(format!(
                "is rotated by {}°: bodies do not rotate",
                self.rotation
            ));
        }
        let (shape, (w, h)) = match self.shape {
            RawShape::Rect(w, h) => {
                let half = Vec2::new(w, h) * scale * 0.5;
                (Shape::Box { half_extents: half }, (w, h))
            }
            RawShape::Ellipse(w, h) => {
                let size = Vec2::new(w, h) * scale;
                if (size.x - size.y).abs() > 1e-4 * size.x.max(size.y) {
                    return Err(format!(
                        "is an ellipse {} m wide and {} m tall: only circles (width = height) become bodies",
                        size.x, size.y
                    ));
                }
                (
                    Shape::Circle {
                        radius: size.x * 0.5,
                    },
                    (w, h),
                )
            }
            RawShape::Other(what) => {
                return Err(format!(
                    "is {what}: only rectangles, ellipses and points are read"
                ));
            }
            RawShape::Point => unreachable!("points are spawns"),
        };
        // Coins gold and goals green; other bodies take the scene's colours.
        let colour = match class.to_ascii_lowercase().as_str() {
            "coin" => Some(Colour([0xf0, 0xc8, 0x30, 0xff])),
            "goal" => Some(Colour([0x5c, 0xb8, 0x5c, 0xff])),
            _ => None,
        };
        let mut spec = BodySpec {
            name,
            colour,
            kind,
            shape: Some(shape),
            position: to_world(self.x + w / 2.0, self.y + h / 2.0),
            sensor: props.flag("sensor")?.unwrap_or(sensor),
            one_way: (props.flag("one_way")?.unwrap_or(one_way)).then_some(Vec2::Y),
            bullet: props.flag("bullet")?.unwrap_or(false),
            ..BodySpec::default()
        };
        if let Some(f) = props.number("friction")? {
            spec.material.friction = f;
        }
        if let Some(e) = props.number("restitution")? {
            spec.material.restitution = e;
        }
        spec.density = props.number("density")?;
        spec.mass = props.number("mass")?;
        let vx = props.number("vx")?.unwrap_or(0.0);
        let vy = props.number("vy")?.unwrap_or(0.0);
        spec.velocity = Vec2::new(vx, vy);
        if let Some(period) = props.number("period")? {
            let by = Vec2::new(
                props.number("path_x")?.unwrap_or(0.0),
                props.number("path_y")?.unwrap_or(0.0),
            );
            spec.path = Some(PlatformPath { by, period });
        }
        level.bodies.push(spec);
        Ok(())
    }
}
