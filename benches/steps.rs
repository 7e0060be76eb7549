//! One-thread step costs of the benchmark scenes, printed one line each:
//! the probe `benches/compare.sh` builds at two commits and runs
//! interleaved, so a change can be compared with the code before it in
//! the same conditions.
//!
//! `cargo run --release -p passo-benches --bin steps -- rain|pyramid|pyramid50|ticks|still|shuffled|sleep|settle|integration|rays|tuning|rest`
//! (and `--features parallel ... -- threads`: one thread against the pool)

use passo_benches::{busy_world, pyramid_world, rain_world, shuffled, with_sleeping};
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, ForceModels, QuadraticDrag, World, WorldSettings};
use std::time::Instant;

/// Passes of the contact solver: substeps, iterations a substep and relax
/// passes a substep (`ContactSettings`).
#[derive(Clone, Copy)]
struct SolverPasses(u32, u32, u32);

/// The settings `tuning` and `rest` compare: the default first.
const SOLVER_PASSES: [SolverPasses; 8] = [
    SolverPasses(4, 1, 1),
    SolverPasses(4, 2, 1),
    SolverPasses(4, 1, 2),
    SolverPasses(4, 1, 3),
    SolverPasses(5, 1, 1),
    SolverPasses(6, 1, 1),
    SolverPasses(8, 1, 1),
    SolverPasses(8, 2, 1),
];

impl SolverPasses {
    fn name(self) -> String {
        let Self(substeps, iterations, relax) = self;
        format!("substeps {substeps}, iterations {iterations}, relax {relax}")
    }

    /// A copy of `world` with these passes (out of range: says so and
    /// exits).
    fn applied(self, world: &World) -> World {
        let mut world = world.clone();
        let mut settings = *world.settings();
        if let Some(c) = &mut settings.contacts {
            (c.substeps, c.iterations, c.relax_iterations) = (self.0, self.1, self.2);
        }
        if let Err(e) = world.set_settings(settings) {
            eprintln!("passes {}: {e}", self.name());
            std::process::exit(2);
        }
        world
    }
}

/// The passes named by the second argument (`6,1,1`), or all of
/// [`SOLVER_PASSES`].
fn chosen_passes() -> Vec<SolverPasses> {
    let Some(arg) = std::env::args().nth(2) else {
        return SOLVER_PASSES.to_vec();
    };
    let n: Vec<u32> = arg
        .split(',')
        .filter_map(|n| n.trim().parse().ok())
        .collect();
    match n[..] {
        [substeps, iterations, relax] => vec![SolverPasses(substeps, iterations, relax)],
        _ => {
            eprintln!("passes are three counts: substeps,iterations,relax (such as 6,1,1)");
            std::process::exit(2);
        }
    }
}

fn ms_per_step(mut world: World, warm: u32, ticks: u32) -> f64 {
    ms_per_step_on(&mut world, false, warm, ticks)
}

