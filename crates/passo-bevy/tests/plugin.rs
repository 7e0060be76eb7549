//! The plugin as a Bevy game uses it: bodies spawned as entities, stepped
//! in FixedUpdate, read back through components and messages.

mod common;

use bevy::prelude::*;
use common::{app, record_hashes, run_until, ticks};
use passo_bevy::passo_physics::{self as passo, glam};
use passo_bevy::prelude::*;

/// A body dropped from rest follows semi-implicit Euler exactly:
/// after n ticks y = y0 - g dt² n (n + 1) / 2, and the same bits as a
/// Passo world stepped by hand, at every tick rate and frame rate.
#[test]
fn a_dropped_body_falls_as_semi_implicit_euler_at_every_rate() {
    for (rate, frame) in [
        (60.0, 1.0 / 60.0),
        (60.0, 1.0 / 144.0),
        (30.0, 1.0 / 75.0),
        (120.0, 1.0 / 50.0),
    ] {
        for y0 in [0.0f32, 3.5, 100.0] {
            let mut app = app(rate, frame);
            let ball = app
                .world_mut()
                .spawn((RigidBody::Dynamic, Transform::from_xyz(1.0, y0, 0.0)))
                .id();
            let n = 90;
            run_until(&mut app, n);
            let ticked = ticks(&app);
            let at = app.world().get::<Position>(ball).unwrap().0;
            let velocity = app.world().get::<LinearVelocity>(ball).unwrap().0;

            let dt = (1.0 / rate) as f32;
            let mut world = passo::World::default();
            let id = world
                .add_body(passo::BodyDef::point_mass(glam::Vec2::new(1.0, y0)))
                .unwrap();
            for _ in 0..ticked {
                world.step(dt);
            }
            let body = world.body(id).unwrap();
            assert_eq!(
                at.y.to_bits(),
                body.position.y.to_bits(),
                "rate {rate}, frame {frame}"
            );
            assert_eq!(velocity.y.to_bits(), body.velocity.y.to_bits());
            assert_eq!(at.x, 1.0);

            let k = ticked as f64;
            let closed = f64::from(y0) - 9.81 * f64::from(dt).powi(2) * k * (k + 1.0) / 2.0;
            assert!(
                (f64::from(at.y) - closed).abs() < 1e-3 * closed.abs().max(1.0),
                "{at} vs {closed}"
            );
            // The Transform follows the body (no interpolation asked).
            let transform = app.world().get::<Transform>(ball).unwrap();
            assert_eq!(transform.translation.truncate(), at);
        }
    }
}

/// Every component given at spawn is in the body the plugin makes.
#[test]
fn every_part_given_at_spawn_is_in_the_body() {
    let mut app = app(60.0, 1.0 / 60.0);
    let filter = CollisionFilter { layers: 4, mask: 6 };
    let material = PhysicsMaterial {
        friction: 0.7,
        restitution: 0.4,
        friction_mix: FrictionMix::Min,
    };
    let ball = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::circle(0.3),
            Mass(2.5),
            material,
            Filter(filter),
            Sensor,
            GravityScale(0.5),
            Bullet,
            LinearVelocity(Vec2::new(1.0, 2.0)),
            Transform::from_xyz(1.0, 2.0, 0.0),
        ))
        .id();
    let ledge = app
        .world_mut()
        .spawn((
            RigidBody::Kinematic,
            Collider::rectangle(2.0, 0.2),
            OneWay(Vec2::Y),
            Transform::from_xyz(0.0, -3.0, 0.0),
        ))
        .id();
    app.update();
    let world = app.world().resource::<PassoWorld>();
    let b = world
        .body(app.world().get::<PassoBody>(ball).unwrap().id())
        .unwrap();
    assert_eq!(b.kind, passo::BodyKind::Dynamic);
    assert_eq!(b.shape, Some(passo::Shape::circle(0.3)));
    assert_eq!(b.mass, 2.5);
    assert_eq!(
        (b.friction, b.restitution, b.friction_mix),
        (0.7, 0.4, FrictionMix::Min)
    );
    assert_eq!(b.filter, filter);
    assert!(b.sensor && b.bullet);
    assert_eq!(b.gravity_scale, 0.5);
    assert_eq!(b.velocity, glam::Vec2::new(1.0, 2.0));
    assert_eq!(b.position, glam::Vec2::new(1.0, 2.0));
    let l = world
        .body(app.world().get::<PassoBody>(ledge).unwrap().id())
        .unwrap();
    assert_eq!(l.kind, passo::BodyKind::Kinematic);
    assert_eq!(l.one_way, Some(glam::Vec2::Y));
}

