//! Per-body buffers of a step's substeps (see [`Motion`]): where the
//! contact passes keep each dynamic body's velocity and push, how a
//! substep loads them from the bodies' velocities and puts them back, and,
//! when a large step splits its contacts in two regions (see `regions`),
//! in which of two arrays each body's state lives ([`Homes`]).

use crate::columns::{ColumnsMut, ColumnsRef};
use crate::parallel::for_chunks;
use crate::solver::scalar::{BodyState, DeepPiles, SolverBodies};
use glam::Vec2;
use std::ops::Range;

/// Where a body's state lives while the passes of a step split in two
/// regions run (see `regions`): the solver's array, the second region's
/// own, or both.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) enum Home {
    /// The solver's array (the first region's bodies).
    #[default]
    Near,
    /// The second region's own array.
    Far,
    /// Both, the same: a body the contacts only read (held still this
    /// step), which either region may read.
    Both,
}

/// Each dynamic body's [`Home`] while a split step's passes run, as runs
/// of bodies with the same home (a rain added row by row and split at the
/// middle of its width: runs of a hundred). The stages around the passes
/// read and write each run where it lives, in a plain loop a run: no test
/// a body.
#[derive(Clone, Debug, Default)]
pub(crate) struct Homes {
    /// Each run's first body and home, in order; the first run starts at
    /// body 0, and each runs to the next one's start (the last to the end).
    runs: Vec<(u32, Home)>,
}

impl Homes {
    /// The runs of `homes`, one a body.
    pub(crate) fn set(&mut self, homes: impl Iterator<Item = Home>) {
        self.runs.clear();
        for (i, home) in homes.enumerate() {
            if self.runs.last().is_none_or(|&(_, last)| last != home) {
                self.runs.push((i as u32, home));
            }
        }
    }

    /// Body `i`'s home: a binary search of the runs.
    pub(crate) fn of(&self, i: usize) -> Home {
        let r = self.runs.partition_point(|&(start, _)| start as usize <= i);
        self.runs[r - 1].1
    }

    /// Calls `f` with each run of the bodies `offset..offset + len` (a
    /// chunk), as a range of the chunk, and its home.
    #[inline(always)]
    pub(crate) fn each(&self, offset: usize, len: usize, mut f: impl FnMut(Range<usize>, Home)) {
        let end = offset + len;
        // The run holding `offset`: the first starts at body 0.
        let mut r = self
            .runs
            .partition_point(|&(start, _)| start as usize <= offset)
            .saturating_sub(1);
        let mut at = offset;
        while at < end {
            let next = self
                .runs
                .get(r + 1)
                .map_or(end, |&(start, _)| (start as usize).min(end));
            f(at - offset..next - offset, self.runs[r].1);
            (at, r) = (next, r + 1);
        }
    }

    /// Calls `f` with each run of the chunk of bodies from `offset` on (as
    /// [`each`](Self::each)) and its states where they live: in `near` or
    /// `far`, the chunk's part of each array. A held run gets its near
    /// states, and is copied to the far array after.
    #[inline(always)]
    pub(crate) fn each_state(
        &self,
        offset: usize,
        near: &mut [BodyState],
        far: &mut [BodyState],
        mut f: impl FnMut(Range<usize>, &mut [BodyState]),
    ) {
        self.each(offset, near.len(), |run, home| match home {
            Home::Near => f(run.clone(), &mut near[run]),
            Home::Far => f(run.clone(), &mut far[run]),
            Home::Both => {
                f(run.clone(), &mut near[run.clone()]);
                far[run.clone()].copy_from_slice(&near[run]);
            }
        });
    }
}

/// Per-body buffers of the substeps, kept between steps.
#[derive(Clone, Debug, Default)]
pub(crate) struct Motion {
    /// Positions at the start of the step.
    pub start: Vec<Vec2>,
    /// Displacement since the start of the step, per dynamic body
    /// (separations are updated from it).
    pub delta: Vec<Vec2>,
    /// Velocity and push of each dynamic body while a substep's passes
    /// run (see [`Motion::load`]), then the rest state (see
    /// [`SolverBodies::state`]).
    pub state: Vec<BodyState>,
    /// Per dynamic body, while the substeps warm start by replaying (see
    /// [`Start::Replay`]): its velocity before the contacts acted in this
    /// substep (moved by any change a speed limit makes in the substep, so
    /// that the change is not replayed), then, once the substep ends, the
    /// change the contacts made.
    pub replay: Vec<Vec2>,
    /// The deep piles of this step.
    pub piles: DeepPiles,
    /// The buffers of the search for crushed bodies.
    pub crushes: crate::solver::crush::Crushes,
}

