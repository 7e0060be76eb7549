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
//! Rigid rods, the bulk of chains, bridges and nets, are coloured as the
//! contacts are and solved side by side in blocks (see `rods`), which
//! keeps each body's rods in slot order; the other joints are solved one
//! after another in slot order after them (Gauss-Seidel), as the contacts
//! no colour takes are. All on the stepping thread: the bits are the same
//! with any number of threads.

use crate::constants::{JOINT_DAMPING_RATIO, JOINT_HERTZ};
use crate::joint::rods::{NONE, RodBlocks, RodRow};
use crate::joint::soft::Soft;
use crate::joint::{JointDef, JointImpulses, JointKind, Joints};
use crate::solver::scalar::BodyState;
use crate::switches::TestSwitches;
use glam::Vec2;

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

/// The rows of a step, and the links between dynamic bodies that make
/// them one island.
#[derive(Clone, Debug, Default)]
pub(crate) struct JointRows {
    pub rows: Vec<JointRow>,
    pub rods: Vec<RodRow>,
    /// The rods in colours of blocks (see `wide`).
    blocks: RodBlocks,
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
    /// zero impulses. `switches`: see `RodBlocks::build`.
    pub(crate) fn prepare(
        &mut self,
        joints: &Joints,
        h: f32,
        warm: bool,
        switches: TestSwitches,
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
        let TestSwitches {
            blocks_always,
            joints_one_by_one,
            ..
        } = switches;
        (self.blocks).build(&self.rods, blocks_always, joints_one_by_one);
    }

    /// Rods the passes solve in blocks.
    pub(crate) fn rods_in_blocks(&self) -> usize {
        self.blocks.in_blocks()
    }

    /// Applies each joint's impulses of the last substep again.
    pub(crate) fn warm_start(&mut self, state: &mut [BodyState], delta: &[Vec2]) {
        self.blocks.warm_start(&self.rods, state, delta);
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
        self.blocks.solve(&mut self.rods, state, delta, rigid);
        for row in &mut self.rows {
            let (va, vb) = row.velocities(state);
            let d = row.separation(delta);
            let (va, vb) = row.solve(va, vb, d, use_bias);
            row.write(state, va, vb);
        }
    }

    /// Writes each joint's impulses and force back; calls `broken` with the
    /// slot of each joint whose force went over its break force.
    pub(crate) fn store(&mut self, joints: &mut Joints, mut broken: impl FnMut(u32)) {
        self.blocks.store(&mut self.rods);
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
