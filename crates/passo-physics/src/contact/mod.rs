//! Contacts as a game sees them: how they are solved (settings), what it
//! can read about them after a step, and their events.

pub(crate) mod constraint;
pub(crate) mod hooks;

use crate::constants::{
    CONTACT_PUSH_SPEED, DEFAULT_SUBSTEPS, LINEAR_SLOP, POSITION_CORRECTION, RESTITUTION_THRESHOLD,
    REUSE_DISTANCE,
};
use crate::error::{non_negative, positive};
use crate::{BodyId, PhysicsError};
use glam::Vec2;

/// How contacts are solved. `WorldSettings::contacts: None` turns the
/// contact stage off altogether.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct ContactSettings {
    /// Substeps per step, >= 1. Default 4 ([`DEFAULT_SUBSTEPS`]).
    pub substeps: u32,
    /// Iterations per substep over every contact (normal, friction, push),
    /// at least 1. Default 1: with shock propagation after it, one holds
    /// piles as well as two did without (BENCHMARKS.md, the stability
    /// table).
    pub iterations: u32,
    /// Velocity iterations per substep after bodies moved ("relax": they see
    /// the new separations), >= 0. Default 1.
    pub relax_iterations: u32,
    /// Fraction of the overlap beyond the slop removed per substep, in
    /// `(0, 1]`. Default 0.2 ([`POSITION_CORRECTION`]).
    pub position_correction: f32,
    /// Cap on the push-apart speed, metres per second, > 0. Default 3.
    pub push_out_speed: f32,
    /// Allowed penetration, metres, >= 0. Default 0.005 ([`LINEAR_SLOP`]).
    pub slop: f32,
    /// Impacts slower than this do not bounce, metres per second, >= 0. Default 1.
    pub restitution_threshold: f32,
    /// Continuous collision: contacts are created ahead of time from each
    /// body's travel this step (speculative contacts), up to its reach
    /// ([`SPECULATIVE_REACH`](crate::constants::SPECULATIVE_REACH)), and a
    /// body that moves farther is swept against static and kinematic
    /// bodies (a bullet against every body) and stopped at its first
    /// impact. So fast bodies cannot pass through thin walls; an ordinary
    /// fast body may pass a thin dynamic body beyond its reach, a bullet
    /// cannot ([`BodyDef::bullet`](crate::BodyDef::bullet)). Default `true`.
    pub continuous: bool,
    /// Start each step from the last step's impulses. Default `true`.
    /// Off, stacks and piles still stand (shock propagation holds them
    /// up), but the passes start from nothing each substep: in the
    /// stability suite a circle among small ones took 6.6 s to rest
    /// instead of 0.6, and a box thrown into a heap 5.2 s instead of 2.3,
    /// with overlaps up to 34 mm. Without shock propagation too, a stack
    /// of 30 boxes falls into itself.
    pub warm_starting: bool,
    /// Shock propagation: after the iterations of each substep, the
    /// contacts that hold bodies up against gravity (normal within about
    /// 45 degrees of straight up) are solved once more, layer by layer
    /// from the ground up, each as if its lower body could not move. No
    /// body then sinks into the one under it, whatever their masses: a
    /// 1000 kg crate on a 1 kg crate rests at once, and a heavy body
    /// landing on a pile stops instead of bouncing off it. The pass gives
    /// a body resting on others a push that the bodies under it do not
    /// feel back (it corrects velocities; the warm start leaves it out).
    /// Off, momentum between touching bodies is kept exactly, but one
    /// iteration no longer holds piles: in the stability suite a stack of
    /// 30 boxes then takes 3.8 s to rest, a 1000 kg box on a 1 kg box never
    /// rests and gains 8 % energy, and a stack growing to 1000 kg throws
    /// boxes out. Turn it off only with `iterations: 2` or more (then those
    /// stacks keep their boxes, but still ring for seconds, and the
    /// 1000 kg box still gains energy). It does
    /// nothing without gravity. Default `true`.
    pub shock_propagation: bool,
    /// Islands of touching bodies that have all been slower than
    /// [`SLEEP_SPEED`] for [`TIME_TO_SLEEP`] fall asleep: their contacts
    /// are kept but no longer solved, and they cost little until an awake
    /// body reaches them or game code changes one of them. Default `true`.
    ///
    /// [`SLEEP_SPEED`]: crate::constants::SLEEP_SPEED
    /// [`TIME_TO_SLEEP`]: crate::constants::TIME_TO_SLEEP
    pub sleeping: bool,
    /// How far two touching bodies may move relative to each other, in
    /// metres (>= 0), before their contact is found afresh: until then a
    /// step keeps the last step's contact (normal, friction, points) and
    /// only moves its separation along the normal by that motion, which
    /// saves 12–16 % of a step in piles. Contacts with a one-way
    /// platform, a kinematic body or restitution are always found afresh,
    /// and so are a body's after game code changes its friction,
    /// restitution, friction mix, filter, sensor flag or one-way side. A
    /// body moved by `set_position` less than this moves as if it had
    /// travelled there. Two boxes' kept separation is exact while their
    /// faces meet; two circles' is off by about the square of the sideways
    /// motion over twice the distance between their centres (0.06 mm for
    /// circles of radius 0.1 m at the default, 0.6 mm at radius 1 cm), so a
    /// game of bodies only millimetres across should lower it. `0` finds
    /// every contact afresh each step. Default 0.005 ([`REUSE_DISTANCE`]).
    pub reuse_distance: f32,
}

