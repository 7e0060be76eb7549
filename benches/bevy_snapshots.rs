//! What a rollback snapshot costs per frame in Bevy: Passo's plugin
//! against bevy_rapier, on the same level. Both apps load the platformer
//! scene's bodies (its tiles, the lift, the crate, coins and goal as
//! sensors), step 600 frames at 60 Hz, and after every frame the state a
//! rollback saves is encoded with postcard: Passo's `WorldSnapshot`, and
//! bevy_rapier's four serializable context components (bodies, colliders,
//! joints, simulation). Rotation is locked on rapier's dynamic bodies,
//! as Passo's do not rotate.
//!
//! Run: `cargo run --release -p passo-benches --features bevy-rapier --bin bevy_snapshots [-- --write]`
//! (`--write` puts the table in BENCHMARKS.md).

use std::time::Duration;

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_rapier2d::prelude as rapier;
use bevy_rapier2d::prelude::{
    RapierContextColliders, RapierContextJoints, RapierContextSimulation, RapierRigidBodySet,
};
use passo_benches::tables::{benchmarks_md, replace, write_flag};
use passo_bevy::passo_physics::{BodyKind, Shape, World};
use passo_bevy::prelude::*;

const FRAMES: usize = 600;

fn scene() -> String {
    format!(
        "{}/../assets/scenes/platformer.ron",
        env!("CARGO_MANIFEST_DIR")
    )
}

fn headless(app: &mut App) {
    app.add_plugins(MinimalPlugins)
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
            1.0 / 60.0,
        )));
}

/// Smallest and largest of a series.
fn range(values: &[usize]) -> (usize, usize) {
    let min = values.iter().copied().min().unwrap_or(0);
    let max = values.iter().copied().max().unwrap_or(0);
    (min, max)
}

/// Passo: postcard bytes and in-memory bytes of the snapshot, per frame.
fn passo_sizes() -> (usize, Vec<usize>, Vec<usize>) {
    let mut app = App::new();
    headless(&mut app);
    app.add_plugins(PassoPlugin::default().with_rate(60.0));
    app.world_mut().commands().queue(LoadScene::file(scene()));
    app.world_mut().flush();
    let (mut wire, mut memory) = (Vec::new(), Vec::new());
    for _ in 0..FRAMES {
        app.update();
        let snapshot = app.world().resource::<PassoWorld>().snapshot();
        memory.push(snapshot.heap_bytes() + size_of_val(&snapshot));
        wire.push(
            postcard::to_allocvec(&snapshot)
                .expect("a snapshot encodes")
                .len(),
        );
    }
    let bodies = app.world().resource::<PassoWorld>().len();
    (bodies, wire, memory)
}

/// The same bodies as rapier colliders.
fn rapier_collider(shape: Shape) -> Option<rapier::Collider> {
    let v = |p: passo_bevy::passo_physics::glam::Vec2| Vec2::new(p.x, p.y);
    Some(match shape {
        Shape::Circle { radius } => rapier::Collider::ball(radius),
        Shape::Box { half_extents } => rapier::Collider::cuboid(half_extents.x, half_extents.y),
        Shape::Capsule {
            half_segment,
            radius,
        } => rapier::Collider::capsule(-v(half_segment), v(half_segment), radius),
        Shape::Segment { half } | Shape::ChainSegment { half, .. } => {
            rapier::Collider::segment(-v(half), v(half))
        }
        Shape::Polygon(polygon) => {
            rapier::Collider::convex_polyline(polygon.vertices().iter().map(|&p| v(p)).collect())?
        }
    })
}

/// bevy_rapier: postcard bytes of its context per frame.
fn rapier_sizes(world: &World) -> (usize, Vec<usize>) {
    let mut app = App::new();
    headless(&mut app);
    app.add_plugins((
        TransformPlugin,
        rapier::RapierPhysicsPlugin::<rapier::NoUserData>::default(),
    ))
    .insert_resource(rapier::TimestepMode::Fixed {
        dt: 1.0 / 60.0,
        substeps: 1,
    });
    let mut bodies = 0;
    for body in world.bodies() {
        let Some(collider) = body.shape.and_then(rapier_collider) else {
            continue;
        };
        let kind = match body.kind {
            BodyKind::Dynamic => rapier::RigidBody::Dynamic,
            BodyKind::Static => rapier::RigidBody::Fixed,
            BodyKind::Kinematic => rapier::RigidBody::KinematicVelocityBased,
        };
        let mut entity = app.world_mut().spawn((
            kind,
            collider,
            rapier::LockedAxes::ROTATION_LOCKED,
            Transform::from_xyz(body.position.x, body.position.y, 0.0),
        ));
        if body.sensor {
            entity.insert(rapier::Sensor);
        }
        bodies += 1;
    }
    let mut wire = Vec::new();
    let mut contexts = app.world_mut().query::<(
        &RapierContextSimulation,
        &RapierContextColliders,
        &RapierRigidBodySet,
        &RapierContextJoints,
    )>();
    for _ in 0..FRAMES {
        app.update();
        let (simulation, colliders, rigid_bodies, joints) =
            contexts.single(app.world()).expect("one rapier context");
        let bytes = [
            postcard::to_allocvec(simulation),
            postcard::to_allocvec(colliders),
            postcard::to_allocvec(rigid_bodies),
            postcard::to_allocvec(joints),
        ]
        .into_iter()
        .map(|encoded| encoded.expect("rapier's context encodes").len())
        .sum();
        wire.push(bytes);
    }
    (bodies, wire)
}

fn main() {
    let write = write_flag();
    let (passo_bodies, passo_wire, passo_memory) = passo_sizes();
    let built = passo_scene::Scene::load(std::path::Path::new(&scene()))
        .and_then(|s| s.build())
        .expect("the platformer scene builds");
    let (rapier_bodies, rapier_wire) = rapier_sizes(&built.world);
    let (pw, rw, pm) = (
        range(&passo_wire),
        range(&rapier_wire),
        range(&passo_memory),
    );
    let table = format!(
        "| engine | bodies | postcard bytes a frame | in memory, bytes a frame |\n\
         |---|---:|---:|---:|\n\
         | Passo (`passo-bevy`) | {passo_bodies} | {}–{} | {}–{} |\n\
         | bevy_rapier2d 0.36 | {rapier_bodies} | {}–{} | |\n",
        pw.0, pw.1, pm.0, pm.1, rw.0, rw.1
    );
    print!("{table}");
    if write {
        let path = benchmarks_md();
        let written = std::fs::read_to_string(&path)
            .map_err(|e| e.to_string())
            .and_then(|doc| replace(&doc, "bevy_snapshots", &table))
            .and_then(|doc| std::fs::write(&path, doc).map_err(|e| e.to_string()));
        if let Err(error) = written {
            eprintln!("{}: {error}", path.display());
            std::process::exit(1);
        }
    }
}
