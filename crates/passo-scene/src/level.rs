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

use crate::art::{LevelArt, TileSprite};
use crate::error::SceneError;
use crate::format::{BodySpec, Colour};
use crate::map_ref::{PlatformPath, TileMapRef};
use crate::tiled_file::{
    Properties, RawMap, RawObject, RawShape, RawTile, Value, read_tmj, read_tmx,
};
use passo_physics::constants::MAX_COORDINATE;
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
    /// Chains from polygon and polyline objects: sloped ground.
    pub chains: Vec<crate::format::ChainSpec>,
    /// How the solid cells look, from the tilesets' images.
    pub art: LevelArt,
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
                chains: Vec::new(),
                art: LevelArt::default(),
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
        let root = match &self.root {
            Some(root) => beside(scene, root),
            None => path.parent().unwrap_or(Path::new("")).to_path_buf(),
        };
        let raw = match path.extension().and_then(|e| e.to_str()) {
            Some("tmj") | Some("json") => read_tmj(&path, &self.layer, &root)?,
            _ => read_tmx(&path, &self.layer, &root)?,
        };
        let mut level = raw.into_level(self, &shown)?;
        // Only images a map may name: regular files inside its folder.
        let budget = crate::limits::MapBudget::new(&root);
        let usable: Vec<bool> = level
            .art
            .images
            .iter()
            .map(|image| budget.check_place(image).is_ok())
            .collect();
        if usable.iter().any(|u| !u) {
            let mut renumbered = Vec::with_capacity(usable.len());
            let mut images = Vec::new();
            for (image, ok) in level.art.images.drain(..).zip(&usable) {
                renumbered.push(images.len());
                if *ok {
                    images.push(image);
                }
            }
            level.art.tiles.retain(|t| usable[t.image]);
            for tile in &mut level.art.tiles {
                tile.image = renumbered[tile.image];
            }
            level.art.images = images;
            level.art.complete = false;
        }
        Ok(level)
    }
}

/// `file` relative to the directory of `scene`.
fn beside(scene: &str, file: &str) -> PathBuf {
    let dir = Path::new(scene).parent().unwrap_or(Path::new(""));
    dir.join(file)
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
    let slope = match tile.class.to_ascii_lowercase().as_str() {
        "slope_up" => Some("up"),
        "slope_down" => Some("down"),
        _ => None,
    };
    if let Some(name) = props.text("slope")?.or(slope) {
        kind.slope = Some(match name {
            "up" => passo_physics::Slope::Up,
            "down" => passo_physics::Slope::Down,
            "up_low" => passo_physics::Slope::UpLow,
            "up_high" => passo_physics::Slope::UpHigh,
            "down_high" => passo_physics::Slope::DownHigh,
            "down_low" => passo_physics::Slope::DownLow,
            other => {
                return Err(format!(
                    "property `slope` is `{other}`; use up, down, up_low, up_high, down_high or down_low"
                ));
            }
        });
        if kind.one_way.is_some() {
            return Err("a one-way tile cannot slope".to_owned());
        }
    }
    Ok(kind)
}

