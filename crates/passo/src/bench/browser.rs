//! The physics' speed in a browser against native: the same worlds, on
//! one thread, timed the same way by the web demo's page (`?bench`) and
//! by the native check (`passo-web-check --bench`), in one run.

use crate::Instant;
use passo_physics::World;

/// A world the comparison times, and how many ticks.
pub struct BrowserCase {
    /// Its name in the table.
    pub name: &'static str,
    /// Builds the world.
    pub world: fn() -> World,
    /// Ticks before the timing starts (the pile forms), then ticks timed.
    pub ticks: (u32, u32),
}

/// The cases: the rain of 1 000 circles once it has piled up (4 s), and
/// the pyramid of base 20, both with sleeping off (a sleeping world costs
/// next to nothing, and would time nothing).
pub const BROWSER_CASES: [BrowserCase; 2] = [
    BrowserCase {
        name: "rain of 1 000 circles",
        world: || passo_benches::with_sleeping(&passo_benches::rain_world(1000), false),
        ticks: (240, 300),
    },
    BrowserCase {
        name: "pyramid, base 20",
        world: || passo_benches::with_sleeping(&passo_benches::pyramid_world(20), false),
        ticks: (240, 300),
    },
];

/// Milliseconds per tick of `case` at 60 Hz, on the calling thread alone,
/// and the state hash at the end (the same bits on every platform).
pub fn time_case(case: &BrowserCase) -> (f64, u64) {
    let mut world = (case.world)();
    world.set_parallel(false);
    let dt = 1.0 / 60.0;
    for _ in 0..case.ticks.0 {
        world.step(dt);
    }
    let start = Instant::now();
    for _ in 0..case.ticks.1 {
        world.step(dt);
    }
    let ms = start.elapsed().as_secs_f64() * 1e3 / f64::from(case.ticks.1);
    (ms, world.state_hash())
}
