//! What happened in a physics tick, as Bevy messages: read them with a
//! [`MessageReader`](bevy::prelude::MessageReader), in the physics
//! schedule after [`PassoSystems::Step`](crate::PassoSystems::Step) or in
//! `Update`. Each is written once, in the tick it happened, in the
//! world's fixed order (by body id).
//!
//! A body that is not an entity's (a tile of a level) has no entity:
//! its `Option<Entity>` is `None` and its id says which body it is.

use bevy::prelude::{Entity, Message};
use passo_physics::{BodyId, JointDef, JointId};

/// Two bodies started touching this tick.
#[derive(Message, Clone, Copy, Debug, PartialEq, Eq)]
pub struct ContactBegan {
    /// One body (the lower id).
    pub a: BodyId,
    /// The other body.
    pub b: BodyId,
    /// `a`'s entity.
    pub entity_a: Option<Entity>,
    /// `b`'s entity.
    pub entity_b: Option<Entity>,
}

/// Two bodies stopped touching this tick (or one of them was removed).
#[derive(Message, Clone, Copy, Debug, PartialEq, Eq)]
pub struct ContactEnded {
    /// One body (the lower id).
    pub a: BodyId,
    /// The other body.
    pub b: BodyId,
    /// `a`'s entity (`None` once it is despawned).
    pub entity_a: Option<Entity>,
    /// `b`'s entity (`None` once it is despawned).
    pub entity_b: Option<Entity>,
}

/// A body entered a [`Sensor`](crate::Sensor) this tick.
#[derive(Message, Clone, Copy, Debug, PartialEq, Eq)]
pub struct SensorEntered {
    /// The sensor.
    pub sensor: BodyId,
    /// The body that entered it.
    pub visitor: BodyId,
    /// The sensor's entity.
    pub sensor_entity: Option<Entity>,
    /// The visitor's entity.
    pub visitor_entity: Option<Entity>,
}

/// A body left a [`Sensor`](crate::Sensor) this tick (or was removed).
#[derive(Message, Clone, Copy, Debug, PartialEq, Eq)]
pub struct SensorExited {
    /// The sensor.
    pub sensor: BodyId,
    /// The body that left it.
    pub visitor: BodyId,
    /// The sensor's entity (`None` once it is despawned).
    pub sensor_entity: Option<Entity>,
    /// The visitor's entity (`None` once it is despawned).
    pub visitor_entity: Option<Entity>,
}

/// A joint broke this tick: its force went past its `break_force`.
#[derive(Message, Clone, Copy, Debug, PartialEq)]
pub struct JointBroke {
    /// The joint's id (no longer in the world).
    pub id: JointId,
    /// What the joint was.
    pub def: JointDef,
    /// The force that broke it, newtons.
    pub force: f32,
}

/// A [`LoadScene`](crate::LoadScene) command could not load its file. The
/// world is left as it was.
#[derive(Message, Clone, Debug, PartialEq, Eq)]
pub struct SceneLoadFailed {
    /// The file it tried.
    pub source: String,
    /// Why it failed, with the field and line where there is one.
    pub error: String,
}
