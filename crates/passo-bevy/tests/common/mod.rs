//! A headless Bevy app with the plugin and a manual clock.

#![allow(dead_code)]

use std::time::Duration;

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use passo_bevy::prelude::*;

/// An app ticking `rate` times a second whose frames last `frame`
/// seconds, with no window and no real clock.
pub fn app(rate: f64, frame: f64) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, PassoPlugin::default().with_rate(rate)))
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
            frame,
        )));
    app
}

/// Ticks stepped so far.
pub fn ticks(app: &App) -> u64 {
    app.world().resource::<PassoWorld>().stats().steps
}

/// Updates the app until it has stepped at least `n` ticks.
pub fn run_until(app: &mut App, n: u64) {
    let mut frames = 0;
    while ticks(app) < n {
        app.update();
        frames += 1;
        assert!(
            frames < 100 * n + 100,
            "the app stopped ticking at {}",
            ticks(app)
        );
    }
}

/// The state hash after each tick, recorded in the physics schedule.
#[derive(Resource, Default)]
pub struct Hashes(pub Vec<u64>);

fn record_hash(world: Res<PassoWorld>, mut hashes: ResMut<Hashes>) {
    hashes.0.push(world.state_hash());
}

/// Records the world's hash after every tick.
pub fn record_hashes(app: &mut App) {
    app.init_resource::<Hashes>()
        .add_systems(FixedUpdate, record_hash.after(PassoSystems::Writeback));
}

/// A scene file shipped in `assets/scenes`.
pub fn scene_path(name: &str) -> String {
    format!(
        "{}/../../assets/scenes/{name}.ron",
        env!("CARGO_MANIFEST_DIR")
    )
}
