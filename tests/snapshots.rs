//! Snapshots: restoring a world (and its loop) and stepping on gives, bit
//! for bit, what the uninterrupted run gives: the rollback pattern. Through
//! RON text and through the binary form alike; damaged snapshots are
//! refused, never trusted.

use passo::snapshot::GameSnapshot;
use passo_loop::FixedTimestep;
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, ContactEvents, PhysicsError, Shape, World, WorldSnapshot};
use passo_scene::Scene;
use proptest::prelude::*;
use std::path::PathBuf;
use std::time::Duration;

const DT: f32 = 1.0 / 60.0;

/// A busy world: the rain scene (2 000 circles, contacts, warm starting)
/// plus a sensor and a body with its own speed limit.
fn busy() -> World {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/rain.ron");
    let mut world = Scene::load(&path).unwrap().build().unwrap().world;
    world
        .add_body(BodyDef {
            sensor: true,
            ..BodyDef::new_static(Vec2::new(0.0, 2.0), Shape::rect(6.0, 2.0))
        })
        .unwrap();
    world
        .add_body(BodyDef {
            position: Vec2::new(3.0, 30.0),
            shape: Some(Shape::circle(0.3)),
            max_speed: Some(6.0),
            ..Default::default()
        })
        .unwrap();
    world
}

/// Steps `n` times, returning the state hash and the events after each step.
fn run(world: &mut World, n: usize) -> Vec<(u64, ContactEvents)> {
    (0..n)
        .map(|_| {
            world.step(DT);
            (world.state_hash(), world.events().clone())
        })
        .collect()
}

#[test]
fn rolling_back_to_a_snapshot_replays_the_same_bits_and_events() {
    let mut world = busy();
    run(&mut world, 90); // the rain has landed: contacts and warm starting
    let snapshot = world.snapshot();
    let ahead = run(&mut world, 60);
    assert!(
        ahead.iter().any(|(_, e)| !e.begin.is_empty()),
        "contacts began"
    );
    assert!(
        ahead
            .iter()
            .any(|(_, e)| !e.sensor_begin.is_empty() || !e.sensor_end.is_empty())
    );

    world.restore(snapshot.clone()).unwrap();
    assert_eq!(run(&mut world, 60), ahead, "rollback in place");

    let mut fresh = World::from_snapshot(snapshot).unwrap();
    assert_eq!(run(&mut fresh, 60), ahead, "a new world from the snapshot");
}

#[test]
fn ron_and_binary_snapshots_of_world_and_loop_continue_exactly() {
    let mut world = busy();
    let mut timestep = FixedTimestep::from_hz(60.0).unwrap();
    // Uneven frames leave a remainder in the accumulator.
    let frames = [11u64, 23, 17, 31, 9, 40, 16, 16, 25];
    let step_frames = |world: &mut World, timestep: &mut FixedTimestep, count: usize| {
        let mut hashes = Vec::new();
        for ms in frames.iter().cycle().take(count) {
            let frame = timestep.advance(Duration::from_millis(*ms));
            for _ in 0..frame.ticks {
                world.step(frame.dt);
            }
            hashes.push((world.state_hash(), timestep.tick(), timestep.remainder()));
        }
        hashes
    };
    step_frames(&mut world, &mut timestep, 100);
    let saved = GameSnapshot::capture(&world, &timestep);
    let ahead = step_frames(&mut world, &mut timestep, 50);

    let text = saved.to_ron();
    let bytes = saved.to_bytes();
    assert!(
        bytes.len() < text.len() / 2,
        "binary {} bytes, RON {}",
        bytes.len(),
        text.len()
    );
    for copy in [
        GameSnapshot::from_ron(&text).unwrap(),
        GameSnapshot::from_bytes(&bytes).unwrap(),
    ] {
        assert_eq!(copy, saved);
        let (mut w, mut t) = copy.restore().unwrap();
        assert_eq!(step_frames(&mut w, &mut t, 50), ahead);
    }

    let dir = std::env::temp_dir().join(format!("passo-snapshots-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for name in ["game.ron", "game.bin"] {
        saved.save(&dir.join(name)).unwrap();
        assert_eq!(
            GameSnapshot::load(&dir.join(name)).unwrap(),
            saved,
            "{name}"
        );
    }
    std::fs::write(dir.join("junk.bin"), b"not a snapshot").unwrap();
    let err = GameSnapshot::load(&dir.join("junk.bin")).unwrap_err();
    assert!(
        format!("{err:#}").contains("is not a Passo snapshot"),
        "{err:#}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_snapshot_with_kinematic_bodies_equals_itself_read_back() {
    // A snapshot read from a file holds the same state, so it is equal to
    // the one written (the documented equality); with a kinematic body it
    // was not, which a game comparing a received snapshot with its own
    // would take for a desync.
    let mut world = World::default();
    let platform = BodyDef::new_kinematic(Vec2::ZERO, Shape::rect(1.0, 0.2), Vec2::X);
    world.add_body(platform).unwrap();
    world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(0.0, 1.0),
            Shape::circle(0.2),
        ))
        .unwrap();
    world.step(1.0 / 60.0);
    let saved = GameSnapshot::capture(&world, &FixedTimestep::from_hz(60.0).unwrap());
    for copy in [
        GameSnapshot::from_ron(&saved.to_ron()).unwrap(),
        GameSnapshot::from_bytes(&saved.to_bytes()).unwrap(),
    ] {
        assert_eq!(copy, saved);
        let (restored, _) = copy.clone().restore().unwrap();
        assert_eq!(restored.snapshot(), copy.world);
    }
}

