//! Joints: links between two bodies, or a body and a point of the world,
//! solved in the contact step's substeps beside the contacts (see
//! `solve`). Bodies do not rotate, so every joint acts on the bodies'
//! centres through fixed offsets: a joint's anchors never turn.
//!
//! This file holds what game code sees (the definitions and their checks)
//! and the store of a world's joints; `solve` holds the maths.

pub(crate) mod soft;
pub(crate) mod rods;
pub(crate) mod solve;

use crate::PhysicsError;
use crate::error::{finite_vec, non_negative, position, positive};
use crate::id::{BodyId, JointId};
use glam::Vec2;

/// A spring: how hard a soft joint pulls toward its rest state.
///
/// `hertz` is the frequency the joint would oscillate at on a body with
/// nothing else attached, `damping_ratio` how fast that oscillation dies:
/// 0 rings for ever, 1 is critical (no overshoot), more is slower still.
/// The spring is implicit (solved as a soft constraint, as in Box2D v3), so
/// it stays stable at any stiffness and step.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointSpring {
    /// Frequency, hertz, >= 0 (0: no spring force).
    pub hertz: f32,
    /// Damping ratio, >= 0.
    pub damping_ratio: f32,
}

impl JointSpring {
    /// A spring of `hertz` with `damping_ratio`.
    pub fn new(hertz: f32, damping_ratio: f32) -> Self {
        Self {
            hertz,
            damping_ratio,
        }
    }

    fn validate(self) -> Result<(), PhysicsError> {
        non_negative("JointSpring::hertz", self.hertz)?;
        non_negative("JointSpring::damping_ratio", self.damping_ratio)?;
        Ok(())
    }
}

/// A motor along a joint's axis: it drives the bodies toward a relative
/// speed with at most a given force.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointMotor {
    /// Target speed of B relative to A along the axis, metres per second.
    pub speed: f32,
    /// Largest force the motor applies, newtons, >= 0.
    pub max_force: f32,
}

/// What a joint holds, by kind.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum JointKind {
    /// Keeps the anchors `length` apart: a rigid rod. With
    /// `min_length < max_length` the distance is free between them (a
    /// rope when `min_length` is 0), and with a spring it is pulled toward
    /// `length` while the limits still hold.
    Distance {
        /// Rest length, metres, in `[min_length, max_length]`.
        length: f32,
        /// Shortest the distance gets, metres, >= 0.
        min_length: f32,
        /// Longest the distance gets, metres (`f32::INFINITY`: no limit).
        max_length: f32,
        /// A spring toward `length`, or none.
        spring: Option<JointSpring>,
    },
    /// A slider: B moves along `axis` relative to A, never across it.
    Prismatic {
        /// The direction of travel (any length but zero; stored as a unit
        /// vector).
        axis: Vec2,
        /// Travel of B's anchor from A's along the axis, metres: least and
        /// most, or none.
        limits: Option<(f32, f32)>,
        /// A motor along the axis, or none.
        motor: Option<JointMotor>,
    },
    /// Holds B's anchor on A's: the two bodies move as one, or, with a
    /// spring, as one linked by a spring.
    Weld {
        /// A spring instead of a rigid link, or none.
        spring: Option<JointSpring>,
    },
    /// Pulls A's anchor toward a point of the world (the joint's `anchor_b`,
    /// with `b` none) with a spring and at most a given force: dragging a
    /// body with the mouse.
    Target {
        /// Largest force, newtons, > 0 (`f32::INFINITY`: no limit).
        max_force: f32,
        /// The spring toward the point.
        spring: JointSpring,
    },
}

