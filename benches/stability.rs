//! The stability suite: hard cases for a contact solver, and what a run of
//! each measures. The same scenes run in Passo and, with the `box2d`
//! feature, in Box2D v3 (rotation fixed): `cargo run --release -p
//! passo-benches --features box2d --bin stability`.
//!
//! Every case runs with sleeping off (awake against awake) at 60 Hz for
//! its length, on one thread. What is measured, from each engine's state
//! after every tick, with Passo's exact geometry and energy:
//! - **rest**: the time after which every dynamic body stays slower than
//!   [`REST_SPEED`] to the end of the run (`None`: still moving at the end);
//! - **rest overlap** and **peak overlap**: the deepest overlap between two
//!   bodies, or a body and the ground, at the end and at its worst;
//! - **energy gain**: how far the total energy (kinetic plus potential)
//!   rose above its start at its highest, as a share of the start;
//! - **returned**: for a case with a probe (a body dropped or thrown), the
//!   share of the probe's impact kinetic energy it had again at its fastest
//!   rebound: `(v_rebound / v_impact)²`, 0 when it never comes back up;
//! - **escaped**: dynamic bodies outside the case's bounds at the end;
//! - **µs per tick**: the time the engine's steps took, divided by the
//!   ticks.

use passo_physics::glam::Vec2;
use passo_physics::{Aabb, BodyDef, BodyId, BodyKind, Shape, World};
use std::time::Instant;

/// The speed under which a body counts as at rest, metres per second.
pub const REST_SPEED: f32 = 0.05;

/// Ticks per second.
pub const HZ: f32 = 60.0;

/// One hard case.
#[derive(Clone)]
pub struct Case {
    /// A short name for the tables (`stack_30`).
    pub name: &'static str,
    /// What the scene is, in a few words.
    pub what: &'static str,
    /// The world at the start, sleeping off.
    pub world: World,
    /// The body whose rebound is measured, if any.
    pub probe: Option<BodyId>,
    /// How long the case runs, seconds.
    pub seconds: f32,
    /// A dynamic body outside these bounds at the end has escaped.
    pub bounds: Aabb,
}

/// What one run of a case measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outcome {
    /// Seconds until every body stays slower than [`REST_SPEED`]; `None`:
    /// still moving at the end.
    pub rest: Option<f32>,
    /// The deepest overlap at the end, metres.
    pub rest_overlap: f32,
    /// The deepest overlap at any tick, metres.
    pub peak_overlap: f32,
    /// `(E_max - E_0) / |E_0|`: the highest the total energy rose above its
    /// start, as a share of the start (0 when it never rose).
    pub energy_gain: f64,
    /// `(v_rebound / v_impact)²` of the probe, if the case has one.
    pub returned: Option<f32>,
    /// Dynamic bodies outside the bounds at the end.
    pub escaped: usize,
    /// Microseconds the steps took, per tick.
    pub us_per_tick: f64,
}

/// A physics engine stepping a case: Passo itself, or a peer given the same
/// bodies.
pub trait Engine {
    /// One tick of 1/60 s.
    fn step(&mut self);
    /// Calls `f` with a Passo world in the engine's current state.
    fn read(&mut self, f: &mut dyn FnMut(&World));
}

/// Passo on one thread.
pub struct Passo(pub World);

impl Engine for Passo {
    fn step(&mut self) {
        self.0.step(1.0 / HZ);
    }

    fn read(&mut self, f: &mut dyn FnMut(&World)) {
        f(&self.0);
    }
}

/// Box2D v3 given the case's bodies.
#[cfg(feature = "box2d")]
pub struct Box2dEngine {
    /// The Box2D world.
    pub box2d: crate::box2d::Box2d,
    /// The case's world, whose bodies the state is copied into.
    pub template: World,
}

#[cfg(feature = "box2d")]
impl Engine for Box2dEngine {
    fn step(&mut self) {
        self.box2d.step();
    }

