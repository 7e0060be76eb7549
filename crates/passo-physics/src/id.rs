//! Body handles: small `Copy` ids with a generation.

use std::fmt;

/// A small `Copy` handle to a body in a [`World`](crate::World).
///
/// The handle carries a generation: when a body is removed its slot's
/// generation is bumped, so an old id never reaches the body that reuses the
/// slot; lookups with it return `None`.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BodyId {
    pub(crate) index: u32,
    pub(crate) generation: u32,
}

impl BodyId {
    /// The slot index (stable while the body lives; reused after removal).
    pub fn index(self) -> u32 {
        self.index
    }

    /// The slot generation (bumped each time the slot is freed).
    pub fn generation(self) -> u32 {
        self.generation
    }
}

impl fmt::Debug for BodyId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "BodyId({}v{})", self.index, self.generation)
    }
}

/// A small `Copy` handle to a joint in a [`World`](crate::World), with a
/// generation as [`BodyId`] has: an id of a removed (or broken) joint
/// never reaches the joint that reuses its slot.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointId {
    pub(crate) index: u32,
    pub(crate) generation: u32,
}

impl JointId {
    /// The slot index (stable while the joint lives; reused after removal).
    pub fn index(self) -> u32 {
        self.index
    }

    /// The slot generation (bumped each time the slot is freed).
    pub fn generation(self) -> u32 {
        self.generation
    }
}

impl fmt::Debug for JointId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "JointId({}v{})", self.index, self.generation)
    }
}
