//! `passo bench`: measurements that belong in benchmarks, not tests.

use anyhow::Result;
use glam::Vec2;
use passo_benches::{
    drive_sweepers, exact_max_overlap, fast_circles_in_a_box, pyramid_world, rain_on_tile_map,
    rain_strip, rain_with_platforms, rain_world, rays, spawned_on_one_spot, time_steps,
    time_steps_with, with_sleeping,
};
use passo_physics::constants::LINEAR_SLOP;
use passo_physics::{BodyKind, QueryFilter, World};
use passo_render::{AdapterChoice, Camera2D, DrawList, Gpu, OffscreenTarget, Renderer};
use std::time::Instant;

/// Options of `passo bench`.
#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    #[command(subcommand)]
    pub what: BenchWhat,
}

/// What to measure.
#[derive(clap::Subcommand, Debug)]
pub enum BenchWhat {
    /// Off-screen frames per second for growing numbers of instances.
    Render(RenderBenchArgs),
    /// Collision scenes: rain of circles into a box, and pyramids.
    Physics(PhysicsBenchArgs),
    /// Integration alone (gravity + quadratic drag) against this machine's
    /// memory bandwidth.
    Integration(IntegrationBenchArgs),
    /// Step cost over growing sizes of a rain strip 20 rows deep (the
    /// same neighbourhood for every body), with the fitted exponent of cost
    /// against size.
    Scaling(ScalingBenchArgs),
    /// What a settled scene costs with sleeping on and off.
    Sleep(SleepBenchArgs),
    /// Ray casts per second against a settled rain, unfiltered and
    /// filtered, with and without a step between batches.
    Queries(QueriesBenchArgs),
    /// A rain with kinematic platforms sweeping through it.
    Platforms(PlatformsBenchArgs),
    /// A rain in a box drawn on a 1000 × 1000 tile map, against the same
    /// rain in a box of three static boxes.
    Tiles(TilesBenchArgs),
    /// Scenes that make work grow faster than the bodies: circles spawned
    /// on one spot, and fast circles in a closed box.
    Extreme(ExtremeBenchArgs),
    /// A long run of a busy scene: no NaN, and no memory growth.
    Soak(SoakBenchArgs),
    /// Saving and restoring snapshots into reused buffers, against a step.
    Rollback(RollbackBenchArgs),
}

/// Options of `passo bench rollback`.
#[derive(clap::Args, Debug)]
pub struct RollbackBenchArgs {
    /// Rain sizes, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "1000,10000", value_parser = crate::count_in(1, 1_000_000))]
    pub rain: Vec<usize>,
    /// Repetitions timed.
    #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub repeats: u32,
}

/// Options of `passo bench soak`.
#[derive(clap::Args, Debug)]
pub struct SoakBenchArgs {
    /// Ticks to run at 60 Hz.
    #[arg(long, default_value_t = 1_000_000, value_parser = clap::value_parser!(u64).range(1..=100_000_000))]
    pub ticks: u64,
    /// Circles in the rain.
    #[arg(long, default_value_t = 300, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub bodies: u32,
}

/// Options of `passo bench extreme`.
#[derive(clap::Args, Debug)]
pub struct ExtremeBenchArgs {
    /// Circles spawned on one spot.
    #[arg(long, default_value_t = 10_000, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub spawn: u32,
    /// Fast circles (100 to 500 m/s) in a closed 60 m × 30 m box.
    #[arg(long, default_value_t = 5_000, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub fast: u32,
    /// Circles in the rain stepped at 1 Hz.
    #[arg(long, default_value_t = 2_000, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub rain: u32,
    /// Ticks to run each 60 Hz scene.
    #[arg(long, default_value_t = 600, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub ticks: u32,
    /// Ticks to run the 1 Hz rain.
    #[arg(long, default_value_t = 60, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub slow_ticks: u32,
}

/// Options of `passo bench queries`.
#[derive(clap::Args, Debug)]
pub struct QueriesBenchArgs {
    /// Rain size (bodies).
    #[arg(long, default_value_t = 10_000, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub bodies: u32,
    /// Rays per batch.
    #[arg(long, default_value_t = 10_000, value_parser = clap::value_parser!(u32).range(1..=10_000_000))]
    pub rays: u32,
}

