//! The interactive demo: a window (winit), the renderer (wgpu), a panel
//! (egui), and scenes driven by the fixed-timestep loop.

mod app;
pub mod replay;
pub mod sim;
mod ui;

use anyhow::{Result, bail};
use passo_scene::Scene;
use sim::Sim;
use std::path::PathBuf;

/// Options of `passo demo` (and of `passo` with no command).
#[derive(clap::Args, Debug, Clone, Default)]
pub struct DemoArgs {
    /// Scene to open first (see `passo scenes`; `integrators` too).
    #[arg(long)]
    pub scene: Option<String>,
    /// Run this many frames, then exit (for tests and recordings).
    #[arg(long)]
    pub frames: Option<u64>,
    /// With --frames: save the last presented frame as a PNG.
    #[arg(long, requires = "frames")]
    pub screenshot: Option<PathBuf>,
    /// Window size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x800", value_parser = crate::render_cmd::parse_size)]
    pub size: (u32, u32),
    /// Render on the software adapter (Mesa lavapipe).
    #[arg(long)]
    pub software: bool,
    /// Record the player's input and commands from the start, and save the
    /// replay to this file on exit.
    #[arg(long, conflicts_with = "replay")]
    pub record: Option<PathBuf>,
    /// Play this replay file in the window; with --frames, exit when it ends.
    #[arg(long)]
    pub replay: Option<PathBuf>,
    /// With --frames: resize the window, minimise it (0×0), restore it and
    /// inject a 400 ms frame along the way (for the window test).
    #[arg(long, hide = true, requires = "frames")]
    pub stress: bool,
}

/// A scene the demo's list offers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Entry {
    /// A scene file, by name or path.
    File(String),
    /// The side-by-side integrator comparison (built in code).
    Integrators,
}

/// The scene list: the showcase first, then every other built-in scene and
/// any extra file in `assets/scenes/`.
pub fn catalogue() -> Vec<(String, Entry)> {
    let showcase = ["playground", "rain", "stack", "pyramid", "drag_race"];
    let mut list: Vec<(String, Entry)> = showcase
        .iter()
        .map(|n| ((*n).to_owned(), Entry::File((*n).to_owned())))
        .collect();
    list.push(("integrators".into(), Entry::Integrators));
    for name in crate::scenes::names() {
        if !showcase.contains(&name) {
            list.push((name.to_owned(), Entry::File(name.to_owned())));
        }
    }
    if let Some(dir) = crate::scenes::assets_dir()
        && let Ok(entries) = std::fs::read_dir(dir)
    {
        let mut extra: Vec<String> = entries
            .filter_map(|e| {
                let path = e.ok()?.path();
                let stem = path.file_stem()?.to_string_lossy().into_owned();
                (path.extension()? == "ron").then_some(stem)
            })
            .filter(|n| !list.iter().any(|(l, _)| l == n))
            .collect();
        extra.sort();
        list.extend(extra.into_iter().map(|n| (n.clone(), Entry::File(n))));
    }
    list
}

/// Loads a scene of the list.
pub fn load(entry: &Entry) -> Result<Sim> {
    match entry {
        Entry::Integrators => Ok(Sim::integrators()),
        Entry::File(name) => {
            let scene: Scene = crate::scenes::load(name)?;
            let mut sim = Sim::from_scene(&scene)?;
            sim.entry_name = name.clone();
            Ok(sim)
        }
    }
}

/// Plays a replay headlessly, one tick after the other, and returns the
/// final state hash (which matches the recorded one if all is well).
pub fn run_replay(replay: &replay::Replay) -> Result<u64> {
    let mut sim = load(&entry_named(&replay.scene))?;
    sim.start_playback(replay.clone())?;
    for _ in 0..replay.ticks {
        sim.timestep.advance_ticks(1);
        sim.tick();
    }
    Ok(sim.state_hash())
}

/// The entry for a `--scene` value.
pub fn entry_named(name: &str) -> Entry {
    if name == "integrators" {
        Entry::Integrators
    } else {
        Entry::File(name.to_owned())
    }
}

/// Opens the demo window and runs until it is closed (or `--frames` ran).
pub fn run(args: DemoArgs) -> Result<()> {
    let first = entry_named(args.scene.as_deref().unwrap_or("playground"));
    // Load the scene before opening a window, so a bad name fails fast.
    let sim = load(&first)?;
    let no_display =
        std::env::var_os("DISPLAY").is_none() && std::env::var_os("WAYLAND_DISPLAY").is_none();
    let event_loop = match winit::event_loop::EventLoop::new() {
        Ok(event_loop) => event_loop,
        Err(e) => bail!(no_display_message(&e.to_string(), no_display)),
    };
    let mut app = app::App::new(args, sim, first);
    event_loop.run_app(&mut app)?;
    app.finish()
}

/// What to say when there is no display to open a window on.
pub fn no_display_message(detail: &str, no_display: bool) -> String {
    let why = if no_display {
        "no display: neither DISPLAY nor WAYLAND_DISPLAY is set".to_owned()
    } else {
        format!("cannot open a window ({detail})")
    };
    format!(
        "{why}. The demo needs a window; without one use the headless commands: \
         `passo simulate SCENE --ticks N`, `passo render SCENE --out FILE.png`, `passo bench`. \
         To run the demo on a machine without a screen, use a virtual one: `xvfb-run -a passo`."
    )
}
