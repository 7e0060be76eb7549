//! Shapes and what is computed from them alone: boxes, manifolds, rays, casts, the static tree.

pub(crate) mod aabb;
pub(crate) mod shape;
pub(crate) mod segment;
pub(crate) mod polygon;
pub(crate) mod ray;
pub(crate) mod manifold;
pub(crate) mod corners;
pub(crate) mod cast;
pub(crate) mod static_tree;
