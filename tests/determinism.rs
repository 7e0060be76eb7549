//! Determinism in the spirit of Box2D's `test_determinism.c`: a busy scene
//! runs a fixed number of ticks and the hash of its final state must equal
//! a constant written here. Any change to the physics that moves a single
//! bit of any body changes the hash.
//!
//! When a change is *meant* to alter the simulation (a new solver feature,
//! a different constant), run this test, check that the other tests still
//! pass, and replace `EXPECTED` with the hash the failure message prints,
//! saying in the commit why the bits moved. A change that was not meant to
//! alter the simulation must leave the constant alone.

// The busy scene: rain (2 000 circles in a box) with a pyramid of boxes
// beside it and a few fast balls thrown through, so every stage of the
// step runs (`steps rest` measures it too).
use passo_benches::busy_world as busy;
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, ChainDef, CharacterMover, Shape, World};
use passo_scene::Scene;
use passo_tests::add_ground;

/// State hash of the scene below after `TICKS` ticks.
const EXPECTED: u64 = 0x98d4_b56c_24a0_87fc;
/// The same with sleeping off: every body is solved every step.
const EXPECTED_AWAKE: u64 = 0x98d4_b56c_24a0_87fc;
/// The busy scene with moving, one-way and plain platforms above it (see
/// `with_platforms`). Added with kinematic bodies and one-way platforms;
/// the two constants above stay valid for scenes without them.
const EXPECTED_PLATFORMS: u64 = 0x69ef_0136_abd3_2d49;
const TICKS: usize = 300;

fn hash_after_ticks(mut world: World) -> u64 {
    for _ in 0..TICKS {
        world.step(1.0 / 60.0);
    }
    world.state_hash()
}

#[test]
fn a_busy_scene_reaches_the_same_bits_as_always() {
    let world = busy();
    assert!(world.settings().contacts.unwrap().sleeping);
    let hash = hash_after_ticks(world);
    assert_eq!(
        hash, EXPECTED,
        "the state after {TICKS} ticks changed: hash {hash:#018x}. If the change was intended, \
         set EXPECTED to {hash:#018x} (see the comment at the top of this file)"
    );
}

#[test]
fn with_sleeping_off_the_same_bits_as_always() {
    let mut world = busy();
    let mut settings = *world.settings();
    settings.contacts.as_mut().unwrap().sleeping = false;
    world.set_settings(settings).unwrap();
    let hash = hash_after_ticks(world);
    assert_eq!(
        hash, EXPECTED_AWAKE,
        "the state after {TICKS} ticks with sleeping off changed: hash {hash:#018x}. If the \
         change was intended, set EXPECTED_AWAKE to {hash:#018x} (see the top of this file)"
    );
}

/// The busy scene with platforms over the rain: a kinematic one moving
/// back and forth (driven through `set_kinematic_target`), a static
/// one-way one, and a kinematic one-way lift, with boxes dropped on them
/// and balls thrown up through the one-way ones.
fn with_platforms() -> World {
    let mut world = busy();
    let slab = Shape::rect(4.0, 0.3);
    world
        .add_body(BodyDef::new_kinematic(
            Vec2::new(8.0, 12.0),
            slab,
            Vec2::new(1.5, 0.0),
        ))
        .unwrap();
    world
        .add_body(BodyDef {
            one_way: Some(Vec2::Y),
            ..BodyDef::new_static(Vec2::new(14.0, 10.0), slab)
        })
        .unwrap();
    world
        .add_body(BodyDef {
            one_way: Some(Vec2::Y),
            ..BodyDef::new_kinematic(Vec2::new(20.0, 6.0), slab, Vec2::new(0.0, 1.0))
        })
        .unwrap();
    for (i, x) in [7.0f32, 8.5, 13.5, 14.5, 19.5, 20.5]
        .into_iter()
        .enumerate()
    {
        let def = BodyDef {
            position: Vec2::new(x, 14.0 + i as f32),
            shape: Some(Shape::rect(0.6, 0.6)),
            ..Default::default()
        };
        world.add_body(def).unwrap();
        let def = BodyDef {
            position: Vec2::new(x, 3.0),
            velocity: Vec2::new(0.0, 14.0),
            shape: Some(Shape::circle(0.2)),
            ..Default::default()
        };
        world.add_body(def).unwrap();
    }
    world
}

