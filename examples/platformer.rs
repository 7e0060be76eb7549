//! A small platformer in a window: the level made in the Tiled editor
//! (`assets/levels/first.tmx`), a player moved by the character mover,
//! a lift, a crate, coins and a goal, a camera that follows the player
//! inside the level's edges, and a HUD of the coins and the time.
//!
//! ```text
//! cargo run --release -p passo-examples --example platformer
//! ```
//!
//! A / D or the arrow keys walk, Shift runs, Space jumps (hold it to jump
//! higher), G glides, Q turns the wind on and off. `--autopilot` plays the level by script;
//! `--frames N` runs N frames and exits, printing a line with the ticks,
//! the coins and the tick the goal was reached (`--until-goal`: or as soon
//! as the goal is reached); `--screenshot FILE` saves the last frame as a
//! PNG; `--software` draws on Mesa's lavapipe.

use passo_examples::platformer::PLAYER_SIZE;
use passo_physics::Shape;

fn main() -> Result<(), String> {
    passo_examples::window::run(
        "Passo platformer",
        "player",
        Shape::rect(PLAYER_SIZE.x, PLAYER_SIZE.y),
    )
}
