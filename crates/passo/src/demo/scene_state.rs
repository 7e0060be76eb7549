//! The state of the scene a demo runs: its lanes, the player and the
//! input for the next tick, the plot. A reset or a new rain count builds a
//! fresh one from the scene's source; what outlives that is in the
//! [`Session`](super::session::Session).

use super::controls::{self, Input, Knobs};
use super::history::History;
use super::lanes::{Lane, integrator_lanes};
use crate::scenes::Plot;
use anyhow::Result;
use glam::Vec2;
use passo_physics::{
    Aabb, BodyId, BodyKind, Integrator, JointDef, JointId, JointKind, World, WorldSnapshot,
};
use passo_scene::{BuiltScene, Generator, LevelArt, Platform, Scene, SceneFile};
use std::collections::VecDeque;
use std::sync::Arc;

/// A scene being run: everything a reset rebuilds.
#[derive(Debug)]
pub struct SceneState {
    /// Scene name.
    pub name: String,
    /// One-line description.
    pub description: String,
    /// The worlds (several only for side-by-side comparisons).
    pub lanes: Vec<Lane>,
    /// The region to show at first.
    pub bounds: Aabb,
    /// The body the keyboard moves, in lane 0.
    pub player: Option<BodyId>,
    /// A physics player the same keys push with forces, beside a
    /// character moved by the character mover (a level's `physics player`
    /// spawn point), so the two controllers can be compared.
    pub twin: Option<BodyId>,
    /// Whether each lane has its own integrator (the integrator picker is off).
    pub fixed_integrators: bool,
    /// The plot.
    pub history: History,
    /// How the level's cells look (lane 0). Shared, so the window knows a
    /// new scene's art by its pointer alone.
    pub art: Arc<LevelArt>,
    /// The bodies of the level's cells, drawn as its tiles.
    pub cell_bodies: Vec<BodyId>,
    /// The scene file, to rebuild (reset, body count) from; `None` for the
    /// integrator comparison.
    pub file: Option<SceneFile>,
    /// Where the scene file was (a path, or a built-in scene's place in
    /// the source tree): a level map it names is found beside it.
    source: String,
    /// Game input for the next tick (jump is consumed by it).
    input: Input,
    /// Kinematic bodies of lane 0 that follow a path (moving platforms).
    platforms: Vec<Platform>,
    /// Ticks this state has stepped: the platforms' clock, which starts
    /// with the scene (a replay or a reset starts it again).
    ticks: u64,
    /// The platforms' time at the end of each tick.
    clock: Clock,
    /// The states before the last ticks, oldest first, for rewinding.
    rewind: Rewind,
}

/// Simulated time at the end of a tick, from the count of ticks and the
/// step: `ticks × dt` while the step stays the same (bit for bit), and
/// running on from where it was when the step changes (the demo's rate
/// picker), instead of rescaling every tick before: at 60 Hz → 120 Hz a
/// lift jumped 2.4 m in a tick, at 290 m/s.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Clock {
    /// The tick count when the step last changed, and the time then.
    since: u64,
    at: f64,
    /// The step, seconds, and the tick count of the last call.
    dt: f64,
    last: u64,
}

impl Clock {
    /// The time at the end of tick `ticks` (counted from the start), with
    /// ticks of `dt` seconds after the last call's.
    pub(crate) fn time(&mut self, ticks: u64, dt: f64) -> f64 {
        if dt != self.dt {
            self.at += self.last.saturating_sub(self.since) as f64 * self.dt;
            self.since = self.last;
            self.dt = dt;
        }
        self.last = ticks;
        self.at + ticks.saturating_sub(self.since) as f64 * dt
    }
}

/// The state of every lane before one tick.
#[derive(Debug, Default)]
struct Saved {
    worlds: Vec<WorldSnapshot>,
    ticks: u64,
    clock: Clock,
    /// Heap bytes of `worlds`, measured when saved.
    bytes: usize,
}

/// The last states of a scene, newest last, in reused buffers: while the
/// ring keeps as many states as before, saving a tick allocates nothing.
#[derive(Debug, Default)]
struct Rewind {
    states: VecDeque<Saved>,
    /// Buffers of states rewound, to fill again.
    spare: Vec<Saved>,
    /// On the timeline: the kept state shown (the newest is the present
    /// when the scrubbing began).
    cursor: Option<usize>,
}

