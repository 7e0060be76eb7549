//! Shock propagation: after the Gauss-Seidel passes of a substep, one
//! more pass over the contacts that hold bodies up, from the ground up,
//! each solved as if the body below could not move.
//!
//! Gauss-Seidel passes spread a contact's impulse one contact per pass.
//! Through a light body under a heavy one they spread it slowly: a
//! 1000 kg box on a 1 kg box needs about a thousand passes to stop
//! sinking, and the impulses a heavy landing leaves to the warm start
//! come back as a bounce before the passes can take them out again. So
//! after the passes, the contacts that carry weight (their normal within
//! about 45 degrees of straight up, against gravity) are solved once
//! more, in layers: first those on static, kinematic or sleeping bodies,
//! then those on the bodies these hold up, and so on. In this pass the
//! lower body of each contact counts as fixed, so only the upper body
//! changes velocity, and when the pass is over no body still moves into
//! the one holding it up, whatever their masses. This is the shock
//! propagation of Guendelman, Bridson and Fedkiw, "Nonconvex rigid bodies
//! with stacking" (SIGGRAPH 2003), applied as one last velocity (and
//! push) pass instead of their whole solve.
//!
//! A body's layer is its distance, in contacts that hold something up,
//! from a body that cannot move (breadth first, in the order of the
//! contacts, so it depends on the contacts alone). A contact between two
//! bodies of the same layer, or whose lower body lies in a higher layer,
//! is left to the Gauss-Seidel passes. So are contacts off the vertical
//! (a box pushed sideways into a row of boxes), and every contact when
//! there is no gravity: between bodies that nothing holds up, momentum
//! is kept exactly.
//!
//! The pass is a correction of the velocities, not part of the solution
//! the warm start carries: its impulses are not added to the contacts'
//! (each is only kept from pulling a contact below zero), and the replay
//! of the next substep leaves the velocity change it made out (see
//! `motion::Start::Replay`). The upper body's push has no reaction on the
//! lower, and warm starting that one-sided push made deep piles of
//! circles sink into themselves and a heavy ball plough through a bed of
//! small ones; kept out, the warm start holds only what the passes found,
//! with every push matched by its reaction.

use crate::contact::constraint::Constraint;
use crate::solver::colouring::Slot;
use crate::solver::motion::Home;
#[cfg(doc)]
use crate::solver::motion::Homes;
use crate::solver::regions::ContactRegions;
use crate::solver::scalar::{SolverBodies, SolverParams, greater, lesser};
use crate::switches::TestSwitches;
use glam::Vec2;

/// A contact holds its upper body up when its normal is within this
/// cosine of straight up: 0.7, about 45 degrees. Circles packed in rows
/// touch at 30 degrees from the vertical. A column of circles leaning
/// further falls as the passes let it, instead of toppling slowly as one
/// stiff body (up to 63 degrees, a rain of 2 000 circles took 4 s longer
/// to fall asleep).
const SUPPORT_COSINE: f32 = 0.7;

/// A contact that holds a body up, as the pass solves it.
#[derive(Clone, Copy, Debug)]
struct Support {
    /// The body below: a dynamic index, or the rest state's index (the
    /// number of dynamic bodies) for a static body.
    lower: u32,
    /// Whether the lower body lives in the far array (see [`Homes`]).
    lower_far: bool,
    /// Whether the body held up is the contact's B.
    upper_is_b: bool,
    /// The contact's normal, from the lower body to the upper one.
    n: Vec2,
    /// The upper body's inverse mass, and its mass.
    inv_mass: f32,
    mass: f32,
    /// The separation when the step began.
    base_separation: f32,
    /// Where the passes keep the contact's impulses.
    slot: Slot,
    /// The contact's index in the rows.
    row: u32,
}

/// A body held up, and its supports in [`Supports::order`].
#[derive(Clone, Copy, Debug)]
struct Held {
    body: u32,
    /// Whether it lives in the far array (see [`Homes`]).
    far: bool,
    first: u32,
    end: u32,
}

/// The contacts that hold bodies up, body by body in layers from the
/// ground up, for one step.
#[derive(Clone, Debug, Default)]
pub(crate) struct Supports {
    /// The bodies held up, in the pass's order.
    held: Vec<Held>,
    /// Their supports, body after body.
    order: Vec<Support>,
    /// Per dynamic body: its layer (`u32::MAX`: held up by nothing fixed).
    layer: Vec<u32>,
    /// Per dynamic body, the start of the supports it gives in `above`
    /// and of those it rests on in `below` (one more entry at the end
    /// of each); `next` is the next free place while they fill.
    above_start: Vec<u32>,
    below_start: Vec<u32>,
    next: Vec<u32>,
    /// By body, the supports (indices into `pairs`) it gives and those it
    /// rests on.
    above: Vec<u32>,
    below: Vec<u32>,
    /// The bodies in breadth-first order from the ground.
    queue: Vec<u32>,
    slot_of: Vec<Slot>,
    /// The rows that hold a body up: row, lower body (`u32::MAX`: one that
    /// cannot move), upper body.
    pairs: Vec<(u32, u32, u32)>,
    /// Per row of the last build: how it holds a body up (see [`class`]).
    classes: Vec<u8>,
    /// The number of dynamic bodies at the last build.
    bodies: usize,
    /// Builds that kept the last build's order (see `StepCounters`).
    pub(crate) reused: u64,
    /// The shortcuts turned off (`order_supports_always`).
    pub(crate) switches: TestSwitches,
}

