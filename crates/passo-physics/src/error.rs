//! Errors returned where values enter the physics API.

use crate::id::{BodyId, JointId};
use std::fmt;

/// Why the physics API refused a value.
///
/// Every value that enters the world (body definitions, settings, forces,
/// impulses) is checked where it enters, so the world never stores a NaN or
/// an infinity.
#[derive(Clone, Debug, PartialEq)]
pub enum PhysicsError {
    /// A value that must be finite was NaN or infinite.
    NonFinite {
        /// The field or argument, e.g. `"BodyDef::position"`.
        what: &'static str,
    },
    /// A finite value outside its allowed range.
    OutOfRange {
        /// The field or argument, e.g. `"BodyDef::mass"`.
        what: &'static str,
        /// The value that was given.
        value: f32,
        /// The allowed range, e.g. `"> 0 kg"`.
        allowed: &'static str,
    },
    /// The id names a body that was removed (or never existed in this world).
    StaleBody(BodyId),
    /// The id names a joint that was removed or broke (or never existed in
    /// this world).
    StaleJoint(JointId),
    /// A joint that cannot be made: both ends the same body, no dynamic
    /// body to move, or contacts turned off (joints are solved with them).
    InvalidJoint(&'static str),
    /// A snapshot that no world could have produced (a damaged file).
    InvalidSnapshot(String),
    /// A tile map that cannot be built: a character not in the legend, a
    /// cell outside the map, an unknown kind.
    InvalidTileMap(String),
}

impl fmt::Display for PhysicsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite { what } => write!(f, "{what} must be finite (got NaN or infinity)"),
            Self::OutOfRange {
                what,
                value,
                allowed,
            } => write!(f, "{what} must be {allowed}, got {value}"),
            Self::StaleBody(id) => write!(f, "{id:?} does not name a body in this world"),
            Self::StaleJoint(id) => write!(f, "{id:?} does not name a joint in this world"),
            Self::InvalidJoint(why) => write!(f, "invalid joint: {why}"),
            Self::InvalidSnapshot(why) => write!(f, "invalid world snapshot: {why}"),
            Self::InvalidTileMap(why) => write!(f, "invalid tile map: {why}"),
        }
    }
}

impl std::error::Error for PhysicsError {}

/// Checks that a scalar is finite.
pub(crate) fn finite(what: &'static str, value: f32) -> Result<f32, PhysicsError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(PhysicsError::NonFinite { what })
    }
}

/// Checks that a position is finite and within [`MAX_COORDINATE`] of the
/// origin along each axis.
///
/// [`MAX_COORDINATE`]: crate::constants::MAX_COORDINATE
pub(crate) fn position(what: &'static str, p: glam::Vec2) -> Result<glam::Vec2, PhysicsError> {
    finite_vec(what, p)?;
    let far = p.abs().max_element();
    if far <= crate::constants::MAX_COORDINATE {
        Ok(p)
    } else {
        Err(PhysicsError::OutOfRange {
            what,
            value: far,
            allowed: "within 1e7 m of the origin along each axis (MAX_COORDINATE)",
        })
    }
}

/// Checks that both components of a vector are finite.
pub(crate) fn finite_vec(
    what: &'static str,
    value: glam::Vec2,
) -> Result<glam::Vec2, PhysicsError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(PhysicsError::NonFinite { what })
    }
}

/// Checks that a scalar is finite and in `[0, 1]`.
pub(crate) fn unit_interval(what: &'static str, value: f32) -> Result<f32, PhysicsError> {
    non_negative(what, value)?;
    if value <= 1.0 {
        Ok(value)
    } else {
        Err(PhysicsError::OutOfRange {
            what,
            value,
            allowed: "in [0, 1]",
        })
    }
}

/// Checks that a scalar is finite and in `[0, max]`.
pub(crate) fn at_most(
    what: &'static str,
    value: f32,
    max: f32,
    allowed: &'static str,
) -> Result<f32, PhysicsError> {
    non_negative(what, value)?;
    if value <= max {
        Ok(value)
    } else {
        Err(PhysicsError::OutOfRange {
            what,
            value,
            allowed,
        })
    }
}

/// Checks a mass: finite, > 0, with a finite inverse (a subnormal mass
/// such as 1e-40 kg has none), and at most [`MAX_MASS`].
///
/// [`MAX_MASS`]: crate::constants::MAX_MASS
pub(crate) fn mass(what: &'static str, value: f32) -> Result<f32, PhysicsError> {
    positive(what, value)?;
    if (1.0 / value).is_finite() && value <= crate::constants::MAX_MASS {
        Ok(value)
    } else {
        Err(PhysicsError::OutOfRange {
            what,
            value,
            allowed: "in [3e-39, 1e30] kg (MAX_MASS; the inverse must be finite)",
        })
    }
}

/// Checks that a scalar is finite and >= 0.
pub(crate) fn non_negative(what: &'static str, value: f32) -> Result<f32, PhysicsError> {
    finite(what, value)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(PhysicsError::OutOfRange {
            what,
            value,
            allowed: ">= 0",
        })
    }
}

/// Checks that a scalar is finite and `> 0`.
pub(crate) fn positive(what: &'static str, value: f32) -> Result<f32, PhysicsError> {
    finite(what, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(PhysicsError::OutOfRange {
            what,
            value,
            allowed: "> 0",
        })
    }
}
