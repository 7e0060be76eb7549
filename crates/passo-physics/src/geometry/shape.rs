//! Collision shapes: circles and axis-aligned boxes. Bodies do not rotate.

use glam::Vec2;

/// The shape of a body, centred on its position.
///
/// Bodies do not rotate, so a box stays axis-aligned.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Shape {
    /// A circle (disc) of the given radius, metres.
    Circle {
        /// Radius, metres, > 0.
        radius: f32,
    },
    /// An axis-aligned box with the given half extents, metres.
    Box {
        /// Half the width and half the height, metres, both > 0.
        half_extents: Vec2,
    },
}

impl Shape {
    /// A circle of the given radius, metres.
    pub const fn circle(radius: f32) -> Self {
        Self::Circle { radius }
    }

    /// A box of the given full width and height, metres (the [`Box`]
    /// variant stores half of each: `Shape::rect(2.0, 1.0)` has half
    /// extents `(1.0, 0.5)`).
    ///
    /// [`Box`]: Self::Box
    pub fn rect(width: f32, height: f32) -> Self {
        Self::Box {
            half_extents: Vec2::new(width * 0.5, height * 0.5),
        }
    }

    /// A box of the given half width and half height, metres (what the
    /// [`Box`](Self::Box) variant stores).
    pub const fn from_half_extents(half_width: f32, half_height: f32) -> Self {
        Self::Box {
            half_extents: Vec2::new(half_width, half_height),
        }
    }

    /// Area in square metres (used to derive mass from density).
    pub fn area(&self) -> f32 {
        match *self {
            Self::Circle { radius } => std::f32::consts::PI * radius * radius,
            Self::Box { half_extents } => 4.0 * half_extents.x * half_extents.y,
        }
    }

    /// Half extents of the shape's bounding box, metres.
    pub fn half_extents(&self) -> Vec2 {
        match *self {
            Self::Circle { radius } => Vec2::splat(radius),
            Self::Box { half_extents } => half_extents,
        }
    }

    /// Checks that every size is finite and strictly positive.
    pub(crate) fn validate(&self) -> Result<(), crate::PhysicsError> {
        match *self {
            Self::Circle { radius } => size("Shape::Circle::radius", radius)?,
            Self::Box { half_extents } => {
                size("Shape::Box::half_extents.x", half_extents.x)?;
                size("Shape::Box::half_extents.y", half_extents.y)?
            }
        };
        Ok(())
    }
}

/// A size: finite, > 0 and at most [`MAX_SHAPE_SIZE`](crate::constants::MAX_SHAPE_SIZE).
fn size(what: &'static str, value: f32) -> Result<f32, crate::PhysicsError> {
    crate::error::positive(what, value)?;
    if value <= crate::constants::MAX_SHAPE_SIZE {
        Ok(value)
    } else {
        Err(crate::PhysicsError::OutOfRange {
            what,
            value,
            allowed: "at most 1e6 m (MAX_SHAPE_SIZE)",
        })
    }
}