/// A joint to add to a world ([`World::add_joint`](crate::World::add_joint)).
///
/// Bodies do not rotate, so an anchor is a fixed offset from its body's
/// centre. `b: None` fixes the joint to the world: `anchor_b` is then a
/// point of the world.
///
/// ```
/// use passo_physics::{BodyDef, JointDef, World, glam::Vec2};
///
/// let mut world = World::default();
/// let bob = world.add_body(BodyDef::point_mass(Vec2::new(1.0, 0.0))).unwrap();
/// // A pendulum: a rod of 1 m from the origin.
/// world.add_joint(JointDef::distance(bob, None, 1.0)).unwrap();
/// for _ in 0..120 {
///     world.step(1.0 / 60.0);
/// }
/// let length = world.body(bob).unwrap().position.length();
/// assert!((length - 1.0).abs() < 1e-3);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointDef {
    /// The first body.
    pub a: BodyId,
    /// The second body, or `None` for the world.
    pub b: Option<BodyId>,
    /// Where the joint holds A: an offset from its centre, metres.
    pub anchor_a: Vec2,
    /// Where the joint holds B: an offset from its centre, or a point of
    /// the world when `b` is `None`.
    pub anchor_b: Vec2,
    /// What the joint holds.
    pub kind: JointKind,
    /// The joint breaks when the force it applies exceeds this, newtons
    /// (> 0; `None`: never). It is then removed at the end of the step and
    /// listed in [`World::broken_joints`](crate::World::broken_joints).
    pub break_force: Option<f32>,
    /// Whether the two bodies still collide with each other. Default
    /// `false`, as in Box2D: a door does not catch on its own frame, nor a
    /// link of a chain on the next.
    #[cfg_attr(feature = "serde", serde(default))]
    pub collide: bool,
    /// A number of the game's own, for finding its object from the joint.
    pub user_data: u64,
}

impl JointDef {
    /// A joint of `kind` between the centres of `a` and `b`.
    pub fn new(a: BodyId, b: Option<BodyId>, kind: JointKind) -> Self {
        Self {
            a,
            b,
            anchor_a: Vec2::ZERO,
            anchor_b: Vec2::ZERO,
            kind,
            break_force: None,
            collide: false,
            user_data: 0,
        }
    }

    /// A rigid rod of `length` metres between the centres of `a` and `b`
    /// (with `b: None`, between `a` and the origin; move that end with
    /// [`anchors`](Self::anchors)).
    pub fn distance(a: BodyId, b: Option<BodyId>, length: f32) -> Self {
        Self::new(
            a,
            b,
            JointKind::Distance {
                length,
                min_length: length,
                max_length: length,
                spring: None,
            },
        )
    }

    /// A rope: the centres of `a` and `b` at most `max_length` apart, free
    /// to come closer.
    pub fn rope(a: BodyId, b: Option<BodyId>, max_length: f32) -> Self {
        Self::new(
            a,
            b,
            JointKind::Distance {
                length: max_length,
                min_length: 0.0,
                max_length,
                spring: None,
            },
        )
    }

    /// A spring of rest length `length` between the centres of `a` and
    /// `b`, with no limits.
    pub fn spring(a: BodyId, b: Option<BodyId>, length: f32, spring: JointSpring) -> Self {
        Self::new(
            a,
            b,
            JointKind::Distance {
                length,
                min_length: 0.0,
                max_length: f32::INFINITY,
                spring: Some(spring),
            },
        )
    }

    /// A slider: `b` moves along `axis` relative to `a`.
    pub fn prismatic(a: BodyId, b: Option<BodyId>, axis: Vec2) -> Self {
        Self::new(
            a,
            b,
            JointKind::Prismatic {
                axis,
                limits: None,
                motor: None,
            },
        )
    }

    /// A weld: `b`'s centre held at `a`'s centre plus `offset` (with
    /// `b: None`, `a`'s centre held at the point `offset`).
    pub fn weld(a: BodyId, b: Option<BodyId>, offset: Vec2) -> Self {
        let mut def = Self::new(a, b, JointKind::Weld { spring: None });
        match b {
            Some(_) => def.anchor_a = offset,
            None => def.anchor_b = offset,
        }
        def
    }

