//! Bodies crushed by a kinematic body: while the press moves (off, past
//! or on), the impulses the crush piled up are let go of.
//!
//! A dynamic body pressed by a kinematic body against an immovable one
//! (static, or kinematic too), directly or through other dynamic bodies
//! (a stack of crates under a press), has no motion that satisfies all of
//! its contacts: each pass of the solver raises the impulses along the
//! column by the press's speed times the mass it pushes, and they balance.
//! Warm started, they stay balanced while the press holds still (and hold
//! a body gripped between two kinematic jaws by friction). When the press
//! moved off, the solver resolved them by sending the column after it: a
//! crate pressed 0.1 m into the ground left with the press at 5 m/s.
//!
//! So at the start of a step, after the warm start, the bodies a moving
//! kinematic body pressed (contacts warm started with a positive impulse)
//! are followed, breadth first, through the pushing contacts that carry
//! the press on in its direction, to the whole cone they reach; if that
//! meets an immovable body that does not move with the press (static, or
//! kinematic and moving otherwise: the press moves off, shears past or
//! presses on), the warm-start impulses (normal, friction and push) of
//! every pushing contact of the bodies met are set to zero, and the step
//! starts them cold. A press removed from the world lets go the same way.

use crate::body::collider::ColliderRef;
use crate::contact::constraint::Constraint;
use glam::Vec2;

/// Bodies one press is followed through, at most (or four for each body
/// it presses, if more): beyond them a pile is left as it is (what was met
/// is let go of if it reached an immovable body).
const COLUMN: usize = 256;

/// Bodies followed in one step, at most, over all presses: the search costs
/// no more than some thousands of steps of a walk whatever the scene (a
/// lift under 500 circles follows each of them once: the contacts of one
/// press with one normal are followed together).
const BUDGET: usize = 16_384;

/// A press moving faster than this, m/s, relative to what the body it
/// presses is pressed against, opens or shears the column and lets go
/// (jaws carrying what they grip, any way, hold on).
pub(crate) const LEAVING: f32 = 0.01;

/// How far a contact's normal may turn from the press's direction and still
/// carry the press on: 60 degrees.
const ALONG: f32 = 0.5;

/// Buffers of [`Crushes::release`], kept between steps.
#[derive(Clone, Debug, Default)]
pub(crate) struct Crushes {
    /// Per body, where its pushing contacts start in `rows` (and, last,
    /// where they end).
    starts: Vec<u32>,
    /// The pushing contacts, body by body (a contact between two dynamic
    /// bodies under both).
    rows: Vec<u32>,
    /// Per body, the mark of the press that last followed it.
    seen: Vec<u32>,
    /// The last press's mark: a number for each press followed, never 0
    /// (`seen`'s fill) and never used twice until it wraps round, when
    /// `seen` is cleared.
    mark: u32,
    /// The bodies met by the press being followed.
    column: Vec<u32>,
    /// The contacts the last search let go of.
    released: Vec<u32>,
    /// The presses of the last search: body B, its normal's bits, contact.
    presses: Vec<(ColliderRef, u32, u32, u32)>,
    /// A copy of the contacts, for a search that must leave them as they
    /// are.
    copy: Vec<Constraint>,
}

impl Crushes {
    /// Lets go of the warm-start impulses of crushed columns among `rows`
    /// (contacts of `bodies` dynamic bodies, warm started) that open or
    /// shear this step; `kinematic(b)`: body B's velocity if it is
    /// kinematic. Deterministic:
    /// the presses are taken in the order of their bodies, and each body's
    /// contacts in the order of `rows`.
    pub(crate) fn release(
        &mut self,
        rows: &mut [Constraint],
        bodies: usize,
        kinematic: impl Fn(ColliderRef) -> Option<Vec2>,
    ) {
        let moves = |v: Vec2| v.length_squared() > LEAVING * LEAVING;
        // A press: a kinematic body that moves.
        let press = |c: &Constraint| kinematic(c.b).filter(|&v| moves(v));
        // The column opens, or is sheared, where what it is pressed against
        // does not move with the press (a static body, or jaws moving apart;
        // jaws carrying what they grip move together).
        let opens =
            |moving: Vec2, far: ColliderRef| moves(moving - kinematic(far).unwrap_or(Vec2::ZERO));
        self.release_with(rows, bodies, press, opens);
    }