    fn read(&mut self, f: &mut dyn FnMut(&World)) {
        f(&self.box2d.state(&self.template));
    }
}

/// Runs `case` in `engine` and measures it.
pub fn run(case: &Case, engine: &mut dyn Engine) -> Outcome {
    let ticks = (case.seconds * HZ).round() as usize;
    let mut start_energy = 0.0;
    engine.read(&mut |w| start_energy = w.total_energy());
    let mut highest = start_energy;
    let (mut peak, mut last_moving, mut stepping) = (0.0f32, None, 0.0f64);
    // The probe's vertical speed: its fastest fall so far, the tick of it,
    // and its fastest rise after that.
    let (mut impact, mut rebound) = (0.0f32, 0.0f32);
    let mut end = (0.0f32, 0usize);
    for tick in 0..ticks {
        let started = Instant::now();
        engine.step();
        stepping += started.elapsed().as_secs_f64();
        engine.read(&mut |w| {
            highest = highest.max(w.total_energy());
            let overlap = w.max_penetration();
            peak = peak.max(overlap);
            let fastest = w
                .bodies()
                .filter(|b| b.kind == BodyKind::Dynamic)
                .map(|b| b.velocity.length())
                .fold(0.0f32, f32::max);
            if fastest >= REST_SPEED {
                last_moving = Some(tick);
            }
            if let Some(probe) = case.probe.and_then(|p| w.body(p)) {
                let vy = probe.velocity.y;
                if vy < -impact {
                    // Still speeding up: no rebound counted yet.
                    impact = -vy;
                    rebound = 0.0;
                } else {
                    rebound = rebound.max(vy);
                }
            }
            if tick + 1 == ticks {
                let escaped = w
                    .bodies()
                    .filter(|b| b.kind == BodyKind::Dynamic)
                    .filter(|b| !case.bounds.contains_point(b.position))
                    .count();
                end = (overlap, escaped);
            }
        });
    }
    let rest = match last_moving {
        Some(t) if t + 1 == ticks => None,
        Some(t) => Some((t + 1) as f32 / HZ),
        None => Some(0.0),
    };
    Outcome {
        rest,
        rest_overlap: end.0,
        peak_overlap: peak,
        energy_gain: ((highest - start_energy) / start_energy.abs().max(1e-9)).max(0.0),
        returned: case.probe.map(|_| {
            if impact > 0.0 {
                (rebound / impact).powi(2)
            } else {
                0.0
            }
        }),
        escaped: end.1,
        us_per_tick: stepping * 1e6 / ticks as f64,
    }
}

/// An empty world with sleeping off and a ground `width` wide, its top at
/// y = 0.
fn ground(width: f32) -> World {
    let mut world = crate::with_sleeping(&World::default(), false);
    world.set_parallel(false);
    world
        .add_body(BodyDef::new_static(
            Vec2::new(0.0, -0.5),
            Shape::rect(width, 1.0),
        ))
        .expect("the ground");
    world
}

/// Adds a static box from `min` to `max`.
fn wall(world: &mut World, min: Vec2, max: Vec2) {
    let def = BodyDef::new_static((min + max) * 0.5, Shape::rect(max.x - min.x, max.y - min.y));
    world.add_body(def).expect("a wall");
}

/// Adds a dynamic body.
fn body(world: &mut World, at: Vec2, shape: Shape, mass: f32) -> BodyId {
    let def = BodyDef {
        position: at,
        shape: Some(shape),
        mass,
        ..Default::default()
    };
    world.add_body(def).expect("a body")
}

