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
    /// The name of the scene the world was built from, if known: a run
    /// resumed from the snapshot must be of that scene, whose platforms it
    /// drives and whose bodies it names (files written before it was kept
    /// have none, and resume anything).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scene: Option<String>,
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
            scene: None,
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

    /// Compact binary (postcard): the world and the loop, then the scene's
    /// name (after them, so files written before it was kept still load).
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut bytes = postcard::to_stdvec(&(&self.world, &self.timestep))
            .expect("a snapshot always serializes");
        if self.scene.is_some() {
            bytes.extend(postcard::to_stdvec(&self.scene).expect("a name always serializes"));
        }
        bytes
    }

    /// Parses the compact binary form.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self> {
        let ((world, timestep), rest) = postcard::take_from_bytes(bytes)?;
        let scene = match rest {
            [] => None,
            rest => postcard::from_bytes(rest)?,
        };
        Ok(Self {
            world,
            timestep,
            scene,
        })
    }

    /// An error unless the snapshot may resume a run of the scene named
    /// `scene` (its own, or one whose name it did not keep).
    pub fn check_scene(&self, scene: &str) -> Result<()> {
        match &self.scene {
            Some(own) if own != scene => bail!(
                "is a snapshot of the scene `{own}`, not `{scene}`: its bodies and platforms \
                 are that scene's"
            ),
            _ => Ok(()),
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scene_name_round_trips_and_files_without_it_still_load() {
        let world = World::default();
        let timestep = FixedTimestep::from_hz(60.0).unwrap();
        let bare = GameSnapshot::capture(&world, &timestep);
        let named = GameSnapshot {
            scene: Some("Rain".into()),
            ..bare.clone()
        };
        for snapshot in [&bare, &named] {
            assert_eq!(
                &GameSnapshot::from_bytes(&snapshot.to_bytes()).unwrap(),
                snapshot
            );
            assert_eq!(
                &GameSnapshot::from_ron(&snapshot.to_ron()).unwrap(),
                snapshot
            );
        }
        // The named form is the bare one with the name after it: a file
        // written before names were kept reads as one with no name.
        let (bare_bytes, named_bytes) = (bare.to_bytes(), named.to_bytes());
        assert!(named_bytes.starts_with(&bare_bytes) && named_bytes.len() > bare_bytes.len());
        assert!(!bare.to_ron().contains("scene"));
        assert!(named.check_scene("Rain").is_ok() && bare.check_scene("Stack").is_ok());
        let err = named.check_scene("Stack").unwrap_err().to_string();
        assert!(err.contains("`Rain`, not `Stack`"), "{err}");
    }
}
