//! Contact hooks: game code that sees each contact before it is solved and
//! may filter it out or change how it is solved (a conveyor belt, ice in
//! one place, a ghost that passes through its own team).

use crate::BodyId;
use glam::Vec2;

/// Game code run on the contacts of every step ([`World::set_contact_hooks`]).
///
/// Both methods are called after the contacts of a step are found and
/// before any is solved, one contact after another in the order of the
/// pairs' ids (lower slot index first), on the thread that steps the world:
/// the same calls in the same order at any frame rate and thread count.
///
/// **What a hook may do**: read its arguments and its own data, and answer.
/// **What it may not**: change the world (it has no access to it), or keep
/// state that changes its answers from step to step in a way the world
/// does not see (a counter, the time, a random number): a snapshot would
/// not restore it, and a rollback would diverge. A hook that depends only
/// on its arguments and on data fixed while the game runs keeps every
/// determinism promise. Hooks are code, not data: snapshots do not carry
/// them, as they do not carry custom force models.
///
/// [`World::set_contact_hooks`]: crate::World::set_contact_hooks
pub trait ContactHooks: Send + Sync {
    /// Whether bodies `a` and `b` may touch this step: `false` drops their
    /// contact (or, when one is a sensor, the sensor's sight of the other)
    /// as a [`CollisionFilter`](crate::CollisionFilter) would. Called for
    /// every pair that passed the collision filters, once a step. Default:
    /// always.
    fn filter_pair(&self, a: &PairInfo, b: &PairInfo) -> bool {
        let _ = (a, b);
        true
    }

    /// Changes one contact before it is solved (see [`PreSolve`]). Called
    /// for every contact that passed [`filter_pair`](Self::filter_pair).
    /// Default: nothing.
    fn pre_solve(&self, contact: &mut PreSolve) {
        let _ = contact;
    }
}

/// One body of a pair, as a hook sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairInfo {
    /// The body.
    pub id: BodyId,
    /// Its [`user_data`](crate::BodyDef::user_data).
    pub user_data: u64,
}

/// A contact as a pre-solve hook sees and changes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreSolve {
    /// Body A (always a dynamic body).
    pub a: PairInfo,
    /// Body B.
    pub b: PairInfo,
    /// Unit normal from A to B.
    pub normal: Vec2,
    /// Separation when the step began, metres (negative: overlap).
    pub separation: f32,
    /// `false` ignores the contact this step: the bodies pass through each
    /// other as if they did not collide. Default `true`.
    pub enabled: bool,
    /// The friction coefficient (as the bodies' friction mix gave it),
    /// >= 0.
    pub friction: f32,
    /// The restitution (the larger of the two bodies'), in `[0, 1]`.
    pub restitution: f32,
    /// How fast B's surface slides past A's along `normal.perp()`, m/s,
    /// which friction drives the bodies toward (within its limit): a
    /// conveyor belt. Set it with [`conveyor`](Self::conveyor). Default 0.
    pub tangent_speed: f32,
}

impl PreSolve {
    /// Makes `belt`'s surface carry what touches it at `velocity` (m/s,
    /// along the surface; the part along the normal is ignored), as a
    /// conveyor belt. Does nothing if `belt` is neither body.
    pub fn conveyor(&mut self, belt: BodyId, velocity: Vec2) {
        let tangent = self.normal.perp();
        if belt == self.b.id {
            // Friction drives (v_b - v_a) . t toward the speed: A is carried
            // along at `velocity` when B's surface moves at it.
            self.tangent_speed = -velocity.dot(tangent);
        } else if belt == self.a.id {
            self.tangent_speed = velocity.dot(tangent);
        }
    }
}
