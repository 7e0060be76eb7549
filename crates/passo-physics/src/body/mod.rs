//! Bodies: definitions, colliders, filters, materials, the body arrays and tile maps.

pub(crate) mod filter;
pub(crate) mod material;
pub(crate) mod collider;
pub(crate) mod def;
pub(crate) mod store;
pub(crate) mod census;
pub(crate) mod tile_map;