/// The plugin's settings reach the world: a body falls under the Moon's
/// gravity, exactly as semi-implicit Euler says; invalid settings fall
/// back to the defaults.
#[test]
fn the_plugins_settings_reach_the_world() {
    use bevy::time::TimeUpdateStrategy;
    let moon = passo::WorldSettings {
        forces: passo::ForceModels {
            gravity: Some(glam::Vec2::new(0.0, -1.62)),
            ..Default::default()
        },
        ..Default::default()
    };
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        PassoPlugin::default().with_rate(60.0).with_settings(moon),
    ))
    .insert_resource(TimeUpdateStrategy::ManualDuration(
        std::time::Duration::from_secs_f64(1.0 / 60.0),
    ));
    let ball = app
        .world_mut()
        .spawn((RigidBody::Dynamic, Transform::from_xyz(0.0, 10.0, 0.0)))
        .id();
    run_until(&mut app, 60);
    let n = ticks(&app) as f64;
    let dt = 1.0 / 60.0f64;
    let y = f64::from(app.world().get::<Position>(ball).unwrap().0.y);
    let closed = 10.0 - 1.62 * dt * dt * n * (n + 1.0) / 2.0;
    assert!((y - closed).abs() < 1e-4, "{y} vs {closed}");

    let broken = passo::WorldSettings {
        max_speed: -1.0,
        ..Default::default()
    };
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, PassoPlugin::default().with_settings(broken)));
    let max_speed = app.world().resource::<PassoWorld>().settings().max_speed;
    assert_eq!(max_speed, passo::WorldSettings::default().max_speed);
}

/// Spawning makes a body, despawning removes it, removing the
/// RigidBody removes it too, and ids map both ways.
#[test]
fn bodies_come_and_go_with_their_entities() {
    let mut app = app(60.0, 1.0 / 60.0);
    let a = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::circle(0.5),
            Transform::from_xyz(0.0, 5.0, 0.0),
        ))
        .id();
    let b = app
        .world_mut()
        .spawn((
            RigidBody::Static,
            Collider::rectangle(10.0, 1.0),
            Position(Vec2::new(0.0, -0.5)),
        ))
        .id();
    app.update();
    let world = app.world().resource::<PassoWorld>();
    assert_eq!(world.len(), 2);
    let id_a = app.world().get::<PassoBody>(a).unwrap().id();
    let id_b = app.world().get::<PassoBody>(b).unwrap().id();
    assert_ne!(id_a, id_b);
    let entities = app.world().resource::<passo_bevy::BodyEntities>();
    assert_eq!(entities.entity(id_a), Some(a));
    assert_eq!(entities.body(b), Some(id_b));
    // A Position given at spawn wins over the Transform.
    assert_eq!(
        app.world()
            .resource::<PassoWorld>()
            .body(id_b)
            .unwrap()
            .position
            .y,
        -0.5
    );
    assert_eq!(app.world().get::<Transform>(b).unwrap().translation.y, -0.5);

    app.world_mut().despawn(a);
    app.update();
    let world = app.world().resource::<PassoWorld>();
    assert_eq!(world.len(), 1);
    assert!(!world.contains(id_a));
    assert!(
        app.world()
            .resource::<passo_bevy::BodyEntities>()
            .entity(id_a)
            .is_none()
    );

    app.world_mut().entity_mut(b).remove::<RigidBody>();
    app.update();
    assert!(app.world().resource::<PassoWorld>().is_empty());
    assert!(app.world().get::<PassoBody>(b).is_none());

    // Back again: a new body.
    app.world_mut().entity_mut(b).insert(RigidBody::Static);
    app.update();
    assert_eq!(app.world().resource::<PassoWorld>().len(), 1);
    assert!(app.world().get::<PassoBody>(b).is_some());
}

#[derive(Resource, Default)]
struct Seen {
    entered: Vec<(Option<Entity>, Option<Entity>, u64)>,
    exited: Vec<(Option<Entity>, Option<Entity>, u64)>,
    began: usize,
}

