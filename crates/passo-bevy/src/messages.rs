//! What happened in a physics tick, as Bevy messages: read them with a
//! [`MessageReader`](bevy::prelude::MessageReader), in the physics
//! schedule after [`PassoSystems::Step`](crate::PassoSystems::Step) or in
//! `Update`. Each is written once, in the tick it happened, in the
//! world's fixed order (by body id).
//!
//! A body that is not an entity's (a tile of a level) has no entity:
//! its `Option<Entity>` is `None` and its id says which body it is.

use bevy::prelude::{Deref, Entity, Message};
use passo_physics::{BodyId, ContactPair, JointDef, JointId, SensorPair};

use crate::BodyEntities;

/// Two bodies in a contact message, with their entities.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BodyPair {
    /// One body (the lower id).
    pub a: BodyId,
    /// The other body.
    pub b: BodyId,
    /// `a`'s entity (`None` for a tile, or once it is despawned).
    pub entity_a: Option<Entity>,
    /// `b`'s entity (`None` for a tile, or once it is despawned).
    pub entity_b: Option<Entity>,
}

impl BodyPair {
    pub(crate) fn new(pair: &ContactPair, entities: &BodyEntities) -> Self {
        Self {
            a: pair.a,
            b: pair.b,
            entity_a: entities.entity(pair.a),
            entity_b: entities.entity(pair.b),
        }
    }
}

/// A sensor and a visitor in a sensor message, with their entities.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SensorVisit {
    /// The sensor.
    pub sensor: BodyId,
    /// The body that entered or left it.
    pub visitor: BodyId,
    /// The sensor's entity (`None` once it is despawned).
    pub sensor_entity: Option<Entity>,
    /// The visitor's entity (`None` for a tile, or once it is despawned).
    pub visitor_entity: Option<Entity>,
}

impl SensorVisit {
    pub(crate) fn new(pair: &SensorPair, entities: &BodyEntities) -> Self {
        Self {
            sensor: pair.sensor,
            visitor: pair.visitor,
            sensor_entity: entities.entity(pair.sensor),
            visitor_entity: entities.entity(pair.visitor),
        }
    }
}

/// Two bodies started touching this tick. Its fields are the
/// [`BodyPair`]'s: `contact.entity_a`.
#[derive(Message, Clone, Copy, Debug, PartialEq, Eq, Deref)]
pub struct ContactBegan(pub BodyPair);

/// Two bodies stopped touching this tick (or one of them was removed).
#[derive(Message, Clone, Copy, Debug, PartialEq, Eq, Deref)]
pub struct ContactEnded(pub BodyPair);

/// A body entered a [`Sensor`](crate::Sensor) this tick. Its fields are
/// the [`SensorVisit`]'s: `visit.visitor_entity`.
#[derive(Message, Clone, Copy, Debug, PartialEq, Eq, Deref)]
pub struct SensorEntered(pub SensorVisit);

/// A body left a [`Sensor`](crate::Sensor) this tick (or was removed).
#[derive(Message, Clone, Copy, Debug, PartialEq, Eq, Deref)]
pub struct SensorExited(pub SensorVisit);

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
