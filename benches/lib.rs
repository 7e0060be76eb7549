//! Benchmark scenes and timing shared by `passo bench`, the criterion
//! benchmarks and the peer comparison (`cargo bench -p passo-benches`,
//! `cargo run --release -p passo-benches --features rapier --bin peer`).

use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyKind, Shape, World};
use std::time::Instant;

#[cfg(feature = "box2d")]
pub mod box2d;
pub mod hashes;
pub mod stability;
pub mod tables;

/// The density that gives a body its Passo mass (1 for immovable ones), for
/// peers that take densities.
pub fn density_of(b: &passo_physics::Body) -> f32 {
    match (b.kind, b.shape) {
        (BodyKind::Dynamic, Some(shape)) => b.mass / shape.area(),
        _ => 1.0,
    }
}

/// Radius of a rain circle, metres.
pub const RAIN_RADIUS: f32 = 0.1;
/// Mass of a rain circle, kilograms.
pub const RAIN_MASS: f32 = 0.1;

/// Circles of radius 0.1 m raining into an open box: `n` bodies on a
/// jittered grid twice as wide as it is tall, 1 cm to 4 cm apart.
pub fn rain_world(n: usize) -> World {
    let columns = ((2.0 * (n as f32).sqrt()).ceil() as usize).max(1);
    rain_grid(n, columns)
}

/// The same rain in a strip 20 rows deep whose width grows with `n`: every
/// body sees the same neighbourhood whatever the size, so the cost per
/// body-step shows how the step scales.
pub fn rain_strip(n: usize) -> World {
    rain_grid(n, n.div_ceil(20).max(1))
}

/// `n` circles in `columns` columns above a floor between two walls.
pub fn rain_grid(n: usize, columns: usize) -> World {
    rain_in(n, columns, box_container)
}

/// The rain's box: a floor and two walls, three static boxes.
fn box_container(world: &mut World, width: f32, height: f32) {
    let fixed = |w: &mut World, centre: Vec2, size: Vec2| {
        w.add_body(BodyDef::new_static(centre, Shape::rect(size.x, size.y)))
            .expect("valid wall");
    };
    fixed(world, Vec2::new(0.0, -0.5), Vec2::new(width + 2.0, 1.0));
    fixed(
        world,
        Vec2::new(-width * 0.5 - 0.5, height * 0.5),
        Vec2::new(1.0, height),
    );
    fixed(
        world,
        Vec2::new(width * 0.5 + 0.5, height * 0.5),
        Vec2::new(1.0, height),
    );
}

/// The same rain in a box drawn on a 1000 × 1000 tile map of 0.25 m cells
/// (250 m square): the floor and walls are cells, and one cell in ten of
/// the rest of the map is solid (scattered blocks of a level), so the map
/// is tens of thousands of boxes.
pub fn rain_on_tile_map(n: usize) -> World {
    let columns = ((2.0 * (n as f32).sqrt()).ceil() as usize).max(1);
    rain_in(n, columns, tile_container)
}

fn tile_container(world: &mut World, width: f32, height: f32) {
    use passo_physics::{BodyKind, TileKind, TileMap};
    let cell = 0.25;
    let cells = 1000u32;
    let origin = Vec2::splat(-0.5 * cells as f32 * cell) + Vec2::new(0.0, 100.0);
    let mut map = TileMap::new(cells, cells, Vec2::splat(cell), origin).expect("valid map");
    let solid = map.add_kind(TileKind::SOLID).expect("valid kind");
    let at = |p: Vec2| map.cell_at(p).expect("inside the map");
    // The box: floor 1 m thick, walls 1 m thick, as in `box_container`.
    let (lo, hi) = (
        at(Vec2::new(-width * 0.5 - 1.0 + 0.01, -1.0 + 0.01)),
        at(Vec2::new(width * 0.5 + 1.0 - 0.01, height - 0.01)),
    );
    let (inner_lo, inner_hi) = (
        at(Vec2::new(-width * 0.5 + 0.01, 0.01)),
        at(Vec2::new(width * 0.5 - 0.01, height)),
    );
    let mut next = xorshift(0x9E37_79B9_7F4A_7C15);
    for y in 0..cells {
        for x in 0..cells {
            let in_box = (lo.0..=hi.0).contains(&x) && (lo.1..=hi.1).contains(&y);
            let hollow = (inner_lo.0..=inner_hi.0).contains(&x) && y >= inner_lo.1;
            let solid_cell = if in_box {
                !hollow
            } else {
                next().is_multiple_of(10) && !(lo.0.saturating_sub(8)..=hi.0 + 8).contains(&x)
            };
            if solid_cell {
                map.set(x, y, Some(solid)).expect("inside");
            }
        }
    }
    world
        .add_tile_map(&map, BodyKind::Static)
        .expect("valid map");
}