#[test]
fn with_platforms_the_same_bits_as_always() {
    let mut world = with_platforms();
    let platform = world
        .bodies()
        .find(|b| b.kind == passo_physics::BodyKind::Kinematic)
        .unwrap()
        .id;
    for tick in 0..TICKS {
        // Back and forth over 2 s, as a game drives a platform.
        let phase = (tick % 240) as f32 / 240.0;
        let x = 8.0 + 3.0 * (1.0 - (2.0 * phase - 1.0).abs());
        world.set_kinematic_target(platform, Vec2::new(x, 12.0), 1.0 / 60.0);
        world.step(1.0 / 60.0);
    }
    let hash = world.state_hash();
    assert_eq!(
        hash, EXPECTED_PLATFORMS,
        "the state after {TICKS} ticks with platforms changed: hash {hash:#018x}. If the \
         change was intended, set EXPECTED_PLATFORMS to {hash:#018x} (see the top of this file)"
    );
}

/// The state after [`TICKS`] ticks of the busy scene with sloped ground
/// and capsules: a hill chain and a plain segment ramp in the rain,
/// capsules dropped on them, and a capsule character walking over the
/// hill with the character mover. Lines, capsules and the slope-aware
/// mover came with it; the constants above stay valid for scenes without
/// them.
const EXPECTED_SLOPES: u64 = 0xfcb7_ab42_b598_8bc2;

fn with_slopes() -> World {
    let mut world = busy();
    world
        .add_chain(&ChainDef::new(vec![
            Vec2::new(2.0, 8.0),
            Vec2::new(6.0, 8.0),
            Vec2::new(9.0, 10.0),
            Vec2::new(12.0, 10.0),
            Vec2::new(15.0, 8.0),
            Vec2::new(22.0, 8.0),
        ]))
        .unwrap();
    world
        .add_body(BodyDef::new_static(
            Vec2::new(24.0, 4.0),
            Shape::segment(Vec2::new(-2.0, -1.0), Vec2::new(2.0, 1.0)),
        ))
        .unwrap();
    for i in 0..12 {
        let x = 3.0 + 1.6 * i as f32;
        let shape = if i % 2 == 0 {
            Shape::capsule(0.4, 0.9)
        } else {
            Shape::capsule(0.9, 0.4)
        };
        world
            .add_body(BodyDef::new_dynamic(
                Vec2::new(x, 13.0 + 0.3 * i as f32),
                shape,
            ))
            .unwrap();
    }
    world
}

#[test]
fn with_slopes_and_capsules_the_same_bits_as_always() {
    let mut world = with_slopes();
    let mover = CharacterMover::default();
    let player = world
        .add_body(BodyDef::new_kinematic(
            Vec2::new(3.0, 8.0 + 0.4 + mover.skin),
            Shape::capsule(0.4, 0.8),
            Vec2::ZERO,
        ))
        .unwrap();
    let dt = 1.0 / 60.0;
    let mut velocity = Vec2::ZERO;
    for tick in 0..TICKS {
        // Right for 3 s, then back.
        velocity.x = if tick < 180 { 4.0 } else { -4.0 };
        velocity.y -= 9.81 * dt;
        let out = world
            .move_character(player, velocity * dt, &mover, dt)
            .unwrap();
        if out.on_ground {
            velocity.y = 0.0;
        }
        world.step(dt);
    }
    let hash = world.state_hash();
    assert_eq!(
        hash, EXPECTED_SLOPES,
        "the state after {TICKS} ticks with slopes changed: hash {hash:#018x}. If the \
         change was intended, set EXPECTED_SLOPES to {hash:#018x} (see the top of this file)"
    );
}

/// The rain with `n` circles: large enough that the per-body stages and the
/// narrow phase go to the thread pool.
fn big_rain(n: u32) -> World {
    // The rain of 30 m walls the determinism tests were written for.
    let mut scene = Scene::parse(passo_benches::BUSY_RAIN, "busy_rain.ron").unwrap();
    for g in &mut scene.file.generators {
        if let passo_scene::Generator::Rain { count, columns, .. } = g {
            *count = n;
            *columns = 60;
        }
    }
    scene.build().unwrap().world
}

/// The rain of 5 000 with a kinematic body sweeping through it, and (with
/// `point_mass`) a body without a shape. Its circles are added row by row,
/// so its steps split in storage order.
fn large_world_with_a_sweeper(point_mass: bool) -> World {
    let mut world = big_rain(5000);
    if point_mass {
        world
            .add_body(BodyDef::point_mass(Vec2::new(0.3, 40.0)))
            .unwrap();
    }
    let sweeper = BodyDef::new_kinematic(
        Vec2::new(-12.0, 1.0),
        Shape::rect(0.5, 2.0),
        Vec2::new(3.0, 0.0),
    );
    world.add_body(sweeper).unwrap();
    world
}

/// The state hash of each of `ticks` steps of `world`.
/// Runs `run` on a pool of `threads` workers, or on this thread with
/// `None`.
fn on_threads<T: Send>(threads: Option<usize>, run: impl FnOnce() -> T + Send) -> T {
    match threads {
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap()
            .install(run),
        None => run(),
    }
}

