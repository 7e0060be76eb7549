//! Helpers shared by the behaviour tests, and by the cross-crate tests in
//! the workspace's `tests/` (which include this file).

use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyId, BodyKind, Shape, World, collide};

/// The deepest overlap between any two shaped bodies (dynamic-dynamic or
/// dynamic-static, sensors excluded), from exact geometry at the current
/// positions: not from the solver's cached contact data. Brute force over
/// all pairs, so it is independent of the broad phase it checks.
pub fn max_penetration(world: &World) -> f32 {
    let bodies: Vec<_> = world
        .bodies()
        .filter(|b| b.shape.is_some() && !b.sensor)
        .collect();
    let mut deepest = 0.0f32;
    for (i, a) in bodies.iter().enumerate() {
        for b in &bodies[i + 1..] {
            if a.kind == BodyKind::Static && b.kind == BodyKind::Static {
                continue;
            }
            if !a.filter.allows(&b.filter) {
                continue;
            }
            let (sa, sb) = (a.shape.unwrap(), b.shape.unwrap());
            if let Some(m) = collide(&sa, a.position, &sb, b.position, 0.0) {
                deepest = deepest.max(-m.separation);
            }
        }
    }
    deepest
}

/// Panics if any body's position or velocity is not finite.
pub fn assert_finite(world: &World) {
    for b in world.bodies() {
        assert!(
            b.position.is_finite() && b.velocity.is_finite(),
            "{:?} became non-finite: {b:?}",
            b.id
        );
    }
}

/// Flat static ground `width` metres wide, centred on x = 0, its top at
/// y = 0 (1 m thick).
pub fn add_ground(world: &mut World, width: f32) -> BodyId {
    let def = BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(width, 1.0));
    world.add_body(def).expect("valid ground")
}

/// A world with no force model at all (no gravity), contacts as by
/// default.
pub fn weightless_world() -> World {
    World::new(passo_physics::WorldSettings {
        forces: passo_physics::ForceModels::none(),
        ..Default::default()
    })
    .expect("valid settings")
}

/// A static box from `min` to `max`.
pub fn add_static_box(world: &mut World, min: Vec2, max: Vec2) -> BodyId {
    let def = BodyDef::new_static((min + max) * 0.5, Shape::rect(max.x - min.x, max.y - min.y));
    world.add_body(def).expect("valid static box")
}

/// A dynamic box of the given size and mass at `centre`.
pub fn add_box(world: &mut World, centre: Vec2, size: Vec2, mass: f32) -> BodyId {
    let def = BodyDef {
        position: centre,
        mass,
        shape: Some(Shape::rect(size.x, size.y)),
        ..Default::default()
    };
    world.add_body(def).expect("valid box")
}

/// A dynamic circle.
pub fn add_circle(world: &mut World, centre: Vec2, radius: f32, mass: f32) -> BodyId {
    let def = BodyDef {
        position: centre,
        mass,
        shape: Some(Shape::circle(radius)),
        ..Default::default()
    };
    world.add_body(def).expect("valid circle")
}

/// The contacts naming `id`, each seen from it, found by scanning every
/// contact of the world: the reference `World::contacts_of` must match.
pub fn contacts_seen_from(world: &World, id: BodyId) -> Vec<passo_physics::Contact> {
    world
        .contacts()
        .filter_map(|c| {
            if c.a == id {
                Some(c)
            } else if c.b == id {
                Some(c.flipped())
            } else {
                None
            }
        })
        .collect()
}

/// Pushes `body` along +x at `speed` every tick (the game sets its
/// horizontal velocity) for `ticks` ticks of `dt`; returns the velocity
/// after each step.
pub fn push_along_x(
    world: &mut World,
    body: BodyId,
    speed: f32,
    ticks: usize,
    dt: f32,
) -> Vec<Vec2> {
    (0..ticks)
        .map(|_| {
            let v = world.body(body).unwrap().velocity;
            world.set_velocity(body, Vec2::new(speed, v.y));
            world.step(dt);
            world.body(body).unwrap().velocity
        })
        .collect()
}

/// Asserts that velocities over joints (`seamed`) keep |v_y| < 1e-4 m/s and
/// match those over one long box (`reference`) to 1e-5 m/s, tick by tick.
pub fn assert_slides_as_on_one_box(seamed: &[Vec2], reference: &[Vec2], what: &str) {
    for (tick, (t, r)) in seamed.iter().zip(reference).enumerate() {
        assert!(
            t.y.abs() < 1e-4,
            "{what}, tick {tick}: vertical speed {}",
            t.y
        );
        assert!(
            (t.x - r.x).abs() < 1e-5,
            "{what}, tick {tick}: {} m/s over the joints, {} on one box",
            t.x,
            r.x
        );
    }
}

/// Presses `body` against a wall on its left with 5 N for two seconds of
/// `dt` steps, asserting each step that it falls freely (to 0.02 m/s: no
/// joint of the wall holds it up) and calling `check` with it.
pub fn assert_falls_freely_along_a_wall(
    world: &mut World,
    body: BodyId,
    dt: f32,
    mut check: impl FnMut(&passo_physics::Body),
) {
    let mut t = 0.0f32;
    for _ in 0..120 {
        world.apply_force(body, Vec2::new(-5.0, 0.0));
        world.step(dt);
        t += dt;
        let b = world.body(body).unwrap();
        let free = -9.81 * t;
        assert!(
            (b.velocity.y - free).abs() < 0.02,
            "at {t:.3} s: {} m/s, free fall {free}",
            b.velocity.y
        );
        check(&b);
    }
}

/// A small deterministic generator (xorshift64*) for jittered schedules and
/// random scenes, so tests need no extra dependency and replay exactly.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed (0 is replaced by a fixed odd constant).
    pub fn new(seed: u64) -> Self {
        Self(if seed == 0 {
            0x9E37_79B9_7F4A_7C15
        } else {
            seed
        })
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// A uniform float in `[lo, hi)`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        let unit = (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32;
        lo + (hi - lo) * unit
    }
}
