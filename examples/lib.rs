//! Examples of Passo; run one with `cargo run -p passo-examples --example NAME`.
#![warn(missing_docs)]

pub mod netplay;
#[path = "platformer_game.rs"]
pub mod platformer;
pub mod window;