fn watch(
    mut entered: MessageReader<SensorEntered>,
    mut exited: MessageReader<SensorExited>,
    mut began: MessageReader<ContactBegan>,
    world: Res<PassoWorld>,
    mut seen: ResMut<Seen>,
) {
    let tick = world.stats().steps;
    for m in entered.read() {
        seen.entered.push((m.sensor_entity, m.visitor_entity, tick));
    }
    for m in exited.read() {
        seen.exited.push((m.sensor_entity, m.visitor_entity, tick));
    }
    seen.began += began.read().count();
}

/// A ball falling through a sensor is reported entering once and leaving
/// once, read in Update, whatever the frame rate (0, 1 or several ticks
/// a frame), and in the ticks where it crosses the sensor's edges.
#[test]
fn sensor_messages_arrive_exactly_once_at_any_frame_rate() {
    let mut crossings = Vec::new();
    for frame in [1.0 / 60.0, 1.0 / 25.0, 1.0 / 144.0, 1.0 / 47.0] {
        let mut app = app(60.0, frame);
        record_hashes(&mut app);
        app.init_resource::<Seen>().add_systems(Update, watch);
        let sensor = app
            .world_mut()
            .spawn((
                RigidBody::Static,
                Collider::rectangle(4.0, 1.0),
                Sensor,
                Transform::from_xyz(0.0, 2.0, 0.0),
            ))
            .id();
        let ball = app
            .world_mut()
            .spawn((
                RigidBody::Dynamic,
                Collider::circle(0.25),
                Transform::from_xyz(0.0, 4.0, 0.0),
            ))
            .id();
        run_until(&mut app, 150);
        for _ in 0..5 {
            app.update();
        }
        let seen = app.world().resource::<Seen>();
        assert_eq!(seen.entered.len(), 1, "frame {frame}: {:?}", seen.entered);
        assert_eq!(seen.exited.len(), 1, "frame {frame}: {:?}", seen.exited);
        assert_eq!(
            (seen.entered[0].0, seen.entered[0].1),
            (Some(sensor), Some(ball))
        );
        assert_eq!(
            (seen.exited[0].0, seen.exited[0].1),
            (Some(sensor), Some(ball))
        );
        // A sensor pushes nothing: no contact began.
        assert_eq!(seen.began, 0);
        crossings.push(app.world().resource::<common::Hashes>().0[149]);
    }
    // The same fall at every frame rate.
    assert!(crossings.windows(2).all(|w| w[0] == w[1]), "{crossings:?}");
}

/// The ball lands once: one ContactBegan, with both entities.
#[test]
fn a_landing_is_one_contact_message() {
    let mut app = app(60.0, 1.0 / 60.0);
    app.init_resource::<Seen>().add_systems(Update, watch);
    app.world_mut().spawn((
        RigidBody::Static,
        Collider::rectangle(10.0, 1.0),
        Transform::from_xyz(0.0, -0.5, 0.0),
    ));
    app.world_mut().spawn((
        RigidBody::Dynamic,
        Collider::circle(0.25),
        Transform::from_xyz(0.0, 1.0, 0.0),
    ));
    run_until(&mut app, 120);
    app.update();
    assert_eq!(app.world().resource::<Seen>().began, 1);
}

/// Steers a kinematic platform at 1 m/s to the right, from 0 at tick 0.
fn steer_platform(world: Res<PassoWorld>, mut platforms: Query<&mut KinematicTarget>) {
    let t_end = (world.stats().steps + 1) as f32 / 60.0;
    for mut target in &mut platforms {
        target.0 = Vec2::new(t_end, 0.0);
    }
}

