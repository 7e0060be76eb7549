//! The joints' part of a substep: each joint a row of the bodies it moves
//! and the impulses it applied, warm started, then solved in the same
//! passes as the contacts (joints first, as Box2D v3 does), on the
//! solver's copy of the velocities.
//!
//! A rigid joint's velocity constraint is exact. Its drift is removed in
//! the solve passes by a stiff spring (soft step: [`JOINT_HERTZ`],
//! [`JOINT_DAMPING_RATIO`]), and the relax passes solve the velocity
//! constraint alone, which takes the spring's speed out again: the
//! correction moves the bodies but adds no energy. A joint's own spring
//! (a spring joint, a soft weld, a target joint) is a force, not a
//! correction: it acts in the solve passes only, once a substep with one
//! iteration, with as little numerical damping as its stiffness allows
//! (see `Soft::of`).
//!
//! Bodies do not rotate: each anchor is a fixed offset from its body's
//! centre, the Jacobian of every constraint is a unit direction, and the
//! effective mass is `1 / (1/m_a + 1/m_b)` along every direction.
//!
//! Joints are solved one after another in slot order (Gauss-Seidel), on
//! one thread: the bits are the same with any number of threads.

use crate::constants::{JOINT_DAMPING_RATIO, JOINT_HERTZ};
use crate::joint::{JointDef, JointImpulses, JointKind, JointSpring, Joints};
use crate::solver::scalar::BodyState;
use glam::Vec2;

/// A soft constraint's coefficients for a substep `h` (Box2D v3's
/// `b2Softness`, with its bias rate and mass scale multiplied out): the
/// impulse is `-m * (mass_scale * cdot + bias * C) - impulse_scale *
/// accumulated`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Soft {
    pub bias: f32,
    pub mass_scale: f32,
    pub impulse_scale: f32,
}

impl Soft {
    /// Rigid, with no correction of drift.
    pub(crate) const RIGID: Self = Self {
        bias: 0.0,
        mass_scale: 1.0,
        impulse_scale: 0.0,
    };

    /// Closes a gap `C` in one substep, no more: a limit not yet reached.
    fn speculative(h: f32) -> Self {
        Self {
            bias: 1.0 / h,
            ..Self::RIGID
        }
    }

    /// The impulse for relative speed `cdot`, error `c`, effective mass
    /// `m` and accumulated impulse `accumulated`.
    #[inline(always)]
    fn impulse<T>(self, m: f32, cdot: T, c: T, accumulated: T) -> T
    where
        T: std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T> + std::ops::Sub<Output = T>,
    {
        (cdot * (-m * self.mass_scale) + c * (-m * self.bias)) - accumulated * self.impulse_scale
    }

    /// A spring of `hertz` and `damping_ratio` over a substep `h`, as
    /// Box2D v3's `b2MakeSoft`: the spring force taken at the end of the
    /// substep (implicit Euler), stable at any stiffness; rigid when
    /// `hertz` is 0.
    pub(crate) fn new(hertz: f32, damping_ratio: f32, h: f32) -> Self {
        Self::weighted(hertz, damping_ratio, h, 1.0)
    }

    /// A spring whose force is taken a fraction `beta` of the way from
    /// the start of the substep to its end (the damping always at the
    /// end): 1 is [`new`](Self::new). With the positions then moved by
    /// the new velocity, a linear spring's step has determinant
    /// `1 / (1 + beta (h w)^2)`: its amplitude shrinks by that much a
    /// substep with no damping asked for. The step is stable when
    /// `(h w)^2 (1 - 2 beta) <= 4`.
    pub(crate) fn weighted(hertz: f32, damping_ratio: f32, h: f32, beta: f32) -> Self {
        if hertz == 0.0 {
            return Self::RIGID;
        }
        let omega = std::f32::consts::TAU * hertz;
        let hw = h * omega;
        let a2 = hw * (2.0 * damping_ratio + beta * hw);
        let a3 = 1.0 / (1.0 + a2);
        Self {
            bias: hw * omega * a3,
            mass_scale: a2 * a3,
            impulse_scale: a3,
        }
    }