    /// The contacts among `rows` (the last step's) whose warm-start
    /// impulses kinematic body `k`, being removed, leaves piled up: what
    /// it pressed against an immovable body, as if it moved off at once.
    /// `rows` is left as it is.
    pub(crate) fn released_by_removal(
        &mut self,
        rows: &[Constraint],
        bodies: usize,
        k: u32,
    ) -> &[u32] {
        let press = |c: &Constraint| (c.b == ColliderRef::dynamic(k)).then_some(Vec2::ZERO);
        self.released.clear();
        // Most removed bodies pressed nothing: no copy for them. (A looser
        // test here costs a copy, never a release: the search below
        // applies the same test again.)
        if !rows
            .iter()
            .any(|c| c.normal_impulse > 0.0 && press(c).is_some())
        {
            return &self.released;
        }
        let mut copy = std::mem::take(&mut self.copy);
        copy.clear();
        copy.extend_from_slice(rows);
        self.release_with(&mut copy, bodies, press, |_, _| true);
        self.copy = copy;
        &self.released
    }

    /// Follows each press (`press(c)`: body B's velocity, if B is one) from
    /// the bodies it pushes, in its direction, all of one press's contacts
    /// of one normal together, and lets go of the column where it meets
    /// an immovable body `far` for which `opens(press velocity, far)`. The
    /// contacts let go of are listed in `released`.
    fn release_with(
        &mut self,
        rows: &mut [Constraint],
        bodies: usize,
        press: impl Fn(&Constraint) -> Option<Vec2>,
        opens: impl Fn(Vec2, ColliderRef) -> bool,
    ) {
        self.released.clear();
        let pushing = |c: &Constraint| c.normal_impulse > 0.0;
        self.presses.clear();
        for (i, c) in rows.iter().enumerate() {
            if pushing(c) && press(c).is_some() {
                let [x, y] = c.normal.to_array().map(f32::to_bits);
                self.presses.push((c.b, x, y, i as u32));
            }
        }
        if self.presses.is_empty() {
            return;
        }
        self.presses.sort_unstable();
        self.index(rows, bodies, pushing);
        let mut budget = BUDGET;
        let presses = std::mem::take(&mut self.presses);
        for group in presses.chunk_by(|p, q| p.0 == q.0 && p.1 == q.1 && p.2 == q.2) {
            if budget == 0 {
                break;
            }
            let (body, x, y, first) = group[0];
            let towards = -Vec2::new(f32::from_bits(x), f32::from_bits(y));
            let moving = press(&rows[first as usize]).unwrap_or(Vec2::ZERO);
            let sources = group.iter().map(|p| rows[p.3 as usize].a);
            let opens = |far: ColliderRef| opens(moving, far);
            if self.reaches_immovable(rows, body, sources, towards, opens, &mut budget) {
                for &b in &self.column {
                    for &r in pushing_contacts(&self.starts, &self.rows, b) {
                        let c = &mut rows[r as usize];
                        if c.normal_impulse != 0.0 {
                            self.released.push(r);
                        }
                        (c.normal_impulse, c.tangent_impulse, c.push_impulse) = (0.0, 0.0, 0.0);
                    }
                }
            }
        }
        self.presses = presses;
    }