impl Default for ContactSettings {
    fn default() -> Self {
        Self {
            substeps: DEFAULT_SUBSTEPS,
            iterations: 1,
            relax_iterations: 1,
            position_correction: POSITION_CORRECTION,
            push_out_speed: CONTACT_PUSH_SPEED,
            slop: LINEAR_SLOP,
            restitution_threshold: RESTITUTION_THRESHOLD,
            continuous: true,
            warm_starting: true,
            shock_propagation: true,
            sleeping: true,
            reuse_distance: REUSE_DISTANCE,
        }
    }
}

impl ContactSettings {
    /// Checks every value, naming the first one that is wrong.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        let count = |what, n: u32, min: u32| {
            if n >= min && n <= 1024 {
                Ok(())
            } else {
                Err(PhysicsError::OutOfRange {
                    what,
                    value: n as f32,
                    allowed: if min == 1 {
                        "in [1, 1024]"
                    } else {
                        "in [0, 1024]"
                    },
                })
            }
        };
        count("ContactSettings::substeps", self.substeps, 1)?;
        count("ContactSettings::iterations", self.iterations, 1)?;
        count(
            "ContactSettings::relax_iterations",
            self.relax_iterations,
            0,
        )?;
        positive(
            "ContactSettings::position_correction",
            self.position_correction,
        )?;
        if self.position_correction > 1.0 {
            return Err(PhysicsError::OutOfRange {
                what: "ContactSettings::position_correction",
                value: self.position_correction,
                allowed: "in (0, 1]",
            });
        }
        positive("ContactSettings::push_out_speed", self.push_out_speed)?;
        non_negative("ContactSettings::slop", self.slop)?;
        non_negative(
            "ContactSettings::restitution_threshold",
            self.restitution_threshold,
        )?;
        non_negative("ContactSettings::reuse_distance", self.reuse_distance)?;
        Ok(())
    }
}

/// A contact between two bodies after the last step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// First body.
    pub a: BodyId,
    /// Second body.
    pub b: BodyId,
    /// Unit normal from `a` to `b`.
    pub normal: Vec2,
    /// Separation along the normal at the end of the step, metres
    /// (negative: overlap). A speculative contact has a positive separation.
    pub separation: f32,
    /// Contact points (world space) where the contact was found: at the
    /// start of the step, or of an earlier one whose contact this step kept
    /// (see [`ContactSettings::reuse_distance`]), within that distance.
    pub points: [Vec2; 2],
    /// Number of valid points, 1 or 2.
    pub point_count: u8,
    /// Normal impulse of the last substep, newton seconds.
    pub normal_impulse: f32,
    /// Friction impulse of the last substep, newton seconds.
    pub tangent_impulse: f32,
    /// Whether the bodies touch: the solver pushed them apart this step, or
    /// they overlap.
    pub touching: bool,
}

impl Contact {
    /// The same contact seen from `b`.
    pub fn flipped(&self) -> Self {
        Self {
            a: self.b,
            b: self.a,
            normal: -self.normal,
            ..*self
        }
    }
}

/// Two bodies that started or stopped touching during the last step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactPair {
    /// One body (the one with the lower index).
    pub a: BodyId,
    /// The other body.
    pub b: BodyId,
}

/// A body that entered or left a sensor during the last step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SensorPair {
    /// The sensor.
    pub sensor: BodyId,
    /// The body that entered or left it.
    pub visitor: BodyId,
}

/// What happened to contacts and sensors in the last step, in a fixed order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactEvents {
    /// The step these events happened in: [`StepStats::steps`] right after
    /// it (0 before the first, right after a restore, and in a world that
    /// has never held a shaped body, where nothing can touch). A game
    /// reading events once per frame handles them only when this changed.
    ///
    /// [`StepStats::steps`]: crate::StepStats::steps
    pub step: u64,
    /// Pairs that started touching.
    pub begin: Vec<ContactPair>,
    /// Pairs that stopped touching (or whose body was removed).
    pub end: Vec<ContactPair>,
    /// Bodies that entered a sensor.
    pub sensor_begin: Vec<SensorPair>,
    /// Bodies that left a sensor (or were removed).
    pub sensor_end: Vec<SensorPair>,
}

impl ContactEvents {
    pub(crate) fn clear(&mut self) {
        self.begin.clear();
        self.end.clear();
        self.sensor_begin.clear();
        self.sensor_end.clear();
    }
}