    /// A joint's own spring, solved once a substep (the solve passes):
    /// explicit (`beta` 0, no numerical damping: the amplitude of an
    /// undamped spring neither grows nor shrinks) while the spring is soft
    /// for the substep, moving toward the midpoint (`beta` 1/2, stable at
    /// any stiffness) as it stiffens: `beta = max(0, 1/2 - 1/(h w)^2)`,
    /// which keeps the step stable with a margin of two.
    fn of(spring: JointSpring, h: f32) -> Self {
        let hw = h * std::f32::consts::TAU * spring.hertz;
        let beta = if hw * hw > 2.0 {
            0.5 - 1.0 / (hw * hw)
        } else {
            0.0
        };
        Self::weighted(spring.hertz, spring.damping_ratio, h, beta)
    }
}

/// Where a joint's end is during a step.
#[derive(Clone, Copy, Debug)]
pub(crate) struct End {
    /// The dynamic body whose state the passes read (a dynamic, kinematic
    /// or sleeping body), or none (a static body, the world).
    pub body: Option<u32>,
    /// Its position at the start of the step (zero for the world).
    pub pos: Vec2,
    /// Its inverse mass in the joint: zero for a kinematic, sleeping or
    /// static body.
    pub inv_mass: f32,
}

/// One joint in a step.
#[derive(Clone, Copy, Debug)]
pub(crate) struct JointRow {
    /// The joint's slot, to write its impulses back.
    slot: u32,
    a: Option<u32>,
    b: Option<u32>,
    ma: f32,
    mb: f32,
    /// Effective mass along any direction, `1 / (ma + mb)`.
    mass: f32,
    /// Anchor B minus anchor A at the start of the step.
    base: Vec2,
    kind: JointKind,
    impulses: JointImpulses,
    /// Drift correction of the rigid parts (solve passes only).
    rigid: Soft,
    /// The joint's own spring, if any (every pass).
    spring: Option<Soft>,
    h: f32,
}

/// Marks a rod's end that no state moves (a static body, the world).
const NONE: u32 = u32::MAX;

/// A rigid rod (a distance joint of one length and no spring), the most
/// common joint (chains, bridges, nets), in a row of its own: 40 bytes
/// against a general row's 120, so a pass over thousands streams a third
/// of the memory.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RodRow {
    /// Body A's and B's dynamic index, or [`NONE`].
    a: u32,
    b: u32,
    ma: f32,
    mb: f32,
    mass: f32,
    base: Vec2,
    length: f32,
    impulse: f32,
    slot: u32,
}

/// The rows of a step, and the links between dynamic bodies that make
/// them one island.
#[derive(Clone, Debug, Default)]
pub(crate) struct JointRows {
    pub rows: Vec<JointRow>,
    pub rods: Vec<RodRow>,
    /// The rods' drift correction this step.
    rigid: Option<Soft>,
    /// The substep, seconds.
    h: f32,
    /// Pairs of dynamic bodies (by index) a joint links: they sleep and
    /// wake together.
    pub links: Vec<(u32, u32)>,
    /// Pairs of bodies a joint links that do not collide, by their order
    /// key, sorted (scratch, see `Joints::apart`).
    pub apart: Vec<(crate::BodyId, crate::BodyId)>,
    /// Joints were added or removed since `apart` was made.
    pub apart_stale: bool,
}