fn hashes_of_steps(world: &mut World, ticks: usize) -> Vec<u64> {
    (0..ticks)
        .map(|_| {
            world.step(1.0 / 60.0);
            world.state_hash()
        })
        .collect()
}

#[test]
fn a_large_world_with_a_point_mass_and_a_kinematic_body_the_same_bits_on_the_pool() {
    // A body without a shape gets no proxy, so the step cannot give every
    // body a proxy of the same index on the pool and takes the one-by-one
    // path; a kinematic body's proxy covers its whole travel. Without the
    // point mass, every body gets a proxy of its own index.
    let run = |parallel: bool, point_mass: bool| {
        let mut world = large_world_with_a_sweeper(point_mass);
        world.set_parallel(parallel);
        // 100 ticks: the rain lands, and its contacts (over 4 096) take
        // the pool's paths too.
        let hashes = hashes_of_steps(&mut world, 100);
        assert!(world.contacts().count() >= 4096);
        hashes
    };
    for point_mass in [false, true] {
        assert_eq!(
            run(true, point_mass),
            run(false, point_mass),
            "point mass: {point_mass}"
        );
    }
}

/// The state hashes after 100 ticks of two worlds whose steps split their
/// contacts in two regions (see `the_same_bits_whatever_the_number_of_threads`):
/// the large world with a sweeper, and the wide pile with platforms.
const EXPECTED_SPLIT: [u64; 2] = [0x76d6_6d1e_2286_ff17, 0x0d06_876e_6c62_e921];

/// A pile of 4 500 circles 45 m wide and 9 m high on the ground, added in
/// a scrambled order (so its steps split it by place, at the middle of its
/// width, not in storage order), with a kinematic platform
/// pushing through each half: each region's contacts read a body they do
/// not move. The world's speed limit (2 m/s) acts on the circles the
/// platforms push.
fn wide_pile_with_platforms() -> World {
    let settings = passo_physics::WorldSettings {
        max_speed: 2.0,
        ..Default::default()
    };
    let mut world = World::new(settings).unwrap();
    add_ground(&mut world, 60.0);
    // Place k of 4 500 = 2^2 3^2 5^3 for the k-th body: 7 919, a prime,
    // divides none of them, so each place comes once.
    for k in 0..4500 {
        let place = k * 7919 % 4500;
        let (row, col) = (place / 150, place % 150);
        let p = Vec2::new(-22.35 + col as f32 * 0.3, 0.15 + row as f32 * 0.3);
        let def = BodyDef::new_dynamic(p, Shape::circle(0.14));
        world.add_body(def).unwrap();
    }
    for x in [-11.0, 11.0] {
        let platform = BodyDef::new_kinematic(
            Vec2::new(x, 1.2),
            Shape::rect(3.0, 0.3),
            Vec2::new(1.5, 0.0),
        );
        world.add_body(platform).unwrap();
    }
    world
}

#[test]
fn worlds_split_in_regions_reach_the_same_bits_as_always() {
    let worlds = [
        large_world_with_a_sweeper(false),
        wide_pile_with_platforms(),
    ];
    for (k, mut world) in worlds.into_iter().enumerate() {
        assert!(world.dynamic_len() >= passo_physics::constants::PARALLEL_MIN_ITEMS);
        let hash = *hashes_of_steps(&mut world, 100).last().unwrap();
        assert_eq!(
            hash, EXPECTED_SPLIT[k],
            "world {k}'s bits changed: if the change was intended, set \
             EXPECTED_SPLIT[{k}] to {hash:#018x} (see the top of this file)"
        );
    }
}

#[test]
fn the_same_bits_whatever_the_number_of_threads() {
    // `threads`: step on a pool of that many workers; `None`: step from
    // this thread (with `parallel`, the step enters the global pool itself).
    let hashes = |parallel: bool, threads: Option<usize>| {
        let mut world = big_rain(6000);
        assert!(world.dynamic_len() >= passo_physics::constants::PARALLEL_MIN_ITEMS);
        world.set_parallel(parallel);
        let hashes = on_threads(threads, || hashes_of_steps(&mut world, 90));
        // From 4 096 bodies the solver splits the pile in two regions and
        // solves them side by side; here with thousands of contacts each.
        let contacts = world.contacts().count();
        assert!(contacts >= 4096, "{contacts} contacts");
        hashes
    };
    let single = hashes(false, None);
    assert_eq!(
        hashes(true, None),
        single,
        "the global pool, entered by the step"
    );
    assert_eq!(hashes(true, Some(1)), single, "one worker thread");
    assert_eq!(hashes(true, Some(2)), single, "two worker threads");
    assert_eq!(
        hashes(true, Some(4)),
        single,
        "four worker threads on two cores"
    );
}