/// `n` circles in `columns` columns in a box made by `container(world,
/// width, height)`.
/// How many pieces the hilly ground of [`rain_on_hills`] is made of.
pub const HILL_PIECES: usize = 1000;

/// The rain of [`rain_world`] falling onto hilly ground between two walls:
/// a chain of [`HILL_PIECES`] segments (`boxes: false`), or as many static
/// boxes, each under one segment with its top at the segment's middle
/// (`boxes: true`). The ground rises and falls 0.3 m every 6 m (17° at
/// its steepest, so friction holds the rain on it), below the rain.
pub fn rain_on_hills(n: usize, boxes: bool) -> World {
    let columns = ((2.0 * (n as f32).sqrt()).ceil() as usize).max(1);
    rain_in(n, columns, if boxes { hill_boxes } else { hill_chain })
}

/// The height of the hilly ground at `x`.
fn hill_height(x: f32) -> f32 {
    -1.0 + 0.3 * (x * std::f32::consts::TAU / 6.0).sin()
}

/// The points of the hilly ground across `width`.
fn hill_points(width: f32) -> Vec<Vec2> {
    (0..=HILL_PIECES)
        .map(|i| {
            let x = -0.5 * width + width * i as f32 / HILL_PIECES as f32;
            Vec2::new(x, hill_height(x))
        })
        .collect()
}

/// The walls of the rain's box, without its floor.
fn walls(world: &mut World, width: f32, height: f32) {
    for side in [-1.0f32, 1.0] {
        world
            .add_body(BodyDef::new_static(
                Vec2::new(side * (width * 0.5 + 0.5), height * 0.5 - 1.5),
                Shape::rect(1.0, height + 3.0),
            ))
            .expect("valid wall");
    }
}

fn hill_chain(world: &mut World, width: f32, height: f32) {
    walls(world, width, height);
    world
        .add_chain(&passo_physics::ChainDef::new(hill_points(width)))
        .expect("valid ground");
}

fn hill_boxes(world: &mut World, width: f32, height: f32) {
    walls(world, width, height);
    let points = hill_points(width);
    for pair in points.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let top = 0.5 * (a.y + b.y);
        let bottom = -3.0;
        world
            .add_body(BodyDef::new_static(
                Vec2::new(0.5 * (a.x + b.x), 0.5 * (top + bottom)),
                Shape::rect(b.x - a.x, top - bottom),
            ))
            .expect("valid ground");
    }
}

fn rain_in(n: usize, columns: usize, container: fn(&mut World, f32, f32)) -> World {
    let mut world = World::default();
    let rows = n.div_ceil(columns);
    let spacing = 0.25;
    let width = columns as f32 * spacing + 1.0;
    let height = rows as f32 * spacing + 5.0;
    container(&mut world, width, height);
    let mut unit = unit_sequence(0x2545_F491_4F6C_DD1D);
    let mut jitter = move || (unit() - 0.5) * 0.03;
    for k in 0..n {
        let (i, j) = (k % columns, k / columns);
        let p = Vec2::new(
            -width * 0.5 + 0.5 + (i as f32 + 0.5) * spacing + jitter(),
            0.5 + j as f32 * spacing + jitter(),
        );
        let def = BodyDef {
            position: p,
            shape: Some(Shape::circle(RAIN_RADIUS)),
            mass: RAIN_MASS,
            ..Default::default()
        };
        world.add_body(def).expect("valid circle");
    }
    world
}

