//! Finding contacts: the broad phase, its proxies and pairs, and the narrow phase.

pub(crate) mod broad_phase;
pub(crate) mod proxies;
pub(crate) mod pair_sort;
pub(crate) mod reuse;
pub(crate) mod narrow_phase;