/// Options of `passo bench platforms`.
#[derive(clap::Args, Debug)]
pub struct TilesBenchArgs {
    /// Rain size (bodies).
    #[arg(long, default_value_t = 10_000, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub bodies: u32,
    /// Ticks to run at 60 Hz, each world in turn, this many rounds.
    #[arg(long, default_value_t = 300, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub ticks: u32,
    /// Rounds: the two worlds run alternately, so both meet the same
    /// machine.
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=100))]
    pub rounds: u32,
}

/// Options of `passo bench platforms`.
#[derive(clap::Args, Debug)]
pub struct PlatformsBenchArgs {
    /// Rain size (bodies).
    #[arg(long, default_value_t = 10_000, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub bodies: u32,
    /// Kinematic platforms.
    #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u32).range(0..=10_000))]
    pub platforms: u32,
    /// Ticks to run at 60 Hz.
    #[arg(long, default_value_t = 300, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub ticks: u32,
    /// Sweep the platforms above where the rain lands instead of through
    /// the pile (what the platforms cost, without what they stir up).
    #[arg(long)]
    pub above: bool,
}

/// Options of `passo bench sleep`.
#[derive(clap::Args, Debug)]
pub struct SleepBenchArgs {
    /// Rain sizes (bodies), comma separated.
    #[arg(long, value_delimiter = ',', default_value = "10000", value_parser = crate::count_in(1, 1_000_000))]
    pub rain: Vec<usize>,
    /// Pyramid base widths, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "50", value_parser = crate::count_in(1, 2_000))]
    pub pyramid: Vec<usize>,
    /// Simulated seconds to let each scene settle first.
    #[arg(long, default_value_t = 15, value_parser = clap::value_parser!(u32).range(0..=3_600))]
    pub settle: u32,
    /// Ticks timed after settling, each way.
    #[arg(long, default_value_t = 120, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub ticks: u32,
}

/// Options of `passo bench integration`.
#[derive(clap::Args, Debug)]
pub struct IntegrationBenchArgs {
    /// Body counts, comma separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "1000,10000,100000,1000000",
        value_parser = crate::count_in(1, 100_000_000)
    )]
    pub sizes: Vec<usize>,
}

/// Options of `passo bench scaling`.
#[derive(clap::Args, Debug)]
pub struct ScalingBenchArgs {
    /// Rain sizes, comma separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "1000,2000,5000,10000,20000,50000,100000",
        value_parser = crate::count_in(1, 10_000_000)
    )]
    pub sizes: Vec<usize>,
    /// Ticks per size; the mean of the last two thirds is kept.
    #[arg(long, default_value_t = 180, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub ticks: u32,
}

/// Options of `passo bench physics`.
#[derive(clap::Args, Debug)]
pub struct PhysicsBenchArgs {
    /// Rain sizes (bodies), comma separated.
    #[arg(long, value_delimiter = ',', default_value = "1000,10000,50000", value_parser = crate::count_in(1, 1_000_000))]
    pub rain: Vec<usize>,
    /// Pyramid base widths, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "20", value_parser = crate::count_in(1, 2_000))]
    pub pyramid: Vec<usize>,
    /// Ticks to run each scene at 60 Hz.
    #[arg(long, default_value_t = 300, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub ticks: u32,
}

/// Options of `passo bench render`.
#[derive(clap::Args, Debug)]
pub struct RenderBenchArgs {
    /// Instance counts to measure, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "1000,10000,100000", value_parser = crate::count_in(1, 10_000_000))]
    pub instances: Vec<usize>,
    /// Frames to time per count (after 3 warm-up frames).
    #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub frames: u32,
    /// Picture size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x720", value_parser = crate::render_cmd::parse_size)]
    pub size: (u32, u32),
    /// Use the software adapter (Mesa lavapipe).
    #[arg(long)]
    pub software: bool,
}