impl JointRows {
    /// The rows of `joints` for a step of substep `h`; `locate` tells where
    /// a body is, `None` for a body no longer in the world (its joints were
    /// removed with it, so never). Without `warm`, each joint starts from
    /// zero impulses.
    pub(crate) fn prepare(
        &mut self,
        joints: &Joints,
        h: f32,
        warm: bool,
        locate: impl Fn(crate::BodyId) -> Option<End>,
    ) {
        self.rows.clear();
        self.rods.clear();
        self.links.clear();
        let hertz = JOINT_HERTZ.min(0.25 / h);
        let rigid = Soft::new(hertz, JOINT_DAMPING_RATIO, h);
        (self.rigid, self.h) = (Some(rigid), h);
        let world = End {
            body: None,
            pos: Vec2::ZERO,
            inv_mass: 0.0,
        };
        for (id, joint) in joints.iter() {
            let def: &JointDef = &joint.def;
            let (Some(a), Some(b)) = (locate(def.a), def.b.map_or(Some(world), &locate)) else {
                continue;
            };
            if let (Some(ia), Some(ib)) = (a.body, b.body) {
                self.links.push((ia, ib));
            }
            let k = a.inv_mass + b.inv_mass;
            if k == 0.0 {
                // Nothing it links can move this step (asleep, kinematic,
                // static): its impulses wait for the bodies to wake.
                continue;
            }
            let base = (b.pos + def.anchor_b) - (a.pos + def.anchor_a);
            if let JointKind::Distance {
                length,
                min_length,
                max_length,
                spring: None,
            } = def.kind
                && min_length == max_length
            {
                self.rods.push(RodRow {
                    a: a.body.unwrap_or(NONE),
                    b: b.body.unwrap_or(NONE),
                    ma: a.inv_mass,
                    mb: b.inv_mass,
                    mass: 1.0 / k,
                    base,
                    length,
                    impulse: if warm { joint.impulses.linear.x } else { 0.0 },
                    slot: id.index,
                });
                continue;
            }
            let spring = match def.kind {
                JointKind::Distance {
                    spring: Some(s),
                    min_length,
                    max_length,
                    ..
                } if min_length < max_length && s.hertz > 0.0 => Some(Soft::of(s, h)),
                JointKind::Weld { spring: Some(s) } if s.hertz > 0.0 => Some(Soft::of(s, h)),
                JointKind::Target { spring, .. } => Some(Soft::of(spring, h)),
                _ => None,
            };
            self.rows.push(JointRow {
                slot: id.index,
                a: a.body,
                b: b.body,
                ma: a.inv_mass,
                mb: b.inv_mass,
                mass: 1.0 / k,
                base,
                kind: def.kind,
                impulses: if warm {
                    joint.impulses
                } else {
                    JointImpulses::default()
                },
                rigid,
                spring,
                h,
            });
        }
    }

    /// Applies each joint's impulses of the last substep again.
    pub(crate) fn warm_start(&mut self, state: &mut [BodyState], delta: &[Vec2]) {
        for rod in &self.rods {
            let (va, vb) = rod.velocities(state);
            let p = rod.impulse * rod.separation(delta).normalize_or_zero();
            rod.write(state, va - rod.ma * p, vb + rod.mb * p);
        }
        for row in &mut self.rows {
            let (mut va, mut vb) = row.velocities(state);
            let d = row.separation(delta);
            let i = &row.impulses;
            let p = match row.kind {
                JointKind::Distance { .. } => {
                    (i.linear.x + i.lower - i.upper) * d.normalize_or_zero()
                }
                JointKind::Prismatic { axis, .. } => {
                    (i.motor + i.lower - i.upper) * axis + i.linear.x * axis.perp()
                }
                JointKind::Weld { .. } | JointKind::Target { .. } => i.linear,
            };
            row.push(&mut va, &mut vb, p);
            row.write(state, va, vb);
        }
    }

    /// One pass over the joints: with `use_bias` (the solve passes) the
    /// rigid parts also remove their drift; without (the relax passes)
    /// they hold the velocities only.
    pub(crate) fn solve(&mut self, state: &mut [BodyState], delta: &[Vec2], use_bias: bool) {
        let rigid = match (use_bias, self.rigid) {
            (true, Some(rigid)) => rigid,
            _ => Soft::RIGID,
        };
        for rod in &mut self.rods {
            let (va, vb) = rod.velocities(state);
            let d = rod.separation(delta);
            let len = d.length();
            let axis = if len > 0.0 { d / len } else { Vec2::ZERO };
            let cdot = axis.dot(vb - va);
            let impulse = rigid.impulse(rod.mass, cdot, len - rod.length, rod.impulse);
            rod.impulse += impulse;
            let p = impulse * axis;
            rod.write(state, va - rod.ma * p, vb + rod.mb * p);
        }
        for row in &mut self.rows {
            let (va, vb) = row.velocities(state);
            let d = row.separation(delta);
            let (va, vb) = row.solve(va, vb, d, use_bias);
            row.write(state, va, vb);
        }
    }

