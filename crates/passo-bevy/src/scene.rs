//! Scenes and Tiled levels through `passo-scene`: the [`LoadScene`]
//! command replaces the world with the one a file describes and spawns an
//! entity for each of its bodies (the tiles of a level stay bodies
//! without entities).

use bevy::prelude::*;
use passo_physics as passo;
use passo_scene::{Platform, Scene};

use crate::components::{
    Bullet, Collider, Filter, GravityScale, LinearVelocity, Mass, OneWay, PassoBody,
    PhysicsMaterial, Position, RigidBody, Sensor,
};
use crate::convert::to_bevy;
use crate::messages::SceneLoadFailed;
use crate::{BodyEntities, PassoTimestep, PassoWorld};

/// What the loaded scene holds besides its bodies: where things spawn,
/// the region to show, the path platforms the plugin drives every tick,
/// and the level's tile bodies. Inserted by [`LoadScene`].
#[derive(Resource, Clone, Debug)]
pub struct PassoLevel {
    /// The file it came from.
    pub source: String,
    /// The level's spawn points, by name, metres.
    pub spawns: Vec<(String, Vec2)>,
    /// The region the scene asks to show, metres: lower-left corner.
    pub camera_min: Vec2,
    /// The region the scene asks to show, metres: upper-right corner.
    pub camera_max: Vec2,
    /// Kinematic bodies on back-and-forth paths. The plugin steers them
    /// every tick to where their path puts them at the end of the tick.
    pub platforms: Vec<Platform>,
    /// The bodies made of the tile map's cells (no entities).
    pub cell_bodies: Vec<passo::BodyId>,
    /// How the tiles look, from the tilesets' images.
    pub art: passo_scene::LevelArt,
}

impl PassoLevel {
    /// The spawn point with this name.
    pub fn spawn(&self, name: &str) -> Option<Vec2> {
        self.spawns.iter().find(|(n, _)| n == name).map(|&(_, p)| p)
    }
}

/// The colour a scene file gives a body: sRGB and alpha, 0–255 each
/// (`Color::srgba_u8(r, g, b, a)` in Bevy).
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq)]
pub struct SceneColour(pub [u8; 4]);

/// Loads a Passo scene (`.ron`) or a Tiled level (`.tmx`, `.tmj`) and
/// makes it the world: `commands.queue(LoadScene::file("level.ron"))`.
///
/// What it does, in order:
/// 1. reads and checks the file (a Tiled map through the same limits as
///    everywhere in Passo: a hostile map is refused, not loaded);
/// 2. despawns every entity that has a body;
/// 3. replaces the [`PassoWorld`] with the scene's world (its gravity,
///    forces, integrator and contact settings) and sets the tick to the
///    scene's `rate_hz`, in the plugin and in Bevy's fixed clock;
/// 4. spawns an entity for every body that is not a tile, with its
///    components, its `Name` (if the scene names it) and a
///    [`SceneColour`];
/// 5. inserts the [`PassoLevel`].
///
/// A file that cannot be loaded leaves everything as it was and writes a
/// [`SceneLoadFailed`] message (and logs the error).
#[derive(Clone, Debug)]
pub struct LoadScene {
    source: String,
    scene: Option<Result<Scene, String>>,
}

impl LoadScene {
    /// A scene file, or a Tiled map with cells 1 m wide whose tile layer
    /// is named `solid` (see [`tiled`](Self::tiled) for other cells).
    pub fn file(path: impl Into<String>) -> Self {
        let source = path.into();
        let is_map = source.ends_with(".tmx") || source.ends_with(".tmj");
        if is_map {
            return Self::tiled(source, 1.0);
        }
        Self {
            source,
            scene: None,
        }
    }