    /// A target joint: `body`'s centre pulled toward `point` by a spring of
    /// 5 Hz and damping ratio 0.7, with no limit on the force (set one with
    /// [`max_force`](Self::max_force)).
    pub fn target(body: BodyId, point: Vec2) -> Self {
        let mut def = Self::new(
            body,
            None,
            JointKind::Target {
                max_force: f32::INFINITY,
                spring: JointSpring::new(5.0, 0.7),
            },
        );
        def.anchor_b = point;
        def
    }

    /// The anchors: offsets from the bodies' centres (`anchor_b` a point of
    /// the world when `b` is `None`).
    pub fn anchors(mut self, anchor_a: Vec2, anchor_b: Vec2) -> Self {
        self.anchor_a = anchor_a;
        self.anchor_b = anchor_b;
        self
    }

    /// The shortest and longest a distance joint gets (ignored by other
    /// kinds); the rest length is clamped into them.
    pub fn limits(mut self, min: f32, max: f32) -> Self {
        match &mut self.kind {
            JointKind::Distance {
                length,
                min_length,
                max_length,
                ..
            } => {
                (*min_length, *max_length) = (min, max);
                *length = length.max(min).min(max);
            }
            JointKind::Prismatic { limits, .. } => *limits = Some((min, max)),
            _ => {}
        }
        self
    }

    /// A spring: softens a distance or weld joint, or sets a target
    /// joint's (ignored by a slider).
    pub fn with_spring(mut self, hertz: f32, damping_ratio: f32) -> Self {
        let s = JointSpring::new(hertz, damping_ratio);
        match &mut self.kind {
            JointKind::Distance { spring, .. } | JointKind::Weld { spring } => *spring = Some(s),
            JointKind::Target { spring, .. } => *spring = s,
            JointKind::Prismatic { .. } => {}
        }
        self
    }

    /// A slider's motor: toward `speed` along the axis with at most
    /// `max_force` (ignored by other kinds).
    pub fn motor(mut self, speed: f32, max_force: f32) -> Self {
        if let JointKind::Prismatic { motor, .. } = &mut self.kind {
            *motor = Some(JointMotor { speed, max_force });
        }
        self
    }

    /// A target joint's largest force (ignored by other kinds).
    pub fn max_force(mut self, force: f32) -> Self {
        if let JointKind::Target { max_force, .. } = &mut self.kind {
            *max_force = force;
        }
        self
    }

    /// Lets the two bodies collide with each other (they do not by
    /// default).
    pub fn colliding(mut self) -> Self {
        self.collide = true;
        self
    }

    /// Breaks above `force` newtons.
    pub fn break_force(mut self, force: f32) -> Self {
        self.break_force = Some(force);
        self
    }

    /// Checks every value (not the bodies: the world does that).
    pub fn validate(&self) -> Result<(), PhysicsError> {
        finite_vec("JointDef::anchor_a", self.anchor_a)?;
        match self.b {
            Some(_) => finite_vec("JointDef::anchor_b", self.anchor_b)?,
            None => position("JointDef::anchor_b", self.anchor_b)?,
        };
        if self.b == Some(self.a) {
            return Err(PhysicsError::InvalidJoint(
                "a joint links two different bodies",
            ));
        }
        if let Some(force) = self.break_force {
            positive("JointDef::break_force", force)?;
        }
        match self.kind {
            JointKind::Distance {
                length,
                min_length,
                max_length,
                spring,
            } => {
                non_negative("JointKind::Distance::length", length)?;
                non_negative("JointKind::Distance::min_length", min_length)?;
                if max_length.is_nan() || !(min_length <= length && length <= max_length) {
                    return Err(PhysicsError::InvalidJoint(
                        "a distance joint needs min_length <= length <= max_length",
                    ));
                }
                if let Some(spring) = spring {
                    spring.validate()?;
                }
            }
            JointKind::Prismatic {
                axis,
                limits,
                motor,
            } => {
                finite_vec("JointKind::Prismatic::axis", axis)?;
                if axis.length_squared() == 0.0 || !axis.length_squared().is_finite() {
                    return Err(PhysicsError::InvalidJoint(
                        "a prismatic joint needs a non-zero, finite axis",
                    ));
                }
                if let Some((lower, upper)) = limits {
                    crate::error::finite("JointKind::Prismatic::limits", lower)?;
                    crate::error::finite("JointKind::Prismatic::limits", upper)?;
                    if lower > upper {
                        return Err(PhysicsError::InvalidJoint(
                            "a prismatic joint's limits need lower <= upper",
                        ));
                    }
                }
                if let Some(motor) = motor {
                    crate::error::finite("JointMotor::speed", motor.speed)?;
                    non_negative("JointMotor::max_force", motor.max_force)?;
                }
            }
            JointKind::Weld { spring } => {
                if let Some(spring) = spring {
                    spring.validate()?;
                }
            }
            JointKind::Target { max_force, spring } => {
                if max_force.is_nan() || max_force <= 0.0 {
                    return Err(PhysicsError::OutOfRange {
                        what: "JointKind::Target::max_force",
                        value: max_force,
                        allowed: "> 0",
                    });
                }
                spring.validate()?;
            }
        }
        Ok(())
    }

