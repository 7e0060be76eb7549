//! `passo bench physics|sleep|queries|platforms|tiles`: the collision
//! scenes, sleeping, ray casts, kinematic platforms and tile maps.

use super::args::{
    PhysicsBenchArgs, PlatformsBenchArgs, QueriesBenchArgs, SleepBenchArgs, TilesBenchArgs,
};
use anyhow::Result;
use glam::Vec2;
use passo_benches::{
    drive_sweepers, pyramid_world, rain_on_tile_map, rain_with_platforms, rain_world, rays,
    time_steps, time_steps_with, with_sleeping,
};
use passo_physics::{BodyKind, QueryFilter, World};
use std::time::Instant;

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

pub(super) fn physics(args: &PhysicsBenchArgs) -> Result<()> {
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

pub(super) fn sleep(args: &SleepBenchArgs) -> Result<()> {
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

pub(super) fn queries(args: &QueriesBenchArgs) -> Result<()> {
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

pub(super) fn platforms(args: &PlatformsBenchArgs) -> Result<()> {
    let (mut world, sweepers) = rain_with_platforms(
        args.bodies as usize,
        args.platforms as usize,
        args.length,
        args.above,
    );
    let mut tick = 0;
    let t = time_steps(args.ticks, || {
        drive_sweepers(&mut world, &sweepers, tick);
        world.step(1.0 / 60.0);
        tick += 1;
    });
    println!(
        "| bodies | kinematic platforms | platform length (m) | ticks | ms per step (mean) | ms per step (last fifth) | max penetration at the end (mm) |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|");
    println!(
        "| {} | {} | {} | {} | {:.2} | {:.2} | {:.1} |",
        world.dynamic_len() - sweepers.len(),
        sweepers.len(),
        args.length,
        args.ticks,
        t.mean_ms,
        t.last_ms,
        world.max_penetration() * 1e3
    );
    Ok(())
}

/// A benchmark scene of `n` bodies.
pub(super) type MakeWorld = fn(usize) -> World;

pub(super) fn tiles(args: &TilesBenchArgs) -> Result<()> {
    grounds(
        args,
        "static boxes",
        &[
            ("three static boxes", rain_world),
            ("1000 × 1000 tile map", rain_on_tile_map),
        ],
    )
}

/// `passo bench slopes`: the rain onto hilly ground of segments and of
/// boxes.
pub(super) fn slopes(args: &TilesBenchArgs) -> Result<()> {
    grounds(
        args,
        "static bodies",
        &[
            ("1000 segments (a chain)", |n| {
                passo_benches::rain_on_hills(n, false)
            }),
            ("1000 boxes", |n| passo_benches::rain_on_hills(n, true)),
        ],
    )
}

/// A rain onto each kind of ground of `scenes`, alternately, so both meet
/// the same machine; `statics` heads the column of static bodies.
fn grounds(args: &TilesBenchArgs, statics: &str, scenes: &[(&str, MakeWorld)]) -> Result<()> {
    println!(
        "| ground | {statics} | bodies | ticks | ms per step (mean) | ms per step (last fifth) | max penetration (mm) |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for _ in 0..args.rounds {
        for &(name, make) in scenes {
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
