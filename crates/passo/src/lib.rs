//! The `passo` app as a library: what the demo and the command-line tools
//! share, and what the cross-crate tests check (drawing a world, finding
//! scenes, headless rendering).

#![warn(unreachable_pub)]

pub mod bench;
pub mod demo;
pub mod draw;
pub mod progress;
pub mod render_cmd;
pub mod report;
pub mod scenes;
pub mod simulate;
pub mod snapshot;
