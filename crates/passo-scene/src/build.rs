//! Building a physics world from a scene.

use crate::art::LevelArt;
use crate::error::SceneError;
use crate::format::{BodySpec, Colour, JointSpec, JointSpecKind, MAX_BODIES, SceneFile};
use crate::generate::generate;
use crate::map_ref::PlatformPath;
use passo_physics::glam::Vec2;
use passo_physics::{
    Aabb, BodyDef, BodyId, BodyKind, ForceModels, JointDef, JointSpring, World, WorldSettings,
};

/// Dynamic bodies without a colour cycle through these (sRGB).
const PALETTE: [[u8; 4]; 6] = [
    [0xe4, 0x6c, 0x3a, 0xff],
    [0x3a, 0x8e, 0xe4, 0xff],
    [0x5c, 0xb8, 0x5c, 0xff],
    [0xe4, 0xb8, 0x3a, 0xff],
    [0xa3, 0x5c, 0xd6, 0xff],
    [0x3a, 0xc8, 0xc0, 0xff],
];

/// Static bodies without a colour.
const STATIC_COLOUR: Colour = Colour([0x6b, 0x70, 0x7a, 0xff]);

/// Kinematic bodies (moving platforms) without a colour (sRGB): a pale
/// lavender, apart from the palette of dynamic bodies and the grey of
/// static ones.
pub const KINEMATIC_COLOUR: Colour = Colour([0xd8, 0xd4, 0xf0, 0xff]);

/// Ice cells (sRGB): a pale blue.
const ICE_COLOUR: Colour = Colour([0xa8, 0xd8, 0xf0, 0xff]);
/// Bouncy cells: a pink.
const BOUNCY_COLOUR: Colour = Colour([0xe8, 0x7a, 0xb8, 0xff]);
/// One-way cells: a lighter grey than solid ground.
const ONE_WAY_COLOUR: Colour = Colour([0xa0, 0xa4, 0xac, 0xff]);

/// The colour of a tile map's box of `kind`, in a map of `body` kind.
fn tile_colour(kind: &passo_physics::TileKind, body: BodyKind) -> Colour {
    if kind.one_way.is_some() {
        ONE_WAY_COLOUR
    } else if kind.restitution > 0.5 {
        BOUNCY_COLOUR
    } else if kind.friction < 0.1 {
        ICE_COLOUR
    } else if body == BodyKind::Kinematic {
        KINEMATIC_COLOUR
    } else {
        STATIC_COLOUR
    }
}

/// What the renderer and the game need to know about a scene body.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneBody {
    /// The body in the world.
    pub id: BodyId,
    /// Its name in the scene, if any.
    pub name: Option<String>,
    /// Its colour.
    pub colour: Colour,
}

/// A scene turned into a world, with what the world does not hold.
#[derive(Clone, Debug)]
pub struct BuiltScene {
    /// The physics world, running only the stages the scene declared.
    pub world: World,
    /// Every body with its name and colour, in creation order.
    pub bodies: Vec<SceneBody>,
    /// The region to show.
    pub camera: Aabb,
    /// The kinematic bodies that follow a path, for
    /// [`drive_platforms`](BuiltScene::drive_platforms).
    pub platforms: Vec<Platform>,
    /// Spawn points of the scene's tile map, by name, metres.
    pub spawns: Vec<(String, Vec2)>,
    /// How the tile map's cells look (empty without a map or images).
    pub art: LevelArt,
    /// The bodies made of the tile map's cells: a game that draws
    /// [`art`](Self::art) when it is [complete](LevelArt::complete) draws
    /// these no more.
    pub cell_bodies: Vec<BodyId>,
    /// Ticks stepped so far, which is also the number of the next tick,
    /// counted from 0 as `passo_loop::FixedTimestep::tick` counts them.
    /// The path platforms are where their path puts them at `tick × dt`
    /// seconds. A game that restores a snapshot sets it to the snapshot's
    /// tick.
    pub tick: u64,
}

