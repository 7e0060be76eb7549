//! `passo bench extreme|soak|rollback`: scenes that make work grow faster
//! than the bodies, long runs, and snapshots against a step.

use super::args::{ExtremeBenchArgs, RollbackBenchArgs, SoakBenchArgs};
use super::scenes::MakeWorld;
use anyhow::Result;
use glam::Vec2;
use passo_benches::{
    drive_sweepers, exact_max_overlap, fast_circles_in_a_box, rain_with_platforms, rain_world,
    spawned_on_one_spot,
};
use passo_physics::BodyKind;
use passo_physics::constants::LINEAR_SLOP;
use std::time::Instant;

pub(super) fn extreme(args: &ExtremeBenchArgs) -> Result<()> {
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

pub(super) fn soak(args: &SoakBenchArgs) -> Result<()> {
    // A rain with two sweeping platforms; every 600 ticks one circle is
    // removed and another thrown in fast, and the world is snapshotted and
    // restored, so every path of the step keeps running.
    let (mut world, sweepers) = rain_with_platforms(args.bodies as usize, 2, 4.0, false);
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

pub(super) fn rollback(args: &RollbackBenchArgs) -> Result<()> {
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