/// A pyramid of unit boxes with `base` boxes in the bottom row.
pub fn pyramid_world(base: usize) -> World {
    let mut world = World::default();
    world
        .add_body(BodyDef::new_static(
            Vec2::new(0.0, -0.5),
            Shape::rect(base as f32 * 2.0 + 10.0, 1.0),
        ))
        .expect("valid ground");
    for row in 0..base {
        for i in 0..base - row {
            let x = i as f32 - (base - row - 1) as f32 * 0.5;
            let def = BodyDef {
                position: Vec2::new(x, 0.5 + row as f32),
                shape: Some(Shape::rect(1.0, 1.0)),
                ..Default::default()
            };
            world.add_body(def).expect("valid box");
        }
    }
    world
}

/// The scene files (`.ron`) in `dir`, sorted by name: the shipped scenes
/// are those of `assets/scenes/` ([`SCENES_DIR`]).
pub fn scene_files(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut paths: Vec<_> = std::fs::read_dir(dir)
        .expect("the scenes folder")
        .map(|e| e.expect("a folder entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    paths.sort();
    paths
}

/// The folder of the shipped scenes.
pub const SCENES_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/scenes");

/// The rain of the busy scene and the determinism tests: 2 000 circles
/// into a box with 30 m walls,
/// kept here rather than read from `assets/scenes/rain.ron`, so the
/// determinism tests' scene does not move when the demo's does.
pub const BUSY_RAIN: &str = r#"(
    name: "Rain",
    forces: (gravity: (0, -9.81)),
    collisions: (),
    bodies: [
        (name: "floor", kind: Static, shape: Box(half_extents: (10.5, 0.5)), position: (0, -0.5)),
        (name: "left wall", kind: Static, shape: Box(half_extents: (0.5, 15)), position: (-10, 15)),
        (name: "right wall", kind: Static, shape: Box(half_extents: (0.5, 15)), position: (10, 15)),
    ],
    generators: [
        Rain(
            count: 2000,
            origin: (-8.7, 2),
            columns: 30,
            spacing: (0.6, 0.6),
            jitter: 0.09,
            seed: 7,
            body: (shape: Circle(radius: 0.2), density: 1, material: (friction: 0.4)),
        ),
    ],
)"#;

/// The busy scene of the determinism tests: the rain of [`BUSY_RAIN`]
/// (2 000 circles in a box) with a pyramid of 36 boxes beside it and five fast
/// balls thrown through, so every stage of the step runs.
pub fn busy_world() -> World {
    let scene = passo_scene::Scene::parse(BUSY_RAIN, "busy_rain.ron").expect("the rain parses");
    let mut world = scene.build().expect("the rain builds").world;
    for row in 0..8 {
        for col in 0..(8 - row) {
            let p = Vec2::new(14.0 + col as f32 - (7 - row) as f32 * 0.5, 0.5 + row as f32);
            let def = BodyDef {
                position: p,
                shape: Some(Shape::rect(1.0, 1.0)),
                ..Default::default()
            };
            world.add_body(def).expect("valid box");
        }
    }
    world
        .add_body(BodyDef::new_static(
            Vec2::new(14.0, -0.5),
            Shape::rect(12.0, 1.0),
        ))
        .expect("valid ground");
    for i in 0..5 {
        let def = BodyDef {
            position: Vec2::new(30.0, 2.0 + i as f32),
            velocity: Vec2::new(-40.0, 3.0),
            shape: Some(Shape::circle(0.3)),
            restitution: 0.5,
            mass: 3.0,
            ..Default::default()
        };
        world.add_body(def).expect("valid ball");
    }
    world
}

/// The same bodies as `world`, with its dynamic ones added in a scrambled
/// order (the same order every run): their storage order and ids no
/// longer follow their places, as when a game spawns bodies over time
/// wherever they are needed.
pub fn shuffled(world: &World) -> World {
    let mut out = World::new(*world.settings()).expect("valid settings");
    let (mut dynamic, fixed): (Vec<_>, Vec<_>) = world
        .bodies()
        .map(|b| b.to_def())
        .partition(|def| def.kind == BodyKind::Dynamic);
    let mut next = xorshift(0x9E37_79B9_7F4A_7C15);
    for i in (1..dynamic.len()).rev() {
        dynamic.swap(i, (next() % (i as u64 + 1)) as usize);
    }
    for def in fixed.into_iter().chain(dynamic) {
        out.add_body(def).expect("a body of a valid world");
    }
    out
}

/// A copy of `world` with sleeping switched on or off.
pub fn with_sleeping(world: &World, on: bool) -> World {
    let mut world = world.clone();
    let mut settings = *world.settings();
    if let Some(contacts) = &mut settings.contacts {
        contacts.sleeping = on;
    }
    world.set_settings(settings).expect("valid settings");
    world
}

/// Mean milliseconds per step over all ticks and over the last fifth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepTimes {
    /// Mean over every tick.
    pub mean_ms: f64,
    /// Mean over the last fifth (settled).
    pub last_ms: f64,
}

