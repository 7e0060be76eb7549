//! `passo simulate`: run a scene headlessly for a number of ticks.

use crate::progress::Progress;
use crate::snapshot::GameSnapshot;
use anyhow::{Context, Result};
use passo_loop::FixedTimestep;
use passo_physics::World;
use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

/// Options of `passo simulate`.
#[derive(clap::Args, Debug)]
pub struct SimulateArgs {
    /// Scene name (see `passo scenes`) or path to a .ron file.
    pub scene: String,
    /// Fixed ticks to run.
    #[arg(long, default_value_t = 600, value_parser = clap::value_parser!(u64).range(0..=1_000_000_000))]
    pub ticks: u64,
    /// Write `tick,body,x,y,vx,vy` rows to this CSV file.
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Write a CSV row set every this many ticks (and at tick 0 and the last).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
    pub every: u64,
    /// Print the 64-bit hash of the final state (equal bits, equal hash).
    #[arg(long)]
    pub hash: bool,
    /// Start from this snapshot (world and loop) instead of the scene's
    /// first state.
    #[arg(long)]
    pub resume: Option<PathBuf>,
    /// After the run, save a snapshot (`.ron`: readable; else binary).
    #[arg(long, value_parser = crate::render_cmd::output_path)]
    pub save: Option<PathBuf>,
}

/// Runs `passo simulate`.
pub fn run(args: &SimulateArgs) -> Result<()> {
    let scene = crate::scenes::load(&args.scene)?;
    let mut built = scene.build()?;
    let mut timestep = FixedTimestep::from_hz(scene.file.rate_hz)?;
    if let Some(path) = &args.resume {
        let snapshot = GameSnapshot::load(path)?;
        snapshot
            .check_scene(&scene.file.name)
            .with_context(|| path.display().to_string())?;
        let (world, resumed) = snapshot.restore()?;
        built.world = world;
        // The platforms go on from the snapshot's tick.
        built.tick = resumed.tick();
        timestep = resumed;
    }
    let dt = timestep.dt();
    // A resumed run is the snapshot's world at the snapshot's rate.
    let resumed = args.resume.as_ref().map_or(String::new(), |p| {
        format!(" (resumed from {})", p.display())
    });
    eprintln!(
        "{}{resumed}: {} bodies, {} Hz, stages: {:?}",
        scene.file.name,
        built.world.len(),
        rate(timestep.hz()),
        built.world.active_stages()
    );

    let mut csv = match &args.csv {
        Some(path) => {
            let file = std::fs::File::create(path)
                .with_context(|| format!("cannot create {}", path.display()))?;
            let mut w = std::io::BufWriter::new(file);
            writeln!(w, "tick,body,x,y,vx,vy")?;
            write_rows(&mut w, &built.world, 0)?;
            Some(w)
        }
        None => None,
    };

    let started = Instant::now();
    let mut progress = Progress::new("simulating", args.ticks);
    let first = timestep.tick();
    for tick in 1..=args.ticks {
        // The loop counts the tick too, so a saved snapshot's tick follows
        // the world (a resumed run goes on from the snapshot's tick).
        timestep.advance_ticks(1);
        built.step(dt);
        if let Some(w) = &mut csv
            && (tick % args.every == 0 || tick == args.ticks)
        {
            write_rows(w, &built.world, tick)?;
        }
        progress.set(tick);
    }
    progress.finish();
    if let Some(mut w) = csv {
        w.flush()?;
    }
    debug_assert_eq!(timestep.tick() - first, args.ticks);
    let world = &built.world;
    if let Some(path) = &args.save {
        let snapshot = GameSnapshot {
            scene: Some(scene.file.name.clone()),
            ..GameSnapshot::capture(world, &timestep)
        };
        snapshot.save(path)?;
    }
    let wall = started.elapsed();
    eprintln!(
        "{} ticks ({:.3} s simulated) in {:.3} s ({:.1} µs per tick)",
        args.ticks,
        args.ticks as f64 * timestep.step().as_secs_f64(),
        wall.as_secs_f64(),
        wall.as_secs_f64() * 1e6 / args.ticks.max(1) as f64
    );
    let stats = world.stats();
    if stats.non_finite_resets > 0 {
        eprintln!(
            "warning: {} body-steps produced a non-finite velocity and were dropped \
             (the body stood still that step); a force model or a force overflowed",
            stats.non_finite_resets
        );
    }
    if args.hash {
        println!("{:016x}", world.state_hash());
    }
    Ok(())
}

/// A rate for people: to a thousandth of a hertz, without trailing zeros
/// (the step is whole nanoseconds, so 60 Hz is 59.999999 Hz to six places).
fn rate(hz: f64) -> String {
    let text = format!("{hz:.3}");
    text.trim_end_matches('0').trim_end_matches('.').to_owned()
}

fn write_rows(w: &mut impl Write, world: &World, tick: u64) -> std::io::Result<()> {
    for b in world.bodies() {
        writeln!(
            w,
            "{tick},{},{},{},{},{}",
            b.id.index(),
            b.position.x,
            b.position.y,
            b.velocity.x,
            b.velocity.y
        )?;
    }
    Ok(())
}
