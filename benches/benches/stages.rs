//! The cost of a step with one force model against all of them, on 10 000
//! point masses: a scene pays only for the models it declares.
//!
//! Each sample steps a fresh copy of the world once, so every case is
//! timed in the same state. Stepping one world for the whole run would
//! time gravity alone on bodies that have fallen for minutes, clamped at
//! the maximum speed every step, against drag cases at their terminal
//! speed.

use criterion::{BatchSize, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use passo_physics::glam::Vec2;
use passo_physics::{
    BodyDef, CentralGravity, ForceModels, LinearDrag, QuadraticDrag, Spring, SurfaceFriction,
    World, WorldSettings,
};

const BODIES: usize = 10_000;

fn world(forces: ForceModels) -> World {
    let mut world = World::new(WorldSettings {
        forces,
        ..Default::default()
    })
    .unwrap();
    for i in 0..BODIES {
        let def = BodyDef {
            position: Vec2::new((i % 100) as f32, (i / 100) as f32),
            velocity: Vec2::new(3.0, 1.0),
            ..Default::default()
        };
        world.add_body(def).unwrap();
    }
    world
}

fn stages(c: &mut Criterion) {
    let gravity = ForceModels::default();
    let cases = [
        ("none", ForceModels::none()),
        ("gravity", gravity),
        (
            "gravity+quadratic_drag",
            ForceModels {
                quadratic_drag: Some(QuadraticDrag::default()),
                ..gravity
            },
        ),
        (
            "all",
            ForceModels {
                quadratic_drag: Some(QuadraticDrag::default()),
                linear_drag: Some(LinearDrag { coefficient: 0.1 }),
                air_velocity: Vec2::new(2.0, 0.0),
                surface_friction: Some(SurfaceFriction::default()),
                force_field: Some(Vec2::new(1.0, 0.0)),
                spring: Some(Spring {
                    anchor: Vec2::ZERO,
                    stiffness: 1.0,
                }),
                central_gravity: Some(CentralGravity {
                    centre: Vec2::new(-50.0, -50.0),
                    gm: 100.0,
                }),
                ..gravity
            },
        ),
    ];
    let mut group = c.benchmark_group("step_10k_point_masses");
    group.throughput(Throughput::Elements(BODIES as u64));
    for (name, forces) in cases {
        let fresh = world(forces);
        group.bench_with_input(BenchmarkId::from_parameter(name), &(), |b, _| {
            b.iter_batched_ref(
                || fresh.clone(),
                |w| w.step(1.0 / 60.0),
                BatchSize::SmallInput,
            );
        });
    }
    group.finish();
}

criterion_group!(benches, stages);
criterion_main!(benches);