/// Steps `ticks` times with `step`, timing each.
pub fn time_steps(ticks: u32, step: impl FnMut()) -> StepTimes {
    time_steps_with(ticks, step, |_| {})
}

/// Like [`time_steps`], with `between(tick)` called before each step and
/// left out of the timing (for measurements of the state).
pub fn time_steps_with(
    ticks: u32,
    mut step: impl FnMut(),
    mut between: impl FnMut(u32),
) -> StepTimes {
    let tail = (ticks / 5).max(1);
    let (mut all, mut last) = (0.0, 0.0);
    for t in 0..ticks {
        between(t);
        let start = Instant::now();
        step();
        let ms = start.elapsed().as_secs_f64() * 1e3;
        all += ms;
        if t >= ticks - tail {
            last += ms;
        }
    }
    StepTimes {
        mean_ms: all / f64::from(ticks.max(1)),
        last_ms: last / f64::from(tail),
    }
}

/// `count` rays (origin, unit direction) from pseudo-random points of the
/// box `min..max` in pseudo-random directions, the same every run.
pub fn rays(min: Vec2, max: Vec2, count: usize) -> Vec<(Vec2, Vec2)> {
    let mut next = unit_sequence(0x9E37_79B9_7F4A_7C15);
    (0..count)
        .map(|_| {
            let origin = min + (max - min) * Vec2::new(next(), next());
            let angle = next() * std::f32::consts::TAU;
            (origin, Vec2::new(angle.cos(), angle.sin()))
        })
        .collect()
}

/// A kinematic platform sweeping back and forth: its body, where it
/// starts, and how far it goes.
#[derive(Clone, Copy, Debug)]
pub struct Sweeper {
    /// The platform.
    pub id: passo_physics::BodyId,
    /// Its position at tick 0.
    pub start: Vec2,
    /// The far end, relative to the start.
    pub by: Vec2,
}

/// The rain of `n` circles with `platforms` kinematic platforms (`length`
/// by 0.3 m) sweeping sideways in rows, as a level's moving platforms: through
/// the pile, or (with `above`) above where it lands; drive them with
/// [`drive_sweepers`] before each step.
pub fn rain_with_platforms(
    n: usize,
    platforms: usize,
    length: f32,
    above: bool,
) -> (World, Vec<Sweeper>) {
    let columns = ((2.0 * (n as f32).sqrt()).ceil() as usize).max(1);
    let mut world = rain_grid(n, columns);
    let width = columns as f32 * 0.25;
    let rows = n.div_ceil(columns) as f32 * 0.25;
    let sweepers = (0..platforms)
        .map(|k| {
            let base = if above { rows + 6.0 } else { 1.0 };
            let start = Vec2::new(
                -width * 0.5 + 2.5 + (k % 4) as f32 * width * 0.2,
                base + (k / 4) as f32 * rows / (platforms.div_ceil(4) as f32).max(1.0),
            );
            let def = BodyDef::new_kinematic(start, Shape::rect(length, 0.3), Vec2::ZERO);
            let id = world.add_body(def).expect("valid platform");
            Sweeper {
                id,
                start,
                by: Vec2::new(width * 0.15, 0.0),
            }
        })
        .collect();
    (world, sweepers)
}

/// Steers the sweepers to their place at the end of tick `tick` (a
/// 4-second triangle wave, 60 Hz).
pub fn drive_sweepers(world: &mut World, sweepers: &[Sweeper], tick: u32) {
    let dt = 1.0 / 60.0;
    let phase = ((tick + 1) % 240) as f32 / 240.0;
    let s = 1.0 - (2.0 * phase - 1.0).abs();
    for p in sweepers {
        world.set_kinematic_target(p.id, p.start + p.by * s, dt);
    }
}