/// Runs `passo bench`.
pub fn run(args: &BenchArgs) -> Result<()> {
    match &args.what {
        BenchWhat::Render(a) => render(a),
        BenchWhat::Physics(a) => physics(a),
        BenchWhat::Integration(a) => integration(a),
        BenchWhat::Scaling(a) => scaling(a),
        BenchWhat::Sleep(a) => sleep(a),
        BenchWhat::Queries(a) => queries(a),
        BenchWhat::Platforms(a) => platforms(a),
        BenchWhat::Tiles(a) => tiles(a),
        BenchWhat::Extreme(a) => extreme(a),
        BenchWhat::Soak(a) => soak(a),
        BenchWhat::Rollback(a) => rollback(a),
    }
}

/// Bytes the integration kernel moves per body-step: it reads position,
/// velocity, force (8 bytes each), inverse mass and drag area (4 each), and
/// writes position and velocity (8 each) and the cleared force (8).
pub const INTEGRATION_BYTES: f64 = 64.0;

/// Best-of-five memory bandwidth of a plain copy over `bytes` bytes, bytes
/// per second (counting what is read and what is written).
pub fn copy_bandwidth(bytes: usize) -> f64 {
    let src = vec![1u8; bytes];
    let mut dst = vec![0u8; bytes];
    let reps = (200_000_000 / bytes.max(1)).clamp(3, 10_000);
    (0..5)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..reps {
                dst.copy_from_slice(std::hint::black_box(&src));
                std::hint::black_box(&mut dst);
            }
            2.0 * bytes as f64 * reps as f64 / start.elapsed().as_secs_f64()
        })
        .fold(0.0, f64::max)
}

/// Best-of-five bandwidth of the STREAM triad `a = b + s c` over three f32
/// arrays of `len` elements, bytes per second.
pub fn triad_bandwidth(len: usize) -> f64 {
    let b = vec![1.0f32; len];
    let c = vec![2.0f32; len];
    let mut a = vec![0.0f32; len];
    let reps = (50_000_000 / len.max(1)).clamp(3, 10_000);
    (0..5)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..reps {
                for ((a, b), c) in a.iter_mut().zip(std::hint::black_box(&b)).zip(&c) {
                    *a = b + 3.0 * c;
                }
                std::hint::black_box(&mut a);
            }
            12.0 * len as f64 * reps as f64 / start.elapsed().as_secs_f64()
        })
        .fold(0.0, f64::max)
}

/// Nanoseconds per body-step of `n` point masses under gravity and
/// quadratic drag (the best of five timed runs), on the calling thread
/// alone or (`parallel`) on the thread pool for large worlds.
pub fn integration_ns(n: usize, parallel: bool) -> f64 {
    let mut world = passo_physics::World::new(passo_physics::WorldSettings {
        forces: passo_physics::ForceModels {
            quadratic_drag: Some(passo_physics::QuadraticDrag::default()),
            ..Default::default()
        },
        ..Default::default()
    })
    .expect("valid settings");
    for i in 0..n {
        let def = passo_physics::BodyDef {
            position: Vec2::new((i % 1000) as f32, (i / 1000) as f32),
            velocity: Vec2::new(3.0, 1.0),
            ..Default::default()
        };
        world.add_body(def).expect("valid body");
    }
    world.set_parallel(parallel);
    let steps = (20_000_000 / n.max(1)).clamp(5, 20_000);
    world.step(1.0 / 60.0);
    (0..5)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..steps {
                world.step(1.0 / 60.0);
            }
            start.elapsed().as_nanos() as f64 / (n * steps) as f64
        })
        .fold(f64::INFINITY, f64::min)
}

