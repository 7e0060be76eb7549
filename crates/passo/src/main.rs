//! `passo`: the interactive demo and the command-line tools of Passo.

use anyhow::Result;
use clap::{Parser, Subcommand};
use passo::{bench, demo, render_cmd, report, scenes, simulate};

/// Passo: 2D game physics on a fixed-timestep loop.
///
/// With no command, opens the interactive demo. The other commands run
/// without a window.
#[derive(Parser, Debug)]
#[command(name = "passo", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Open the interactive demo (the default when no command is given).
    Demo(demo::DemoArgs),
    /// Run a scene headlessly for N ticks; write CSV, print the state hash.
    Simulate(simulate::SimulateArgs),
    /// Simulate a scene headlessly, then render it off-screen to a PNG.
    Render(render_cmd::RenderArgs),
    /// Measure speed against error for every integrator and force model.
    Report(report::ReportArgs),
    /// Measure speed: collision scenes, off-screen rendering.
    Bench(bench::BenchArgs),
    /// List the built-in scenes.
    Scenes,
    /// Play a replay file headlessly; print the final state hash and check
    /// it against the recorded one.
    Replay {
        /// A replay saved by the demo (`passo demo --record FILE`, or the
        /// panel's record button).
        file: std::path::PathBuf,
    },
}

fn main() {
    // wgpu probes every backend; on a machine without a GL driver the EGL
    // probe logs a harmless error before Vulkan is chosen. RUST_LOG overrides.
    env_logger::Builder::from_env(
        env_logger::Env::default().default_filter_or("warn,wgpu_hal::gles::egl=off"),
    )
    .init();
    let cli = Cli::parse();
    if let Err(e) = run(cli) {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Some(Command::Simulate(args)) => simulate::run(&args),
        Some(Command::Render(args)) => render_cmd::run(&args),
        Some(Command::Bench(args)) => bench::run(&args),
        Some(Command::Report(args)) => report::run(&args),
        Some(Command::Scenes) => {
            for name in scenes::names() {
                let scene = scenes::load(name)?;
                println!("{name:16} {}", scene.file.description);
            }
            let (name, description) = scenes::INTEGRATORS;
            println!("{name:16} {description}");
            Ok(())
        }
        Some(Command::Demo(args)) => demo::run(args),
        Some(Command::Replay { file }) => {
            let replay = demo::Replay::load(&file)?;
            let hash = demo::run_replay(&replay)?;
            println!("{hash:016x}");
            if hash != replay.final_hash {
                anyhow::bail!(
                    "the replay ended in state {hash:016x}, not the recorded {:016x}",
                    replay.final_hash
                );
            }
            eprintln!(
                "{}: {} ticks, same final state as recorded",
                file.display(),
                replay.ticks
            );
            Ok(())
        }
        None => demo::run(demo::DemoArgs {
            size: (1280, 800),
            ..Default::default()
        }),
    }
}