    /// Writes each joint's impulses and force back; calls `broken` with the
    /// slot of each joint whose force went over its break force.
    pub(crate) fn store(&self, joints: &mut Joints, mut broken: impl FnMut(u32)) {
        for rod in &self.rods {
            let Some(joint) = joints.slots[rod.slot as usize].joint.as_mut() else {
                continue;
            };
            joint.impulses.linear.x = rod.impulse;
            joint.force = rod.impulse.abs() / self.h;
            if joint.def.break_force.is_some_and(|f| joint.force > f) {
                broken(rod.slot);
            }
        }
        for row in &self.rows {
            let slot = &mut joints.slots[row.slot as usize];
            let Some(joint) = slot.joint.as_mut() else {
                continue;
            };
            joint.impulses = row.impulses;
            joint.force = row.force();
            if joint.def.break_force.is_some_and(|f| joint.force > f) {
                broken(row.slot);
            }
        }
    }
}

impl RodRow {
    #[inline(always)]
    fn velocities(&self, state: &[BodyState]) -> (Vec2, Vec2) {
        let v = |i: u32| {
            if i == NONE {
                Vec2::ZERO
            } else {
                state[i as usize].vel
            }
        };
        (v(self.a), v(self.b))
    }

    /// Anchor B minus anchor A now.
    #[inline(always)]
    fn separation(&self, delta: &[Vec2]) -> Vec2 {
        let d = |i: u32| {
            if i == NONE {
                Vec2::ZERO
            } else {
                delta[i as usize]
            }
        };
        self.base + (d(self.b) - d(self.a))
    }

    /// Writes the velocities of the bodies the rod moves.
    #[inline(always)]
    fn write(&self, state: &mut [BodyState], va: Vec2, vb: Vec2) {
        if self.a != NONE && self.ma > 0.0 {
            state[self.a as usize].vel = va;
        }
        if self.b != NONE && self.mb > 0.0 {
            state[self.b as usize].vel = vb;
        }
    }
}

impl JointRow {
    #[inline(always)]
    fn velocities(&self, state: &[BodyState]) -> (Vec2, Vec2) {
        let v = |i: Option<u32>| i.map_or(Vec2::ZERO, |i| state[i as usize].vel);
        (v(self.a), v(self.b))
    }

    /// Anchor B minus anchor A now.
    #[inline(always)]
    fn separation(&self, delta: &[Vec2]) -> Vec2 {
        let d = |i: Option<u32>| i.map_or(Vec2::ZERO, |i| delta[i as usize]);
        self.base + (d(self.b) - d(self.a))
    }

    /// Writes the velocities of the bodies the joint moves.
    #[inline(always)]
    fn write(&self, state: &mut [BodyState], va: Vec2, vb: Vec2) {
        if let (Some(a), true) = (self.a, self.ma > 0.0) {
            state[a as usize].vel = va;
        }
        if let (Some(b), true) = (self.b, self.mb > 0.0) {
            state[b as usize].vel = vb;
        }
    }

    /// The force of the last substep, newtons.
    fn force(&self) -> f32 {
        let i = &self.impulses;
        let impulse = match self.kind {
            JointKind::Distance { .. } => (i.linear.x + i.lower - i.upper).abs(),
            JointKind::Prismatic { .. } => {
                Vec2::new(i.linear.x, i.motor + i.lower - i.upper).length()
            }
            JointKind::Weld { .. } | JointKind::Target { .. } => i.linear.length(),
        };
        impulse / self.h
    }

    /// Applies impulse `p` (on B; minus on A).
    #[inline(always)]
    fn push(&self, va: &mut Vec2, vb: &mut Vec2, p: Vec2) {
        *va -= self.ma * p;
        *vb += self.mb * p;
    }