/// Nanoseconds per body-step of a bare structure-of-arrays loop doing the
/// arithmetic of [`integration_ns`]'s step (gravity, the accumulated force,
/// stable quadratic drag, the non-finite guard and subnormal flush, the
/// world's default speed limits, the position, the force cleared) on `n`
/// bodies, best of five: what the step would cost with nothing around the
/// arithmetic.
pub fn bare_soa_ns(n: usize) -> f64 {
    let (mut px, mut py) = (vec![0.0f32; n], vec![0.0f32; n]);
    let (mut vx, mut vy) = (vec![3.0f32; n], vec![1.0f32; n]);
    let (mut fx, mut fy) = (vec![0.0f32; n], vec![0.0f32; n]);
    let inv_mass = vec![1.0f32; n];
    let drag_area = vec![passo_physics::constants::DEFAULT_DRAG_AREA; n];
    let (g, dt) = (-9.81f32, 1.0f32 / 60.0);
    let (min, max) = (
        passo_physics::constants::DEFAULT_MIN_SPEED,
        passo_physics::constants::DEFAULT_MAX_SPEED,
    );
    let half_rho = 0.5 * passo_physics::QuadraticDrag::default().density;
    let steps = (20_000_000 / n.max(1)).clamp(5, 20_000);
    let mut step = || {
        // Equal lengths, so the compiler drops the bounds checks and can
        // vectorise the loop.
        let (px, py, vx, vy) = (&mut px[..n], &mut py[..n], &mut vx[..n], &mut vy[..n]);
        let (fx, fy, inv_mass, drag_area) =
            (&mut fx[..n], &mut fy[..n], &inv_mass[..n], &drag_area[..n]);
        for i in 0..n {
            let im = inv_mass[i];
            let mut x = vx[i] + fx[i] * im * dt;
            let mut y = vy[i] + (g + fy[i] * im) * dt;
            let k = half_rho * drag_area[i] * im;
            let scale = 1.0 / (1.0 + k * (x * x + y * y).sqrt() * dt);
            x *= scale;
            y *= scale;
            let finite = (x * x + y * y).is_finite();
            let flush = |c: f32| if c.abs() < f32::MIN_POSITIVE { 0.0 } else { c };
            x = if finite { flush(x) } else { 0.0 };
            y = if finite { flush(y) } else { 0.0 };
            // The speed limits: clamp to the maximum, snap below the minimum.
            let s2 = x * x + y * y;
            let clamp = if s2 > max * max { max / s2.sqrt() } else { 1.0 };
            let keep = if s2 < min * min { 0.0 } else { clamp };
            x *= keep;
            y *= keep;
            vx[i] = x;
            vy[i] = y;
            px[i] += x * dt;
            py[i] += y * dt;
            fx[i] = 0.0;
            fy[i] = 0.0;
        }
        std::hint::black_box((px, py));
    };
    step();
    (0..5)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..steps {
                step();
            }
            start.elapsed().as_nanos() as f64 / (n * steps) as f64
        })
        .fold(f64::INFINITY, f64::min)
}

fn integration(args: &IntegrationBenchArgs) -> Result<()> {
    // One thread against one thread: the copy and triad loops run on the
    // calling thread, and so does the kernel for the fraction; the last
    // column is the same step with the thread pool (large worlds only).
    println!(
        "| bodies | ns per body-step | bare SoA loop, ns | step / bare loop | kernel bandwidth | copy bandwidth | triad bandwidth | fraction of copy | ns per body-step, thread pool |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for &n in &args.sizes {
        let ns = integration_ns(n, false);
        let bare = bare_soa_ns(n);
        let kernel = INTEGRATION_BYTES / ns; // bytes per ns = GB/s
        let copy = copy_bandwidth(n * 32) / 1e9;
        let triad = triad_bandwidth(n * 8) / 1e9;
        let pooled = integration_ns(n, true);
        println!(
            "| {n} | {ns:.2} | {bare:.2} | {:.2}× | {kernel:.1} GB/s | {copy:.1} GB/s | {triad:.1} GB/s | {:.0} % | {pooled:.2} |",
            ns / bare,
            100.0 * kernel / copy
        );
    }
    Ok(())
}

/// The exponent `k` of the least-squares fit `cost = c n^k`.
pub fn fitted_exponent(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let logs: Vec<(f64, f64)> = points.iter().map(|(x, y)| (x.ln(), y.ln())).collect();
    let (mx, my) = logs
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (sxy, sxx) = logs.iter().fold((0.0, 0.0), |(a, b), (x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx) * (x - mx))
    });
    sxy / sxx
}