/// The states the passes start from, in `state`, for bodies moving at
/// `vel`; see [`Start`] (and [`Motion::load`]).
#[inline(always)]
fn load_run(state: &mut [BodyState], vel: ColumnsRef<'_>, replay: &mut [Vec2], start: Start) {
    let bodies = state.iter_mut().zip(vel.iter()).zip(replay);
    match start {
        Start::Replay => {
            for ((s, v), replay) in bodies {
                *s = BodyState::moving(v + *replay);
                *replay = v;
            }
        }
        Start::Track => {
            for ((s, v), replay) in bodies {
                *s = BodyState::moving(v);
                *replay = v;
            }
        }
        Start::Plain => {
            for ((s, v), _) in bodies {
                *s = BodyState::moving(v);
            }
        }
    }
}

/// The velocities the passes left in `state`, back into `vel`; with
/// `track`, each body's change in the substep kept in `replay` (see
/// [`Motion::unload`]).
#[inline(always)]
fn unload_run(vel: ColumnsMut<'_>, state: &[BodyState], replay: &mut [Vec2], track: bool) {
    let (vx, vy) = vel.into_parts();
    let (state, replay) = (&state[..vx.len()], &mut replay[..vx.len()]);
    for i in 0..vx.len() {
        let v = state[i].vel;
        (vx[i], vy[i]) = (v.x, v.y);
        if track {
            replay[i] = v - replay[i];
        }
    }
}

/// How a substep's passes start.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Start {
    /// From the bodies' velocities; the warm start pass applies each
    /// contact's impulses (or none is warm started).
    Plain,
    /// As `Plain`, and the change of each body's velocity that the
    /// contacts make in the substep is kept for the next one.
    Track,
    /// From the bodies' velocities plus the change the contacts made in
    /// the last substep, kept as for `Track`. Within a step the contacts
    /// are the same and each applies its impulses again at the start of
    /// the next substep (warm starting), so each body's velocity changes
    /// by what all of its contacts did in the last substep: applied here
    /// per body, in the loop that loads the states, instead of in a pass
    /// over the contacts. The sum is the same up to rounding.
    Replay,
}

impl Motion {
    /// Starts a step at positions `pos`.
    pub(crate) fn begin(&mut self, pos: ColumnsRef<'_>) {
        self.start.clear();
        self.start.extend(pos.iter());
        self.delta.clear();
        self.delta.resize(pos.len(), Vec2::ZERO);
        self.replay.resize(pos.len(), Vec2::ZERO);
    }

    /// Starts the passes of a substep: the bodies' velocities `vel`, and
    /// no push yet; see [`Start`]. In chunks on the thread pool when
    /// `parallel` and the world is large (each body on its own). `far`:
    /// while the step splits, each body's home and the second region's
    /// states, where each body's state is written (see [`Home`]).
    pub(crate) fn load(
        &mut self,
        vel: ColumnsRef<'_>,
        start: Start,
        parallel: bool,
        far: Option<(&Homes, &mut [BodyState])>,
    ) {
        debug_assert_eq!(self.replay.len(), vel.len(), "a replay entry a body");
        // Every state is written below: only the length and the rest
        // state after the bodies are set here.
        self.state.resize(vel.len(), BodyState::default());
        self.state.push(BodyState::default());
        let parts = (&mut self.state[..vel.len()], vel, &mut self.replay[..]);
        let Some((homes, far)) = far else {
            for_chunks(parallel, parts, |_, (state, vel, replay)| {
                load_run(state, vel, replay, start);
                0
            });
            return;
        };
        let (state, vel, replay) = parts;
        let far = &mut far[..vel.len()];
        let parts = (state, vel, replay, far);
        for_chunks(parallel, parts, |offset, (state, vel, replay, far)| {
            homes.each_state(offset, state, far, |run, states| {
                load_run(states, vel.slice(run.clone()), &mut replay[run], start);
            });
            0
        });
    }

    /// Ends them: the velocities the passes left, back into `vel`; with
    /// `track`, the change of each body's velocity in the substep kept.
    /// In chunks as [`load`](Self::load). `far`: while the step splits,
    /// each body's home and the second region's states (see [`Home`]).
    pub(crate) fn unload(
        &mut self,
        vel: ColumnsMut<'_>,
        track: bool,
        parallel: bool,
        far: Option<(&Homes, &[BodyState])>,
    ) {
        debug_assert_eq!(
            self.state.last(),
            Some(&BodyState::default()),
            "the rest state"
        );
        debug_assert_eq!(self.replay.len(), vel.len(), "a replay entry a body");
        let parts = (
            vel,
            &self.state[..self.state.len() - 1],
            &mut self.replay[..],
        );
        for_chunks(parallel, parts, |offset, (vel, state, replay)| {
            let Some((homes, far)) = far else {
                unload_run(vel, state, replay, track);
                return 0;
            };
            let mut vel = vel;
            homes.each(offset, vel.len(), |run, home| {
                let (vel, replay) = (vel.slice(run.clone()), &mut replay[run.clone()]);
                let state = match home {
                    Home::Far => &far[offset + run.start..offset + run.end],
                    Home::Near | Home::Both => &state[run],
                };
                unload_run(vel, state, replay, track);
            });
            0
        });
    }

