//! `passo bench`: measurements that belong in benchmarks, not tests.

use anyhow::Result;
use glam::Vec2;
use passo_physics::{BodyDef, Shape, World};
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
}

/// Options of `passo bench physics`.
#[derive(clap::Args, Debug)]
pub struct PhysicsBenchArgs {
    /// Rain sizes (bodies), comma separated.
    #[arg(long, value_delimiter = ',', default_value = "1000,10000,50000")]
    pub rain: Vec<usize>,
    /// Pyramid base widths, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "20")]
    pub pyramid: Vec<usize>,
    /// Ticks to run each scene at 60 Hz.
    #[arg(long, default_value_t = 300)]
    pub ticks: u32,
}

/// Options of `passo bench render`.
#[derive(clap::Args, Debug)]
pub struct RenderBenchArgs {
    /// Instance counts to measure, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "1000,10000,100000")]
    pub instances: Vec<usize>,
    /// Frames to time per count (after 3 warm-up frames).
    #[arg(long, default_value_t = 20)]
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
    }
}

/// Circles of radius 0.1 m raining into an open box: `n` bodies on a
/// jittered grid twice as wide as it is tall, 1 cm to 4 cm apart.
pub fn rain_world(n: usize) -> World {
    let mut world = World::default();
    let columns = ((2.0 * (n as f32).sqrt()).ceil() as usize).max(1);
    let rows = n.div_ceil(columns);
    let spacing = 0.25;
    let width = columns as f32 * spacing + 1.0;
    let height = rows as f32 * spacing + 5.0;
    let fixed = |w: &mut World, centre: Vec2, size: Vec2| {
        w.add_body(BodyDef::fixed(centre, Shape::rect(size.x, size.y)))
            .expect("valid wall");
    };
    fixed(
        &mut world,
        Vec2::new(0.0, -0.5),
        Vec2::new(width + 2.0, 1.0),
    );
    fixed(
        &mut world,
        Vec2::new(-width * 0.5 - 0.5, height * 0.5),
        Vec2::new(1.0, height),
    );
    fixed(
        &mut world,
        Vec2::new(width * 0.5 + 0.5, height * 0.5),
        Vec2::new(1.0, height),
    );
    let mut seed = 0x2545_F491_4F6C_DD1Du64;
    let mut jitter = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        ((seed >> 40) as f32 / (1u64 << 24) as f32 - 0.5) * 0.03
    };
    for k in 0..n {
        let (i, j) = (k % columns, k / columns);
        let p = Vec2::new(
            -width * 0.5 + 0.5 + (i as f32 + 0.5) * spacing + jitter(),
            0.5 + j as f32 * spacing + jitter(),
        );
        let def = BodyDef {
            position: p,
            shape: Some(Shape::circle(0.1)),
            mass: 0.1,
            ..Default::default()
        };
        world.add_body(def).expect("valid circle");
    }
    world
}

/// A pyramid of unit boxes with `base` boxes in the bottom row.
pub fn pyramid_world(base: usize) -> World {
    let mut world = World::default();
    world
        .add_body(BodyDef::fixed(
            Vec2::new(0.0, -0.5),
            Shape::rect(base as f32 * 2.0 + 10.0, 1.0),
        ))
        .expect("valid ground");
    for row in 0..base {
        for i in 0..base - row {
            let x = i as f32 - (base - row - 1) as f32 * 0.5;
            let def = BodyDef {
                position: Vec2::new(x, 0.5 + row as f32),
                shape: Some(Shape::rect(1.0, 1.0)),
                ..Default::default()
            };
            world.add_body(def).expect("valid box");
        }
    }
    world
}

/// Steps `world` `ticks` times at 60 Hz; returns the mean milliseconds per
/// step over all ticks and over the last fifth.
pub fn time_steps(world: &mut World, ticks: u32) -> (f64, f64) {
    let tail = (ticks / 5).max(1);
    let (mut all, mut last) = (0.0, 0.0);
    for t in 0..ticks {
        let start = Instant::now();
        world.step(1.0 / 60.0);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        all += ms;
        if t >= ticks - tail {
            last += ms;
        }
    }
    (all / f64::from(ticks.max(1)), last / f64::from(tail))
}

fn physics(args: &PhysicsBenchArgs) -> Result<()> {
    println!(
        "| scene | bodies | ms per step (mean of {} ticks) | ms per step (last {}) | max penetration (mm) |",
        args.ticks,
        (args.ticks / 5).max(1)
    );
    println!("|---|---:|---:|---:|---:|");
    let scenes = args
        .rain
        .iter()
        .map(|&n| (format!("rain {n}"), rain_world(n)))
        .chain(
            args.pyramid
                .iter()
                .map(|&b| (format!("pyramid {b}"), pyramid_world(b))),
        );
    for (name, mut world) in scenes {
        let (mean, last) = time_steps(&mut world, args.ticks);
        println!(
            "| {name} | {} | {mean:.2} | {last:.2} | {:.2} |",
            world.dynamic_len(),
            world.max_penetration() * 1e3
        );
    }
    Ok(())
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