/// State hash of `every_force_model` after `TICKS` ticks, per integrator
/// (`Integrator::ALL` order). Added with the portable-maths work; the
/// constants above are unchanged by it. Verlet's and RK4's moved when they
/// began to split dry friction off their stages (the Euler methods'
/// stayed), and again when friction began to hold a body at rest still.
/// Explicit Euler's, Verlet's and RK4's moved when a speed limit that acts
/// began to leave out their position correction (semi-implicit Euler has
/// none). All four moved, with every constant here, when each contact
/// pass began to solve the normal row before friction, and again when
/// shock propagation came in and the iterations went from two to one.
const EXPECTED_FORCES: [u64; 4] = [
    0xa935_a6be_340b_4a37,
    0x8eb7_1013_2f99_38e2,
    0x48c1_19a2_25c5_d7df,
    0xe582_bdad_8518_e1df,
];

/// A world with every force model on (gravity, a force field, a spring,
/// central gravity, quadratic and linear drag with wind, surface friction,
/// a custom model and friction applied by game code), bodies of both
/// shapes on a ground, under `integrator`.
fn every_force_model(integrator: passo_physics::Integrator) -> World {
    use passo_physics::{
        CentralGravity, ForceModel, ForceModels, LinearDrag, QuadraticDrag, Spring,
        SurfaceFriction, WorldSettings,
    };
    struct Swirl;
    impl ForceModel for Swirl {
        fn force(&self, p: Vec2, v: Vec2, mass: f32) -> Vec2 {
            Vec2::new(-p.y, p.x) * 0.3 * mass - v * 0.05
        }
    }
    let forces = ForceModels {
        gravity: Some(Vec2::new(0.0, -9.81)),
        force_field: Some(Vec2::new(0.7, 0.0)),
        spring: Some(Spring {
            anchor: Vec2::new(2.0, 6.0),
            stiffness: 3.0,
        }),
        central_gravity: Some(CentralGravity {
            centre: Vec2::new(-4.0, 8.0),
            gm: 20.0,
        }),
        quadratic_drag: Some(QuadraticDrag::default()),
        linear_drag: Some(LinearDrag { coefficient: 0.2 }),
        air_velocity: Vec2::new(1.5, 0.0),
        surface_friction: Some(SurfaceFriction::default()),
    };
    let mut world = World::new(WorldSettings {
        forces,
        integrator,
        ..Default::default()
    })
    .unwrap();
    world.add_force_model(std::sync::Arc::new(Swirl));
    add_ground(&mut world, 30.0);
    for i in 0..24 {
        let p = Vec2::new((i % 6) as f32 * 1.1 - 3.0, 1.0 + (i / 6) as f32 * 1.2);
        let shape = if i % 2 == 0 {
            Shape::circle(0.3)
        } else {
            Shape::rect(0.6, 0.5)
        };
        world
            .add_body(BodyDef::new_dynamic(p, shape).with_velocity(Vec2::new(0.5, 2.0)))
            .unwrap();
    }
    world
}

#[test]
fn every_force_model_under_every_integrator_the_same_bits_as_always() {
    for (k, integrator) in passo_physics::Integrator::ALL.into_iter().enumerate() {
        let mut world = every_force_model(integrator);
        let ids: Vec<_> = world.bodies().map(|b| b.id).collect();
        for tick in 0..TICKS {
            world.apply_friction(ids[1 + tick % 24], 0.3, 5.0);
            world.step(1.0 / 60.0);
        }
        let hash = world.state_hash();
        assert_eq!(
            hash, EXPECTED_FORCES[k],
            "{integrator:?}: the state after {TICKS} ticks changed: hash {hash:#018x}. If the \
             change was intended, set EXPECTED_FORCES[{k}] to {hash:#018x}"
        );
    }
}

/// A net of rods large enough that the per-body stages go to the thread
/// pool (Box2D's joint grid without rotation, 70 × 70): the joints are
/// solved on one thread, the rest in chunks, and the bits are the same
/// with the pool or without, on one worker or two.
#[test]
fn joints_give_the_same_bits_whatever_the_number_of_threads() {
    let hashes = |parallel: bool, threads: Option<usize>| {
        let mut world = passo_benches::joint_grid(70);
        assert!(world.dynamic_len() >= passo_physics::constants::PARALLEL_MIN_ITEMS);
        world.set_parallel(parallel);
        on_threads(threads, || hashes_of_steps(&mut world, 60))
    };
    let single = hashes(false, None);
    assert_eq!(hashes(true, None), single, "the global pool");
    assert_eq!(hashes(true, Some(1)), single, "one worker thread");
    assert_eq!(hashes(true, Some(2)), single, "two worker threads");
}
