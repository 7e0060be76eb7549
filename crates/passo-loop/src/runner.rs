//! The runner shape: a game with a fixed update and a render.

use crate::{FixedTimestep, Frame};
use std::time::Duration;

/// A game driven by [`run_frame`].
pub trait Game {
    /// Advances the simulation by one fixed step of `dt` seconds; `tick` is
    /// the number of this tick, counted from 0.
    fn fixed_update(&mut self, dt: f32, tick: u64);

    /// Draws the state `alpha` of the way from the previous tick to the
    /// latest one (`alpha` in `[0, 1)`).
    fn render(&mut self, alpha: f32);
}

/// Drives one frame: advances `timestep` by `frame_time`, runs the fixed
/// updates it asks for, then renders once.
///
/// ```
/// use passo_loop::{run_frame, FixedTimestep, Game};
/// use std::time::Duration;
///
/// #[derive(Default)]
/// struct Counter { ticks: u64, alpha: f32 }
/// impl Game for Counter {
///     fn fixed_update(&mut self, _dt: f32, _tick: u64) { self.ticks += 1; }
///     fn render(&mut self, alpha: f32) { self.alpha = alpha; }
/// }
///
/// let mut timestep = FixedTimestep::from_hz(100.0).unwrap();
/// let mut game = Counter::default();
/// run_frame(&mut timestep, &mut game, Duration::from_millis(25));
/// assert_eq!((game.ticks, game.alpha), (2, 0.5));
/// ```
pub fn run_frame<G: Game + ?Sized>(
    timestep: &mut FixedTimestep,
    game: &mut G,
    frame_time: Duration,
) -> Frame {
    let frame = timestep.advance(frame_time);
    for tick in frame.tick_numbers() {
        game.fixed_update(frame.dt, tick);
    }
    game.render(frame.alpha);
    frame
}