/// How contact `c` holds a body up against `up`: 1 holds B up, 2 holds A
/// up, 0 neither (the normal too far from the vertical, or the upper
/// body not one the contact moves).
fn class(c: &Constraint, up: Vec2) -> u8 {
    let along = c.normal.dot(up);

    let (a, b) = c.moved();
    if along >= SUPPORT_COSINE && b.is_some() {
        1
    } else if along <= -SUPPORT_COSINE && a.is_some() {
        2
    } else {
        0
    }
}

/// Counts into `start` (`bodies + 1` entries) the pairs each body has
/// at `key`, and lays their indices out in `list` by body, in pair
/// order. `next` is scratch.
fn by_body(
    pairs: &[(u32, u32, u32)],
    key: impl Fn(&(u32, u32, u32)) -> u32,
    bodies: usize,
    start: &mut Vec<u32>,
    next: &mut Vec<u32>,
    list: &mut Vec<u32>,
) {
    start.clear();
    start.resize(bodies + 1, 0);
    for p in pairs {
        let k = key(p);
        if k != u32::MAX {
            start[k as usize + 1] += 1;
        }
    }
    // (A running sum in a register: adding each entry to the one stored
    // just before waits on that store.)
    let mut sum = 0;
    for x in start.iter_mut() {
        sum += *x;
        *x = sum;
    }
    list.clear();
    list.resize(start[bodies] as usize, 0);
    next.clear();
    next.extend_from_slice(&start[..bodies]);
    for (i, p) in pairs.iter().enumerate() {
        let k = key(p);
        if k != u32::MAX {
            let at = &mut next[k as usize];
            list[*at as usize] = i as u32;
            *at += 1;
        }
    }
}

impl Supports {
    /// Finds the contacts of `rows` that hold bodies up against `gravity`
    /// (none when it is zero), over `bodies` dynamic bodies, and the
    /// pass's order. `regions` must be built from `rows`.
    pub(crate) fn build(
        &mut self,
        rows: &[Constraint],
        gravity: Vec2,
        bodies: usize,
        regions: &ContactRegions,
    ) {
        let g = gravity.length();
        // (A NaN gravity counts as none.)
        if g.is_nan() || g <= 0.0 || rows.is_empty() {
            self.clear();
            return;
        }
        let up = -gravity / g;
        // A pile whose contacts move the same bodies as at the last build,
        // in the same order and with the same slots, each holding the same
        // body up, keeps its layers and order: only the numbers change.
        let same = !self.switches.order_supports_always
            && regions.slots_kept()
            && bodies == self.bodies
            && rows.len() == self.classes.len()
            && rows
                .iter()
                .zip(&self.classes)
                .all(|(c, &k)| class(c, up) == k);
        if same {
            self.reused += 1;
            self.refresh(rows, bodies, regions);
            return;
        }
        self.held.clear();
        self.order.clear();
        self.bodies = bodies;
        self.classes.clear();
        self.classes.extend(rows.iter().map(|c| class(c, up)));
        self.pairs.clear();
        for (r, (c, &k)) in rows.iter().zip(&self.classes).enumerate() {
            let (a, b) = c.moved();
            let (lower, upper) = match k {
                1 => (a, b),
                2 => (b, a),
                _ => continue,
            };
            let upper = upper.expect("the class names a body the contact moves");
            let lower = lower.map_or(u32::MAX, |i| i as u32);
            self.pairs.push((r as u32, lower, upper as u32));
        }
        if self.pairs.is_empty() {
            return;
        }
        let (pairs, next) = (&self.pairs, &mut self.next);
        by_body(
            pairs,
            |p| p.1,
            bodies,
            &mut self.above_start,
            next,
            &mut self.above,
        );
        by_body(
            pairs,
            |p| p.2,
            bodies,
            &mut self.below_start,
            next,
            &mut self.below,
        );
        // Layers, breadth first from the bodies resting on fixed ones.
        self.layer.clear();
        self.layer.resize(bodies, u32::MAX);
        self.queue.clear();
        for &(_, lower, upper) in &self.pairs {
            if lower == u32::MAX && self.layer[upper as usize] == u32::MAX {
                self.layer[upper as usize] = 1;
                self.queue.push(upper);
            }
        }
        let mut head = 0;
        while let Some(&body) = self.queue.get(head) {
            head += 1;
            let next_layer = self.layer[body as usize] + 1;
            let (s, e) = (
                self.above_start[body as usize],
                self.above_start[body as usize + 1],
            );
            for &k in &self.above[s as usize..e as usize] {
                let upper = self.pairs[k as usize].2 as usize;
                if self.layer[upper] == u32::MAX {
                    self.layer[upper] = next_layer;
                    self.queue.push(upper as u32);
                }
            }
        }
        // Body by body in breadth-first order (so layer by layer), the
        // supports each rests on from a lower layer, in row order.
        self.slot_of.clear();
        self.slot_of.resize(rows.len(), Slot::None);
        regions.note_slots(&mut self.slot_of);
        for &body in &self.queue {
            let layer = self.layer[body as usize];
            let first = self.order.len() as u32;
            let (s, e) = (
                self.below_start[body as usize],
                self.below_start[body as usize + 1],
            );
            for &k in &self.below[s as usize..e as usize] {
                let (r, lower, _) = self.pairs[k as usize];
                let below = if lower == u32::MAX {
                    0
                } else {
                    self.layer[lower as usize]
                };
                if below >= layer {
                    continue;
                }
                let c = &rows[r as usize];
                let upper_is_b = self.classes[r as usize] == 1;
                // A static lower body reads the rest state; a held one
                // (asleep or kinematic), its own.
                let lower = if lower != u32::MAX {
                    lower
                } else {
                    let other = if upper_is_b {
                        Some(c.a as usize)
                    } else {
                        c.b.dynamic_index()
                    };
                    other.map_or(bodies as u32, |i| i as u32)
                };
                self.order.push(Support {
                    lower,
                    lower_far: false,
                    upper_is_b,
                    n: Vec2::ZERO,
                    inv_mass: 0.0,
                    mass: 0.0,
                    base_separation: 0.0,
                    slot: self.slot_of[r as usize],
                    row: r,
                });
            }
            let end = self.order.len() as u32;
            if end > first {
                self.held.push(Held {
                    body,
                    far: false,
                    first,
                    end,
                });
            }
        }
        self.refresh(rows, bodies, regions);
    }

