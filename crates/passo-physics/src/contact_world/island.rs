//! Islands: dynamic bodies joined by touching contacts, or by contacts
//! close enough that one body would wake the other. An island falls asleep
//! when all its bodies have rested long enough, and wakes as one (see
//! `sleeping` for what sleeping means to the step).

use crate::body::store::{DynamicBodies, SleepState};
use crate::constants::{SLEEP_SPEED, TIME_TO_SLEEP};
use crate::contact::constraint::{Constraint, ContactInfo};
use glam::Vec2;

/// Scratch space of the island pass, kept between steps so it allocates
/// nothing once warm.
#[derive(Clone, Debug, Default)]
pub(crate) struct Islands {
    parent: Vec<u32>,
    /// Least rest time in each island, by root.
    least_rest: Vec<f32>,
    /// Islands to wake at the next chance, sorted and deduplicated there.
    to_wake: Vec<u32>,
}

impl Islands {
    fn find(&mut self, mut i: u32) -> u32 {
        while self.parent[i as usize] != i {
            let p = self.parent[i as usize];
            // Path halving: every visited node skips to its grandparent.
            self.parent[i as usize] = self.parent[p as usize];
            i = p;
        }
        i
    }

    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        // The lower index becomes the root: the result depends only on the
        // contacts, not on the order of the unions.
        if ra < rb {
            self.parent[rb as usize] = ra;
        } else if rb < ra {
            self.parent[ra as usize] = rb;
        }
    }

    /// Forgets every mark (and the scratch of the last pass).
    pub(crate) fn clear(&mut self) {
        self.parent.clear();
        self.least_rest.clear();
        self.to_wake.clear();
    }

    /// Forgets the islands marked to wake: every body woke. A mark left
    /// behind would name an island that no longer exists, and wake the
    /// next one given its id (its root's slot) for nothing, in a live world
    /// but not in one restored from a save (which has no marks).
    pub(crate) fn forget_marks(&mut self) {
        self.to_wake.clear();
    }

    /// Marks the island of sleeping body `i` (and the body itself, at once)
    /// to be woken.
    pub(crate) fn wake_body(&mut self, bodies: &mut DynamicBodies, i: usize) {
        let s = &mut bodies.sleep[i];
        if let Some(island) = s.island() {
            self.to_wake.push(island);
        }
        *s = SleepState::awake();
    }

    /// Wakes every body of the islands marked by [`wake_body`]: one pass
    /// over the bodies, only when some island was marked.
    ///
    /// [`wake_body`]: Self::wake_body
    pub(crate) fn wake_marked(&mut self, bodies: &mut DynamicBodies) {
        if self.to_wake.is_empty() {
            return;
        }
        self.to_wake.sort_unstable();
        self.to_wake.dedup();
        for s in &mut bodies.sleep {
            if s.island()
                .is_some_and(|i| self.to_wake.binary_search(&i).is_ok())
            {
                *s = SleepState::awake();
            }
        }
        self.to_wake.clear();
    }

    /// After a step: adds `dt` to the rest time of every awake body that
    /// ends the step slower than [`SLEEP_SPEED`] and moved less than that
    /// speed allows (so a body still being pushed out of an overlap, with
    /// zero velocity, is not resting), and resets the others. `moved` is
    /// each body's displacement over the step.
    pub(crate) fn rest(&mut self, bodies: &mut DynamicBodies, moved: &[Vec2], dt: f32) {
        let sleep_sq = SLEEP_SPEED * SLEEP_SPEED;
        let travel_sq = sleep_sq * dt * dt;
        let states = bodies.sleep.iter_mut().zip(bodies.vel.iter()).zip(moved);
        for (((s, v), d), &im) in states.zip(&bodies.inv_mass) {
            if !s.is_asleep() {
                // A kinematic body (inverse mass zero) rests only when game
                // code stopped it: sleeping would stop a slow platform.
                let resting = if im == 0.0 {
                    v == Vec2::ZERO
                } else {
                    v.length_squared() < sleep_sq && d.length_squared() < travel_sq
                };
                s.rest_time = if resting { s.rest_time + dt } else { 0.0 };
            }
        }
    }

    /// Joins awake bodies that touch, or that a joint links (`links`), into islands and puts to sleep each
    /// island whose bodies have all rested for [`TIME_TO_SLEEP`] (their
    /// velocities become exactly zero). Returns whether any island fell
    /// asleep.
    ///
    /// Bodies closer than `slop` plus what two resting bodies close in a
    /// step of `dt` join too, touching or not: an awake body that near a
    /// sleeping one wakes it at the next step (`wake_reached` in the
    /// contact stage), so two such neighbours in islands of their own
    /// would take turns falling asleep and waking each other for ever.
    pub(crate) fn fall_asleep(
        &mut self,
        bodies: &mut DynamicBodies,
        constraints: &[Constraint],
        infos: &[ContactInfo],
        links: &[(u32, u32)],
        slop: f32,
        dt: f32,
    ) -> bool {
        let reach = slop + 2.0 * SLEEP_SPEED * dt;
        let n = bodies.len();
        self.parent.clear();
        self.parent.extend(0..n as u32);
        for (c, info) in constraints.iter().zip(infos) {
            let Some(b) = c.b.dynamic_index() else {
                continue;
            };
            let both_awake =
                !bodies.sleep[c.a as usize].is_asleep() && !bodies.sleep[b].is_asleep();
            if both_awake && (info.is_touching(c) || info.separation <= reach) {
                self.union(c.a, b as u32);
            }
        }
        // Bodies a joint links are one island, touching or not.
        for &(a, b) in links {
            if !bodies.sleep[a as usize].is_asleep() && !bodies.sleep[b as usize].is_asleep() {
                self.union(a, b);
            }
        }
        self.least_rest.clear();
        self.least_rest.resize(n, f32::INFINITY);
        // At most one island per body to wake: room for all, so waking
        // never allocates inside a step.
        self.to_wake.reserve(n);
        for i in 0..n {
            if !bodies.sleep[i].is_asleep() {
                let root = self.find(i as u32) as usize;
                self.least_rest[root] = self.least_rest[root].min(bodies.sleep[i].rest_time);
            }
        }
        let mut fell = false;
        for i in 0..n {
            if bodies.sleep[i].is_asleep() {
                continue;
            }
            let root = self.find(i as u32) as usize;
            if self.least_rest[root] >= TIME_TO_SLEEP {
                bodies.sleep[i].sleep_in(bodies.meta[root].id.index);
                bodies.vel.set(i, Vec2::ZERO);
                fell = true;
            }
        }
        fell
    }
}