/// `n` circles of radius 0.1 m spawned on one spot, no gravity.
pub fn spawned_on_one_spot(n: usize) -> World {
    let settings = passo_physics::WorldSettings {
        forces: passo_physics::ForceModels::none(),
        ..Default::default()
    };
    let mut world = World::new(settings).expect("valid settings");
    for _ in 0..n {
        world
            .add_body(BodyDef::new_dynamic(Vec2::ZERO, Shape::circle(0.1)))
            .expect("valid circle");
    }
    world
}

/// The deepest overlap of any two shaped bodies (one of them dynamic,
/// sensors left out), metres, from exact geometry: a sweep along x over
/// every body, with no bound on pairs (unlike the broad phase's crowded
/// buckets, which [`World::max_penetration`] shares), so a pile spawned on
/// one spot costs `n²` here until it spreads.
pub fn exact_max_overlap(world: &World) -> f32 {
    let mut bodies: Vec<_> = world
        .bodies()
        .filter(|b| b.shape.is_some() && !b.sensor)
        .map(|b| {
            let shape = b.shape.expect("shaped");
            let h = shape.half_extents();
            (b.position.x - h.x, b.position.x + h.x, b)
        })
        .collect();
    bodies.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut deepest = 0.0f32;
    for (i, (_, max_x, a)) in bodies.iter().enumerate() {
        for (min_x, _, b) in &bodies[i + 1..] {
            if min_x > max_x {
                break;
            }
            let dynamic = a.kind == passo_physics::BodyKind::Dynamic
                || b.kind == passo_physics::BodyKind::Dynamic;
            if !dynamic || !a.filter.allows(&b.filter) {
                continue;
            }
            let (sa, sb) = (a.shape.expect("shaped"), b.shape.expect("shaped"));
            if let Some(m) = passo_physics::collide(&sa, a.position, &sb, b.position, 0.0) {
                deepest = deepest.max(-m.separation);
            }
        }
    }
    deepest
}

/// `n` circles of radius 0.1 m flying at 100 to 500 m/s in pseudo-random
/// directions inside a closed 60 m × 30 m box, no gravity.
pub fn fast_circles_in_a_box(n: usize) -> World {
    let settings = passo_physics::WorldSettings {
        forces: passo_physics::ForceModels::none(),
        ..Default::default()
    };
    let mut world = World::new(settings).expect("valid settings");
    let wall = |w: &mut World, centre: Vec2, size: Vec2| {
        w.add_body(BodyDef::new_static(centre, Shape::rect(size.x, size.y)))
            .expect("valid wall");
    };
    wall(&mut world, Vec2::new(0.0, -15.5), Vec2::new(62.0, 1.0));
    wall(&mut world, Vec2::new(0.0, 15.5), Vec2::new(62.0, 1.0));
    wall(&mut world, Vec2::new(-30.5, 0.0), Vec2::new(1.0, 30.0));
    wall(&mut world, Vec2::new(30.5, 0.0), Vec2::new(1.0, 30.0));
    let mut next = unit_sequence(0xD1B5_4A32_D192_ED03);
    for _ in 0..n {
        let p = Vec2::new(next() * 58.0 - 29.0, next() * 28.0 - 14.0);
        let angle = next() * std::f32::consts::TAU;
        let speed = 100.0 + 400.0 * next();
        let def = BodyDef::new_dynamic(p, Shape::circle(0.1))
            .with_velocity(Vec2::new(angle.cos(), angle.sin()) * speed);
        world.add_body(def).expect("valid circle");
    }
    world
}

/// The states of a xorshift from `seed`, the same on every run and
/// machine.
fn xorshift(mut seed: u64) -> impl FnMut() -> u64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    }
}

/// Pseudo-random numbers in `[0, 1)` from a xorshift of `seed`, the same
/// on every run and machine.
fn unit_sequence(seed: u64) -> impl FnMut() -> f32 {
    let mut next = xorshift(seed);
    move || (next() >> 40) as f32 / (1u64 << 24) as f32
}

