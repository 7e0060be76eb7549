//! The platformer's slopes, in a window: a capsule player starts at the
//! foot of the slopes past the Platformer level's goal (`assets/levels/
//! first.tmx`): a hill, a 2:1 ramp up to a ledge and a wall too steep to
//! walk, all drawn in Tiled as polygons. The character mover walks it up
//! and down them at its walking speed, and the steep wall stops it.
//!
//! ```text
//! cargo run --release -p passo-examples --example slopes
//! ```
//!
//! The keys and options are the platformer's: A / D or the arrows walk,
//! Space jumps; `--autopilot` runs right and jumps when blocked, `--frames
//! N` runs N frames and exits, `--screenshot FILE` saves the last frame as
//! a PNG, and `--software` draws on Mesa's lavapipe.

use passo_examples::platformer::PLAYER_SIZE;
use passo_physics::Shape;

fn main() -> Result<(), String> {
    passo_examples::window::run(
        "Passo slopes",
        "slopes",
        Shape::capsule(PLAYER_SIZE.x, PLAYER_SIZE.y),
    )
}