/// A kinematic body on a back-and-forth path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Platform {
    /// The body.
    pub id: BodyId,
    /// Where the path starts (the body's position in the scene).
    pub start: Vec2,
    /// The path.
    pub path: PlatformPath,
}

impl Platform {
    /// Where the platform is at `t` seconds of simulated time.
    pub fn at(&self, t: f64) -> Vec2 {
        self.start + self.path.offset(t)
    }
}

impl BuiltScene {
    /// Steers each path platform so it reaches its place at `t_end`
    /// seconds (the simulated time at the end of the next step of `dt`):
    /// call it before every step, with the step's end time from the tick
    /// count so it does not drift.
    pub fn drive_platforms(platforms: &[Platform], world: &mut World, t_end: f64, dt: f32) {
        for p in platforms {
            world.set_kinematic_target(p.id, p.at(t_end), dt);
        }
    }

    /// One fixed tick of `dt` seconds, in the order a game with characters
    /// needs:
    /// 1. the path platforms are steered to where they are at the end of
    ///    the tick ([`drive_platforms`](BuiltScene::drive_platforms));
    /// 2. `game` runs with the world: move the characters here
    ///    ([`World::move_character`] meets each platform where it will be);
    /// 3. the world steps;
    /// 4. [`tick`](Self::tick) counts it.
    ///
    /// ```
    /// # use passo_scene::Scene;
    /// # use passo_physics::{BodyDef, CharacterMover, Shape, glam::Vec2};
    /// let scene = Scene::parse(r#"(name: "Floor", collisions: Some(()),
    ///     bodies: [(kind: Static, shape: Some(Box(half_extents: (10.0, 0.5))))])"#, "floor.ron").unwrap();
    /// let mut built = scene.build().unwrap();
    /// let mover = CharacterMover::default();
    /// let player = built.world.add_body(BodyDef::new_kinematic(
    ///     Vec2::new(0.0, 0.9 + mover.skin), Shape::rect(0.4, 0.8), Vec2::ZERO)).unwrap();
    /// let dt = 1.0 / 60.0;
    /// for _ in 0..60 {
    ///     built.tick_with(dt, |world| {
    ///         world.move_character(player, Vec2::new(2.0, -0.1) * dt, &mover, dt).unwrap();
    ///     });
    /// }
    /// assert_eq!(built.tick, 60);
    /// let x = built.world.body(player).unwrap().position.x;
    /// assert!((x - 2.0).abs() < 1e-3, "{x}");
    /// ```
    ///
    /// A game with its own clock calls
    /// [`drive_platforms`](BuiltScene::drive_platforms) and
    /// [`World::step`] itself.
    pub fn tick_with(&mut self, dt: f32, game: impl FnOnce(&mut World)) {
        let t_end = (self.tick.saturating_add(1)) as f64 * f64::from(dt);
        Self::drive_platforms(&self.platforms, &mut self.world, t_end, dt);
        game(&mut self.world);
        self.world.step(dt);
        self.tick = self.tick.saturating_add(1);
    }

    /// One fixed tick of `dt` seconds with nothing moved by the game:
    /// [`tick_with`](Self::tick_with) with nothing to do.
    pub fn step(&mut self, dt: f32) {
        self.tick_with(dt, |_| {});
    }

    /// The body with this name, if any.
    pub fn body_named(&self, name: &str) -> Option<BodyId> {
        self.bodies
            .iter()
            .find(|b| b.name.as_deref() == Some(name))
            .map(|b| b.id)
    }

    /// The scene body record of an id (binary search: ids are in order).
    pub fn scene_body(&self, id: BodyId) -> Option<&SceneBody> {
        self.bodies
            .binary_search_by_key(&id, |b| b.id)
            .ok()
            .map(|i| &self.bodies[i])
    }
}