fn scaling(args: &ScalingBenchArgs) -> Result<()> {
    println!("| bodies | ms per step | µs per body-step |");
    println!("|---:|---:|---:|");
    let mut points = Vec::new();
    for &n in &args.sizes {
        let mut world = rain_strip(n);
        let warm = args.ticks / 3;
        for _ in 0..warm {
            world.step(1.0 / 60.0);
        }
        let t = time_steps(args.ticks - warm, || world.step(1.0 / 60.0));
        println!(
            "| {n} | {:.2} | {:.3} |",
            t.mean_ms,
            t.mean_ms * 1e3 / n as f64
        );
        points.push((n as f64, t.mean_ms));
    }
    println!(
        "\nfitted exponent of ms per step against bodies: {:.3}",
        fitted_exponent(&points)
    );
    Ok(())
}

/// The benchmark scenes, named: rains of the given sizes, then pyramids of
/// the given base widths.
fn scenes<'a>(
    rain: &'a [usize],
    pyramid: &'a [usize],
) -> impl Iterator<Item = (String, passo_physics::World)> + 'a {
    let rains = rain.iter().map(|&n| (format!("rain {n}"), rain_world(n)));
    rains.chain(
        pyramid
            .iter()
            .map(|&b| (format!("pyramid {b}"), pyramid_world(b))),
    )
}

fn physics(args: &PhysicsBenchArgs) -> Result<()> {
    println!(
        "| scene | bodies | ms per step (mean of {} ticks) | ms per step (last {}) | max penetration at the end (mm) | worst of every 30th tick (mm) |",
        args.ticks,
        (args.ticks / 5).max(1)
    );
    println!("|---|---:|---:|---:|---:|---:|");
    let scenes = scenes(&args.rain, &args.pyramid);
    for (name, world) in scenes {
        // Penetration is sampled between timed steps, outside the timing.
        let worst = std::cell::Cell::new(0.0f32);
        let world = std::cell::RefCell::new(world);
        let t = time_steps_with(
            args.ticks,
            || world.borrow_mut().step(1.0 / 60.0),
            |tick| {
                if tick % 30 == 29 {
                    worst.set(worst.get().max(world.borrow().max_penetration()));
                }
            },
        );
        let (world, worst) = (world.into_inner(), worst.get());
        let end = world.max_penetration();
        println!(
            "| {name} | {} | {:.2} | {:.2} | {:.2} | {:.2} |",
            world.dynamic_len(),
            t.mean_ms,
            t.last_ms,
            end * 1e3,
            worst.max(end) * 1e3
        );
    }
    Ok(())
}

fn sleep(args: &SleepBenchArgs) -> Result<()> {
    println!(
        "| scene | bodies | asleep after {} s | ms per step, sleeping on | ms per step, sleeping off | ratio |",
        args.settle
    );
    println!("|---|---:|---:|---:|---:|---:|");
    let scenes = scenes(&args.rain, &args.pyramid);
    for (name, mut world) in scenes {
        for _ in 0..args.settle * 60 {
            world.step(1.0 / 60.0);
        }
        let asleep = world.sleeping_len();
        // Each timed world starts from the settled state with its own
        // setting; the awake one first re-solves everything for a second.
        let mut on = with_sleeping(&world, true);
        let mut off = with_sleeping(&world, false);
        for _ in 0..60 {
            on.step(1.0 / 60.0);
            off.step(1.0 / 60.0);
        }
        let t_on = time_steps(args.ticks, || on.step(1.0 / 60.0)).mean_ms;
        let t_off = time_steps(args.ticks, || off.step(1.0 / 60.0)).mean_ms;
        println!(
            "| {name} | {} | {asleep} | {t_on:.2} | {t_off:.2} | {:.1}× |",
            world.dynamic_len(),
            t_off / t_on
        );
    }
    Ok(())
}