/// A crate resting on a kinematic platform is carried at the platform's
/// speed, and a Mover character standing on it rides it exactly.
#[test]
fn a_kinematic_platform_carries_its_riders() {
    let mut app = app(60.0, 1.0 / 60.0);
    app.add_systems(FixedUpdate, steer_platform.before(PassoSystems::Prepare));
    let platform = app
        .world_mut()
        .spawn((
            RigidBody::Kinematic,
            Collider::rectangle(8.0, 0.5),
            KinematicTarget(Vec2::ZERO),
            Transform::default(),
        ))
        .id();
    let crate_ = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::rectangle(0.5, 0.5),
            Transform::from_xyz(-2.0, 0.5 + 0.001, 0.0),
        ))
        .id();
    let mover = CharacterMover::default();
    let rider = app
        .world_mut()
        .spawn((
            RigidBody::Kinematic,
            Collider::rectangle(0.4, 0.8),
            Mover {
                settings: mover,
                velocity: Vec2::new(0.0, -2.0),
            },
            Transform::from_xyz(2.0, 0.25 + 0.4 + mover.skin, 0.0),
        ))
        .id();
    run_until(&mut app, 120);
    let speed = app.world().get::<LinearVelocity>(crate_).unwrap().0;
    assert!(
        (speed.x - 1.0).abs() < 1e-3 && speed.y.abs() < 1e-3,
        "{speed}"
    );
    let crate_at = app.world().get::<Position>(crate_).unwrap().0;
    assert!((crate_at.y - 0.5).abs() < 0.01, "{crate_at}");
    let platform_at = app.world().get::<Position>(platform).unwrap().0;
    assert!((platform_at.x - 2.0).abs() < 1e-4, "{platform_at}");

    let outcome = app.world().get::<MoverOutcome>(rider).unwrap();
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert!(outcome.outcome.on_ground);
    let platform_id = app.world().get::<PassoBody>(platform).unwrap().id();
    assert_eq!(outcome.outcome.ground, Some(platform_id));
    let rider_at = app.world().get::<Position>(rider).unwrap().0;
    assert!((rider_at.x - 4.0).abs() < 1e-3, "{rider_at}");

    // Without its Mover the rider stops where it is (it was riding at
    // the platform's speed).
    let riding = app.world().get::<LinearVelocity>(rider).unwrap().0;
    assert!((riding.x - 1.0).abs() < 1e-3, "{riding}");
    app.world_mut().entity_mut(rider).remove::<Mover>();
    run_until(&mut app, 122);
    assert_eq!(
        app.world().get::<LinearVelocity>(rider).unwrap().0,
        Vec2::ZERO
    );

    // Without its target the platform stops where it is.
    app.world_mut()
        .entity_mut(platform)
        .remove::<KinematicTarget>();
    run_until(&mut app, 130);
    let stopped = app.world().get::<Position>(platform).unwrap().0;
    assert_eq!(
        app.world().get::<LinearVelocity>(platform).unwrap().0,
        Vec2::ZERO
    );
    run_until(&mut app, 140);
    assert_eq!(app.world().get::<Position>(platform).unwrap().0, stopped);
}

/// The mover walks along tiles and climbs a step as Passo's own mover
/// does, to the bit.
#[test]
fn the_mover_walks_and_climbs_on_tiles() {
    let art = "
        ..........
        .......###
        ##########";
    let map = passo::TileMap::from_ascii(art, glam::Vec2::splat(0.25), glam::Vec2::ZERO).unwrap();
    let settings = CharacterMover::default();
    let start = Vec2::new(0.5, 0.5 + 0.01);
    let walk = Vec2::new(3.0, -5.0);

    let mut app = app(60.0, 1.0 / 60.0);
    app.world_mut()
        .resource_mut::<PassoWorld>()
        .add_tile_map(&map, passo::BodyKind::Static)
        .unwrap();
    let player = app
        .world_mut()
        .spawn((
            RigidBody::Kinematic,
            Collider::rectangle(0.3, 0.5),
            Mover {
                settings,
                velocity: walk,
            },
            Transform::from_xyz(start.x, start.y, 0.0),
        ))
        .id();
    run_until(&mut app, 30);
    let at = app.world().get::<Position>(player).unwrap().0;
    assert!(
        (at.x - 2.0).abs() < 0.05 && (at.y - 0.76).abs() < 0.02,
        "{at}"
    );
    assert!(
        app.world()
            .get::<MoverOutcome>(player)
            .unwrap()
            .outcome
            .on_ground
    );

    let mut world = passo::World::default();
    world.add_tile_map(&map, passo::BodyKind::Static).unwrap();
    let id = world
        .add_body(passo::BodyDef::new_kinematic(
            glam::Vec2::new(start.x, start.y),
            passo::Shape::rect(0.3, 0.5),
            glam::Vec2::ZERO,
        ))
        .unwrap();
    let dt = 1.0f32 / 60.0;
    for _ in 0..ticks(&app) {
        world
            .move_character(id, glam::Vec2::new(walk.x, walk.y) * dt, &settings, dt)
            .unwrap();
        world.step(dt);
    }
    let expected = world.body(id).unwrap().position;
    assert_eq!(
        (at.x.to_bits(), at.y.to_bits()),
        (expected.x.to_bits(), expected.y.to_bits())
    );
}