/// The world settings a scene declares.
pub(crate) fn settings(file: &SceneFile) -> WorldSettings {
    let f = &file.forces;
    WorldSettings {
        forces: ForceModels {
            gravity: f.gravity,
            quadratic_drag: f.quadratic_drag,
            linear_drag: f.linear_drag,
            air_velocity: f.wind,
            surface_friction: f.surface_friction,
            force_field: f.force_field,
            spring: f.spring,
            central_gravity: f.central_gravity,
        },
        integrator: file.integrator,
        force_form: file.force_form,
        min_speed: file.min_speed,
        max_speed: file.max_speed,
        interpolation: file.interpolation,
        contacts: file.collisions,
    }
}

/// The physics definition of a body spec placed at `position`.
pub(crate) fn body_def(spec: &BodySpec, position: Vec2) -> BodyDef {
    let mass = match (spec.mass, spec.density, &spec.shape) {
        (Some(mass), _, _) => mass,
        (None, Some(density), Some(shape)) => density * shape.area(),
        _ => 1.0,
    };
    BodyDef {
        kind: spec.kind,
        position,
        velocity: spec.velocity,
        mass,
        shape: spec.shape,
        drag_area: spec.material.drag_area,
        friction: spec.material.friction,
        friction_mix: spec.material.friction_mix,
        restitution: spec.material.restitution,
        filter: spec.filter.unwrap_or_default(),
        sensor: spec.sensor,
        one_way: spec.one_way,
        conveyor: spec.conveyor,
        bullet: spec.bullet,
        gravity_scale: spec.gravity_scale.unwrap_or(1.0),
        min_speed: spec.min_speed,
        max_speed: spec.max_speed,
        user_data: 0,
    }
}

/// Finds a body by name: its id and position, or why there is none.
pub(crate) type FindBody<'a> = dyn FnMut(&str) -> Result<(BodyId, Vec2), String> + 'a;

/// The physics joint of a scene joint; `find` gives a body's id and
/// position by name (the first body of that name), or says none has it.
pub(crate) fn joint_def(spec: &JointSpec, find: &mut FindBody<'_>) -> Result<JointDef, String> {
    let (a, pa) = find(&spec.a)?;
    let (b, pb) = match &spec.b {
        Some(name) => {
            let (id, at) = find(name)?;
            (Some(id), at)
        }
        None => (None, Vec2::ZERO),
    };
    // The distance between the anchors as placed.
    let placed = ((pb + spec.anchor_b) - (pa + spec.anchor_a)).length();
    let def = match spec.kind {
        JointSpecKind::Rod { length } => JointDef::distance(a, b, length.unwrap_or(placed)),
        JointSpecKind::Rope { length } => JointDef::rope(a, b, length.unwrap_or(placed)),
        JointSpecKind::Spring {
            length,
            hertz,
            damping_ratio,
            limits,
        } => {
            let def = JointDef::spring(
                a,
                b,
                length.unwrap_or(placed),
                JointSpring::new(hertz, damping_ratio),
            );
            match limits {
                Some((min, max)) => def.limits(min, max),
                None => def,
            }
        }
        JointSpecKind::Slider {
            axis,
            limits,
            motor,
        } => {
            let mut def = JointDef::prismatic(a, b, axis);
            if let Some((min, max)) = limits {
                def = def.limits(min, max);
            }
            if let Some(m) = motor {
                def = def.motor(m.speed, m.max_force);
            }
            def
        }
        JointSpecKind::Weld {
            hertz,
            damping_ratio,
        } => {
            // Held as placed: B's centre where it is now, seen from A's
            // (or A's centre where it is, in the world).
            let def = match b {
                Some(_) => JointDef::weld(a, b, pb - pa),
                None => JointDef::weld(a, None, pa),
            };
            if hertz > 0.0 {
                def.with_spring(hertz, damping_ratio)
            } else {
                def
            }
        }
    };
    let def = match spec.kind {
        JointSpecKind::Weld { .. } => def,
        _ => def.anchors(spec.anchor_a, spec.anchor_b),
    };
    Ok(JointDef {
        break_force: spec.break_force,
        collide: spec.collide,
        ..def
    })
}