/// A stack of `masses.len()` boxes `size` wide and tall on the ground, the
/// first at the bottom.
fn stack(name: &'static str, what: &'static str, size: f32, masses: &[f32]) -> Case {
    let mut world = ground(20.0 * size);
    for (i, &m) in masses.iter().enumerate() {
        let at = Vec2::new(0.0, size * (0.5 + i as f32));
        body(&mut world, at, Shape::rect(size, size), m);
    }
    let height = size * masses.len() as f32;
    Case {
        name,
        what,
        world,
        probe: None,
        seconds: 10.0,
        bounds: Aabb::from_centre(Vec2::new(0.0, height * 0.5), Vec2::new(3.0 * size, height)),
    }
}

/// Masses growing `ratio` times from one box to the next, from `first`.
fn growing(first: f32, ratio: f32, n: usize) -> Vec<f32> {
    (0..n).map(|i| first * ratio.powi(i as i32)).collect()
}

/// Circles of radius `r` and mass `m` filling a bin `width` wide to
/// `layers` layers, in rows offset by half a circle.
fn fill_bin(world: &mut World, width: f32, r: f32, m: f32, layers: usize) {
    let per_row = ((width - r) / (2.0 * r)).floor() as usize;
    for row in 0..layers {
        let offset = if row % 2 == 0 { r } else { 2.0 * r };
        for i in 0..per_row - row % 2 {
            let at = Vec2::new(
                -width * 0.5 + offset + 2.0 * r * i as f32,
                r + 1.8 * r * row as f32,
            );
            body(world, at, Shape::circle(r), m);
        }
    }
}

/// A bin `width` wide, walls `height` high, on the ground.
fn bin(world: &mut World, width: f32, height: f32) {
    wall(
        world,
        Vec2::new(-width * 0.5 - 1.0, 0.0),
        Vec2::new(-width * 0.5, height),
    );
    wall(
        world,
        Vec2::new(width * 0.5, 0.0),
        Vec2::new(width * 0.5 + 1.0, height),
    );
}