    /// The definition as stored: a prismatic axis of unit length.
    pub(crate) fn normalized(mut self) -> Self {
        if let JointKind::Prismatic { axis, .. } = &mut self.kind {
            *axis = axis.normalize();
        }
        self
    }
}

/// A joint that broke in the last step: its force went over its
/// [`break_force`](JointDef::break_force). It is gone from the world.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BrokenJoint {
    /// The joint's id (stale now).
    pub id: JointId,
    /// Its definition.
    pub def: JointDef,
    /// The force it applied in the last substep, newtons.
    pub force: f32,
}

/// The impulses a joint applied in its last substep, kept to warm start
/// the next one (each newton-second; divided by the substep, a force).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct JointImpulses {
    /// Along the distance joint's axis (rigid or spring), across a
    /// slider's axis (x), or both axes of a weld or target joint.
    pub linear: Vec2,
    /// A limit's push apart (distance: min length; slider: lower).
    pub lower: f32,
    /// A limit's pull together (distance: max length; slider: upper).
    pub upper: f32,
    /// A slider's motor.
    pub motor: f32,
}

impl JointImpulses {
    fn is_finite(&self) -> bool {
        self.linear.is_finite()
            && self.lower.is_finite()
            && self.upper.is_finite()
            && self.motor.is_finite()
    }
}

/// One slot of the joint table.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct JointSlot {
    pub generation: u32,
    pub joint: Option<StoredJoint>,
}

/// A live joint: its definition and its impulses.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct StoredJoint {
    pub def: JointDef,
    pub impulses: JointImpulses,
    /// The force it applied in the last substep, newtons (0 before its
    /// first step).
    pub force: f32,
}

/// A world's joints: slots with generations, solved in slot order (which
/// depends only on the adds and removals, so the same calls give the same
/// bits).
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Joints {
    pub slots: Vec<JointSlot>,
    pub free: Vec<u32>,
    /// Live joints.
    pub count: usize,
}

impl Joints {
    /// Stores a checked definition; returns its id.
    pub(crate) fn insert(&mut self, def: JointDef) -> JointId {
        let joint = Some(StoredJoint {
            def,
            impulses: JointImpulses::default(),
            force: 0.0,
        });
        self.count += 1;
        if let Some(index) = self.free.pop() {
            let slot = &mut self.slots[index as usize];
            slot.joint = joint;
            return JointId {
                index,
                generation: slot.generation,
            };
        }
        self.slots.push(JointSlot {
            generation: 0,
            joint,
        });
        JointId {
            index: self.slots.len() as u32 - 1,
            generation: 0,
        }
    }

    /// The live joint `id` names.
    pub(crate) fn get(&self, id: JointId) -> Option<&StoredJoint> {
        let slot = self.slots.get(id.index as usize)?;
        (slot.generation == id.generation)
            .then_some(slot.joint.as_ref())
            .flatten()
    }