/// The index of `kind` in `map`, added the first time (`kinds` lists the
/// map's kinds in order).
fn kind_in(
    map: &mut TileMap,
    kinds: &mut Vec<TileKind>,
    kind: TileKind,
) -> Result<u8, passo_physics::PhysicsError> {
    if let Some(k) = kinds.iter().position(|k| *k == kind) {
        return Ok(k as u8);
    }
    let k = map.add_kind(kind)?;
    kinds.push(kind);
    Ok(k)
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
    /// The quads of the solid cells whose tiles have an image.
    fn art(&self, cells: &[Option<u32>], wanted: &TileMapRef) -> LevelArt {
        let mut art = LevelArt {
            complete: true,
            ..LevelArt::default()
        };
        let half = Vec2::splat(0.5 * wanted.cell);
        for (i, &tile) in cells.iter().enumerate() {
            let Some(tile) = tile else { continue };
            let Some(look) = &self.tiles[tile as usize].art else {
                art.complete = false;
                continue;
            };
            let image = match art.images.iter().position(|p| *p == look.image) {
                Some(at) => at,
                None => {
                    art.images.push(look.image.clone());
                    art.images.len() - 1
                }
            };
            let (x, row) = (i as u32 % self.width, i as u32 / self.width);
            // Tiled's rows run from the top; the cell's row up from the bottom.
            let y = self.height - 1 - row;
            let size = Vec2::new(look.image_size.0 as f32, look.image_size.1 as f32);
            let [rx, ry, rw, rh] = look.rect.map(|v| v as f32);
            art.tiles.push(TileSprite {
                centre: wanted.origin + (Vec2::new(x as f32, y as f32) + 0.5) * wanted.cell,
                half_extents: half,
                image,
                uv_min: Vec2::new(rx, ry) / size,
                uv_max: Vec2::new(rx + rw, ry + rh) / size,
            });
        }
        art
    }

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
        if !(self.tile_width >= 1.0 && self.tile_height >= 1.0) {
            return Err(invalid(
                "map".into(),
                format!(
                    "tiles must be at least 1 px wide and high, got {} × {}",
                    self.tile_width, self.tile_height
                ),
            ));
        }
        let cell = Vec2::splat(wanted.cell);
        let mut map = TileMap::new(self.width, self.height, cell, wanted.origin)
            .map_err(|e| invalid("map".into(), e.to_string()))?;
        let layer_field = format!("layer `{}`", wanted.layer);
        let mut kinds: Vec<TileKind> = Vec::new();
        // Each distinct tile's kind in the map, worked out at the first
        // cell that shows it (so an error names that cell).
        let mut kind_of: Vec<Option<u8>> = vec![None; self.tiles.len()];
        for (i, &tile) in cells.iter().enumerate() {
            let Some(tile) = tile else { continue };
            let (x, row) = (i as u32 % self.width, i as u32 / self.width);
            let at = || format!("{layer_field}, tile ({x}, {row})");
            let k = match kind_of[tile as usize] {
                Some(k) => k,
                None => {
                    let kind =
                        tile_kind(&self.tiles[tile as usize]).map_err(|m| invalid(at(), m))?;
                    let k = kind_in(&mut map, &mut kinds, kind)
                        .map_err(|e| invalid(at(), e.to_string()))?;
                    kind_of[tile as usize] = Some(k);
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
        let art = self.art(cells, wanted);
        let mut level = Level {
            map,
            bodies: Vec::new(),
            spawns: Vec::new(),
            chains: Vec::new(),
            art,
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
                crate::validate::check_body(spec, shown, &what)?;
            }
            checked = level.bodies.len();
        }
        Ok(level)
    }
}

impl RawObject {
    /// A polygon (a closed chain, solid inside) or a polyline (an open
    /// chain, solid on the right of the way it is drawn: drawn left to
    /// right, solid below).
    fn read_chain(
        &self,
        points: &[(f32, f32)],
        kind: BodyKind,
        sensor: bool,
        name: Option<String>,
        to_world: &dyn Fn(f32, f32) -> Vec2,
        level: &mut Level,
    ) -> Result<(), String> {
        let props = Props(&self.properties);
        let closed = matches!(self.shape, RawShape::Polygon(_));
        if kind == BodyKind::Dynamic {
            return Err("is a polygon or polyline: it becomes a chain, which is Static or Kinematic, not Dynamic".to_owned());
        }
        if props.flag("sensor")?.unwrap_or(sensor) {
            return Err(
                "is a polygon or polyline: it becomes a chain, which cannot be a sensor".to_owned(),
            );
        }
        if points.len() > passo_physics::MAX_CHAIN_POINTS {
            return Err(format!(
                "has {} points; a chain has at most {}",
                points.len(),
                passo_physics::MAX_CHAIN_POINTS
            ));
        }
        let mut world: Vec<Vec2> = points
            .iter()
            .map(|&(x, y)| to_world(self.x + x, self.y + y))
            .collect();
        if let Some(p) = world
            .iter()
            .find(|p| !(p.is_finite() && p.abs().max_element() <= MAX_COORDINATE))
        {
            return Err(format!(
                "has a point at {p}, beyond the world's coordinates (±{MAX_COORDINATE} m)"
            ));
        }
        if closed {
            // Clockwise, so it is solid inside however it was drawn.
            let twice_area: f32 = (0..world.len())
                .map(|i| world[i].perp_dot(world[(i + 1) % world.len()]))
                .sum();
            if twice_area > 0.0 {
                world.reverse();
            }
        }
        let mut material = crate::format::Material::default();
        if let Some(f) = props.number("friction")? {
            material.friction = f;
        }
        if let Some(e) = props.number("restitution")? {
            material.restitution = e;
        }
        level.chains.push(crate::format::ChainSpec {
            name,
            points: world,
            closed,
            kind,
            material,
            colour: None,
        });
        Ok(())
    }

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
            if !(at.is_finite() && at.abs().max_element() <= MAX_COORDINATE) {
                return Err(format!(
                    "is a spawn point at {at}, beyond the world's coordinates (±{MAX_COORDINATE} m)"
                ));
            }
            level
                .spawns
                .push((name.unwrap_or_else(|| "spawn".to_owned()), at));
            return Ok(());
        }
        let ObjectRole::Body(kind, sensor, one_way) = role else {
            unreachable!("spawns returned above")
        };
        if matches!(self.shape, RawShape::Polygon(_) | RawShape::Polyline(_))
            && props.flag("one_way")?.unwrap_or(one_way)
        {
            return Err("is a one-way polygon or polyline: a chain is solid from one side already (the right of the way it is drawn); one-way platforms are rectangles".to_owned());
        }
        if self.rotation != 0.0 {
            return Err(format!(
                "is rotated by {}°: bodies do not rotate",
                self.rotation
            ));
        }
        if let RawShape::Polygon(points) | RawShape::Polyline(points) = &self.shape {
            return self.read_chain(points, kind, sensor, name, to_world, level);
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
            RawShape::Polygon(_) | RawShape::Polyline(_) => unreachable!("chains returned above"),
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