/// Every case of the suite, in the order of the tables.
pub fn cases() -> Vec<Case> {
    let mut out = vec![
        stack("stack_30", "30 unit boxes of 1 kg", 1.0, &[1.0; 30]),
        stack(
            "mass_up_1.2",
            "20 unit boxes, each 1.2x heavier than the one below (1 to 32 kg)",
            1.0,
            &growing(1.0, 1.2, 20),
        ),
        stack(
            "mass_up_1000",
            "20 unit boxes growing 1 to 1000 kg upward",
            1.0,
            &growing(1.0, 1000f32.powf(1.0 / 19.0), 20),
        ),
        stack(
            "mass_down_1000",
            "20 unit boxes growing 1 to 1000 kg downward",
            1.0,
            &growing(1000.0, 1000f32.powf(-1.0 / 19.0), 20),
        ),
        stack(
            "heavy_on_light",
            "a 1000 kg box on a 1 kg box",
            1.0,
            &[1.0, 1000.0],
        ),
        stack(
            "small_5cm",
            "10 boxes of 5 cm, 10 g each",
            0.05,
            &[0.01; 10],
        ),
        stack("big_5m", "5 boxes of 5 m, 25 t each", 5.0, &[25_000.0; 5]),
    ];
    // A 1000 kg ball dropped from 3 m onto a pyramid of 1 kg boxes.
    let mut world = ground(40.0);
    for row in 0..8 {
        for i in 0..8 - row {
            let x = i as f32 - (7 - row) as f32 * 0.5;
            body(
                &mut world,
                Vec2::new(x, 0.5 + row as f32),
                Shape::rect(1.0, 1.0),
                1.0,
            );
        }
    }
    let ball = body(&mut world, Vec2::new(0.0, 12.0), Shape::circle(1.0), 1000.0);
    out.push(Case {
        name: "ball_on_pyramid",
        what: "a 1000 kg ball dropped 3 m onto a pyramid of 36 boxes of 1 kg",
        world,
        probe: Some(ball),
        seconds: 10.0,
        bounds: Aabb::from_centre(Vec2::new(0.0, 10.0), Vec2::new(20.0, 20.0)),
    });
    // A heavy circle landing at about 2.9 m/s on a bed of small ones.
    let mut world = ground(20.0);
    bin(&mut world, 12.0, 3.0);
    fill_bin(&mut world, 12.0, 0.1, 0.1, 4);
    let top = 0.1 + 1.8 * 0.1 * 3.0 + 0.1;
    let heavy = body(
        &mut world,
        Vec2::new(0.0, top + 2.0 + 0.43),
        Shape::circle(2.0),
        100.0,
    );
    out.push(Case {
        name: "heavy_on_circles",
        what: "a 100 kg circle of radius 2 landing at 2.9 m/s on 4 layers of small circles",
        world,
        probe: Some(heavy),
        seconds: 10.0,
        bounds: Aabb::from_centre(Vec2::new(0.0, 5.0), Vec2::new(7.0, 10.0)),
    });
    // A big circle among many small ones.
    let mut world = ground(20.0);
    bin(&mut world, 8.0, 6.0);
    fill_bin(&mut world, 8.0, 0.15, 0.2, 8);
    body(&mut world, Vec2::new(0.0, 4.0), Shape::circle(1.0), 10.0);
    out.push(Case {
        name: "big_among_small",
        what: "a 10 kg circle of radius 1 dropped into 8 layers of small circles",
        world,
        probe: None,
        seconds: 10.0,
        bounds: Aabb::from_centre(Vec2::new(0.0, 5.0), Vec2::new(5.0, 10.0)),
    });
    // Boxes packed wall to wall in a container.
    let mut world = ground(20.0);
    bin(&mut world, 6.0, 8.0);
    for row in 0..10 {
        for i in 0..12 {
            let at = Vec2::new(-2.75 + 0.5 * i as f32, 0.25 + 0.51 * row as f32);
            body(&mut world, at, Shape::rect(0.5, 0.5), 1.0);
        }
    }
    out.push(Case {
        name: "packed_container",
        what: "120 boxes of 0.5 m packed wall to wall, ten rows",
        world,
        probe: None,
        seconds: 10.0,
        bounds: Aabb::from_centre(Vec2::new(0.0, 4.0), Vec2::new(3.5, 8.0)),
    });
    // A bouncy pile.
    let mut world = ground(20.0);
    bin(&mut world, 6.0, 10.0);
    for k in 0..100 {
        let at = Vec2::new(-2.5 + 0.55 * (k % 10) as f32, 1.0 + 0.6 * (k / 10) as f32);
        let def = BodyDef {
            position: at,
            shape: Some(Shape::circle(0.25)),
            restitution: 0.5,
            ..Default::default()
        };
        world.add_body(def).expect("a ball");
    }
    out.push(Case {
        name: "bouncy_pile",
        what: "100 circles of restitution 0.5 dropped into a bin",
        world,
        probe: None,
        seconds: 10.0,
        bounds: Aabb::from_centre(Vec2::new(0.0, 6.0), Vec2::new(3.5, 12.0)),
    });
    // A box thrown at 20 m/s into a heap.
    let mut world = ground(60.0);
    for row in 0..6 {
        for i in 0..6 - row {
            let x = i as f32 - (5 - row) as f32 * 0.5;
            body(
                &mut world,
                Vec2::new(x, 0.5 + row as f32),
                Shape::rect(1.0, 1.0),
                1.0,
            );
        }
    }
    let thrown = BodyDef {
        position: Vec2::new(-8.0, 1.0),
        velocity: Vec2::new(20.0, 0.0),
        shape: Some(Shape::rect(1.0, 1.0)),
        mass: 5.0,
        ..Default::default()
    };
    world.add_body(thrown).expect("the thrown box");
    out.push(Case {
        name: "thrown_into_heap",
        what: "a 5 kg box thrown at 20 m/s into a heap of 21 boxes",
        world,
        probe: None,
        seconds: 10.0,
        bounds: Aabb::from_centre(Vec2::ZERO, Vec2::new(30.0, 10.0)),
    });
    // A plank across a gap with a load on it.
    let mut world = ground(20.0);
    wall(&mut world, Vec2::new(-4.0, 0.0), Vec2::new(-2.0, 2.0));
    wall(&mut world, Vec2::new(2.0, 0.0), Vec2::new(4.0, 2.0));
    body(&mut world, Vec2::new(0.0, 2.1), Shape::rect(6.0, 0.2), 5.0);
    body(&mut world, Vec2::new(0.0, 2.7), Shape::rect(1.0, 1.0), 20.0);
    out.push(Case {
        name: "plank_over_gap",
        what: "a 5 kg plank across a 4 m gap with a 20 kg box on it",
        world,
        probe: None,
        seconds: 10.0,
        bounds: Aabb::from_centre(Vec2::new(0.0, 2.5), Vec2::new(4.0, 2.0)),
    });
    out
}