fn queries(args: &QueriesBenchArgs) -> Result<()> {
    let mut world = rain_world(args.bodies as usize);
    for _ in 0..120 {
        world.step(1.0 / 60.0);
    }
    let rays = rays(
        Vec2::new(-20.0, 0.0),
        Vec2::new(20.0, 15.0),
        args.rays as usize,
    );
    let player = world
        .bodies()
        .find(|b| b.kind == BodyKind::Dynamic)
        .map(|b| b.id);
    let solid = match player {
        Some(id) => QueryFilter::solid().excluding(id),
        None => QueryFilter::solid(),
    };
    let batch = |world: &World, filter: &QueryFilter| {
        let start = Instant::now();
        let hits = rays
            .iter()
            .filter(|(o, d)| world.ray_cast_with(*o, *d, 10.0, filter).is_some())
            .count();
        (start.elapsed().as_secs_f64(), hits)
    };
    println!(
        "{} bodies, {} rays of up to 10 m per batch",
        world.len(),
        rays.len()
    );
    println!("| batch | rays per second | µs per ray | hits |");
    println!("|---|---:|---:|---:|");
    // The first batch after a step builds the moving bodies' tree.
    world.step(1.0 / 60.0);
    let (first, hits) = batch(&world, &QueryFilter::default());
    let (again, _) = batch(&world, &QueryFilter::default());
    let (filtered, filtered_hits) = batch(&world, &solid);
    let n = rays.len() as f64;
    for (name, secs, hits) in [
        ("first after a step (tree built)", first, hits),
        ("again, same step", again, hits),
        (
            "filtered: solid, excluding one body",
            filtered,
            filtered_hits,
        ),
    ] {
        println!(
            "| {name} | {:.0} | {:.2} | {hits} |",
            n / secs,
            secs / n * 1e6
        );
    }
    Ok(())
}

fn platforms(args: &PlatformsBenchArgs) -> Result<()> {
    let (mut world, sweepers) =
        rain_with_platforms(args.bodies as usize, args.platforms as usize, args.above);
    let mut tick = 0;
    let t = time_steps(args.ticks, || {
        drive_sweepers(&mut world, &sweepers, tick);
        world.step(1.0 / 60.0);
        tick += 1;
    });
    println!(
        "| bodies | kinematic platforms | ticks | ms per step (mean) | ms per step (last fifth) | max penetration at the end (mm) |"
    );
    println!("|---:|---:|---:|---:|---:|---:|");
    println!(
        "| {} | {} | {} | {:.2} | {:.2} | {:.1} |",
        world.dynamic_len() - sweepers.len(),
        sweepers.len(),
        args.ticks,
        t.mean_ms,
        t.last_ms,
        world.max_penetration() * 1e3
    );
    Ok(())
}

/// A benchmark scene of `n` bodies.
type MakeWorld = fn(usize) -> World;

fn tiles(args: &TilesBenchArgs) -> Result<()> {
    println!(
        "| ground | static boxes | bodies | ticks | ms per step (mean) | ms per step (last fifth) | max penetration (mm) |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    let scenes: [(&str, MakeWorld); 2] = [
        ("three static boxes", rain_world),
        ("1000 × 1000 tile map", rain_on_tile_map),
    ];
    for _ in 0..args.rounds {
        for (name, make) in scenes {
            let mut world = make(args.bodies as usize);
            let statics = world
                .bodies()
                .filter(|b| b.kind == BodyKind::Static)
                .count();
            let t = time_steps(args.ticks, || world.step(1.0 / 60.0));
            println!(
                "| {name} | {statics} | {} | {} | {:.2} | {:.2} | {:.1} |",
                args.bodies,
                args.ticks,
                t.mean_ms,
                t.last_ms,
                world.max_penetration() * 1e3
            );
        }
    }
    Ok(())
}