#[test]
fn a_body_that_flew_past_the_coordinate_limit_saves_and_loads_back() {
    let mut world = World::new(passo_physics::WorldSettings {
        forces: passo_physics::ForceModels::none(),
        ..Default::default()
    })
    .unwrap();
    let def =
        BodyDef::new_dynamic(Vec2::ZERO, Shape::circle(0.5)).with_velocity(Vec2::new(1000.0, 0.0));
    let id = world.add_body(def).unwrap();
    // Three hours at 1 000 m/s: 1.08e7 m, past `MAX_COORDINATE` (1e7).
    for _ in 0..3 {
        world.step(3600.0);
    }
    let far = world.body(id).unwrap().position;
    assert!(far.x > passo_physics::constants::MAX_COORDINATE, "{far}");
    let saved = GameSnapshot::capture(&world, &FixedTimestep::from_hz(60.0).unwrap());
    world.step(1.0 / 60.0);
    for copy in [
        GameSnapshot::from_ron(&saved.to_ron()).unwrap(),
        GameSnapshot::from_bytes(&saved.to_bytes()).unwrap(),
    ] {
        let (mut restored, _) = copy.restore().unwrap();
        assert_eq!(restored.body(id).unwrap().position, far);
        restored.step(1.0 / 60.0);
        assert_eq!(restored.state_hash(), world.state_hash());
    }
    // Placing a body there is still refused.
    assert!(world.try_set_position(id, far).is_err());
}

#[test]
fn damaged_snapshots_are_refused_with_the_reason() {
    let mut world = busy();
    run(&mut world, 5);
    let good = world.snapshot();
    let text = ron::to_string(&good).unwrap();

    // A NaN written into a position.
    let nan = text.replacen("pos:[(", "pos:[(NaN,0.0),(", 1);
    let err = World::from_snapshot(ron::from_str::<WorldSnapshot>(&nan).unwrap()).unwrap_err();
    assert!(matches!(err, PhysicsError::InvalidSnapshot(_)), "{err}");
    assert!(
        err.to_string().starts_with("invalid world snapshot:"),
        "{err}"
    );

    // Carried touching pairs and sensor overlaps out of order, or naming one
    // body twice: the first step after the load reported a false `end` and
    // `begin` for a pair still touching. (Pairs may name bodies removed
    // since the step, which the next step reports ended.)
    assert!(
        text.contains("touching:[("),
        "the busy world has touching pairs"
    );
    assert!(text.contains("sensors:[("), "and sensor overlaps");
    let id = |i: u32, g: u32| format!("(index:{i},generation:{g})");
    for (field, entry) in [
        (
            "touching:[",
            format!("({},{}),", id(99_998, 0), id(99_999, 0)),
        ),
        ("touching:[", format!("({},{}),", id(9, 5), id(7, 3))),
        ("touching:[", format!("({},{}),", id(1, 0), id(1, 0))),
        (
            "sensors:[",
            format!("(sensor:{},visitor:{}),", id(99_999, 0), id(43, 0)),
        ),
        (
            "sensors:[",
            format!("(sensor:{},visitor:{}),", id(3, 0), id(3, 0)),
        ),
    ] {
        let damaged = text.replacen(field, &format!("{field}{entry}"), 1);
        assert_ne!(damaged, text);
        let Err(err) = World::from_snapshot(ron::from_str::<WorldSnapshot>(&damaged).unwrap())
        else {
            panic!("accepted {field}{entry}");
        };
        assert!(
            matches!(err, PhysicsError::InvalidSnapshot(_)),
            "{entry}: {err}"
        );
    }

    // A loop with a zero step.
    let mut game = GameSnapshot::capture(&world, &FixedTimestep::default());
    let ron_game = game.to_ron().replace("16666667", "0");
    assert!(
        GameSnapshot::from_ron(&ron_game)
            .unwrap()
            .restore()
            .is_err()
    );
    game.world = good;
    assert!(game.restore().is_ok());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// Random edits of a snapshot's text: refused or accepted, never a
    /// panic, and an accepted one steps without producing a NaN.
    #[test]
    fn edited_snapshot_text_is_refused_or_steps_safely(
        edits in prop::collection::vec((any::<prop::sample::Index>(), "[0-9.eE,\\-]{1,3}"), 1..4)
    ) {
        let mut world = World::default();
        world.add_body(BodyDef::new_static(Vec2::ZERO, Shape::rect(10.0, 1.0))).unwrap();
        for i in 0..5 {
            world.add_body(BodyDef {
                position: Vec2::new(i as f32, 2.0),
                shape: Some(Shape::circle(0.4)),
                ..Default::default()
            }).unwrap();
        }
        world.step(DT);
        let mut text = ron::to_string(&world.snapshot()).unwrap();
        for (at, insert) in edits {
            let i = at.index(text.len());
            if text.is_char_boundary(i) {
                text.insert_str(i, &insert);
            }
        }
        if let Ok(snapshot) = ron::from_str::<WorldSnapshot>(&text)
            && let Ok(mut w) = World::from_snapshot(snapshot)
        {
            w.step(DT);
            prop_assert!(w.bodies().all(|b| b.position.is_finite() && b.velocity.is_finite()));
        }
    }
}