    /// The solver's view of the bodies.
    pub(crate) fn bodies(&mut self) -> SolverBodies<'_> {
        self.bodies_and_replay().0
    }

    /// [`bodies`](Self::bodies), and beside them each body's velocity
    /// before the contacts acted in this substep (see [`Motion::replay`]).
    pub(crate) fn bodies_and_replay(&mut self) -> (SolverBodies<'_>, &mut [Vec2]) {
        let bodies = SolverBodies {
            state: &mut self.state,
            delta: &self.delta,
            deep: &self.piles.deep,
        };
        (bodies, &mut self.replay)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::columns::Columns;

    /// Homes in runs of uneven lengths (1 to 7), cycling through the three.
    fn homes(bodies: usize) -> Vec<Home> {
        let kinds = [Home::Near, Home::Far, Home::Both];
        let mut out = Vec::new();
        let mut k = 0;
        while out.len() < bodies {
            let run = 1 + (k * 5) % 7;
            out.extend(std::iter::repeat_n(kinds[k % 3], run));
            k += 1;
        }
        out.truncate(bodies);
        out
    }

    #[test]
    fn each_run_of_a_chunk_comes_once_in_order_with_its_home() {
        let expected = homes(40);
        let mut runs = Homes::default();
        runs.set(expected.iter().copied());
        for offset in 0..40 {
            for len in 0..=40 - offset {
                let mut seen = Vec::new();
                runs.each(offset, len, |run, home| {
                    assert!(!run.is_empty(), "chunk {offset}+{len}");
                    seen.extend(run.map(|k| (k, home)));
                });
                let want: Vec<_> = (0..len).map(|k| (k, expected[offset + k])).collect();
                assert_eq!(seen, want, "chunk {offset}+{len}");
            }
        }
        for (i, &home) in expected.iter().enumerate() {
            assert_eq!(runs.of(i), home);
        }
    }

    #[test]
    fn a_substep_loads_and_unloads_each_body_where_it_lives_with_the_same_bits() {
        // Enough bodies for the loops to go to the pool in chunks (with
        // the feature), whose edges fall inside runs.
        let n = 3 * crate::constants::PARALLEL_MIN_ITEMS + 17;
        let vel: Columns = (0..n)
            .map(|i| Vec2::new(i as f32 * 0.25 - 7.0, 1.0 - i as f32 * 0.125))
            .collect();
        let home = homes(n);
        let mut runs = Homes::default();
        runs.set(home.iter().copied());
        for parallel in [false, true] {
            for (start, track) in [
                (Start::Plain, false),
                (Start::Track, true),
                (Start::Replay, true),
            ] {
                let mut one = Motion::default();
                one.begin(vec![Vec2::ZERO; n].into_iter().collect::<Columns>().view());
                one.replay
                    .iter_mut()
                    .enumerate()
                    .for_each(|(i, r)| *r = Vec2::splat(i as f32));
                let mut two = one.clone();
                let mut far = vec![BodyState::default(); n + 1];

                one.load(vel.view(), start, parallel, None);
                two.load(vel.view(), start, parallel, Some((&runs, &mut far)));
                for i in 0..n {
                    let (near, far) = (two.state[i], far[i]);
                    match home[i] {
                        Home::Near => assert_eq!(near, one.state[i], "body {i}"),
                        Home::Far => assert_eq!(far, one.state[i], "body {i}"),
                        Home::Both => assert_eq!((near, far), (one.state[i], one.state[i])),
                    }
                }
                assert_eq!(two.replay, one.replay);

                // What the passes would leave: each state changed where it
                // lives (and held bodies, in both arrays, not at all).
                let moved = |s: BodyState| BodyState::moving(s.vel * 2.0 + Vec2::X);
                for i in 0..n {
                    match home[i] {
                        Home::Near => two.state[i] = moved(two.state[i]),
                        Home::Far => far[i] = moved(far[i]),
                        Home::Both => {}
                    }
                    if home[i] != Home::Both {
                        one.state[i] = moved(one.state[i]);
                    }
                }
                let (mut out_one, mut out_two) = (vel.clone(), vel.clone());
                one.unload(out_one.view_mut(), track, parallel, None);
                two.unload(out_two.view_mut(), track, parallel, Some((&runs, &far)));
                assert_eq!(out_two, out_one, "{start:?}, parallel {parallel}");
                assert_eq!(two.replay, one.replay, "{start:?}, parallel {parallel}");
            }
        }
    }
}