/// With TransformInterpolation the Transform is drawn between the last
/// two ticks at the fixed clock's overstep; without it, at the last tick.
#[test]
fn transforms_are_interpolated_between_ticks() {
    // Frames of 1/150 s against ticks of 1/60 s: the overstep walks
    // through many fractions.
    let mut app = app(60.0, 1.0 / 150.0);
    let smooth = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            TransformInterpolation,
            Transform::from_xyz(0.0, 10.0, 0.0),
            LinearVelocity(Vec2::new(3.0, 0.0)),
        ))
        .id();
    let plain = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Transform::from_xyz(0.0, 10.0, 0.0),
            LinearVelocity(Vec2::new(3.0, 0.0)),
        ))
        .id();
    let mut fractions = Vec::new();
    for _ in 0..60 {
        app.update();
        let alpha = app.world().resource::<Time<Fixed>>().overstep_fraction();
        let now = app.world().get::<Position>(smooth).unwrap().0;
        let before = app.world().get::<PreviousPosition>(smooth).unwrap().0;
        let drawn = app
            .world()
            .get::<Transform>(smooth)
            .unwrap()
            .translation
            .truncate();
        let expected = before.lerp(now, alpha);
        assert!(
            (drawn - expected).length() < 1e-5,
            "{drawn} vs {expected} at {alpha}"
        );
        if ticks(&app) > 1 {
            // 3 m/s over a tick of 1/60 s: the two positions are 5 cm apart.
            assert!((now.x - before.x - 0.05).abs() < 1e-5, "{before} {now}");
        }
        let plain_drawn = app
            .world()
            .get::<Transform>(plain)
            .unwrap()
            .translation
            .truncate();
        assert_eq!(plain_drawn, app.world().get::<Position>(plain).unwrap().0);
        fractions.push(alpha);
    }
    // It really was between ticks, not only on them.
    assert!(
        fractions.iter().any(|&a| a > 0.3 && a < 0.7),
        "{fractions:?}"
    );

    // A teleport is drawn where it lands.
    app.world_mut().get_mut::<Position>(smooth).unwrap().0 = Vec2::new(-5.0, 1.0);
    let next = ticks(&app) + 1;
    run_until(&mut app, next);
    let before = app.world().get::<PreviousPosition>(smooth).unwrap().0;
    assert!((before - Vec2::new(-5.0, 1.0)).length() < 1e-6, "{before}");
    let landed = app.world().get::<Position>(smooth).unwrap().0;
    assert!((landed - Vec2::new(-5.0, 1.0)).length() < 0.1, "{landed}");
}

/// Two apps fed the same inputs at different frame rates step the same
/// bits, tick by tick, and the same as the scene stepped by Passo alone.
#[test]
fn the_same_inputs_give_the_same_bits_at_any_frame_rate() {
    let ticks_wanted = 240;
    // Joints and ropes; path platforms and a Tiled level; floating crates.
    for name in ["joints", "platformer", "water"] {
        let mut runs = Vec::new();
        for frame in [1.0 / 60.0, 1.0 / 23.0, 1.0 / 144.0] {
            let mut app = app(60.0, frame);
            record_hashes(&mut app);
            app.world_mut()
                .commands()
                .queue(LoadScene::file(common::scene_path(name)));
            app.world_mut().flush();
            run_until(&mut app, ticks_wanted);
            let hashes = app.world().resource::<common::Hashes>().0.clone();
            runs.push(hashes[..ticks_wanted as usize].to_vec());
        }
        assert_eq!(runs[0], runs[1], "{name}");
        assert_eq!(runs[0], runs[2], "{name}");

        let path = common::scene_path(name);
        let scene = passo_scene::Scene::load(std::path::Path::new(&path)).unwrap();
        let mut built = scene.build().unwrap();
        let dt = (1.0 / scene.file.rate_hz) as f32;
        let native: Vec<u64> = (0..ticks_wanted)
            .map(|_| {
                built.step(dt);
                built.world.state_hash()
            })
            .collect();
        assert_eq!(runs[0], native, "{name}");
        // And it moved: a still world would prove nothing.
        assert!(native.windows(2).all(|w| w[0] != w[1]), "{name}");
    }
}