    /// Holds no support (shock propagation off, or no gravity).
    pub(crate) fn clear(&mut self) {
        self.held.clear();
        self.order.clear();
        self.classes.clear();
    }

    /// Takes each support's numbers from its row, and where its bodies
    /// live (see [`Homes`]).
    fn refresh(&mut self, rows: &[Constraint], bodies: usize, regions: &ContactRegions) {
        for s in &mut self.order {
            let c = &rows[s.row as usize];
            (s.n, s.inv_mass) = if s.upper_is_b {
                (c.normal, c.inv_mass_b)
            } else {
                (-c.normal, c.inv_mass_a)
            };
            s.mass = 1.0 / s.inv_mass;
            s.base_separation = c.base_separation;
        }
        let homes = regions.homes();
        let far =
            |i: u32| homes.is_some_and(|h| (i as usize) < bodies && h.of(i as usize) == Home::Far);
        for h in &mut self.held {
            h.far = far(h.body);
        }
        for s in &mut self.order {
            s.lower_far = far(s.lower);
        }
    }

    /// The pass: body by body, from the ground up, the contacts that hold
    /// each up, solved with the lower body fixed, on the velocities, and
    /// on the pushes of the contacts that overlapped by more than the
    /// slop when the step began. (The others do not sink further: this
    /// pass stops them. Leaving their pushes out halves the pass in a pile
    /// at rest.)
    pub(crate) fn run(
        &mut self,
        regions: &mut ContactRegions,
        bodies: &mut SolverBodies<'_>,
        params: &SolverParams,
        mut replay: Option<&mut [Vec2]>,
    ) {
        let inv_h = 1.0 / params.h;
        let push_rate = params.position_correction * inv_h;
        let (groups, far) = regions.parts_mut();
        let near = &mut *bodies.state;
        let far = far.map_or(&mut [][..], |(_, far)| far);
        let delta = bodies.delta;
        for h in &self.held {
            let i = h.body as usize;
            let mut upper = if h.far { far[i] } else { near[i] };
            let before = upper.vel;
            let upper_delta = delta[i];
            for s in &self.order[h.first as usize..h.end as usize] {
                let j = s.lower as usize;
                let lower = if s.lower_far { far[j] } else { near[j] };
                let lower_delta = delta.get(j).copied().unwrap_or(Vec2::ZERO);
                let sep = s.base_separation + (upper_delta - lower_delta).dot(s.n);
                let [normal_impulse, push_impulse, _] = groups[s.slot.group()].impulses_mut(s.slot);
                // The same rule as the passes: v_n >= 0, or >= -s / h while
                // still apart, the impulse kept >= 0 with the passes'. The
                // lower body counts as fixed, but never as rising into the
                // upper one: a light body the passes threw upwards would
                // otherwise throw a heavy one resting on it.
                let bias = if sep > 0.0 { sep * inv_h } else { 0.0 };
                let vn = upper.vel.dot(s.n) - lesser(lower.vel.dot(s.n), 0.0);
                let dn = greater(-s.mass * (vn + bias), -*normal_impulse);
                upper.vel += s.n * (dn * s.inv_mass);
                if s.base_separation >= -params.slop {
                    continue;
                }
                // The push out of overlap deeper than the slop, the same way.
                let target = lesser(
                    greater(push_rate * (-sep - params.slop), 0.0),
                    params.push_out_speed,
                );
                let pn = upper.push.dot(s.n) - lesser(lower.push.dot(s.n), 0.0);
                let dp = greater(s.mass * (target - pn), -*push_impulse);
                upper.push += s.n * (dp * s.inv_mass);
            }
            if h.far {
                far[i] = upper;
            } else {
                near[i] = upper;
            }
            if let Some(replay) = replay.as_deref_mut() {
                replay[i] += upper.vel - before;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::collider::ColliderRef;
    use crate::testing::pile;
    use crate::{TestSwitches, World};
    use glam::Vec2;

    #[test]
    fn the_order_kept_in_a_pile_at_rest_is_the_order_worked_out_anew() {
        // The pile beside a copy that works the order out every step, a box
        // dropped on both halfway (new contacts, a new order, then kept
        // again): the same bits every tick.
        let (mut world, boxes) = pile();
        world.step(1.0 / 60.0);
        let mut anew = world.clone();
        anew.set_test_switches(TestSwitches {
            order_supports_always: true,
            ..Default::default()
        });
        crate::testing::step_side_by_side(
            (&mut world, &mut anew),
            &boxes,
            (90, 45),
            |w| w.set_position(boxes[0], Vec2::new(0.0, 4.0)),
            |_, _, _| {},
        );
        let kept = |w: &mut World| w.counters().supports_reused;
        assert_eq!(kept(&mut anew), 0);
        assert!(kept(&mut world) > 60, "kept {} times", kept(&mut world));
        assert!(kept(&mut world) < 89, "the drop was ordered anew");
    }

    /// Two bodies each on a body on the ground; `on[k]` is the body
    /// resting on body `2 k` (a static ground under bodies 0 and 2).
    fn two_stacks(on: [u32; 2]) -> Vec<Constraint> {
        let row = |a: u32, b: Option<u32>| Constraint {
            a,
            b: b.map_or(ColliderRef::fixed(0), ColliderRef::dynamic),
            // From A down to B.
            normal: -Vec2::Y,
            base_separation: 0.0,
            inv_mass_a: 1.0,
            inv_mass_b: if b.is_some() { 1.0 } else { 0.0 },
            mass: 0.5,
            friction: 0.6,
            normal_impulse: 1.0,
            tangent_impulse: 0.0,
            push_impulse: 0.0,
            max_normal_impulse: 1.0,
            tangent_speed: 0.0,
        };
        vec![
            row(0, None),
            row(on[0], Some(0)),
            row(2, None),
            row(on[1], Some(2)),
        ]
    }

    /// The bodies held up, in the pass's order, each with its rows.
    fn order(supports: &Supports) -> Vec<(u32, Vec<u32>)> {
        let rows = |h: &Held| supports.order[h.first as usize..h.end as usize].iter();
        let held = supports.held.iter();
        held.map(|h| (h.body, rows(h).map(|s| s.row).collect()))
            .collect()
    }

    #[test]
    fn contacts_that_name_other_bodies_are_ordered_anew() {
        // Bodies 1 and 3 trade stacks: as many contacts, each holding a
        // body up the same way, but naming other bodies (coloured anew).
        // The order kept would hold body 1 up by the contact that now
        // holds body 3.
        let pos = [Vec2::ZERO, Vec2::Y, Vec2::X, Vec2::ONE];
        let gravity = Vec2::new(0.0, -9.81);
        let mut regions = ContactRegions::default();
        let mut kept = Supports::default();
        for on in [[1, 3], [1, 3], [3, 1]] {
            let rows = two_stacks(on);
            regions.build(&rows, &pos, &[], false, false);
            kept.build(&rows, gravity, 4, &regions);
            let mut anew = Supports::default();
            anew.build(&rows, gravity, 4, &regions);
            assert_eq!(order(&kept), order(&anew), "{on:?}");
        }
        // The second build kept the first's order; the third did not.
        assert_eq!(kept.reused, 1);
        assert_eq!(order(&kept)[2..], [(3, vec![1]), (1, vec![3])]);
    }
}