/// Box2D's `joint_grid` benchmark without rotation: `n × n` circles of
/// radius 0.4 m one metre apart, each linked to its neighbours below and
/// to the right by a rod of 1 m (a distance joint between centres), the
/// seven middle bodies of the top row static, and no two circles
/// colliding (layer 2, mask all but 2). It falls and swings as a net.
pub fn joint_grid(n: usize) -> World {
    let mut world = World::default();
    let filter = passo_physics::CollisionFilter {
        layers: 2,
        mask: !2,
    };
    let mut ids = Vec::with_capacity(n * n);
    for k in 0..n {
        for i in 0..n {
            let position = Vec2::new(k as f32, -(i as f32));
            let middle = k + 3 >= n / 2 && k <= n / 2 + 3;
            let shape = Shape::circle(0.4);
            let def = if middle && i == 0 {
                BodyDef::new_static(position, shape)
            } else {
                BodyDef {
                    mass: std::f32::consts::PI * 0.16,
                    ..BodyDef::new_dynamic(position, shape)
                }
            };
            let fixed = def.kind == BodyKind::Static;
            let id = world.add_body(def.with_filter(filter)).expect("valid body");
            // (Two static neighbours need no joint: Box2D ignores one.)
            let mut link = |other: (passo_physics::BodyId, bool)| {
                if !(fixed && other.1) {
                    let rod = passo_physics::JointDef::distance(other.0, Some(id), 1.0);
                    world.add_joint(rod).expect("valid joint");
                }
            };
            if i > 0 {
                link(ids[ids.len() - 1]);
            }
            if k > 0 {
                link(ids[ids.len() - n]);
            }
            ids.push((id, fixed));
        }
    }
    world
}

/// A bridge of `n` planks (0.9 m × 0.2 m, 2 kg) one metre apart between
/// two static posts, each plank's ends linked to its neighbours' by rods
/// of 0.1 m: straight as built, it sags under its weight as far as the
/// rods give. Planks do not collide with each other.
pub fn bridge_world(n: usize) -> World {
    let mut world = World::default();
    let width = n as f32;
    let post = |world: &mut World, x: f32| {
        let def = BodyDef::new_static(Vec2::new(x, -1.0), Shape::rect(1.0, 2.0));
        world.add_body(def).expect("valid post")
    };
    let left = post(&mut world, -0.5 * width - 0.5);
    let right = post(&mut world, 0.5 * width + 0.5);
    let mut last = (left, Vec2::new(0.5, 1.0));
    for i in 0..n {
        let x = -0.5 * width + 0.5 + i as f32;
        let def = BodyDef {
            mass: 2.0,
            ..BodyDef::new_dynamic(Vec2::new(x, -0.1), Shape::rect(0.9, 0.2))
        };
        let plank = world.add_body(def).expect("valid plank");
        let rod = passo_physics::JointDef::distance(last.0, Some(plank), 0.05)
            .anchors(last.1, Vec2::new(-0.45, 0.1));
        world.add_joint(rod).expect("valid joint");
        last = (plank, Vec2::new(0.45, 0.1));
    }
    let rod = passo_physics::JointDef::distance(last.0, Some(right), 0.05)
        .anchors(last.1, Vec2::new(-0.5, 1.0));
    world.add_joint(rod).expect("valid joint");
    world
}

/// How far the lowest plank of a bridge (every dynamic body) hangs below
/// where it was built, metres.
pub fn sag(start: &World, now: &World) -> f32 {
    start
        .bodies()
        .filter(|b| b.kind == BodyKind::Dynamic)
        .map(|b| b.position.y - now.body(b.id).map_or(b.position.y, |n| n.position.y))
        .fold(0.0, f32::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_shuffled_world_has_the_same_bodies_in_another_order() {
        let world = rain_world(200);
        let copy = shuffled(&world);
        let places = |w: &World| w.bodies().map(|b| b.position).collect::<Vec<_>>();
        let (before, after) = (places(&world), places(&copy));
        assert_ne!(before, after, "the order changed");
        let sorted = |mut p: Vec<Vec2>| {
            p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
            p
        };
        assert_eq!(sorted(before), sorted(after));
        assert_eq!(copy.settings(), world.settings());
    }
}
