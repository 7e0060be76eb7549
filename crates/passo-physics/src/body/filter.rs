//! Collision filters: which bodies may touch.

/// Which bodies may touch: A and B collide when `A.layers & B.mask != 0`
/// and `B.layers & A.mask != 0`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct CollisionFilter {
    /// The layers the body is on. Default `1`.
    pub layers: u32,
    /// The layers the body collides with. Default all (`u32::MAX`).
    pub mask: u32,
}

impl Default for CollisionFilter {
    fn default() -> Self {
        Self {
            layers: 1,
            mask: u32::MAX,
        }
    }
}

impl CollisionFilter {
    /// Whether bodies with these filters may touch.
    pub fn allows(&self, other: &Self) -> bool {
        self.layers & other.mask != 0 && other.layers & self.mask != 0
    }
}