    /// The pushing contacts of each body, in `starts` and `rows` (a
    /// counting sort: linear in the contacts).
    fn index(&mut self, rows: &[Constraint], bodies: usize, pushing: impl Fn(&Constraint) -> bool) {
        self.starts.clear();
        self.starts.resize(bodies + 1, 0);
        for c in rows.iter().filter(|c| pushing(c)) {
            self.starts[c.a as usize + 1] += 1;
            if let Some(b) = moved_b(c) {
                self.starts[b + 1] += 1;
            }
        }
        for b in 1..=bodies {
            self.starts[b] += self.starts[b - 1];
        }
        self.rows.resize(self.starts[bodies] as usize, 0);
        // Dealt from the last contact to the first, each body's `start`
        // ends where its run begins.
        for (i, c) in rows.iter().enumerate().rev().filter(|(_, c)| pushing(c)) {
            for body in std::iter::once(c.a as usize).chain(moved_b(c)) {
                self.starts[body + 1] -= 1;
                self.rows[self.starts[body + 1] as usize] = i as u32;
            }
        }
        // `starts[b + 1]` now holds body b's start: shift back by one.
        self.starts.rotate_left(1);
        self.starts[bodies] = self.rows.len() as u32;
        self.seen.resize(bodies, 0);
    }

    /// Follows the push of press `press` from the bodies `sources` in
    /// direction `towards` through the contacts that carry it on, breadth
    /// first, to every body they reach (at most [`COLUMN`], or four per
    /// source, within `budget`); `true` if that meets an immovable body for
    /// which `opens`. The bodies met are left in `column`, all of them, so
    /// that a pile's every branch is let go of.
    fn reaches_immovable(
        &mut self,
        rows: &[Constraint],
        press: ColliderRef,
        sources: impl Iterator<Item = u32>,
        towards: Vec2,
        opens: impl Fn(ColliderRef) -> bool,
        budget: &mut usize,
    ) -> bool {
        self.mark = self.mark.wrapping_add(1);
        // (Clearing `seen` before every search would find the same: the
        // marks only save that pass.)
        if self.mark == 0 {
            self.seen.fill(0);
            self.mark = 1;
        }
        let mark = self.mark;
        self.column.clear();
        for body in sources {
            if self.seen[body as usize] != mark {
                self.seen[body as usize] = mark;
                self.column.push(body);
            }
        }
        let most = COLUMN.max(4 * self.column.len());
        let mut crushed = false;
        // `column` is the queue: bodies before `next` have been followed.
        let mut next = 0;
        while next < self.column.len() && *budget > 0 {
            let x = self.column[next];
            next += 1;
            *budget -= 1;
            for &r in pushing_contacts(&self.starts, &self.rows, x) {
                let c = &rows[r as usize];
                // (The press's own contact points back at it, so the test of
                // direction below would pass it over too: this only saves
                // the work.)
                if c.a == x && c.b == press {
                    continue;
                }
                // The normal out of x, and the body on the other side.
                let (out, other) = if c.a == x {
                    (c.normal, moved_b(c))
                } else {
                    (-c.normal, Some(c.a as usize))
                };
                if out.dot(towards) < ALONG {
                    continue;
                }
                match other {
                    // Static or kinematic: the column is crushed, and let
                    // go of if it opens there.
                    None => crushed |= opens(c.b),
                    Some(other) if self.seen[other] != mark && self.column.len() < most => {
                        self.seen[other] = mark;
                        self.column.push(other as u32);
                    }
                    Some(_) => {}
                }
            }
        }
        crushed
    }
}

/// Body B of contact `c` if the contacts move it: dynamic, and neither
/// kinematic, static nor held asleep.
fn moved_b(c: &Constraint) -> Option<usize> {
    c.b.dynamic_index().filter(|_| c.inv_mass_b > 0.0)
}

/// The pushing contacts of body `b`, from the index `starts` and `rows`
/// (see `Crushes::index`).
fn pushing_contacts<'a>(starts: &[u32], rows: &'a [u32], b: u32) -> &'a [u32] {
    &rows[starts[b as usize] as usize..starts[b as usize + 1] as usize]
}

#[cfg(test)]
mod tests;
