//! A running demo scene: a [`Session`] driving a [`SceneState`] one fixed
//! tick at a time, applying the player's and the panel's commands, and
//! recording or replaying them. Nothing here touches a window, so tests
//! drive it with exact frame times.

use super::catalogue::Entry;
use super::controls::Knobs;
use super::replay::{Command, Replay};
use super::scene_state::{Clock, SceneState};
use super::session::{Session, Stats};
use crate::Instant;
use anyhow::Result;
use glam::Vec2;
use passo_loop::{FixedTimestep, Frame};
use passo_physics::BodyId;
use passo_scene::SceneFile;
use std::time::Duration;

/// A running demo scene.
#[derive(Debug)]
pub struct Sim {
    /// What a reset keeps: the loop, the sliders, recording and playback.
    pub session: Session,
    /// What a reset rebuilds: the worlds, the player, the plot.
    pub scene: SceneState,
    /// Held down (Backspace): ticks run backwards through the kept states
    /// instead of stepping, while not recording or replaying.
    pub rewinding: bool,
    /// Whether the loop was paused when the timeline was first dragged.
    paused_before_scrub: bool,
    /// The plot's time: the loop's ticks, run on from a change of rate.
    plot_clock: Clock,
    /// Whether each tick keeps the state before it, for rewinding (not
    /// when a replay is checked headless: nobody rewinds it there, and a
    /// replay that spawns thousands of bodies held ten states of them).
    keeps_rewind: bool,
}

/// Loads a scene of the list.
pub fn load(entry: &Entry) -> Result<Sim> {
    match entry {
        Entry::Integrators => Ok(Sim::new(
            SceneState::integrators(),
            FixedTimestep::from_hz(own_rate(None)).expect("60 Hz is valid"),
            "integrators".into(),
        )),
        Entry::File(name) => {
            let scene = crate::scenes::load(name)?;
            let state = SceneState::from_scene(&scene, crate::scenes::plot(name))?;
            let timestep = FixedTimestep::from_hz(own_rate(Some(&scene.file)))?;
            Ok(Sim::new(state, timestep, name.clone()))
        }
    }
}

/// A scene's own fixed rate, Hz: its file's, or 60 Hz for the
/// integrators' comparison (which has no file).
fn own_rate(file: Option<&SceneFile>) -> f64 {
    file.map_or(60.0, |f| f.rate_hz)
}

/// Plays a replay headlessly, one tick after the other, and returns the
/// final state hash (which matches the recorded one if all is well).
pub fn run_replay(replay: &Replay) -> Result<u64> {
    let mut sim = load(&Entry::named(&replay.scene))?;
    sim.keeps_rewind = false;
    sim.start_playback(replay.clone())?;
    for _ in 0..replay.ticks {
        sim.session.timestep.advance_ticks(1);
        sim.tick();
    }
    Ok(sim.scene.state_hash())
}

impl Sim {
    /// A session of `scene` loaded as `entry_name`, its sliders read from
    /// lane 0.
    fn new(mut scene: SceneState, timestep: FixedTimestep, entry_name: String) -> Self {
        let knobs = Knobs::of(&scene.lanes[0].world);
        scene.update_reference_lines(&knobs);
        Self {
            session: Session::new(timestep, knobs, entry_name),
            scene,
            rewinding: false,
            paused_before_scrub: false,
            plot_clock: Clock::default(),
            keeps_rewind: true,
        }
    }

    /// Advances by one rendered frame of `frame_time`: the loop decides how
    /// many fixed ticks run.
    pub fn frame(&mut self, frame_time: Duration) -> Frame {
        if self.rewinding && self.can_rewind() {
            // A finished replay goes live: it can run back and on.
            self.leave_finished_replay();
            // Backspace leaves the timeline and rewinds from where it was,
            // when the loop will run (paused, the timeline is the way).
            if !self.paused_before_scrub {
                self.resume_from_timeline();
            }
        }
        let frame = self.session.timestep.advance(frame_time);
        self.run_frame(frame)
    }

    /// Runs exactly `n` ticks now, whatever the clock says and paused or
    /// not: for drivers that count ticks (the web demo's `?ticks=N`).
    pub fn frame_of_ticks(&mut self, n: u32) -> Frame {
        let frame = self.session.timestep.advance_ticks(n);
        self.run_frame(frame)
    }