/// At most this many ticks are kept for rewinding (10 s at 60 Hz)...
const REWIND_TICKS: usize = 600;
/// ...and at least this many, whatever the size...
const REWIND_MIN_TICKS: usize = 10;
/// ...within about this many bytes of snapshots, as each measured when it
/// was kept; the next is taken to hold what the newest did (give or take a
/// state: a reused buffer may be larger). A settled pile of 10 000 circles
/// takes 930 bytes a body.
pub const REWIND_BYTES: usize = 128 << 20;

impl SceneState {
    /// The state of a scene file, with interpolated drawing on and the
    /// plot the scene table chose.
    pub fn from_scene(scene: &Scene, plot: Plot) -> Result<Self> {
        let mut built = scene.build()?;
        let file = scene.file.clone();
        let player = built
            .body_named("player")
            .or_else(|| controls::add_character(&mut built));
        let twin = controls::add_physics_player(&mut built);
        let platforms = built.platforms;
        let (art, cell_bodies) = (built.art, built.cell_bodies);
        let lanes = vec![Lane::new(
            String::new(),
            built.world,
            built.bodies,
            Vec2::ZERO,
        )];
        let mut state = Self {
            name: file.name.clone(),
            description: file.description.clone(),
            history: History::new(plot, &lanes),
            art: Arc::new(art),
            cell_bodies,
            lanes,
            bounds: built.camera,
            player,
            twin,
            fixed_integrators: false,
            file: Some(file),
            source: scene.source.clone(),
            input: Input::default(),
            platforms,
            ticks: 0,
            clock: Clock::default(),
            rewind: Rewind::default(),
        };
        state.set_interpolation(true);
        Ok(state)
    }

    /// The same spring under each integrator side by side.
    pub fn integrators() -> Self {
        let lanes = integrator_lanes();
        Self {
            name: "Integrators".into(),
            description:
                "One spring (period 1 s) under each integrator: explicit Euler gains energy, \
                          semi-implicit Euler keeps it bounded, Verlet and RK4 follow the cosine."
                    .into(),
            history: History::new(Plot::Energy, &lanes),
            art: Arc::default(),
            cell_bodies: Vec::new(),
            lanes,
            bounds: Aabb {
                min: Vec2::new(-6.5, -3.0),
                max: Vec2::new(6.5, 3.0),
            },
            player: None,
            twin: None,
            fixed_integrators: true,
            file: None,
            source: String::new(),
            input: Input::default(),
            platforms: Vec::new(),
            ticks: 0,
            clock: Clock::default(),
            rewind: Rewind::default(),
        }
    }

    /// A fresh state from the same source (`file` replacing the scene file,
    /// if given), with the sliders applied and this state's integrator and
    /// interpolation switch kept.
    pub(crate) fn rebuilt(&self, file: Option<SceneFile>, knobs: &Knobs) -> Result<Self> {
        let mut fresh = match file.or_else(|| self.file.clone()) {
            Some(file) => {
                let scene = Scene {
                    file,
                    source: self.source.clone(),
                };
                scene.file.validate(&scene.source)?;
                Self::from_scene(&scene, self.history.plot())?
            }
            None => Self::integrators(),
        };
        fresh.apply_knobs(knobs);
        fresh.set_integrator(self.integrator());
        fresh.set_interpolation(self.interpolation());
        Ok(fresh)
    }

    /// The game input for the coming ticks; a jump stays pending until a
    /// tick takes it.
    pub fn set_input(&mut self, input: Input) {
        let jump = self.input.jump || input.jump;
        self.input = Input { jump, ..input };
    }

    /// The input the next tick uses.
    pub(crate) fn input(&self) -> Input {
        self.input
    }

    /// Replaces the input outright (a replayed one).
    pub(crate) fn replace_input(&mut self, input: Input) {
        self.input = input;
    }

