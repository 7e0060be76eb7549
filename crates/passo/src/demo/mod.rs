//! The interactive demo: a window (winit), the renderer (wgpu), a panel
//! (egui), and scenes driven by the fixed-timestep loop.
//!
//! The files, each one concept, from the window down (a file imports only
//! those below it):
//! - `web` (in a browser only): starting the demo on a page.
//! - `app`: the window, its events and the frame loop; `passo demo`'s options.
//! - `running`: what exists while the window does (surface, renderer, egui,
//!   scene, camera), what keys and clicks do to it, and drawing a frame.
//! - `ui`: the panel.
//! - `sim`: a running scene, its ticks and commands, recording and replay.
//! - `catalogue`: the scene list.
//! - `scene_state`: what a reset rebuilds (the lanes, the player, the plot).
//! - `session`: what a reset keeps (the loop, the sliders, a replay under way).
//! - `replay`: the replay file: input and commands by tick.
//! - `history`: the plot's samples and reference lines.
//! - `lanes`: the worlds, and the integrator comparison.
//! - `controls`: the keys, the sliders and the player's controller.
//! - `page` (in a browser only): the page's options, where errors show,
//!   downloads, and what tests read.

#[cfg(target_arch = "wasm32")]
pub mod web;
mod app;
mod catalogue;
mod controls;
mod history;
mod lanes;
mod replay;
mod running;
mod scene_state;
mod session;
mod sim;
mod ui;
#[cfg(target_arch = "wasm32")]
mod page;

pub use app::{DemoArgs, no_display_message, run};
pub use catalogue::{Entry, catalogue};
pub use controls::{Input, Knobs};
pub use history::History;
pub use lanes::Lane;
pub use replay::{Command, Replay};
#[cfg(not(target_arch = "wasm32"))]
pub use running::render_scene_offscreen;
pub use scene_state::{REWIND_BYTES, SceneState};
pub use session::{Session, Stats};
pub use sim::{Sim, load, run_replay};
