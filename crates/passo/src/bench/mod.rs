//! `passo bench`: measurements that belong in benchmarks, not tests. One
//! file per kind of measurement, after the options of them all.

mod args;
// The measurements, after the options they read.
mod integration;
mod scenes;
// Uses the scenes' type of world maker.
mod stress;
// Needs a GPU adapter (or lavapipe).
mod render;
// Run in a browser too: the web demo's `?bench`.
mod browser;

use anyhow::Result;
pub use args::*;
pub use browser::{BROWSER_CASES, BrowserCase, time_case};
pub use integration::{
    INTEGRATION_BYTES, bare_soa_ns, copy_bandwidth, fitted_exponent, integration_ns,
    triad_bandwidth,
};

/// Runs `passo bench`.
pub fn run(args: &BenchArgs) -> Result<()> {
    match &args.what {
        BenchWhat::Render(a) => render::render(a),
        BenchWhat::Physics(a) => scenes::physics(a),
        BenchWhat::Integration(a) => integration::integration(a),
        BenchWhat::Scaling(a) => integration::scaling(a),
        BenchWhat::Sleep(a) => scenes::sleep(a),
        BenchWhat::Queries(a) => scenes::queries(a),
        BenchWhat::Platforms(a) => scenes::platforms(a),
        BenchWhat::Tiles(a) => scenes::tiles(a),
        BenchWhat::Slopes(a) => scenes::slopes(a),
        BenchWhat::Extreme(a) => stress::extreme(a),
        BenchWhat::Soak(a) => stress::soak(a),
        BenchWhat::Rollback(a) => stress::rollback(a),
    }
}
