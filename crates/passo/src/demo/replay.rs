//! Replays: the player's input and the panel's commands by tick, so a run
//! can be played again, in the window or headless, to the same bits.

use super::controls::{Input, Knobs};
use passo_physics::Integrator;
use serde::{Deserialize, Serialize};

/// Something the player or the panel did between ticks.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Command {
    /// Spawn a ball (or a box) at a world point.
    Spawn {
        /// Where, metres.
        at: [f32; 2],
        /// A ball rather than a box.
        round: bool,
    },
    /// Set a body's velocity (the mouse fling).
    Fling {
        /// The body's slot index.
        index: u32,
        /// Its generation.
        generation: u32,
        /// The new velocity, m/s.
        velocity: [f32; 2],
    },
    /// New slider values, and which per-body ones to apply.
    Knobs {
        /// All slider values.
        knobs: Knobs,
        /// Apply the friction slider to every dynamic body.
        friction: bool,
        /// Apply the restitution slider to every dynamic body.
        restitution: bool,
        /// Apply the drag-area multiplier.
        drag: bool,
    },
    /// A new fixed rate, Hz.
    Rate(f64),
    /// A new integrator.
    Integrator(Integrator),
    /// Restart the scene.
    Reset,
    /// Rebuild the rain with this many bodies.
    RainCount(u32),
}

/// A recorded run: replaying it from the scene's first state reproduces
/// `final_hash` after `ticks` ticks.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Replay {
    /// The scene, by name (as `passo demo --scene` takes it).
    pub scene: String,
    /// Ticks recorded.
    pub ticks: u64,
    /// The input from each listed tick on (only changes are listed).
    pub inputs: Vec<(u64, Input)>,
    /// Commands applied before each listed tick, in order.
    pub commands: Vec<(u64, Command)>,
    /// State hash after the last tick.
    pub final_hash: u64,
}

impl Replay {
    /// RON text.
    pub fn to_ron(&self) -> String {
        ron::ser::to_string_pretty(self, ron::ser::PrettyConfig::new().struct_names(false))
            .expect("a replay always serializes")
    }

    /// Parses RON text.
    pub fn from_ron(text: &str) -> anyhow::Result<Self> {
        Ok(ron::from_str(text)?)
    }

    /// Reads a replay file.
    pub fn load(path: &std::path::Path) -> anyhow::Result<Self> {
        use anyhow::Context;
        let text =
            std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        Self::from_ron(&text).with_context(|| format!("{} is not a Passo replay", path.display()))
    }

    /// Writes a replay file.
    pub fn save(&self, path: &std::path::Path) -> anyhow::Result<()> {
        use anyhow::Context;
        std::fs::write(path, self.to_ron()).with_context(|| format!("writing {}", path.display()))
    }
}
