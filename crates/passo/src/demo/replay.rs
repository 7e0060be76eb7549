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

    /// Parses RON text and checks it ([`validate`](Self::validate)).
    pub fn from_ron(text: &str) -> anyhow::Result<Self> {
        let replay: Self = ron::from_str(text)?;
        replay.validate()?;
        Ok(replay)
    }

    /// Checks what a recording could have produced: inputs and commands in
    /// tick order, none after the last tick, and fixed rates a scene file
    /// may have (1 to 10 000 Hz). A command out of order would be applied
    /// at the wrong tick and one past the end never, so they are refused.
    pub fn validate(&self) -> anyhow::Result<()> {
        use anyhow::bail;
        let in_order = |ticks: &mut dyn Iterator<Item = u64>, what: &str| {
            let mut last = 0;
            for tick in ticks {
                if tick < last {
                    bail!("{what} at tick {tick} comes after one at tick {last}: out of order");
                }
                if tick > self.ticks {
                    bail!(
                        "{what} at tick {tick} is past the last tick, {}",
                        self.ticks
                    );
                }
                last = tick;
            }
            Ok(())
        };
        in_order(&mut self.inputs.iter().map(|(t, _)| *t), "an input")?;
        in_order(&mut self.commands.iter().map(|(t, _)| *t), "a command")?;
        for (tick, command) in &self.commands {
            if let Command::Rate(hz) = command
                && !(hz.is_finite() && (1.0..=10_000.0).contains(hz))
            {
                bail!("the rate set at tick {tick} must be in [1, 10000] Hz, got {hz:?}");
            }
        }
        Ok(())
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