    /// Runs the ticks of `frame` (fewer when a replay ends, the timeline
    /// holds the scene, or the scene rewinds instead).
    fn run_frame(&mut self, frame: Frame) -> Frame {
        let started = Instant::now();
        let mut rewound = false;
        for _ in frame.tick_numbers() {
            // A finished playback holds its final state.
            if self.session.playback_finished() {
                break;
            }
            // On the timeline the scene holds still until it resumes.
            if self.scene.scrubbing().is_some() {
                break;
            }
            if self.rewinding && self.can_rewind() {
                rewound |= self.scene.step_back();
                continue;
            }
            self.tick();
        }
        if rewound {
            self.knobs_from_world();
        }
        self.session.stats = Stats {
            ticks: frame.ticks,
            dropped: frame.dropped,
            step_ms: started.elapsed().as_secs_f64() * 1e3,
            alpha: frame.alpha,
        };
        frame
    }

    /// One fixed tick: replayed commands and input, the player's forces,
    /// the step, a plot sample. The step length is read after replayed
    /// commands, one of which may change the rate.
    pub fn tick(&mut self) {
        // Kept while recording and replaying too: a finished replay can be
        // rewound.
        if self.keeps_rewind {
            self.scene.save_for_rewind();
        }
        self.replay_commands_and_input();
        self.session.record_input(self.scene.input());
        let timestep = &self.session.timestep;
        let dt = timestep.dt();
        let t = self
            .plot_clock
            .time(timestep.tick(), timestep.step().as_secs_f64()) as f32;
        self.scene.step(dt, t, &self.session.knobs);
        self.session.count_tick();
        self.end_playback_if_due();
    }

    /// Ends a playback that has played its last tick. Commands recorded
    /// after that tick (made while paused, before the recording stopped)
    /// apply first: the recorded hash was taken after them.
    fn end_playback_if_due(&mut self) {
        if self.session.playback_due_to_end() {
            self.replay_commands();
            let hash = self.scene.state_hash();
            self.session.end_playback(hash);
        }
    }

    /// The sliders as the (rewound) worlds are set: a rewind past a slider
    /// change undoes it. The drag-area multiplier is read from the bodies'
    /// areas against the scene's; a calm wind's speed is not in the worlds
    /// and stays.
    fn knobs_from_world(&mut self) {
        let old = self.session.knobs;
        let mut knobs = Knobs::of(&self.scene.lanes[0].world);
        knobs.drag_scale = (self.scene.lanes[0])
            .drag_scale_in_world(self.scene.player)
            .unwrap_or(old.drag_scale);
        if !knobs.wind {
            knobs.wind_speed = old.wind_speed;
        }
        self.session.knobs = knobs;
        self.scene.update_reference_lines(&knobs);
    }

    /// Shows kept state `i` of the timeline (0: the oldest), when rewinding
    /// is possible; the sliders follow the worlds.
    pub fn scrub_to(&mut self, i: usize) {
        if !self.can_rewind() {
            return;
        }
        if self.scene.scrubbing().is_none() {
            // A finished replay (whose loop is paused) goes live, and runs
            // on from the state shown when resumed.
            let replay_done = self.leave_finished_replay();
            // The loop holds still on the timeline.
            self.paused_before_scrub = self.session.timestep.is_paused() && !replay_done;
            self.session.timestep.pause();
        }
        self.scene.scrub_to(i);
        self.knobs_from_world();
    }

    /// Ends a finished replay so the scene runs live again (the loop runs);
    /// returns whether there was one.
    fn leave_finished_replay(&mut self) -> bool {
        if !self.session.playback_finished() {
            return false;
        }
        self.session.stop_replays();
        self.session.timestep.resume();
        true
    }

    /// Leaves the timeline and runs on from the state it shows, discarding
    /// the states after it.
    pub fn resume_from_timeline(&mut self) {
        if self.scene.scrubbing().is_some() {
            self.scene.resume();
            if !self.paused_before_scrub {
                self.session.timestep.resume();
            }
        }
    }

    /// Rewinding goes with neither a recording nor a running replay: both
    /// run forward by tick. A finished replay can be rewound.
    pub fn can_rewind(&self) -> bool {
        !self.session.is_recording()
            && (!self.session.is_playing() || self.session.playback_finished())
    }

    /// In playback, applies the commands due and takes the recorded input.
    fn replay_commands_and_input(&mut self) {
        self.replay_commands();
        if let Some(input) = self.session.replayed_input() {
            self.scene.replace_input(input);
        }
    }

    /// In playback, applies the commands due.
    fn replay_commands(&mut self) {
        while let Some(command) = self.session.next_replayed_command() {
            if let Err(e) = self.apply(&command) {
                log::warn!("replayed command failed: {e:#}");
            }
        }
    }

    /// Applies a command from the player or the panel, recording it when
    /// recording. In playback, live commands are ignored.
    pub fn command(&mut self, command: Command) -> Result<()> {
        if self.session.is_playing() {
            return Ok(());
        }
        self.session.record_command(&command);
        self.apply(&command)
    }