/// `m` metres in millimetres to one decimal.
fn mm(m: f32) -> String {
    format!("{:.1}", m * 1000.0)
}

/// One row of the table: the case, the engine and what it measured.
pub fn row(case: &Case, engine: &str, o: &Outcome) -> String {
    let rest = match o.rest {
        Some(t) => format!("{t:.2}"),
        None => format!("> {:.0}", case.seconds),
    };
    let returned = o
        .returned
        .map_or("".to_string(), |r| format!("{:.1}", r * 100.0));
    format!(
        "| {} | {engine} | {rest} | {} | {} | {:.2} | {returned} | {} | {:.0} |",
        case.name,
        mm(o.rest_overlap),
        mm(o.peak_overlap),
        o.energy_gain * 100.0,
        o.escaped,
        o.us_per_tick
    )
}

/// The table's heading.
pub const HEADER: &str = "| case | engine | rest (s) | rest overlap (mm) | peak overlap (mm) | energy gain (%) | returned (%) | escaped | µs/tick |\n|---|---|---:|---:|---:|---:|---:|---:|---:|";

#[cfg(test)]
mod tests {
    use super::*;

    /// A case of one body, the ground and nothing else.
    fn one_body(def: BodyDef, seconds: f32) -> Case {
        let mut world = ground(20.0);
        let id = world.add_body(def).unwrap();
        Case {
            name: "one",
            what: "one body",
            world,
            probe: Some(id),
            seconds,
            bounds: Aabb::from_centre(Vec2::new(0.0, 5.0), Vec2::new(5.0, 5.0)),
        }
    }

    #[test]
    fn a_box_resting_on_the_ground_is_at_rest_from_the_start_and_gains_nothing() {
        let def = BodyDef::new_dynamic(Vec2::new(0.0, 0.5), Shape::rect(1.0, 1.0));
        let o = run(&one_body(def, 1.0), &mut Passo(one_body(def, 1.0).world));
        assert_eq!(o.rest, Some(0.0));
        assert!(o.peak_overlap < 0.005, "{o:?}");
        assert_eq!((o.energy_gain, o.escaped), (0.0, 0));
    }

    #[test]
    fn an_elastic_ball_returns_its_energy_and_a_dead_one_none() {
        for (restitution, low, high) in [(1.0, 0.9, 1.05), (0.5, 0.2, 0.3), (0.0, 0.0, 0.01)] {
            let def = BodyDef {
                position: Vec2::new(0.0, 3.0),
                shape: Some(Shape::circle(0.25)),
                restitution,
                ..Default::default()
            };
            let case = one_body(def, 1.5);
            let o = run(&case, &mut Passo(case.world.clone()));
            let returned = o.returned.unwrap();
            assert!((low..high).contains(&returned), "{restitution}: {o:?}");
        }
    }

