//! What game code does with joints: add, read, steer, remove (see
//! `crate::joint` for the joints themselves).

use crate::constants::MAX_JOINTS;
use crate::error::{finite, non_negative, position};
use crate::joint::solve::End;
use crate::joint::{BrokenJoint, JointDef, JointKind, JointMotor};
use crate::world::{Location, World};
use crate::{BodyId, JointId, PhysicsError};
use glam::Vec2;

/// A joint as game code reads it ([`World::joint`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Joint {
    /// Its definition (a slider's axis of unit length).
    pub def: JointDef,
    /// The force it applied in the last substep of the last step, newtons
    /// (0 before its first step, and while its bodies sleep).
    pub force: f32,
    /// Where its anchors are now: on A, and on B (or the world's point).
    pub anchors: (Vec2, Vec2),
}

impl World {
    /// Adds a joint between two bodies, or a body and the world.
    ///
    /// At least one end must be a dynamic body that is not kinematic. Both
    /// bodies wake. Contacts must be on (`WorldSettings::contacts`): joints
    /// are solved in the contact step's substeps.
    ///
    /// ```
    /// use passo_physics::{BodyDef, JointDef, Shape, World, glam::Vec2};
    ///
    /// let mut world = World::default();
    /// let anchor = world.add_body(BodyDef::new_static(Vec2::new(0.0, 5.0), Shape::circle(0.1))).unwrap();
    /// let crate_ = world.add_body(BodyDef {
    ///     position: Vec2::new(0.0, 3.0),
    ///     shape: Some(Shape::rect(0.5, 0.5)),
    ///     ..Default::default()
    /// }).unwrap();
    /// // A rope of 2.5 m: the crate falls 0.5 m and hangs.
    /// world.add_joint(JointDef::rope(anchor, Some(crate_), 2.5)).unwrap();
    /// for _ in 0..300 {
    ///     world.step(1.0 / 60.0);
    /// }
    /// assert!((world.body(crate_).unwrap().position.y - 2.5).abs() < 0.01);
    /// ```
    pub fn add_joint(&mut self, def: JointDef) -> Result<JointId, PhysicsError> {
        def.validate()?;
        if self.settings.contacts.is_none() {
            return Err(PhysicsError::InvalidJoint(
                "joints need contacts on (WorldSettings::contacts)",
            ));
        }
        let movable = |id: BodyId| -> Result<bool, PhysicsError> {
            Ok(match self.locate(id).ok_or(PhysicsError::StaleBody(id))? {
                Location::Dynamic(i) => !self.dynamic.meta[i as usize].kinematic,
                Location::Static(_) => false,
            })
        };
        let moves_a = movable(def.a)?;
        let moves_b = match def.b {
            Some(b) => movable(b)?,
            None => false,
        };
        if !moves_a && !moves_b {
            return Err(PhysicsError::InvalidJoint(
                "a joint needs a dynamic body that is not kinematic",
            ));
        }
        if self.joints.count >= MAX_JOINTS {
            return Err(PhysicsError::OutOfRange {
                what: "World::add_joint",
                value: self.joints.count as f32,
                allowed: "fewer than MAX_JOINTS joints",
            });
        }
        self.wake_joint_ends(&def);
        self.joint_rows.apart_stale = true;
        Ok(self.joints.insert(def.normalized()))
    }

    /// Removes a joint and returns its definition, or `None` for a stale
    /// id. Its bodies wake.
    pub fn remove_joint(&mut self, id: JointId) -> Option<JointDef> {
        let joint = self.joints.remove(id)?;
        self.wake_joint_ends(&joint.def);
        self.joint_rows.apart_stale = true;
        Some(joint.def)
    }

    /// The joint `id` names, or `None` for a stale id (removed, or broken).
    pub fn joint(&self, id: JointId) -> Option<Joint> {
        let joint = self.joints.get(id)?;
        Some(Joint {
            def: joint.def,
            force: joint.force,
            anchors: self.anchors(&joint.def),
        })
    }