    /// A Tiled map (`.tmx` or `.tmj`) whose tiles are `cell` metres wide,
    /// with Passo's default world (gravity, contacts on) and 60 ticks a
    /// second. Its tile layer must be named `solid`; its object layers
    /// give bodies and spawn points (see the guide's Tiled chapter).
    pub fn tiled(path: impl Into<String>, cell: f32) -> Self {
        let source = path.into();
        let file = std::path::Path::new(&source)
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_default();
        let text = format!(
            "(name: {file:?}, collisions: Some(()), tilemap: (file: {file:?}, cell: {cell:?}))"
        );
        // The scene stands where the map is, so the map is found beside it.
        let scene = Scene::parse(&text, &source).map_err(|e| e.to_string());
        Self {
            source,
            scene: Some(scene),
        }
    }

    /// A scene from its text; `source` names it in errors (and a Tiled
    /// map it names is looked for beside `source`).
    pub fn text(text: &str, source: impl Into<String>) -> Self {
        let source = source.into();
        let scene = Scene::parse(text, &source).map_err(|e| e.to_string());
        Self {
            source,
            scene: Some(scene),
        }
    }
}

impl Command for LoadScene {
    type Out = ();

    fn apply(self, world: &mut World) {
        let scene = match self.scene {
            Some(scene) => scene,
            None => Scene::load(std::path::Path::new(&self.source)).map_err(|e| e.to_string()),
        };
        let built = scene.and_then(|scene| {
            let built = scene.build().map_err(|e| e.to_string())?;
            Ok((scene.file.rate_hz, built))
        });
        let (rate_hz, built) = match built {
            Ok(built) => built,
            Err(error) => {
                error!("Passo: cannot load {}: {error}", self.source);
                world.write_message(SceneLoadFailed {
                    source: self.source,
                    error,
                });
                return;
            }
        };

        // The old bodies go with their entities.
        let old: Vec<Entity> = world
            .query_filtered::<Entity, With<PassoBody>>()
            .iter(world)
            .collect();
        for entity in old {
            world.despawn(entity);
        }

        let dt = (1.0 / rate_hz) as f32;
        world.insert_resource(PassoTimestep(Some(dt)));
        if let Some(mut fixed) = world.get_resource_mut::<Time<Fixed>>() {
            fixed.set_timestep_hz(rate_hz);
        }
        world.insert_resource(PassoWorld(built.world));
        world.insert_resource(BodyEntities::default());

        let cells: std::collections::BTreeSet<passo::BodyId> =
            built.cell_bodies.iter().copied().collect();
        for record in &built.bodies {
            if cells.contains(&record.id) {
                continue;
            }
            let Some(body) = world.resource::<PassoWorld>().body(record.id) else {
                continue;
            };
            let at = to_bevy(body.position);
            let mut entity = world.spawn((
                PassoBody(record.id),
                RigidBody::from_kind(body.kind),
                Position(at),
                LinearVelocity(to_bevy(body.velocity)),
                Transform::from_xyz(at.x, at.y, 0.0),
                Mass(body.mass),
                PhysicsMaterial {
                    friction: body.friction,
                    restitution: body.restitution,
                    friction_mix: body.friction_mix,
                },
                Filter(body.filter),
                GravityScale(body.gravity_scale),
                SceneColour(record.colour.0),
            ));
            if let Some(shape) = body.shape {
                entity.insert(Collider(shape));
            }
            if body.sensor {
                entity.insert(Sensor);
            }
            if let Some(direction) = body.one_way {
                entity.insert(OneWay(to_bevy(direction)));
            }
            if body.bullet {
                entity.insert(Bullet);
            }
            if let Some(name) = &record.name {
                entity.insert(Name::new(name.clone()));
            }
            // The body is made from all of the above: none of it is a
            // change for the plugin to apply.
            let made = entity.world().read_change_tick();
            entity.insert(crate::sync::Made(made));
            let entity = entity.id();
            world
                .resource_mut::<BodyEntities>()
                .insert(record.id, entity);
        }

        world.insert_resource(PassoLevel {
            source: self.source,
            spawns: built
                .spawns
                .iter()
                .map(|(name, p)| (name.clone(), to_bevy(*p)))
                .collect(),
            camera_min: to_bevy(built.camera.min),
            camera_max: to_bevy(built.camera.max),
            platforms: built.platforms,
            cell_bodies: built.cell_bodies,
            art: built.art,
        });
    }
}