    #[test]
    fn a_body_still_falling_at_the_end_has_not_rested_and_one_thrown_away_escaped() {
        let def = BodyDef {
            position: Vec2::new(0.0, 1.0),
            velocity: Vec2::new(30.0, 0.0),
            shape: Some(Shape::circle(0.25)),
            ..Default::default()
        };
        let case = one_body(def, 1.0);
        let o = run(&case, &mut Passo(case.world.clone()));
        assert_eq!((o.rest, o.escaped), (None, 1), "{o:?}");
    }

    /// Runs the case named `name` in Passo.
    fn outcome(name: &str) -> Outcome {
        let case = cases().into_iter().find(|c| c.name == name).unwrap();
        run(&case, &mut Passo(case.world.clone()))
    }

    /// A stack of boxes of `masses` (bottom first), with `settings`
    /// changed by `change`.
    fn stack_of(masses: &[f32], change: impl Fn(&mut passo_physics::ContactSettings)) -> Case {
        let mut case = stack("stack", "a stack", 1.0, masses);
        let mut settings = *case.world.settings();
        change(settings.contacts.as_mut().unwrap());
        case.world.set_settings(settings).unwrap();
        case.seconds = 3.0;
        case
    }

    #[test]
    fn stacks_rest_at_once_at_any_mass_ratio_and_in_either_order() {
        for ratio in [1.0f32, 1.5, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0, 3000.0] {
            for n in [2, 3, 5, 10] {
                let up = growing(1.0, ratio.powf(1.0 / (n - 1) as f32), n);
                let down: Vec<f32> = up.iter().rev().copied().collect();
                for masses in [up, down] {
                    let o = run(
                        &stack_of(&masses, |_| {}),
                        &mut Passo(stack_of(&masses, |_| {}).world),
                    );
                    let what = format!("{n} boxes, {masses:?}: {o:?}");
                    assert!(o.rest.is_some_and(|t| t <= 0.5), "{what}");
                    assert!(o.peak_overlap <= 0.005, "{what}");
                    assert!(o.energy_gain <= 1e-3, "{what}");
                }
            }
        }
    }

    #[test]
    fn a_heavy_box_on_a_light_one_stays_on_a_floor_two_centimetres_thin() {
        for heavy in [10.0, 100.0, 1000.0, 10_000.0] {
            let mut world = crate::with_sleeping(&World::default(), false);
            world.set_parallel(false);
            let floor = BodyDef::new_static(Vec2::new(0.0, -0.01), Shape::rect(20.0, 0.02));
            world.add_body(floor).unwrap();
            let light = body(&mut world, Vec2::new(0.0, 0.5), Shape::rect(1.0, 1.0), 1.0);
            body(
                &mut world,
                Vec2::new(0.0, 1.5),
                Shape::rect(1.0, 1.0),
                heavy,
            );
            for _ in 0..600 {
                world.step(1.0 / HZ);
            }
            let y = world.body(light).unwrap().position.y;
            assert!(
                (y - 0.5).abs() < 0.005,
                "{heavy} kg on 1 kg: the light box at {y}"
            );
        }
    }

    #[test]
    fn the_suites_stacks_rest_within_half_a_second_without_sinking() {
        for name in [
            "stack_30",
            "mass_up_1.2",
            "mass_up_1000",
            "mass_down_1000",
            "heavy_on_light",
            "small_5cm",
            "big_5m",
        ] {
            let o = outcome(name);
            assert!(o.rest.is_some_and(|t| t <= 0.5), "{name}: {o:?}");
            assert!(o.peak_overlap <= 0.005, "{name}: {o:?}");
            assert!(o.energy_gain <= 1e-3, "{name}: {o:?}");
        }
    }

    #[test]
    fn a_heavy_ball_dropped_on_a_light_pyramid_stops_without_bouncing() {
        let o = outcome("ball_on_pyramid");
        assert!(o.returned.unwrap() <= 0.01, "{o:?}");
        assert!(o.rest.is_some_and(|t| t <= 1.5), "{o:?}");
        assert!(o.rest_overlap <= 0.02 && o.escaped == 0, "{o:?}");
    }