    /// Steps every lane by `dt` seconds after the player's controls and
    /// the moving platforms, then samples the plot at simulated time `t`.
    pub(crate) fn step(&mut self, dt: f32, t: f32, knobs: &Knobs) {
        self.ticks += 1;
        let t_end = self.clock.time(self.ticks, f64::from(dt));
        BuiltScene::drive_platforms(&self.platforms, &mut self.lanes[0].world, t_end, dt);
        if let Some(twin) = self.twin {
            // The same keys, jump included, before the player takes them.
            let lane = &mut self.lanes[0];
            let base_drag = lane.base_drag(twin);
            let mut input = self.input;
            controls::drive_player(&mut lane.world, twin, &mut input, knobs, base_drag);
        }
        if let Some(player) = self.player {
            let lane = &mut self.lanes[0];
            if controls::is_character(&lane.world, player) {
                controls::drive_character(&mut lane.world, player, &mut self.input, knobs, dt);
            } else {
                let base_drag = lane.base_drag(player);
                controls::drive_player(&mut lane.world, player, &mut self.input, knobs, base_drag);
            }
        }
        for lane in &mut self.lanes {
            lane.world.step(dt);
        }
        self.history.sample(t, &self.lanes);
    }

    /// Keeps the state of every lane as it is now, to rewind to: before
    /// each tick while rewinding is possible. Only the last ticks are kept
    /// (10 s at 60 Hz, fewer for big scenes: about [`REWIND_BYTES`], or 10
    /// ticks). Returns how many of the oldest states made room.
    pub fn save_for_rewind(&mut self) -> usize {
        let r = &mut self.rewind;
        let next = r.states.back().map_or(0, |newest| newest.bytes);
        let mut held: usize = r.states.iter().map(|s| s.bytes).sum();
        let mut dropped = 0;
        while r.states.len() >= REWIND_TICKS
            || (r.states.len() >= REWIND_MIN_TICKS && held + next > REWIND_BYTES)
        {
            let Some(oldest) = r.states.pop_front() else {
                break;
            };
            held -= oldest.bytes;
            // One spare buffer is reused by this save; the others (the
            // scene grew, and many states go at once) are let go.
            if r.spare.is_empty() {
                r.spare.push(oldest);
            }
            dropped += 1;
        }
        let mut saved = r.spare.pop().unwrap_or_default();
        saved
            .worlds
            .resize_with(self.lanes.len(), WorldSnapshot::default);
        for (lane, snapshot) in self.lanes.iter().zip(&mut saved.worlds) {
            lane.world.snapshot_into(snapshot);
        }
        saved.ticks = self.ticks;
        saved.clock = self.clock;
        saved.bytes = saved.worlds.iter().map(WorldSnapshot::heap_bytes).sum();
        r.states.push_back(saved);
        dropped
    }

    /// Goes back one tick: every lane (and the platforms' clock) as it was
    /// before the last tick kept. False when no tick is left to rewind.
    /// The plot keeps its samples.
    pub(crate) fn step_back(&mut self) -> bool {
        self.resume();
        let Some(last) = self.rewind.states.len().checked_sub(1) else {
            return false;
        };
        self.show(last);
        self.rewind.spare.extend(self.rewind.states.pop_back());
        for lane in &mut self.lanes {
            lane.forget_removed();
        }
        true
    }

    /// Puts every lane (and the platforms' clock) in kept state `i`.
    fn show(&mut self, i: usize) {
        let saved = &self.rewind.states[i];
        for (lane, snapshot) in self.lanes.iter_mut().zip(&saved.worlds) {
            // A snapshot this world made always restores; should it not,
            // the lane keeps its state rather than stopping the demo.
            if let Err(e) = lane.world.restore_from(snapshot) {
                log::warn!("rewind failed: {e}");
            }
        }
        self.ticks = saved.ticks;
        self.clock = saved.clock;
    }

    /// Ticks that can be rewound now.
    pub fn rewindable(&self) -> usize {
        self.rewind.states.len()
    }

    /// Bytes the kept states hold.
    pub fn rewind_bytes(&self) -> usize {
        let r = &self.rewind;
        (r.states.iter().chain(&r.spare))
            .flat_map(|saved| &saved.worlds)
            .map(WorldSnapshot::heap_bytes)
            .sum()
    }

    /// Shows kept state `i` (0: the oldest) without discarding any, for
    /// the timeline; the first call keeps the present as the newest.
    /// [`resume`](Self::resume) runs on from the state shown.
    pub fn scrub_to(&mut self, i: usize) {
        let mut i = i;
        if self.rewind.cursor.is_none() {
            i = i.saturating_sub(self.save_for_rewind());
        }
        let i = i.min(self.rewind.states.len() - 1);
        // The lanes keep the names and colours of bodies the state shown
        // does not have yet: scrubbing forward brings them back.
        self.show(i);
        self.rewind.cursor = Some(i);
    }

