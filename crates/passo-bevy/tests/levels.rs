//! Scenes and Tiled levels loaded through the LoadScene command.

mod common;

use bevy::prelude::*;
use common::{app, run_until, ticks};
use passo_bevy::prelude::*;

fn level_path(file: &str) -> String {
    format!("{}/../../assets/levels/{file}", env!("CARGO_MANIFEST_DIR"))
}

fn named(app: &mut App, name: &str) -> Entity {
    let mut query = app.world_mut().query::<(Entity, &Name)>();
    query
        .iter(app.world())
        .find(|(_, n)| n.as_str() == name)
        .map(|(e, _)| e)
        .unwrap_or_else(|| panic!("no entity named {name}"))
}

/// Bodies in the world, and bodies with an entity.
fn body_counts(app: &App) -> (usize, usize) {
    let world = app.world().resource::<PassoWorld>().len();
    let entities = app.world().resource::<passo_bevy::BodyEntities>();
    (world, entities.iter().count())
}

/// The platformer scene (a Tiled map) becomes a world with an entity per
/// object, spawn points, and a lift the plugin drives along its path.
#[test]
fn the_platformer_scene_loads_with_its_objects_and_lift() {
    let mut app = app(60.0, 1.0 / 60.0);
    app.world_mut()
        .commands()
        .queue(LoadScene::file(common::scene_path("platformer")));
    app.world_mut().flush();

    let level = app.world().resource::<PassoLevel>().clone();
    let spawn = level.spawn("player").expect("the player's spawn point");
    // Tiled's (32, 208) px in a 16 px grid of 0.5 m cells, y up.
    assert!((spawn.x - 1.0).abs() < 1e-5, "{spawn}");
    assert!(!level.cell_bodies.is_empty());
    assert_eq!(level.platforms.len(), 1);
    let (world_len, entities) = body_counts(&app);
    assert_eq!(entities + level.cell_bodies.len(), world_len);

    let goal = named(&mut app, "goal");
    assert!(app.world().get::<Sensor>(goal).is_some());
    let crate_ = named(&mut app, "crate");
    assert_eq!(
        app.world().get::<RigidBody>(crate_),
        Some(&RigidBody::Dynamic)
    );
    let lift = named(&mut app, "lift");
    assert_eq!(
        app.world().get::<RigidBody>(lift),
        Some(&RigidBody::Kinematic)
    );

    // The lift follows its path: where the scene's own ticking puts it.
    run_until(&mut app, 90);
    let lift_id = app.world().get::<PassoBody>(lift).unwrap().id();
    let scene =
        passo_scene::Scene::load(std::path::Path::new(&common::scene_path("platformer"))).unwrap();
    let mut built = scene.build().unwrap();
    for _ in 0..ticks(&app) {
        built.step(1.0 / 60.0);
    }
    let expected = built.world.body(lift_id).unwrap().position;
    let at = app.world().get::<Position>(lift).unwrap().0;
    assert_eq!((at.x, at.y), (expected.x, expected.y));
    let start = level.platforms[0].start;
    assert!(
        (at - Vec2::new(start.x, start.y)).length() > 0.01,
        "the lift never moved: {at}"
    );
}

/// `LoadScene::file` knows a Tiled map by its name, in both formats:
/// cells 1 m wide.
#[test]
fn a_map_given_as_a_file_loads_as_a_map() {
    for file in ["first.tmx", "first.tmj"] {
        let mut app = app(60.0, 1.0 / 60.0);
        app.world_mut()
            .commands()
            .queue(LoadScene::file(level_path(file)));
        app.world_mut().flush();
        let level = app.world().get_resource::<PassoLevel>().expect(file);
        // The player's spawn at (32, 208) px of 16 px cells: x = 2 cells.
        let spawn = level.spawn("player").unwrap();
        assert!((spawn.x - 2.0).abs() < 1e-5, "{file}: {spawn}");
    }
}

/// A Tiled map on its own, in both formats, gives the same world.
#[test]
fn a_tiled_map_loads_on_its_own_in_both_formats() {
    let mut hashes = Vec::new();
    for file in ["first.tmx", "first.tmj"] {
        let mut app = app(60.0, 1.0 / 60.0);
        common::record_hashes(&mut app);
        app.world_mut()
            .commands()
            .queue(LoadScene::tiled(level_path(file), 0.5));
        app.world_mut().flush();
        let level = app.world().resource::<PassoLevel>();
        assert!(level.spawn("player").is_some(), "{file}");
        run_until(&mut app, 60);
        hashes.push(app.world().resource::<common::Hashes>().0[59]);
    }
    assert_eq!(hashes[0], hashes[1]);
}

#[derive(Resource, Default)]
struct Failures(Vec<SceneLoadFailed>);

fn collect(mut failed: MessageReader<SceneLoadFailed>, mut seen: ResMut<Failures>) {
    seen.0.extend(failed.read().cloned());
}

/// A file that cannot be loaded leaves the world as it was and says why.
#[test]
fn a_bad_file_leaves_the_world_alone_and_says_why() {
    let mut app = app(60.0, 1.0 / 60.0);
    app.init_resource::<Failures>().add_systems(Update, collect);
    let ball = app
        .world_mut()
        .spawn((RigidBody::Dynamic, Transform::default()))
        .id();
    app.update();
    let dir = std::env::temp_dir().join(format!("passo-bevy-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.ron");
    std::fs::write(&bad, "(name: \"bad\", bodies: [(mass: -1.0)])").unwrap();
    let cases = [
        LoadScene::file(bad.display().to_string()),
        LoadScene::file(dir.join("missing.ron").display().to_string()),
        LoadScene::text("(name: ", "broken.ron"),
        LoadScene::tiled(dir.join("missing.tmx").display().to_string(), 0.5),
    ];
    let count = cases.len();
    for case in cases {
        app.world_mut().commands().queue(case);
    }
    app.update();
    let failures = &app.world().resource::<Failures>().0;
    assert_eq!(failures.len(), count, "{failures:?}");
    assert!(failures[0].error.contains("mass"), "{}", failures[0].error);
    assert!(app.world().get::<PassoBody>(ball).is_some());
    assert_eq!(app.world().resource::<PassoWorld>().len(), 1);
    assert!(app.world().get_resource::<PassoLevel>().is_none());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Loading a scene replaces the old bodies and their entities.
#[test]
fn a_new_scene_replaces_the_old_bodies() {
    let mut app = app(60.0, 1.0 / 60.0);
    let old = app
        .world_mut()
        .spawn((RigidBody::Dynamic, Transform::default()))
        .id();
    app.update();
    app.world_mut()
        .commands()
        .queue(LoadScene::file(common::scene_path("stack")));
    app.world_mut().flush();
    assert!(app.world().get_entity(old).is_err());
    let (world_len, entities) = body_counts(&app);
    assert_eq!(world_len, entities);
    assert!(world_len > 1);
}

/// The guide's first app is the example that builds in `examples/bevy`.
#[test]
fn the_guides_first_app_is_the_hello_example() {
    let root = format!("{}/../..", env!("CARGO_MANIFEST_DIR"));
    let guide = std::fs::read_to_string(format!("{root}/docs/guide/src/bevy.md")).unwrap();
    let example =
        std::fs::read_to_string(format!("{root}/examples/bevy/src/bin/hello.rs")).unwrap();
    let start = guide
        .find("```rust,ignore\n")
        .expect("the first app's block")
        + "```rust,ignore\n".len();
    let end = start + guide[start..].find("```").unwrap();
    assert_eq!(&guide[start..end], example);
}