/// A bad body is refused with a BodyError, not a panic, and made once
/// the game fixes it.
#[test]
fn a_bad_body_gets_an_error_and_is_made_once_fixed() {
    let mut app = app(60.0, 1.0 / 60.0);
    let e = app
        .world_mut()
        .spawn((RigidBody::Dynamic, Mass(0.0), Transform::default()))
        .id();
    let nan = app
        .world_mut()
        .spawn((RigidBody::Dynamic, Transform::from_xyz(f32::NAN, 0.0, 0.0)))
        .id();
    app.update();
    assert!(app.world().get::<BodyError>(e).is_some());
    assert!(app.world().get::<PassoBody>(e).is_none());
    assert!(app.world().get::<BodyError>(nan).is_some());
    assert!(app.world().resource::<PassoWorld>().is_empty());

    app.world_mut().get_mut::<Mass>(e).unwrap().0 = 2.0;
    // Any part fixes it: here the position.
    app.world_mut()
        .get_mut::<Transform>(nan)
        .unwrap()
        .translation
        .x = 1.0;
    run_until(&mut app, 1);
    app.update();
    assert!(app.world().get::<BodyError>(e).is_none());
    let id = app.world().get::<PassoBody>(e).unwrap().id();
    assert_eq!(
        app.world().resource::<PassoWorld>().body(id).unwrap().mass,
        2.0
    );
    assert!(app.world().get::<BodyError>(nan).is_none());
    let id = app.world().get::<PassoBody>(nan).unwrap().id();
    let body = app.world().resource::<PassoWorld>().body(id).unwrap();
    assert_eq!(body.position.x, 1.0);
}

/// A tick length the world cannot step is refused once with a warning,
/// and nothing steps.
#[test]
fn an_impossible_rate_steps_nothing_and_does_not_panic() {
    for rate in [0.0, -60.0, f64::NAN] {
        let mut app = app(rate, 1.0 / 60.0);
        app.world_mut()
            .spawn((RigidBody::Dynamic, Transform::default()));
        for _ in 0..10 {
            app.update();
        }
        // Bevy's own fixed clock (64 Hz) drives it instead.
        assert!(ticks(&app) > 0, "rate {rate}");
    }
}

/// A tick length set by hand that the world cannot step is refused: no
/// step, no panic; a good one steps again.
#[test]
fn an_impossible_tick_length_steps_nothing() {
    let mut app = app(60.0, 1.0 / 60.0);
    app.world_mut()
        .spawn((RigidBody::Dynamic, Transform::default()));
    for dt in [0.0, -1.0 / 60.0, f32::NAN, f32::INFINITY, 7200.0] {
        app.insert_resource(PassoTimestep(Some(dt)));
        for _ in 0..5 {
            app.update();
        }
        assert_eq!(ticks(&app), 0, "dt {dt}");
    }
    app.insert_resource(PassoTimestep(Some(1.0 / 60.0)));
    for _ in 0..5 {
        app.update();
    }
    assert!(ticks(&app) > 0);
}

