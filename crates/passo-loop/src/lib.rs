//! # passo-loop
//!
//! A fixed-timestep game loop: feed it each frame's duration, and it tells
//! you how many fixed ticks of simulation to run now and how far the render
//! sits between the last two ticks. The simulation then always advances by
//! the same `dt`, whatever the frame rate: the result no longer depends on
//! how fast the machine renders, and stiff forces stay stable.
//!
//! The crate knows nothing about physics or windows and never reads a clock:
//! callers pass time in ([`RealClock`] measures it for a real game), so tests
//! feed exact durations.
//!
//! ```
//! use passo_loop::FixedTimestep;
//! use std::time::Duration;
//!
//! let mut clock = FixedTimestep::from_hz(50.0).unwrap(); // dt = 20 ms
//! let frame = clock.advance(Duration::from_millis(50));
//! assert_eq!(frame.ticks, 2); // 40 ms simulated now
//! assert_eq!(clock.remainder(), Duration::from_millis(10));
//! assert_eq!(frame.alpha, 0.5); // draw halfway between the last two ticks
//! ```
#![warn(missing_docs)]
#![forbid(unsafe_code)]

mod clock;
mod runner;
mod timestep;

pub use clock::RealClock;
pub use runner::{Game, run_frame};
pub use timestep::{
    DEFAULT_MAX_FRAME_TIME, DEFAULT_MAX_TICKS_PER_FRAME, FixedTimestep, Frame, LoopError, MAX_STEP,
    MAX_TIME_SCALE,
};