    fn apply(&mut self, command: &Command) -> Result<()> {
        match command {
            Command::Spawn { at, round } => {
                self.spawn(Vec2::from_array(*at), *round);
            }
            Command::Grab {
                index,
                generation,
                at,
            } => {
                if let Some(id) = self.scene.body_with(*index, *generation) {
                    self.scene.grab(id, Vec2::from_array(*at));
                }
            }
            Command::Drag { at } => self.scene.drag_to(Vec2::from_array(*at)),
            Command::Release => self.scene.release(),
            Command::Fling {
                index,
                generation,
                velocity,
            } => {
                if let Some(id) = self.scene.body_with(*index, *generation) {
                    self.scene.fling(id, Vec2::from_array(*velocity));
                }
            }
            Command::Knobs {
                knobs,
                friction,
                restitution,
                drag,
            } => {
                // The panel's sliders are always finite; a value from
                // elsewhere that is not would reach the player's forces.
                if !knobs.is_finite() {
                    anyhow::bail!("slider values must be finite, got {knobs:?}");
                }
                self.session.knobs = *knobs;
                self.apply_knobs();
                if *friction {
                    self.scene.apply_friction(knobs.friction);
                }
                if *restitution {
                    self.scene.apply_restitution(knobs.restitution);
                }
                if *drag {
                    self.scene.apply_drag_scale(knobs);
                }
            }
            Command::Rate(hz) => self.session.timestep.set_hz(*hz)?,
            Command::Integrator(integrator) => self.scene.set_integrator(*integrator),
            Command::Reset => self.reset()?,
            Command::RainCount(n) => self.set_rain_count(*n)?,
        }
        Ok(())
    }

    /// Applies the sliders to every lane.
    pub fn apply_knobs(&mut self) {
        self.scene.apply_knobs(&self.session.knobs);
    }

    /// Adds a body at a world point (lane 0): a circle or a box of 0.6 m
    /// with the sliders' friction and restitution.
    pub fn spawn(&mut self, at: Vec2, round: bool) -> Option<BodyId> {
        self.scene.lanes[0].spawn(at, round, &self.session.knobs)
    }

    /// Starts recording from the scene's first state (the scene restarts).
    pub fn start_recording(&mut self) -> Result<()> {
        self.session.stop_replays();
        self.reset()?;
        self.session.start_recording();
        // The restart keeps the session's settings, which a replay played
        // from the scene's first state would not have: the recording
        // begins by setting each of them (the rain's size first, since it
        // rebuilds the scene).
        let mut settings = Vec::new();
        settings.extend(self.scene.rain_count().map(Command::RainCount));
        // The rate only if it is not the scene's own (as `load` sets it).
        let own = own_rate(self.scene.file.as_ref());
        let step = self.session.timestep.step();
        if FixedTimestep::from_hz(own).map(|t| t.step()) != Ok(step) {
            settings.push(Command::Rate(self.session.timestep.hz()));
        }
        settings.extend([
            Command::Integrator(self.scene.integrator()),
            Command::Knobs {
                knobs: self.session.knobs,
                friction: false,
                restitution: false,
                drag: false,
            },
        ]);
        for command in &settings {
            self.session.record_command(command);
        }
        Ok(())
    }

    /// Stops recording; the replay reproduces the state hash of now.
    pub fn stop_recording(&mut self) -> Option<Replay> {
        let hash = self.scene.state_hash();
        self.session.stop_recording(hash)
    }

    /// Plays `replay` from the scene's first state: its inputs and commands
    /// replace the live ones until its last tick, when the loop pauses.
    pub fn start_playback(&mut self, replay: Replay) -> Result<()> {
        self.session.stop_replays();
        self.reset()?;
        self.session.start_playback(replay);
        // A replay of no tick ends at once (after its commands).
        self.end_playback_if_due();
        Ok(())
    }

    /// Rebuilds the scene with another rain count.
    pub fn set_rain_count(&mut self, n: u32) -> Result<()> {
        match self.scene.file_with_rain(n) {
            Some(file) => self.rebuild(Some(file)),
            None => Ok(()),
        }
    }

    /// Restarts the scene from its source, keeping the session (rate,
    /// pause, sliders, recording or playback) and the integrator and
    /// interpolation switches.
    pub fn reset(&mut self) -> Result<()> {
        self.rebuild(None)
    }

    /// Replaces the scene state with a fresh one (from `file`, or from the
    /// scene's own source); the partial tick in the loop is dropped.
    fn rebuild(&mut self, file: Option<SceneFile>) -> Result<()> {
        // A fresh scene has no timeline: the loop runs again if it held
        // still for one.
        self.resume_from_timeline();
        self.scene = self.scene.rebuilt(file, &self.session.knobs)?;
        self.session.timestep.reset_accumulator();
        Ok(())
    }
}
