//! How a world steps: its settings, checked where they enter.

use crate::body::def::check_max_speed;
use crate::constants::{DEFAULT_MAX_SPEED, DEFAULT_MIN_SPEED};
use crate::error::non_negative;
use crate::{BodyDef, BodyKind, ContactSettings, ForceForm, ForceModels, Integrator, PhysicsError};

/// How a world steps. Start from [`Default`] and change what differs.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct WorldSettings {
    /// The force models the world evaluates. Default: gravity only.
    pub forces: ForceModels,
    /// Time-stepping method. Default [`Integrator::SemiImplicitEuler`].
    pub integrator: Integrator,
    /// Stable or plain explicit drag and friction (Euler methods only).
    /// Default [`ForceForm::Stable`].
    pub force_form: ForceForm,
    /// Below this speed, metres per second, a velocity becomes exactly zero:
    /// at least 0 and at most `max_speed`; 0 turns the snap off. Keep it well
    /// under the speed gravity adds in a substep (see
    /// [`DEFAULT_MIN_SPEED`]). Default 0.001.
    pub min_speed: f32,
    /// Velocities are clamped to this speed, metres per second. > 0;
    /// `f32::INFINITY` turns the clamp off. Default 1000 ([`DEFAULT_MAX_SPEED`]).
    pub max_speed: f32,
    /// Keep each body's position from before the last step, so a renderer
    /// can draw [`World::interpolated_position`](crate::World::interpolated_position). Costs one copy of the
    /// positions per step. Default `false`.
    pub interpolation: bool,
    /// How contacts between shaped bodies are solved; `None` turns
    /// collisions off. Default `Some(ContactSettings::default())`. The
    /// contact stage runs only while the world holds a shaped dynamic or
    /// kinematic body and another shaped body; it then advances in
    /// [`ContactSettings::substeps`] substeps.
    pub contacts: Option<ContactSettings>,
}

impl Default for WorldSettings {
    fn default() -> Self {
        Self {
            forces: ForceModels::default(),
            integrator: Integrator::default(),
            force_form: ForceForm::default(),
            min_speed: DEFAULT_MIN_SPEED,
            max_speed: DEFAULT_MAX_SPEED,
            interpolation: false,
            contacts: Some(ContactSettings::default()),
        }
    }
}

impl WorldSettings {
    /// Checks every value, naming the first one that is wrong.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        self.forces.validate()?;
        non_negative("WorldSettings::min_speed", self.min_speed)?;
        check_max_speed("WorldSettings::max_speed", self.max_speed)?;
        if self.min_speed > self.max_speed {
            return Err(PhysicsError::OutOfRange {
                what: "WorldSettings::min_speed",
                value: self.min_speed,
                allowed: "at most WorldSettings::max_speed",
            });
        }
        if let Some(contacts) = &self.contacts {
            contacts.validate()?;
        }
        Ok(())
    }

    /// Whether a world of these settings takes `def` in
    /// [`World::add_body`](crate::World::add_body): the body's own checks
    /// ([`BodyDef::validate`]), a velocity with a finite square, a dynamic
    /// body's minimum speed (its own or the world's) at most its maximum,
    /// and a kinematic body's speed (which nothing else limits) at most
    /// `max_speed`, as [`World::try_set_velocity`](crate::World::try_set_velocity)
    /// asks. For checking bodies before a world exists (a scene file).
    ///
    /// # Errors
    /// What `add_body` would return.
    pub fn check_body(&self, def: &BodyDef) -> Result<(), PhysicsError> {
        def.validate()?;
        self.check_restored_body(def)?;
        let max = self.max_speed;
        let speed_sq = def.velocity.length_squared();
        if def.kind == BodyKind::Kinematic && speed_sq > max * max {
            return Err(PhysicsError::OutOfRange {
                what: "BodyDef::velocity",
                value: speed_sq.sqrt(),
                allowed: "at most WorldSettings::max_speed for a kinematic body",
            });
        }
        Ok(())
    }

    /// What a body restored from a snapshot must be in a world of these
    /// settings, beyond its own checks: its velocity has a finite square,
    /// and a dynamic body's speed limits
    /// ([`check_speed_limits`](Self::check_speed_limits)) leave it room to
    /// move. (A kinematic body may be faster than `max_speed`: the limit was
    /// lowered after it was set going, which `set_settings` allows.)
    pub(crate) fn check_restored_body(&self, def: &BodyDef) -> Result<(), PhysicsError> {
        if !def.velocity.length_squared().is_finite() {
            return Err(PhysicsError::NonFinite {
                what: "BodyDef::velocity (its square)",
            });
        }
        if def.kind == BodyKind::Dynamic {
            self.check_speed_limits(def.min_speed, def.max_speed)?;
        }
        Ok(())
    }

    /// A dynamic body's minimum speed (`min`, or the world's) must not
    /// exceed its maximum (`max`, or the world's): the snap to zero tests
    /// the speed before the clamp, so speeds between the two would stop
    /// dead and faster ones drop to the maximum.
    pub(crate) fn check_speed_limits(
        &self,
        min: Option<f32>,
        max: Option<f32>,
    ) -> Result<(), PhysicsError> {
        let (min, max) = (min.unwrap_or(self.min_speed), max.unwrap_or(self.max_speed));
        if min > max {
            return Err(PhysicsError::OutOfRange {
                what: "minimum speed (the body's min_speed, or the world's)",
                value: min,
                allowed: "at most the maximum speed (the body's max_speed, or the world's)",
            });
        }
        Ok(())
    }
}
