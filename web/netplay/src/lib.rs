//! Rollback netplay with Passo: two players in one world, kept in step by
//! GGRS.
//!
//! - [`game`]: the game, whatever the transport. Its state is a world
//!   snapshot and a tick; it carries out GGRS's save, load and advance
//!   requests. `passo-examples` plays it over UDP (`examples/netplay.rs`).
//! - In a browser (`wasm32`), the `passo-netplay` program plays it in a
//!   tab against another tab over WebRTC: `bash web/netplay.sh` builds it
//!   and serves the page and a signalling server on 127.0.0.1.
//! - [`signal`] (natively): that signalling server, which the
//!   `passo-signal` program runs.

pub mod game;

#[cfg(not(target_arch = "wasm32"))]
pub mod signal;

#[cfg(target_arch = "wasm32")]
pub mod browser;