    #[test]
    fn a_heavy_ball_landing_on_a_bed_of_circles_stops_on_it() {
        let o = outcome("heavy_on_circles");
        assert!(o.returned.unwrap() <= 0.01, "{o:?}");
        assert!(o.rest.is_some_and(|t| t <= 1.0), "{o:?}");
        assert!(o.peak_overlap <= 0.01 && o.escaped == 0, "{o:?}");
        assert!(o.energy_gain <= 1e-3, "{o:?}");
    }

    #[test]
    fn piles_heaps_and_bins_settle_within_two_and_a_half_seconds_without_sinking() {
        for name in [
            "big_among_small",
            "packed_container",
            "bouncy_pile",
            "thrown_into_heap",
            "plank_over_gap",
        ] {
            let o = outcome(name);
            assert!(o.rest.is_some_and(|t| t <= 2.5), "{name}: {o:?}");
            assert!(o.rest_overlap <= 0.01, "{name}: {o:?}");
            assert!(o.energy_gain <= 0.01 && o.escaped == 0, "{name}: {o:?}");
        }
    }

    #[test]
    fn without_warm_starting_stacks_still_stand_at_any_mass_ratio() {
        for masses in [
            vec![1.0; 30],
            vec![1.0, 1000.0],
            growing(1.0, 1000f32.powf(1.0 / 9.0), 10),
        ] {
            let case = stack_of(&masses, |c| c.warm_starting = false);
            let o = run(&case, &mut Passo(case.world.clone()));
            let what = format!("{} boxes: {o:?}", masses.len());
            assert!(o.rest.is_some_and(|t| t <= 0.5), "{what}");
            assert!(o.peak_overlap <= 0.005, "{what}");
        }
    }

    #[test]
    fn no_contact_setting_makes_a_pile_gain_energy_or_throw_a_body_out() {
        // Each setting a scene file can name, at its extremes (shock
        // propagation off is the exception its documentation states).
        type Change = fn(&mut passo_physics::ContactSettings);
        let changes: [(&str, Change); 9] = [
            ("one substep", |c| c.substeps = 1),
            ("no relax", |c| c.relax_iterations = 0),
            ("full correction", |c| c.position_correction = 1.0),
            ("fast push", |c| c.push_out_speed = 100.0),
            ("no slop", |c| c.slop = 0.0),
            ("no reuse", |c| c.reuse_distance = 0.0),
            ("no continuous", |c| c.continuous = false),
            ("many passes", |c| {
                (c.iterations, c.relax_iterations) = (8, 8)
            }),
            ("bare", |c| {
                (c.substeps, c.relax_iterations, c.warm_starting) = (1, 0, false)
            }),
        ];
        let names = [
            "stack_30",
            "heavy_on_light",
            "heavy_on_circles",
            "bouncy_pile",
            "thrown_into_heap",
        ];
        for case in cases().into_iter().filter(|c| names.contains(&c.name)) {
            for (what, change) in changes {
                let mut world = case.world.clone();
                let mut settings = *world.settings();
                change(settings.contacts.as_mut().unwrap());
                world.set_settings(settings).unwrap();
                let o = run(&case, &mut Passo(world));
                let name = case.name;
                assert!(o.energy_gain <= 0.01, "{name}, {what}: {o:?}");
                assert_eq!(o.escaped, 0, "{name}, {what}: {o:?}");
            }
        }
    }

    #[test]
    fn every_case_builds_and_starts_without_overlaps_deeper_than_the_slop() {
        for case in cases() {
            assert!(case.seconds > 0.0 && case.world.len() > 1, "{}", case.name);
            let overlap = case.world.max_penetration();
            assert!(overlap <= 0.005, "{}: {overlap}", case.name);
        }
    }
}
