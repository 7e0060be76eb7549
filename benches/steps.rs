//! One-thread step costs of the benchmark scenes, printed one line each:
//! the probe `benches/compare.sh` builds at two commits and runs
//! interleaved, so a change can be compared with the code before it in
//! the same conditions.
//!
//! `cargo run --release -p passo-benches --bin steps -- rain|pyramid|sleep|integration`

use passo_benches::{pyramid_world, rain_world, with_sleeping};
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, ForceModels, QuadraticDrag, World, WorldSettings};
use std::time::Instant;

fn ms_per_step(mut world: World, warm: u32, ticks: u32) -> f64 {
    world.set_parallel(false);
    for _ in 0..warm {
        world.step(1.0 / 60.0);
    }
    let start = Instant::now();
    for _ in 0..ticks {
        world.step(1.0 / 60.0);
    }
    start.elapsed().as_secs_f64() * 1e3 / ticks as f64
}

fn integration(n: usize) -> f64 {
    let mut world = World::new(WorldSettings {
        forces: ForceModels {
            quadratic_drag: Some(QuadraticDrag::default()),
            ..Default::default()
        },
        ..Default::default()
    })
    .unwrap();
    for i in 0..n {
        let def = BodyDef {
            position: Vec2::new(i as f32, 0.0),
            velocity: Vec2::new((i % 7) as f32, 3.0),
            ..Default::default()
        };
        world.add_body(def).unwrap();
    }
    world.set_parallel(false);
    let steps = (20_000_000 / n).clamp(5, 20_000);
    world.step(1.0 / 60.0);
    let start = Instant::now();
    for _ in 0..steps {
        world.step(1.0 / 60.0);
    }
    start.elapsed().as_nanos() as f64 / (n * steps) as f64
}

fn main() {
    let which = std::env::args().nth(1).unwrap_or_default();
    match which.as_str() {
        "integration" => {
            for n in [1_000, 10_000, 100_000, 1_000_000] {
                println!("integration {n}: {:.2} ns/body-step", integration(n));
            }
        }
        "rain" => {
            let w = with_sleeping(&rain_world(10_000), false);
            println!("rain 10000 awake: {:.2} ms/step", ms_per_step(w, 60, 240));
            let w = with_sleeping(&rain_world(1_000), false);
            println!("rain 1000 awake: {:.3} ms/step", ms_per_step(w, 60, 600));
        }
        "pyramid" => {
            let w = with_sleeping(&pyramid_world(50), false);
            println!("pyramid 50 awake: {:.3} ms/step", ms_per_step(w, 60, 300));
            let w = with_sleeping(&pyramid_world(20), false);
            println!("pyramid 20 awake: {:.3} ms/step", ms_per_step(w, 60, 600));
        }
        "sleep" => {
            let w = rain_world(10_000);
            println!(
                "rain 10000 settled, sleeping: {:.3} ms/step",
                ms_per_step(w, 900, 300)
            );
        }
        _ => {
            eprintln!("usage: steps integration|rain|pyramid|sleep");
            std::process::exit(2);
        }
    }
}