    /// Every joint with its id, in id order.
    pub fn joints(&self) -> impl Iterator<Item = (JointId, Joint)> + '_ {
        self.joints.iter().map(|(id, joint)| {
            let view = Joint {
                def: joint.def,
                force: joint.force,
                anchors: self.anchors(&joint.def),
            };
            (id, view)
        })
    }

    /// Number of joints.
    pub fn joint_len(&self) -> usize {
        self.joints.count
    }

    /// The joints attached to `body`, in id order.
    pub fn joints_of(&self, body: BodyId) -> Vec<JointId> {
        self.joints.attached_to(body)
    }

    /// The joints that broke in the last step (their force went over their
    /// [`break_force`](JointDef::break_force)), in id order. They are gone
    /// from the world.
    pub fn broken_joints(&self) -> &[BrokenJoint] {
        &self.broken_joints
    }

    /// Moves a target joint's point (the mouse moved). Its body wakes.
    pub fn set_joint_target(&mut self, id: JointId, point: Vec2) -> Result<(), PhysicsError> {
        position("World::set_joint_target", point)?;
        let joint = self
            .joints
            .get_mut(id)
            .ok_or(PhysicsError::StaleJoint(id))?;
        if !matches!(joint.def.kind, JointKind::Target { .. }) {
            return Err(PhysicsError::InvalidJoint(
                "set_joint_target needs a target joint",
            ));
        }
        joint.def.anchor_b = point;
        let def = joint.def;
        self.wake_joint_ends(&def);
        Ok(())
    }

    /// Sets a slider's motor: toward `speed` (m/s, B relative to A along
    /// the axis) with at most `max_force` newtons; `None` turns it off.
    /// Its bodies wake.
    pub fn set_joint_motor(
        &mut self,
        id: JointId,
        motor: Option<JointMotor>,
    ) -> Result<(), PhysicsError> {
        if let Some(m) = motor {
            finite("JointMotor::speed", m.speed)?;
            non_negative("JointMotor::max_force", m.max_force)?;
        }
        let joint = self
            .joints
            .get_mut(id)
            .ok_or(PhysicsError::StaleJoint(id))?;
        let JointKind::Prismatic { motor: slot, .. } = &mut joint.def.kind else {
            return Err(PhysicsError::InvalidJoint(
                "set_joint_motor needs a prismatic joint",
            ));
        };
        *slot = motor;
        if motor.is_none() {
            joint.impulses.motor = 0.0;
        }
        let def = joint.def;
        self.wake_joint_ends(&def);
        Ok(())
    }

    /// Where a joint's anchors are now.
    fn anchors(&self, def: &JointDef) -> (Vec2, Vec2) {
        let at = |id: BodyId| self.body(id).map_or(Vec2::ZERO, |b| b.position);
        let b = def.b.map_or(Vec2::ZERO, at);
        (at(def.a) + def.anchor_a, b + def.anchor_b)
    }

    /// Wakes the dynamic bodies a joint links.
    fn wake_joint_ends(&mut self, def: &JointDef) {
        for id in std::iter::once(def.a).chain(def.b) {
            if let Some(Location::Dynamic(i)) = self.locate(id) {
                self.wake_index(i as usize);
            }
        }
    }

    /// Removes the joints attached to `body` (it is being removed), waking
    /// their other bodies.
    pub(crate) fn remove_joints_of(&mut self, body: BodyId) {
        if self.joints.count == 0 {
            return;
        }
        for id in self.joints.attached_to(body) {
            self.remove_joint(id);
        }
    }

    /// Where a body is for the joints' rows of a step.
    pub(crate) fn joint_end(&self, id: BodyId) -> Option<End> {
        Some(match self.locate(id)? {
            Location::Dynamic(i) => {
                let i = i as usize;
                let asleep = self.dynamic.sleep[i].is_asleep();
                End {
                    body: Some(i as u32),
                    pos: self.dynamic.pos.at(i),
                    inv_mass: if asleep {
                        0.0
                    } else {
                        self.dynamic.inv_mass[i]
                    },
                }
            }
            Location::Static(i) => End {
                body: None,
                pos: self.statics.pos[i as usize],
                inv_mass: 0.0,
            },
        })
    }
}
