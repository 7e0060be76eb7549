//! `passo bench render`: off-screen frames per second.

use super::args::RenderBenchArgs;
use anyhow::Result;
use glam::Vec2;
use passo_render::{AdapterChoice, Camera2D, DrawList, Gpu, OffscreenTarget, Renderer};
use std::time::Instant;

pub(super) fn render(args: &RenderBenchArgs) -> Result<()> {
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
