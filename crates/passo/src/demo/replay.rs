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
    /// Take hold of a body with the mouse: a target joint from the point
    /// `at` on it, pulled toward the pointer (see `SceneState::grab`).
    Grab {
        /// The body's slot index.
        index: u32,
        /// Its generation.
        generation: u32,
        /// The point taken, metres.
        at: [f32; 2],
    },
    /// Move the held body's target to the pointer.
    Drag {
        /// The pointer, metres.
        at: [f32; 2],
    },
    /// Let go of the held body.
    Release,
    /// Set a body's velocity (the mouse fling of earlier versions; kept so
    /// their replays still play).
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
    /// State hash after the last tick: written as the sixteen hex digits
    /// `passo replay` prints; a decimal number (older files) is read too.
    #[serde(with = "hex_hash")]
    pub final_hash: u64,
}

/// A state hash in a replay file: the hex digits the commands print, or a
/// plain integer.
mod hex_hash {
    use serde::de::{self, Visitor};
    use serde::{Deserializer, Serializer};
    use std::fmt;

    pub(super) fn serialize<S: Serializer>(hash: &u64, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&format!("{hash:016x}"))
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<u64, D::Error> {
        d.deserialize_any(HashVisitor)
    }

    struct HashVisitor;

    impl Visitor<'_> for HashVisitor {
        type Value = u64;

        fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
            f.write_str("a state hash: up to sixteen hex digits in quotes, or an integer")
        }

        fn visit_u64<E: de::Error>(self, v: u64) -> Result<u64, E> {
            Ok(v)
        }

        fn visit_i64<E: de::Error>(self, v: i64) -> Result<u64, E> {
            u64::try_from(v).map_err(|_| E::custom(format!("a negative state hash: {v}")))
        }

        fn visit_str<E: de::Error>(self, v: &str) -> Result<u64, E> {
            let digits = v.strip_prefix("0x").unwrap_or(v);
            let hex = digits.bytes().all(|b| b.is_ascii_hexdigit());
            if !hex || digits.is_empty() || digits.len() > 16 {
                return Err(E::custom(format!(
                    "a state hash is 1 to 16 hex digits, not `{v}`"
                )));
            }
            u64::from_str_radix(digits, 16).map_err(E::custom)
        }
    }
}

impl Replay {
    /// Most ticks a replay may have: 2^32, over two years of play at
    /// 60 Hz. A file asking for more would keep `passo replay` busy for
    /// ever.
    pub const MAX_TICKS: u64 = 1 << 32;

    /// Most commands a replay may have: 2^20, more than one every frame of
    /// four hours of slider dragging at 60 FPS. (Commands can outnumber
    /// ticks: a slider dragged while paused records one a frame.)
    pub const MAX_COMMANDS: usize = 1 << 20;

    /// Most commands that rebuild the scene ([`Command::Reset`] and
    /// [`Command::RainCount`]) a replay may have: 4096.
    pub const MAX_REBUILDS: usize = 4096;

    /// Largest rain count a [`Command::RainCount`] may set: 20 000, the top
    /// of the panel's slider.
    pub const MAX_RAIN_COUNT: u32 = 20_000;

    /// Most bodies a replay may spawn ([`Command::Spawn`], one a click),
    /// 20 000: as many as the rain slider's top. A file of a million
    /// spawns on one spot (37 MB) made a world that ran `passo replay` out
    /// of memory.
    pub const MAX_SPAWNS: usize = 20_000;

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
    /// tick order, none after the last tick, fixed rates a scene file may
    /// have (1 to 10 000 Hz), finite slider values, and at most [`MAX_TICKS`](Self::MAX_TICKS)
    /// ticks, [`MAX_COMMANDS`](Self::MAX_COMMANDS) commands,
    /// [`MAX_REBUILDS`](Self::MAX_REBUILDS) of them rebuilding the scene,
    /// [`MAX_SPAWNS`](Self::MAX_SPAWNS) of them spawning a body,
    /// and rain counts up to [`MAX_RAIN_COUNT`](Self::MAX_RAIN_COUNT). A
    /// command out of order would be applied at the wrong tick and one past
    /// the end never, so they are refused; the limits keep a replay from
    /// running for ever.
    pub fn validate(&self) -> anyhow::Result<()> {
        use anyhow::bail;
        if self.ticks > Self::MAX_TICKS {
            bail!(
                "the replay has {} ticks, more than the most a replay may have, {}",
                self.ticks,
                Self::MAX_TICKS
            );
        }
        if self.commands.len() > Self::MAX_COMMANDS {
            bail!(
                "the replay has {} commands, more than the most a replay may have, {}",
                self.commands.len(),
                Self::MAX_COMMANDS
            );
        }
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
        let (mut rebuilds, mut spawns) = (0, 0);
        for (tick, command) in &self.commands {
            match *command {
                Command::Rate(hz) if !(hz.is_finite() && (1.0..=10_000.0).contains(&hz)) => {
                    bail!("the rate set at tick {tick} must be in [1, 10000] Hz, got {hz:?}");
                }
                Command::RainCount(n) if n > Self::MAX_RAIN_COUNT => {
                    bail!(
                        "the rain count set at tick {tick} must be at most {}, got {n}",
                        Self::MAX_RAIN_COUNT
                    );
                }
                Command::Knobs { knobs, .. } if !knobs.is_finite() => {
                    bail!("the slider values set at tick {tick} must be finite, got {knobs:?}");
                }
                Command::Reset | Command::RainCount(_) => rebuilds += 1,
                Command::Spawn { .. } => spawns += 1,
                _ => {}
            }
        }
        if spawns > Self::MAX_SPAWNS {
            bail!(
                "the replay spawns {spawns} bodies, more than the most a replay may, {}",
                Self::MAX_SPAWNS
            );
        }
        if rebuilds > Self::MAX_REBUILDS {
            bail!(
                "the replay rebuilds the scene {rebuilds} times (resets and rain counts), \
                 more than the most a replay may, {}",
                Self::MAX_REBUILDS
            );
        }
        Ok(())
    }

    /// Reads a replay file: at most [`passo_scene::MAX_FILE_BYTES`] long
    /// (a recording of hours is a few megabytes).
    pub fn load(path: &std::path::Path) -> anyhow::Result<Self> {
        use anyhow::Context;
        let bytes = crate::read_file_at_most(path, passo_scene::MAX_FILE_BYTES, "replay")?;
        let text = String::from_utf8(bytes)
            .with_context(|| format!("{} is not UTF-8 text", path.display()))?;
        Self::from_ron(&text).with_context(|| format!("{} is not a Passo replay", path.display()))
    }

    /// Writes a replay file.
    pub fn save(&self, path: &std::path::Path) -> anyhow::Result<()> {
        use anyhow::Context;
        std::fs::write(path, self.to_ron()).with_context(|| format!("writing {}", path.display()))
    }
}