    /// The kept state the timeline shows, if scrubbing.
    pub fn scrubbing(&self) -> Option<usize> {
        self.rewind.cursor
    }

    /// Leaves the timeline at the state shown: the states after it (its
    /// future) are discarded, as a rollback does, and ticks run on from it.
    pub fn resume(&mut self) {
        if let Some(i) = self.rewind.cursor.take() {
            let r = &mut self.rewind;
            // The state shown is the present again; the next tick keeps it.
            r.spare.extend(r.states.drain(i..));
            for lane in &mut self.lanes {
                lane.forget_removed();
            }
        }
    }

    /// Applies the sliders' settings to every lane.
    pub(crate) fn apply_knobs(&mut self, knobs: &Knobs) {
        for lane in &mut self.lanes {
            lane.apply_knobs(knobs);
        }
        self.update_reference_lines(knobs);
    }

    /// Recomputes the plot's reference lines for the sliders' gravity and
    /// air density.
    pub(crate) fn update_reference_lines(&mut self, knobs: &Knobs) {
        self.history
            .update_lines(&self.lanes, knobs.gravity, knobs.density);
    }

    /// Sets the friction of every dynamic body.
    pub(crate) fn apply_friction(&mut self, mu: f32) {
        for lane in &mut self.lanes {
            lane.for_each_dynamic(|w, id| w.try_set_friction(id, mu));
        }
    }

    /// Sets the restitution of every dynamic body.
    pub(crate) fn apply_restitution(&mut self, e: f32) {
        for lane in &mut self.lanes {
            lane.for_each_dynamic(|w, id| w.set_restitution(id, e));
        }
    }

    /// Scales every dynamic body's scene drag area.
    pub(crate) fn apply_drag_scale(&mut self, knobs: &Knobs) {
        for lane in &mut self.lanes {
            lane.scale_drag(knobs.drag_scale);
        }
        self.update_reference_lines(knobs);
    }

    /// The integrator of every lane (unless each lane has its own).
    pub fn set_integrator(&mut self, integrator: Integrator) {
        if self.fixed_integrators {
            return;
        }
        for lane in &mut self.lanes {
            lane.update_settings(|s| s.integrator = integrator);
        }
    }

    /// The integrator of lane 0.
    pub fn integrator(&self) -> Integrator {
        self.lanes[0].world.settings().integrator
    }

    /// Whether the worlds keep previous positions for interpolated drawing.
    pub fn interpolation(&self) -> bool {
        self.lanes[0].world.settings().interpolation
    }

    /// Turns interpolated drawing on or off.
    pub fn set_interpolation(&mut self, on: bool) {
        for lane in &mut self.lanes {
            lane.update_settings(|s| s.interpolation = on);
        }
    }

    /// Whether the scene solves contacts (the continuous-collision switch applies).
    pub fn has_contacts(&self) -> bool {
        self.lanes
            .iter()
            .any(|l| l.world.settings().contacts.is_some())
    }

    /// Bodies in every lane.
    pub fn body_count(&self) -> usize {
        self.lanes.iter().map(|l| l.world.len()).sum()
    }

    /// Sleeping bodies, contacts solved in the last step, and all contacts,
    /// over every lane.
    pub fn sleep_counts(&self) -> (usize, usize, usize) {
        self.lanes.iter().fold((0, 0, 0), |(s, v, c), l| {
            let w = &l.world;
            (
                s + w.sleeping_len(),
                v + w.solved_contacts(),
                c + w.contacts().count(),
            )
        })
    }

    /// Total energy of every lane, joules.
    pub fn energy(&self) -> f64 {
        self.lanes.iter().map(|l| l.world.total_energy()).sum()
    }

    /// A 64-bit hash of every lane's state: the lanes' `World::state_hash`
    /// words folded with the same FNV-1a.
    pub fn state_hash(&self) -> u64 {
        let mut h = passo_physics::StateHasher::new();
        for lane in &self.lanes {
            h.write_u64(lane.world.state_hash());
        }
        h.finish()
    }