    /// The joint's velocities after one pass over its constraints.
    fn solve(&mut self, mut va: Vec2, mut vb: Vec2, d: Vec2, use_bias: bool) -> (Vec2, Vec2) {
        let rigid = if use_bias { self.rigid } else { Soft::RIGID };
        match self.kind {
            JointKind::Distance {
                length,
                min_length,
                max_length,
                ..
            } => {
                let len = d.length();
                let axis = d.normalize_or_zero();
                if min_length < max_length {
                    if let (Some(spring), true) = (self.spring, use_bias) {
                        let cdot = axis.dot(vb - va);
                        let c = len - length;
                        let old = self.impulses.linear.x;
                        let impulse = spring.impulse(self.mass, cdot, c, old);
                        self.impulses.linear.x = old + impulse;
                        self.push(&mut va, &mut vb, impulse * axis);
                    }
                    let lower = self.limit(va, vb, axis, len - min_length, rigid, Limit::Lower);
                    self.push(&mut va, &mut vb, lower * axis);
                    if max_length.is_finite() {
                        let upper = self.limit(va, vb, axis, max_length - len, rigid, Limit::Upper);
                        self.push(&mut va, &mut vb, -upper * axis);
                    }
                } else {
                    let cdot = axis.dot(vb - va);
                    let c = len - length;
                    let old = self.impulses.linear.x;
                    let impulse = rigid.impulse(self.mass, cdot, c, old);
                    self.impulses.linear.x = old + impulse;
                    self.push(&mut va, &mut vb, impulse * axis);
                }
            }
            JointKind::Prismatic {
                axis,
                limits,
                motor,
            } => {
                if let Some(motor) = motor {
                    let cdot = axis.dot(vb - va);
                    let max = motor.max_force * self.h;
                    let old = self.impulses.motor;
                    let new = (old + self.mass * (motor.speed - cdot)).clamp(-max, max);
                    self.impulses.motor = new;
                    self.push(&mut va, &mut vb, (new - old) * axis);
                }
                if let Some((lower, upper)) = limits {
                    let t = axis.dot(d);
                    let lo = self.limit(va, vb, axis, t - lower, rigid, Limit::Lower);
                    self.push(&mut va, &mut vb, lo * axis);
                    let hi = self.limit(va, vb, axis, upper - t, rigid, Limit::Upper);
                    self.push(&mut va, &mut vb, -hi * axis);
                }
                let normal = axis.perp();
                let cdot = normal.dot(vb - va);
                let c = normal.dot(d);
                let old = self.impulses.linear.x;
                let impulse = rigid.impulse(self.mass, cdot, c, old);
                self.impulses.linear.x = old + impulse;
                self.push(&mut va, &mut vb, impulse * normal);
            }
            JointKind::Weld { .. } => {
                let soft = match self.spring {
                    Some(_) if !use_bias => return (va, vb),
                    Some(spring) => spring,
                    None => rigid,
                };
                let cdot = vb - va;
                let old = self.impulses.linear;
                let impulse = soft.impulse(self.mass, cdot, d, old);
                self.impulses.linear = old + impulse;
                self.push(&mut va, &mut vb, impulse);
            }
            JointKind::Target { max_force, .. } => {
                let Some(soft) = self.spring.filter(|_| use_bias) else {
                    return (va, vb);
                };
                let cdot = vb - va;
                let old = self.impulses.linear;
                let impulse = soft.impulse(self.mass, cdot, d, old);
                let max = max_force * self.h;
                let new = (old + impulse).clamp_length_max(max);
                self.impulses.linear = new;
                self.push(&mut va, &mut vb, new - old);
            }
        }
        (va, vb)
    }

    /// One side of a limit along `axis`: `c` is how far inside the limit
    /// the joint is (negative: past it). Returns the impulse's change,
    /// along `axis` for the lower side and against it for the upper.
    /// Ahead of the limit the constraint is speculative: it lets the
    /// bodies close the gap in this substep, no more (as contacts do).
    fn limit(&mut self, va: Vec2, vb: Vec2, axis: Vec2, c: f32, rigid: Soft, side: Limit) -> f32 {
        let cdot = match side {
            Limit::Lower => axis.dot(vb - va),
            Limit::Upper => axis.dot(va - vb),
        };
        let soft = if c > 0.0 {
            Soft::speculative(self.h)
        } else {
            rigid
        };
        let accumulated = match side {
            Limit::Lower => &mut self.impulses.lower,
            Limit::Upper => &mut self.impulses.upper,
        };
        let impulse = soft.impulse(self.mass, cdot, c, *accumulated);
        let new = (*accumulated + impulse).max(0.0);
        let change = new - *accumulated;
        *accumulated = new;
        change
    }
}

/// Which side of a limit.
#[derive(Clone, Copy)]
enum Limit {
    Lower,
    Upper,
}