/// Changing components changes the body: its material, its shape (the
/// body is rebuilt where it is), its sensor flag, its velocity.
#[test]
fn component_changes_reach_the_body() {
    let mut app = app(60.0, 1.0 / 60.0);
    let e = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::circle(0.5),
            GravityScale(0.0),
            Transform::from_xyz(1.0, 2.0, 0.0),
        ))
        .id();
    run_until(&mut app, 1);
    let body = |app: &App| {
        let id = app.world().get::<PassoBody>(e).unwrap().id();
        app.world().resource::<PassoWorld>().body(id).unwrap()
    };
    app.world_mut().entity_mut(e).insert(PhysicsMaterial {
        friction: 0.9,
        restitution: 0.25,
        friction_mix: FrictionMix::Max,
    });
    app.world_mut().get_mut::<LinearVelocity>(e).unwrap().0 = Vec2::new(2.0, 0.0);
    run_until(&mut app, 2);
    let b = body(&app);
    assert_eq!(
        (b.friction, b.restitution, b.friction_mix),
        (0.9, 0.25, FrictionMix::Max)
    );
    assert_eq!(b.velocity.x, 2.0);
    assert_eq!(b.gravity_scale, 0.0);

    let old = app.world().get::<PassoBody>(e).unwrap().id();
    let at = app.world().get::<Position>(e).unwrap().0;
    app.world_mut()
        .entity_mut(e)
        .insert(Collider::rectangle(1.0, 2.0));
    run_until(&mut app, 3);
    let new = app.world().get::<PassoBody>(e).unwrap().id();
    assert_ne!(old, new);
    let b = body(&app);
    assert_eq!(b.shape.unwrap().half_extents(), glam::Vec2::new(0.5, 1.0));
    // Rebuilt where it was, still moving at 2 m/s, one tick on.
    assert!(
        (b.position.x - (at.x + 2.0 / 60.0)).abs() < 1e-5,
        "{} {}",
        b.position,
        at
    );
    assert_eq!(b.velocity.x, 2.0);
    assert_eq!(b.friction, 0.9);

    app.world_mut().entity_mut(e).insert(Sensor);
    run_until(&mut app, 4);
    assert!(body(&app).sensor);
    app.world_mut().entity_mut(e).remove::<Sensor>();
    run_until(&mut app, 5);
    assert!(!body(&app).sensor);
    // Settings come and go in place: the same body, not a rebuilt one.
    assert_eq!(app.world().get::<PassoBody>(e).unwrap().id(), new);
    // Without its GravityScale and material it falls again, as any body.
    app.world_mut()
        .entity_mut(e)
        .remove::<(GravityScale, PhysicsMaterial)>();
    run_until(&mut app, 6);
    assert_eq!(body(&app).gravity_scale, 1.0);
    assert_eq!(body(&app).friction, PhysicsMaterial::default().friction);
    assert_eq!(app.world().get::<PassoBody>(e).unwrap().id(), new);

    // A filter, and a one-way side on a static body.
    let filter = CollisionFilter {
        layers: 0b10,
        mask: 0b01,
    };
    app.world_mut().entity_mut(e).insert(Filter(filter));
    let ledge = app
        .world_mut()
        .spawn((
            RigidBody::Static,
            Collider::rectangle(2.0, 0.2),
            Transform::default(),
        ))
        .id();
    run_until(&mut app, 7);
    assert_eq!(body(&app).filter, filter);
    app.world_mut().entity_mut(ledge).insert(OneWay(Vec2::Y));
    run_until(&mut app, 8);
    let ledge_id = app.world().get::<PassoBody>(ledge).unwrap().id();
    let one_way = app
        .world()
        .resource::<PassoWorld>()
        .body(ledge_id)
        .unwrap()
        .one_way;
    assert_eq!(one_way, Some(glam::Vec2::Y));
    app.world_mut().entity_mut(ledge).remove::<OneWay>();
    app.world_mut().entity_mut(e).remove::<Filter>();
    run_until(&mut app, 9);
    assert_eq!(app.world().get::<PassoBody>(ledge).unwrap().id(), ledge_id);
    let ledge_body = app.world().resource::<PassoWorld>().body(ledge_id).unwrap();
    assert_eq!(ledge_body.one_way, None);
    assert_eq!(body(&app).filter, CollisionFilter::default());
    assert_eq!(app.world().get::<PassoBody>(e).unwrap().id(), new);

    // A bullet, and back.
    app.world_mut().entity_mut(e).insert(Bullet);
    run_until(&mut app, 10);
    assert!(body(&app).bullet);
    app.world_mut().entity_mut(e).remove::<Bullet>();
    run_until(&mut app, 11);
    assert!(!body(&app).bullet);

    // Without its Collider the body is rebuilt as a point, where it was.
    let at = app.world().get::<Position>(e).unwrap().0;
    app.world_mut().entity_mut(e).remove::<Collider>();
    run_until(&mut app, 12);
    assert_ne!(app.world().get::<PassoBody>(e).unwrap().id(), new);
    assert_eq!(body(&app).shape, None);
    assert!((body(&app).position.x - at.x).abs() < 0.1);

    // A new Mass rebuilds it with that mass, a new kind with that kind.
    app.world_mut().entity_mut(e).insert(Mass(4.0));
    run_until(&mut app, 13);
    assert_eq!(body(&app).mass, 4.0);
    app.world_mut().entity_mut(e).insert(RigidBody::Kinematic);
    run_until(&mut app, 14);
    assert_eq!(body(&app).kind, passo::BodyKind::Kinematic);
}

fn spawn_in_two_steps(mut commands: Commands) {
    let e = commands
        .spawn((RigidBody::Dynamic, Transform::from_xyz(0.0, 2.0, 0.0)))
        .id();
    commands
        .entity(e)
        .insert((Collider::circle(0.25), Mass(3.0)));
}