    /// The dynamic body under a world point (lane 0), if any.
    pub fn pick(&self, at: Vec2) -> Option<BodyId> {
        let lane = &self.lanes[0];
        lane.world
            .query_point(at - lane.offset)
            .into_iter()
            .find(|&id| {
                lane.world
                    .body(id)
                    .is_some_and(|b| b.kind == BodyKind::Dynamic)
            })
    }

    /// The body of lane 0 with this slot index and generation, if it lives.
    pub(crate) fn body_with(&self, index: u32, generation: u32) -> Option<BodyId> {
        self.lanes[0]
            .world
            .bodies()
            .map(|b| b.id)
            .find(|id| id.index() == index && id.generation() == generation)
    }

    /// Takes hold of dynamic body `id` of lane 0 at the world point `at`:
    /// a target joint from that point of the body, pulled toward the
    /// pointer by a 5 Hz spring with at most 1 000 times the body's weight
    /// (as Box2D's samples drag bodies). What held a body before lets go.
    pub fn grab(&mut self, id: BodyId, at: Vec2) {
        self.release();
        let world = &mut self.lanes[0].world;
        let Some(body) = world.body(id) else {
            return;
        };
        let g = world
            .settings()
            .forces
            .gravity
            .map_or(9.81, |g| g.length().max(9.81));
        let def = JointDef::target(id, at)
            .anchors(at - body.position, at)
            .max_force(1000.0 * body.mass * g);
        if let Err(e) = world.add_joint(def) {
            log::warn!("grab refused: {e}");
        }
    }

    /// Moves the held body's target to `at`.
    pub fn drag_to(&mut self, at: Vec2) {
        let world = &mut self.lanes[0].world;
        if let Some(id) = grab_joint(world)
            && let Err(e) = world.set_joint_target(id, at)
        {
            log::warn!("drag refused: {e}");
        }
    }

    /// Lets go of the held body, if any.
    pub fn release(&mut self) {
        let world = &mut self.lanes[0].world;
        while let Some(id) = grab_joint(world) {
            world.remove_joint(id);
        }
    }

    /// Sets a body's velocity (a fling).
    pub fn fling(&mut self, id: BodyId, velocity: Vec2) {
        if let Err(e) = self.lanes[0].world.try_set_velocity(id, velocity) {
            log::warn!("fling refused: {e}");
        }
    }

    /// Number of bodies of the scene's rain generator, if it has one.
    pub fn rain_count(&self) -> Option<u32> {
        self.file.as_ref()?.generators.iter().find_map(|g| match g {
            Generator::Rain { count, .. } => Some(*count),
            _ => None,
        })
    }

    /// The scene file with `n` bodies (at least 1) in its rain generators,
    /// if the scene has a file.
    pub(crate) fn file_with_rain(&self, n: u32) -> Option<SceneFile> {
        let mut file = self.file.clone()?;
        for g in &mut file.generators {
            if let Generator::Rain { count, .. } = g {
                *count = n.max(1);
            }
        }
        Some(file)
    }
}

/// The joint by which the mouse holds a body: the world's target joint
/// (scene files make none), found in the world rather than remembered, so
/// a rewind or a replay that removes it leaves nothing stale.
fn grab_joint(world: &World) -> Option<JointId> {
    world
        .joints()
        .find(|(_, j)| matches!(j.def.kind, JointKind::Target { .. }))
        .map(|(id, _)| id)
}

#[cfg(test)]
mod tests {
    use super::Clock;

    #[test]
    fn the_clock_is_ticks_times_the_step_and_runs_on_from_a_change() {
        let mut clock = Clock::default();
        let dt = 1.0 / 60.0;
        for ticks in 1..=360u64 {
            // The very bits of `ticks × dt`: no scene's motion changes.
            assert_eq!(clock.time(ticks, dt), ticks as f64 * dt);
        }
        let six = 360.0 * dt;
        assert_eq!(clock.time(361, 1.0 / 120.0), six + 1.0 / 120.0);
        assert!((clock.time(480, 1.0 / 120.0) - (six + 1.0)).abs() < 1e-12);
        // Back to 60 Hz from there.
        assert!((clock.time(540, dt) - (six + 2.0)).abs() < 1e-12);
    }
}
