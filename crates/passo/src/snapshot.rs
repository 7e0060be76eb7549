//! Game snapshots: a world and its loop, saved as RON (readable) or as a
//! compact binary (postcard), and loaded back with every value checked.

use anyhow::{Context, Result, bail};
use passo_loop::FixedTimestep;
use passo_physics::{World, WorldSnapshot};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// A running game's state: the world and the fixed-timestep loop (tick and
/// accumulated remainder). Restoring it and stepping on gives, bit for bit,
/// what the original would have given.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GameSnapshot {
    /// The world.
    pub world: WorldSnapshot,
    /// The loop.
    pub timestep: FixedTimestep,
}

impl GameSnapshot {
    /// The largest snapshot file [`load`](Self::load) reads: 1 GiB (a RON
    /// snapshot takes a few hundred bytes a body, binary about a hundred).
    pub const MAX_FILE_BYTES: u64 = 1 << 30;

    /// Captures a world and its loop.
    pub fn capture(world: &World, timestep: &FixedTimestep) -> Self {
        Self {
            world: world.snapshot(),
            timestep: timestep.clone(),
        }
    }

    /// Rebuilds the world and the loop, after checking both (the loop's
    /// check refuses a step longer than a world takes,
    /// [`passo_loop::MAX_STEP`]).
    pub fn restore(self) -> Result<(World, FixedTimestep)> {
        self.timestep.validate().context("snapshot loop")?;
        let world = World::from_snapshot(self.world).context("snapshot world")?;
        Ok((world, self.timestep))
    }

    /// RON text.
    pub fn to_ron(&self) -> String {
        ron::ser::to_string_pretty(self, ron::ser::PrettyConfig::new().struct_names(false))
            .expect("a snapshot always serializes")
    }

    /// Parses RON text.
    pub fn from_ron(text: &str) -> Result<Self> {
        Ok(ron::from_str(text)?)
    }

    /// Compact binary (postcard).
    pub fn to_bytes(&self) -> Vec<u8> {
        postcard::to_stdvec(self).expect("a snapshot always serializes")
    }

    /// Parses the compact binary form.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self> {
        Ok(postcard::from_bytes(bytes)?)
    }

    /// Writes `.ron` files as RON and any other as binary.
    pub fn save(&self, path: &Path) -> Result<()> {
        let data = if is_ron(path) {
            self.to_ron().into_bytes()
        } else {
            self.to_bytes()
        };
        std::fs::write(path, data).with_context(|| format!("writing {}", path.display()))
    }

    /// Reads a file written by [`save`](Self::save).
    pub fn load(path: &Path) -> Result<Self> {
        let data = crate::read_file_at_most(path, Self::MAX_FILE_BYTES, "snapshot")?;
        let parsed = if is_ron(path) {
            match std::str::from_utf8(&data) {
                Ok(text) => Self::from_ron(text),
                Err(_) => bail!("{} is not UTF-8 text", path.display()),
            }
        } else {
            Self::from_bytes(&data)
        };
        parsed.with_context(|| format!("{} is not a Passo snapshot", path.display()))
    }
}

fn is_ron(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("ron"))
}