/// Parts inserted by a later command than the RigidBody's still shape
/// the body before its first tick.
#[test]
fn parts_inserted_after_the_spawn_shape_the_body() {
    let mut app = app(60.0, 1.0 / 60.0);
    app.add_systems(Startup, spawn_in_two_steps);
    run_until(&mut app, 1);
    let world = app.world().resource::<PassoWorld>();
    let body = world.bodies().next().unwrap();
    assert_eq!(body.shape, Some(passo::Shape::circle(0.25)));
    assert_eq!(body.mass, 3.0);
    assert_eq!(world.len(), 1);
}

/// The step's diagnostics reach Bevy's store.
#[test]
fn diagnostics_count_bodies_and_contacts() {
    use bevy::diagnostic::DiagnosticsStore;
    let mut app = app(60.0, 1.0 / 60.0);
    app.world_mut().spawn((
        RigidBody::Static,
        Collider::rectangle(10.0, 1.0),
        Transform::from_xyz(0.0, -0.5, 0.0),
    ));
    for i in 0..3 {
        app.world_mut().spawn((
            RigidBody::Dynamic,
            Collider::rectangle(0.5, 0.5),
            Transform::from_xyz(i as f32, 0.25, 0.0),
        ));
    }
    run_until(&mut app, 10);
    app.update();
    let store = app.world().resource::<DiagnosticsStore>();
    let value =
        |path: &bevy::diagnostic::DiagnosticPath| store.get_measurement(path).map(|m| m.value);
    let (bodies, contacts, time) = (
        passo_bevy::diagnostics::BODIES,
        passo_bevy::diagnostics::CONTACTS,
        passo_bevy::diagnostics::STEP_TIME,
    );
    assert_eq!(value(&bodies), Some(4.0));
    assert_eq!(value(&contacts), Some(3.0));
    assert!(value(&time).is_some_and(|ms| ms >= 0.0));
}

/// Rays and casts answer with entities.
#[test]
fn queries_answer_with_entities() {
    use bevy::ecs::system::RunSystemOnce;
    let mut app = app(60.0, 1.0 / 60.0);
    let ground = app
        .world_mut()
        .spawn((
            RigidBody::Static,
            Collider::rectangle(10.0, 1.0),
            Transform::from_xyz(0.0, -0.5, 0.0),
        ))
        .id();
    app.update();
    let (ray, cast, point) = app
        .world_mut()
        .run_system_once(|q: SpatialQuery| {
            let filter = QueryFilter::default();
            (
                q.ray_cast(Vec2::new(1.0, 5.0), Vec2::NEG_Y, 10.0, &filter),
                q.cast_shape(
                    &Collider::circle(0.5),
                    Vec2::new(0.0, 3.0),
                    Vec2::new(0.0, -5.0),
                    &filter,
                ),
                q.point(Vec2::new(2.0, -0.5), &filter),
            )
        })
        .unwrap();
    let ray = ray.unwrap();
    assert_eq!(ray.entity, Some(ground));
    assert!(
        (ray.distance - 5.0).abs() < 1e-5 && ray.normal == Vec2::Y,
        "{ray:?}"
    );
    let cast = cast.unwrap();
    assert_eq!(cast.entity, Some(ground));
    assert!((cast.fraction - 2.5 / 5.0).abs() < 1e-5, "{cast:?}");
    assert_eq!(point, vec![ground]);

    // A box resting on the ground: it stands, and the ground's box query
    // finds both.
    let crate_ = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::rectangle(0.5, 0.5),
            Transform::from_xyz(3.0, 0.25, 0.0),
        ))
        .id();
    run_until(&mut app, 30);
    let ground_id = app.world().get::<PassoBody>(ground).unwrap().id();
    let (standing, floating, found, body, bodies) = app
        .world_mut()
        .run_system_once(move |q: SpatialQuery| {
            let filter = QueryFilter::default();
            (
                q.is_standing(crate_, 0.5),
                q.is_standing(ground, 0.5),
                q.aabb(Vec2::new(2.0, -1.0), Vec2::new(4.0, 1.0), &filter),
                q.body(ground),
                q.world().len(),
            )
        })
        .unwrap();
    assert!(standing);
    assert!(!floating);
    assert_eq!(found, vec![ground, crate_]);
    assert_eq!(body, Some(ground_id));
    assert_eq!(bodies, 2);
    assert_eq!(
        Collider::rectangle(0.5, 0.25).half_extents(),
        Vec2::new(0.25, 0.125)
    );
}
