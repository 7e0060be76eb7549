//! Vectors across the boundary: Bevy and Passo use different versions of
//! `glam`, so their `Vec2`s are different types with the same layout.

use bevy::math::Vec2;
use passo_physics::glam;

/// A Passo vector as Bevy's.
pub(crate) fn to_bevy(v: glam::Vec2) -> Vec2 {
    Vec2::new(v.x, v.y)
}

/// A Bevy vector as Passo's.
pub(crate) fn to_passo(v: Vec2) -> glam::Vec2 {
    glam::Vec2::new(v.x, v.y)
}