    /// The live joint `id` names, to change.
    pub(crate) fn get_mut(&mut self, id: JointId) -> Option<&mut StoredJoint> {
        let slot = self.slots.get_mut(id.index as usize)?;
        if slot.generation != id.generation {
            return None;
        }
        slot.joint.as_mut()
    }

    /// Removes joint `id`; returns it.
    pub(crate) fn remove(&mut self, id: JointId) -> Option<StoredJoint> {
        let slot = self.slots.get_mut(id.index as usize)?;
        if slot.generation != id.generation {
            return None;
        }
        let joint = slot.joint.take()?;
        slot.generation = slot.generation.wrapping_add(1);
        self.free.push(id.index);
        self.count -= 1;
        Some(joint)
    }

    /// Every live joint with its id, in slot order.
    pub(crate) fn iter(&self) -> impl Iterator<Item = (JointId, &StoredJoint)> {
        self.slots.iter().enumerate().filter_map(|(i, slot)| {
            let id = JointId {
                index: i as u32,
                generation: slot.generation,
            };
            slot.joint.as_ref().map(|j| (id, j))
        })
    }

    /// The ids of the joints attached to `body`, in slot order.
    pub(crate) fn attached_to(&self, body: BodyId) -> Vec<JointId> {
        self.iter()
            .filter(|(_, j)| j.def.a == body || j.def.b == Some(body))
            .map(|(id, _)| id)
            .collect()
    }

    /// The pairs of bodies a joint links that do not collide (its
    /// `collide` is off), by their order key, sorted and each once, into
    /// `out`.
    pub(crate) fn apart(&self, out: &mut Vec<(BodyId, BodyId)>) {
        out.clear();
        for (_, joint) in self.iter() {
            if let (false, Some(b)) = (joint.def.collide, joint.def.b) {
                out.push(crate::contact::constraint::key(joint.def.a, b));
            }
        }
        out.sort_unstable();
        out.dedup();
    }

    /// Drops impulses that overflowed `f32` (see `put_back_non_finite`).
    pub(crate) fn drop_non_finite(&mut self) {
        for joint in self.slots.iter_mut().filter_map(|s| s.joint.as_mut()) {
            if !joint.impulses.is_finite() || !joint.force.is_finite() {
                joint.impulses = JointImpulses::default();
                joint.force = 0.0;
            }
        }
    }

    /// Bytes on the heap.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.slots.capacity() * std::mem::size_of::<JointSlot>()
            + self.free.capacity() * std::mem::size_of::<u32>()
    }

    /// Checks a table read from a file: slots and free list agree, counts
    /// match, every definition passes its checks.
    pub(crate) fn validate(&self) -> Result<(), PhysicsError> {
        let bad = |why: &str| Err(PhysicsError::InvalidSnapshot(format!("joints: {why}")));
        if self.slots.len() > crate::constants::MAX_JOINTS {
            return bad("more than MAX_JOINTS slots");
        }
        let live = self.slots.iter().filter(|s| s.joint.is_some()).count();
        if live != self.count || live + self.free.len() != self.slots.len() {
            return bad("the count and the free list disagree with the slots");
        }
        let mut freed = vec![false; self.slots.len()];
        for &i in &self.free {
            let Some(slot) = self.slots.get(i as usize) else {
                return bad("a free slot out of range");
            };
            if slot.joint.is_some() || std::mem::replace(&mut freed[i as usize], true) {
                return bad("a free slot in use or listed twice");
            }
        }
        for joint in self.slots.iter().filter_map(|s| s.joint.as_ref()) {
            joint.def.validate()?;
            if !axis_is_unit(&joint.def) {
                return bad("a slider's axis is not of unit length");
            }
            if !joint.impulses.is_finite() || !joint.force.is_finite() {
                return bad("a non-finite impulse");
            }
        }
        Ok(())
    }
}

/// Whether a slider's axis is of unit length (within rounding).
fn axis_is_unit(def: &JointDef) -> bool {
    match def.kind {
        JointKind::Prismatic { axis, .. } => (axis.length_squared() - 1.0).abs() < 1e-5,
        _ => true,
    }
}