fn extreme(args: &ExtremeBenchArgs) -> Result<()> {
    println!(
        "| scene | bodies | step | ticks | ms per tick (mean) | ms per tick (last fifth) | peak memory (MB) | max overlap at the end (mm) | apart after (s) | escaped |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let in_box = |b: &passo_physics::Body| b.position.x.abs() > 31.0 || b.position.y.abs() > 16.0;
    // (name, scene, bodies, rate in Hz, ticks, what escaping means)
    type Escaped = Option<fn(&passo_physics::Body) -> bool>;
    let scenes: [(&str, MakeWorld, u32, u32, u32, Escaped); 3] = [
        (
            "spawned on one spot",
            spawned_on_one_spot,
            args.spawn,
            60,
            args.ticks,
            None,
        ),
        (
            "fast circles in a box",
            fast_circles_in_a_box,
            args.fast,
            60,
            args.ticks,
            Some(in_box),
        ),
        (
            "rain at 1 Hz",
            rain_world,
            args.rain,
            1,
            args.slow_ticks,
            None,
        ),
    ];
    for (name, make, n, hz, ticks, escaped) in scenes {
        reset_peak_memory();
        let mut world = make(n as usize);
        let dt = 1.0 / hz as f32;
        let (mut total, mut last, mut apart) = (0.0, 0.0, None);
        let tail = (ticks / 5).max(1);
        for tick in 1..=ticks {
            let crowded = world.stats().crowded_steps;
            let started = Instant::now();
            world.step(dt);
            let ms = started.elapsed().as_secs_f64() * 1e3;
            total += ms;
            if tick > ticks - tail {
                last += ms;
            }
            // Once a simulated second, when no bucket was crowded (the
            // exact check costs n² on a pile), note when all are apart.
            let second = tick % hz == 0 && world.stats().crowded_steps == crowded;
            if apart.is_none() && second && exact_max_overlap(&world) <= 2.0 * LINEAR_SLOP {
                apart = Some(tick / hz);
            }
        }
        let escaped = escaped.map_or("–".to_owned(), |out| {
            let dynamic = world.bodies().filter(|b| b.kind == BodyKind::Dynamic);
            dynamic.filter(out).count().to_string()
        });
        println!(
            "| {name} | {n} | 1/{hz} s | {ticks} | {:.2} | {:.2} | {} | {:.1} | {} | {escaped} |",
            total / f64::from(ticks),
            last / f64::from(tail),
            peak_memory_mb().map_or("n/a".to_owned(), |mb| format!("{mb:.0}")),
            exact_max_overlap(&world) * 1e3,
            apart.map_or("not yet".to_owned(), |s| s.to_string()),
        );
    }
    Ok(())
}

fn soak(args: &SoakBenchArgs) -> Result<()> {
    // A rain with two sweeping platforms; every 600 ticks one circle is
    // removed and another thrown in fast, and the world is snapshotted and
    // restored, so every path of the step keeps running.
    let (mut world, sweepers) = rain_with_platforms(args.bodies as usize, 2, false);
    let started = Instant::now();
    let mut memory_at_10k = None;
    let mut thrown = 0u64;
    for tick in 0..args.ticks {
        drive_sweepers(&mut world, &sweepers, (tick % 240) as u32);
        if tick % 600 == 599 {
            let victim = world
                .bodies()
                .filter(|b| b.kind == BodyKind::Dynamic)
                .nth((tick / 600) as usize % args.bodies as usize)
                .map(|b| b.id);
            if let Some(id) = victim {
                world.remove_body(id);
            }
            let def = passo_physics::BodyDef::new_dynamic(
                Vec2::new(0.0, 20.0),
                passo_physics::Shape::circle(0.1),
            )
            .with_velocity(Vec2::new(((tick / 600) % 7) as f32 * 10.0 - 30.0, -60.0));
            world.add_body(def)?;
            thrown += 1;
            let snapshot = world.snapshot();
            world.restore(snapshot)?;
        }
        world.step(1.0 / 60.0);
        if tick % 10_000 == 9_999 {
            if world
                .bodies()
                .any(|b| !(b.position.is_finite() && b.velocity.is_finite()))
            {
                anyhow::bail!("a non-finite body at tick {}", tick + 1);
            }
            if tick + 1 == 10_000 {
                memory_at_10k = peak_memory_mb();
            }
        }
    }
    let stats = world.stats();
    let mb = |m: Option<f64>| m.map_or("n/a".to_owned(), |mb| format!("{mb:.1}"));
    println!(
        "| ticks | bodies | bodies thrown in | seconds | peak memory at tick 10 000 (MB) | peak memory at the end (MB) | non-finite resets | crowded steps |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|");
    println!(
        "| {} | {} | {thrown} | {:.0} | {} | {} | {} | {} |",
        args.ticks,
        world.len(),
        started.elapsed().as_secs_f64(),
        mb(memory_at_10k),
        mb(peak_memory_mb()),
        stats.non_finite_resets,
        stats.crowded_steps
    );
    Ok(())
}

fn rollback(args: &RollbackBenchArgs) -> Result<()> {
    println!(
        "| bodies | save, µs | load, µs | step, µs | save + load / step | rollback of 8 ticks, ms |"
    );
    println!("|---:|---:|---:|---:|---:|---:|");
    for &n in &args.rain {
        let mut world = rain_world(n);
        world.set_parallel(false);
        // Half a second in: the rain falls, awake, in contact.
        for _ in 0..30 {
            world.step(1.0 / 60.0);
        }
        let mut saved = passo_physics::WorldSnapshot::default();
        world.snapshot_into(&mut saved);
        world.restore_from(&saved)?;
        let reps = args.repeats;
        let time = |f: &mut dyn FnMut()| {
            let start = Instant::now();
            for _ in 0..reps {
                f();
            }
            start.elapsed().as_secs_f64() * 1e6 / f64::from(reps)
        };
        let save = time(&mut || world.snapshot_into(&mut saved));
        let mut result = Ok(());
        let load = time(&mut || {
            if let Err(e) = world.restore_from(&saved) {
                result = Err(e);
            }
        });
        result?;
        // A step from the saved state, restored each time.
        let mut step_sum = 0.0;
        for _ in 0..reps.min(50) {
            world.restore_from(&saved)?;
            let start = Instant::now();
            world.step(1.0 / 60.0);
            step_sum += start.elapsed().as_secs_f64() * 1e6;
        }
        let step = step_sum / f64::from(reps.min(50));
        let start = Instant::now();
        world.restore_from(&saved)?;
        for _ in 0..8 {
            world.step(1.0 / 60.0);
        }
        let roll = start.elapsed().as_secs_f64() * 1e3;
        println!(
            "| {n} | {save:.1} | {load:.1} | {step:.0} | {:.1} % | {roll:.2} |",
            (save + load) / step * 100.0
        );
    }
    Ok(())
}

/// Starts a new peak of resident memory (Linux: `/proc/self/clear_refs`).
fn reset_peak_memory() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

/// The peak resident memory since the last reset, MB (Linux only).
fn peak_memory_mb() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

fn render(args: &RenderBenchArgs) -> Result<()> {
    let choice = if args.software {
        AdapterChoice::Software
    } else {
        AdapterChoice::from_env()?
    };
    let gpu = Gpu::headless(choice)?;
    let target = OffscreenTarget::new(&gpu, args.size.0, args.size.1);
    let mut renderer = Renderer::new(&gpu, target.format());
    let camera = Camera2D::fit(Vec2::ZERO, Vec2::new(160.0, 90.0), target.size());
    println!("adapter: {}", gpu.adapter_summary());
    println!("| instances | frames | ms per frame | frames per second |");
    println!("|---:|---:|---:|---:|");
    let mut list = DrawList::default();
    for &n in &args.instances {
        list.clear([24, 26, 32, 255]);
        // Half circles, half boxes, spread over the view with a golden-ratio walk.
        for i in 0..n {
            let t = i as f32 * 0.618_034;
            let p = Vec2::new(t.fract() * 160.0, (i as f32 / n.max(1) as f32) * 90.0);
            let colour = [(i * 37 % 256) as u8, (i * 91 % 256) as u8, 200, 255];
            if i % 2 == 0 {
                list.circle(p, 0.4, colour);
            } else {
                list.rect(p, Vec2::splat(0.35), colour);
            }
        }
        let frame = |renderer: &mut Renderer| {
            renderer.render(target.view(), target.size(), &camera, &list);
            gpu.device.poll(wgpu::PollType::wait_indefinitely())
        };
        for _ in 0..3 {
            frame(&mut renderer)?;
        }
        let start = Instant::now();
        for _ in 0..args.frames {
            frame(&mut renderer)?;
        }
        let secs = start.elapsed().as_secs_f64();
        let per = secs / f64::from(args.frames.max(1));
        println!(
            "| {n} | {} | {:.2} | {:.1} |",
            args.frames,
            per * 1e3,
            1.0 / per
        );
    }
    Ok(())
}