pub(crate) fn build(file: &SceneFile, source: &str) -> Result<BuiltScene, SceneError> {
    let fail = |field: String, message: String| SceneError::Invalid {
        source_name: source.to_owned(),
        field,
        message,
    };
    let invalid = |field: String, e: passo_physics::PhysicsError| fail(field, e.to_string());
    let mut world = World::new(settings(file)).map_err(|e| invalid("settings".into(), e))?;
    let mut bodies = Vec::new();
    let mut platforms = Vec::new();
    let mut bounds: Option<Aabb> = None;
    let mut cell_bodies = Vec::new();
    // The level's cells first, as boxes coloured by their kind.
    let level = file.tilemap.as_ref().map(|t| t.load(source)).transpose()?;
    if let (Some(level), Some(tilemap)) = (&level, &file.tilemap) {
        // Each rectangle of the level's cells is a body: a checkerboard of
        // 4096 × 4096 cells would be eight million.
        let rects = level.map.rects();
        // Its slopes, with the ground they touch, are chains: a body per
        // segment.
        let chains = level.map.chains();
        let segments: usize = chains.iter().map(|c| c.points.len()).sum();
        let objects: u64 = level
            .chains
            .iter()
            .map(crate::format::ChainSpec::segments)
            .sum();
        let level_bodies = (rects.len() + segments + level.bodies.len()) as u64 + objects;
        let total = file.listed_bodies().saturating_add(level_bodies);
        if total > MAX_BODIES as u64 {
            return Err(fail(
                "tilemap".into(),
                format!(
                    "makes {level_bodies} bodies, {total} with the rest of the scene; at most {MAX_BODIES} are allowed"
                ),
            ));
        }
        let ids = world
            .add_tile_rects(&level.map, &rects, tilemap.kind)
            .map_err(|e| invalid("tilemap".into(), e))?;
        cell_bodies.extend(&ids);
        for (id, rect) in ids.into_iter().zip(&rects) {
            let aabb = level.map.rect_aabb(rect);
            bounds = Some(bounds.map_or(aabb, |b| b.union(&aabb)));
            let kind = level.map.kinds()[rect.kind as usize];
            bodies.push(SceneBody {
                id,
                name: None,
                colour: tile_colour(&kind, tilemap.kind),
            });
            if let Some(path) = tilemap.path {
                path.check_speed(file.max_speed)
                    .map_err(|message| fail("tilemap.path".into(), message))?;
                platforms.push(Platform {
                    id,
                    start: aabb.centre(),
                    path,
                });
            }
        }
        let ids = world
            .add_tile_chains(&level.map, &chains, tilemap.kind)
            .map_err(|e| invalid("tilemap".into(), e))?;
        cell_bodies.extend(&ids);
        let mut ids = ids.into_iter();
        for chain in &chains {
            let kind = level.map.kinds()[usize::from(chain.kind)];
            for id in ids.by_ref().take(chain.points.len()) {
                let at = world.body(id).map_or(Vec2::ZERO, |b| b.position);
                bodies.push(SceneBody {
                    id,
                    name: None,
                    colour: tile_colour(&kind, tilemap.kind),
                });
                if let Some(path) = tilemap.path {
                    platforms.push(Platform {
                        id,
                        start: at,
                        path,
                    });
                }
            }
            for p in &chain.points {
                let point = Aabb::from_centre(*p, Vec2::ZERO);
                bounds = Some(bounds.map_or(point, |b| b.union(&point)));
            }
        }
        // Cell bodies in id order, as the art expects.
        cell_bodies.sort_unstable();
    }
    let mut add = |spec: &BodySpec, position: Vec2, path_of: &dyn Fn() -> String| {
        let def = body_def(spec, position);
        let id = world.add_body(def).map_err(|e| invalid(path_of(), e))?;
        if let Some(zone) = spec.zone {
            (world.add_force_zone(id, zone))
                .map_err(|e| invalid(format!("{}.zone", path_of()), e))?;
        }
        let half = spec.shape.map_or(Vec2::ZERO, |s| s.half_extents());
        let aabb = Aabb::from_centre(position, half);
        bounds = Some(bounds.map_or(aabb, |b| b.union(&aabb)));
        let colour = spec.colour.unwrap_or(match spec.kind {
            BodyKind::Static => STATIC_COLOUR,
            BodyKind::Kinematic => KINEMATIC_COLOUR,
            BodyKind::Dynamic => Colour(PALETTE[bodies.len() % PALETTE.len()]),
        });
        bodies.push(SceneBody {
            id,
            name: spec.name.clone(),
            colour,
        });
        if let Some(path) = spec.path {
            path.check_speed(file.max_speed)
                .map_err(|message| fail(format!("{}.path", path_of()), message))?;
            platforms.push(Platform {
                id,
                start: position,
                path,
            });
        }
        Ok::<(), SceneError>(())
    };
    for (i, spec) in file.bodies.iter().enumerate() {
        add(spec, spec.position, &|| format!("bodies[{i}]"))?;
    }
    let mut spawns = Vec::new();
    let mut art = LevelArt::default();
    let mut level_chains = Vec::new();
    if let Some(level) = level {
        art = level.art;
        level_chains = level.chains;
        for (i, spec) in level.bodies.iter().enumerate() {
            let name = spec.name.clone().unwrap_or_default();
            add(spec, spec.position, &|| {
                format!("tilemap object {i} `{name}`")
            })?;
        }
        spawns = level.spawns;
    }
    for (i, g) in file.generators.iter().enumerate() {
        let mut result = Ok(());
        generate(g, |spec, position| {
            if result.is_ok() {
                result = add(spec, position, &|| format!("generators[{i}]"));
            }
        });
        result?;
    }
    let named = file
        .chains
        .iter()
        .enumerate()
        .map(|(i, c)| (format!("chains[{i}]"), c))
        .chain(level_chains.iter().enumerate().map(|(i, c)| {
            let name = c.name.clone().unwrap_or_default();
            (format!("tilemap chain {i} `{name}`"), c)
        }));
    for (field, chain) in named {
        let def = passo_physics::ChainDef {
            points: chain.points.clone(),
            closed: chain.closed,
            kind: chain.kind,
            friction: chain.material.friction,
            restitution: chain.material.restitution,
            ..passo_physics::ChainDef::new(Vec::new())
        };
        let ids = world
            .add_chain(&def)
            .map_err(|e| invalid(field.clone(), e))?;
        for &id in &ids {
            bodies.push(SceneBody {
                id,
                name: chain.name.clone(),
                colour: chain.colour.unwrap_or(STATIC_COLOUR),
            });
        }
        for p in &chain.points {
            let point = Aabb::from_centre(*p, Vec2::ZERO);
            bounds = Some(bounds.map_or(point, |b| b.union(&point)));
        }
    }
    for (i, spec) in file.joints.iter().enumerate() {
        let field = format!("joints[{i}]");
        let mut find = |name: &str| {
            let id = bodies
                .iter()
                .find(|b| b.name.as_deref() == Some(name))
                .map(|b| b.id)
                .ok_or_else(|| format!("no body is named {name:?}"))?;
            Ok((id, world.body(id).map_or(Vec2::ZERO, |b| b.position)))
        };
        let def = joint_def(spec, &mut find).map_err(|m| fail(field.clone(), m))?;
        world.add_joint(def).map_err(|e| invalid(field, e))?;
    }
    let camera = match &file.camera {
        Some(c) => Aabb {
            min: c.min,
            max: c.max,
        },
        None => {
            let b = bounds.unwrap_or(Aabb::from_centre(Vec2::ZERO, Vec2::splat(10.0)));
            let pad = (b.size() * 0.1).max(Vec2::splat(1.0));
            Aabb {
                min: b.min - pad,
                max: b.max + pad,
            }
        }
    };
    Ok(BuiltScene {
        world,
        bodies,
        camera,
        platforms,
        spawns,
        art,
        cell_bodies,
        tick: 0,
    })
}
