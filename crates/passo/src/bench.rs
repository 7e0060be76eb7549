//! `passo bench`: measurements that belong in benchmarks, not tests.

use anyhow::Result;
use glam::Vec2;
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
    }
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