/// Snapshot files of the playground after 200 ticks, written by `cargo
/// run -p passo -- simulate playground --ticks 200 --save FILE` (`.ron` and
/// binary). They load, hold the state a fresh run of 200 ticks reaches,
/// and are written back byte for byte: a change to the format or to the
/// bits fails here until the files are written again (a change to the
/// bits moves the determinism constants too). The layout in memory does
/// not show in the files: they were first written before the dynamic
/// bodies' arrays were split into x and y, and loaded unchanged after.
#[test]
fn reference_snapshot_files_load_and_write_back_the_same() {
    let scene = passo::scenes::load("playground").unwrap();
    let mut built = scene.build().unwrap();
    let mut timestep = FixedTimestep::from_hz(scene.file.rate_hz).unwrap();
    for _ in 0..200 {
        timestep.advance_ticks(1);
        built.step(timestep.dt());
    }
    let fresh = built.world.snapshot();

    let reference = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("reference");
    let bytes = std::fs::read(reference.join("playground_200_ticks.bin")).unwrap();
    let text = std::fs::read_to_string(reference.join("playground_200_ticks.ron")).unwrap();
    let from_bytes = GameSnapshot::from_bytes(&bytes).unwrap();
    let from_text = GameSnapshot::from_ron(&text).unwrap();
    assert_eq!(from_bytes.to_bytes(), bytes);
    assert_eq!(from_text.to_ron(), text);
    for snapshot in [from_bytes, from_text] {
        assert_eq!(snapshot.timestep.tick(), 200);
        let (world, _) = snapshot.restore().unwrap();
        assert_eq!(world.snapshot(), fresh);
        assert_eq!(world.state_hash(), built.world.state_hash());
    }
}

/// The same files written before contacts carried what their reuse needs
/// (`tests/reference/*_before_reuse.*`). The RON one loads, its contacts
/// found afresh at the next step, and steps on; the binary one, whose
/// compact form has no field names to go by, is refused with an error.
#[test]
fn snapshot_files_from_before_contact_reuse() {
    let reference = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("reference");
    let text =
        std::fs::read_to_string(reference.join("playground_200_ticks_before_reuse.ron")).unwrap();
    let (mut world, _) = GameSnapshot::from_ron(&text).unwrap().restore().unwrap();
    let saved: Vec<_> = world.bodies().map(|b| b.position).collect();
    assert!(world.contacts().count() > 0, "its contacts load");
    for _ in 0..60 {
        world.step(DT);
    }
    assert!(world.bodies().all(|b| b.position.is_finite()));
    assert_ne!(
        saved,
        world.bodies().map(|b| b.position).collect::<Vec<_>>()
    );
    let bytes = std::fs::read(reference.join("playground_200_ticks_before_reuse.bin")).unwrap();
    let refused = GameSnapshot::from_bytes(&bytes).and_then(|s| s.restore().map(|_| ()));
    assert!(
        refused.is_err(),
        "a binary file of the format before is refused"
    );
}