/// Milliseconds per step on the calling thread alone, or (`parallel`)
/// with the thread pool.
fn ms_per_step_on(world: &mut World, parallel: bool, warm: u32, ticks: u32) -> f64 {
    world.set_parallel(parallel);
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

/// 10 000 rays through the rain's box, the same every run (a copy of
/// `passo_benches::rays`, which older commits lack).
fn passo_benches_rays() -> Vec<(Vec2, Vec2)> {
    let mut seed = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 40) as f32 / (1u64 << 24) as f32
    };
    (0..10_000)
        .map(|_| {
            let origin = Vec2::new(-20.0, 0.0) + Vec2::new(40.0, 15.0) * Vec2::new(next(), next());
            let angle = next() * std::f32::consts::TAU;
            (origin, Vec2::new(angle.cos(), angle.sin()))
        })
        .collect()
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
        "joints" => {
            // Box2D's joint grid without rotation (see `joint_grid`).
            let w = with_sleeping(&passo_benches::joint_grid(100), false);
            println!(
                "joint grid 100 awake: {:.3} ms/step",
                ms_per_step(w, 30, 300)
            );
        }
        "pyramid50" => {
            // The pyramid of base 50 alone, short enough for a profiler
            // that counts instructions (`valgrind --tool=cachegrind`).
            let w = with_sleeping(&pyramid_world(50), false);
            println!("pyramid 50 awake: {:.3} ms/step", ms_per_step(w, 60, 200));
        }
        "pyramid" => {
            let w = with_sleeping(&pyramid_world(50), false);
            println!("pyramid 50 awake: {:.3} ms/step", ms_per_step(w, 60, 300));
            let w = with_sleeping(&pyramid_world(20), false);
            println!("pyramid 20 awake: {:.3} ms/step", ms_per_step(w, 60, 600));
        }
        "still" => {
            // The pyramid of base 50 once it has come to rest (from tick
            // 220 on: its boxes no longer move, its pairs are kept).
            let w = with_sleeping(&pyramid_world(50), false);
            println!(
                "pyramid 50 awake, at rest: {:.3} ms/step",
                ms_per_step(w, 220, 300)
            );
        }
        "ticks" => {
            // The pyramid of base 50 from its start, as the peer bench
            // steps it: ms per step in each stretch of 20 ticks (the
            // fastest of five runs).
            let start = with_sleeping(&pyramid_world(50), false);
            let mut best = [f64::INFINITY; 15];
            for _ in 0..5 {
                let mut w = start.clone();
                w.set_parallel(false);
                for slot in &mut best {
                    *slot = slot.min(ms_per_step_on(&mut w, false, 0, 20));
                }
            }
            for (i, ms) in best.iter().enumerate() {
                println!(
                    "pyramid 50 ticks {}-{}: {ms:.3} ms/step",
                    i * 20,
                    i * 20 + 19
                );
            }
        }
        "shuffled" => {
            // The rain of 10 000 in the order of its places, and the same
            // bodies added in a scrambled order (one thread each, and the
            // pool with `--features parallel`).
            let ordered = with_sleeping(&rain_world(10_000), false);
            let scrambled = shuffled(&ordered);
            let modes: &[bool] = if cfg!(feature = "parallel") {
                &[false, true]
            } else {
                &[false]
            };
            for (name, world) in [("in order", ordered), ("scrambled", scrambled)] {
                for &parallel in modes {
                    let on = if parallel {
                        "thread pool"
                    } else {
                        "one thread"
                    };
                    let ms = ms_per_step_on(&mut world.clone(), parallel, 60, 240);
                    println!("rain 10000 awake, added {name}, {on}: {ms:.2} ms/step");
                }
            }
        }
        "threads" => {
            // One thread against the pool (build with `--features parallel`).
            for parallel in [false, true] {
                let on = if parallel {
                    "thread pool"
                } else {
                    "one thread"
                };
                let mut w = with_sleeping(&rain_world(10_000), false);
                let ms = ms_per_step_on(&mut w, parallel, 60, 240);
                println!("rain 10000 awake, {on}: {ms:.2} ms/step");
                let mut w = with_sleeping(&pyramid_world(100), false);
                let ms = ms_per_step_on(&mut w, parallel, 60, 240);
                println!("pyramid 100 awake, {on}: {ms:.2} ms/step");
            }
        }
        "pool" => {
            // The rain of 10 000 on the pool alone, long enough to profile.
            let mut w = with_sleeping(&rain_world(10_000), false);
            let ms = ms_per_step_on(&mut w, true, 60, 1200);
            println!("rain 10000 awake, thread pool: {ms:.2} ms/step");
        }
        "rays" => {
            let mut w = rain_world(10_000);
            w.set_parallel(false);
            for _ in 0..120 {
                w.step(1.0 / 60.0);
            }
            let rays = passo_benches_rays();
            // A step, then a batch of rays (the first builds any index).
            w.step(1.0 / 60.0);
            let start = Instant::now();
            let hits = rays
                .iter()
                .filter(|(o, d)| w.ray_cast(*o, *d, 10.0).is_some())
                .count();
            let secs = start.elapsed().as_secs_f64();
            println!(
                "rays against 10000 (first batch after a step): {:.0} rays/s ({hits} hits)",
                rays.len() as f64 / secs
            );
        }
        "sleep" => {
            let w = rain_world(10_000);
            println!(
                "rain 10000 settled, sleeping: {:.3} ms/step",
                ms_per_step(w, 900, 300)
            );
        }
        "settle" => {
            // Sleeping on, while the rain lands and islands fall asleep
            // one after another (sleep bookkeeping at its busiest).
            let w = rain_world(10_000);
            println!(
                "rain 10000 settling, sleeping on (ticks 60-900): {:.3} ms/step",
                ms_per_step(w, 60, 840)
            );
            let w = pyramid_world(50);
            println!(
                "pyramid 50 settling, sleeping on (ticks 0-300): {:.3} ms/step",
                ms_per_step(w, 0, 300)
            );
        }
        "tuning" => {
            // Substeps, iterations and relax passes: cost (ticks 60-360 of
            // the pyramid, 60-300 of the rain) and the deepest overlap at
            // the end. `tuning 6,1,1` runs only those passes.
            for passes in chosen_passes() {
                let mut line = format!("{}:", passes.name());
                for (name, world, ticks) in [
                    ("pyramid 50", pyramid_world(50), 300),
                    ("rain 10000", rain_world(10_000), 240),
                ] {
                    let mut world = passes.applied(&with_sleeping(&world, false));
                    let ms = ms_per_step_on(&mut world, false, 60, ticks);
                    let overlap = world.max_penetration() * 1e3;
                    line += &format!(" {name} {ms:.3} ms/step, overlap {overlap:.2} mm;");
                }
                println!("{line}");
            }
        }
        "rest" => {
            // The same settings with sleeping on: the tick at which 99 % of
            // the dynamic bodies sleep (of 3 000 at most), from the start.
            for passes in chosen_passes() {
                let mut line = format!("{}:", passes.name());
                for (name, world) in [
                    ("busy scene", busy_world()),
                    ("pyramid 50", pyramid_world(50)),
                    ("rain 10000", rain_world(10_000)),
                ] {
                    let mut world = passes.applied(&world);
                    world.set_parallel(false);
                    let n = world.dynamic_len();
                    let asleep_at = (1..=3000).find(|_| {
                        world.step(1.0 / 60.0);
                        world.sleeping_len() * 100 >= n * 99
                    });
                    let at = asleep_at.map_or("never".to_string(), |t| format!("tick {t}"));
                    line += &format!(" {name} 99 % asleep at {at};");
                }
                println!("{line}");
            }
        }
        _ => {
            eprintln!(
                "usage: steps integration|rain|joints|pyramid|pyramid50|ticks|still|shuffled|sleep|settle|rays|threads|pool|tuning|rest"
            );
            std::process::exit(2);
        }
    }
}
