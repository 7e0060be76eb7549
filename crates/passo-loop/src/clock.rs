//! Real time, for games: the one place that reads a clock.

use std::time::Duration;
// The standard library's clock panics in a browser: there, `web-time` reads
// `performance.now()`, a monotonic clock, behind the same API.
#[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
use std::time::Instant;
#[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
use web_time::Instant;

/// Measures real frame times with a monotonic clock: `std`'s `Instant`,
/// or in a browser (`wasm32-unknown-unknown`) `performance.now()`.
///
/// ```
/// use passo_loop::{FixedTimestep, RealClock};
///
/// let mut clock = RealClock::new();
/// let mut timestep = FixedTimestep::default();
/// let frame = timestep.advance(clock.frame_time());
/// assert!(frame.ticks <= timestep.max_ticks_per_frame());
/// ```
#[derive(Debug, Clone)]
pub struct RealClock {
    last: Instant,
}

impl RealClock {
    /// Starts measuring now.
    pub fn new() -> Self {
        Self {
            last: Instant::now(),
        }
    }

    /// Time since the previous call (or since [`new`](Self::new)).
    pub fn frame_time(&mut self) -> Duration {
        let now = Instant::now();
        let elapsed = now.duration_since(self.last);
        self.last = now;
        elapsed
    }
}

impl Default for RealClock {
    fn default() -> Self {
        Self::new()
    }
}
