//! The session: what a demo run keeps while its scene is reset or rebuilt —
//! the fixed-timestep loop, the panel's sliders, the name the scene was
//! loaded by, the tick count, and a replay being recorded or played.

use super::controls::{Input, Knobs};
use super::replay::{Command, Replay};
use passo_loop::FixedTimestep;
use std::time::Duration;

/// What the last frame did, for the panel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stats {
    /// Ticks run in the last frame.
    pub ticks: u32,
    /// Time dropped by the loop's guards in the last frame.
    pub dropped: Duration,
    /// Wall time of the last frame's steps, milliseconds.
    pub step_ms: f64,
    /// Interpolation factor of the last frame.
    pub alpha: f32,
}

/// Everything a reset keeps.
#[derive(Debug)]
pub struct Session {
    /// The fixed-timestep loop.
    pub timestep: FixedTimestep,
    /// The panel's sliders.
    pub knobs: Knobs,
    /// The name the scene was loaded by (for replays).
    pub entry_name: String,
    /// The last frame.
    pub stats: Stats,
    /// Ticks run since the scene was loaded.
    ticks_run: u64,
    recorder: Option<Recorder>,
    playback: Option<Playback>,
}

/// A recording in progress.
#[derive(Clone, Debug)]
struct Recorder {
    /// The tick count when it started.
    start: u64,
    inputs: Vec<(u64, Input)>,
    commands: Vec<(u64, Command)>,
}

/// A replay being played.
#[derive(Clone, Debug)]
struct Playback {
    replay: Replay,
    /// The tick count when it started.
    start: u64,
    next_input: usize,
    next_command: usize,
    /// The replayed input in force.
    input: Input,
    /// The hash after the last tick, once played.
    result: Option<u64>,
}

impl Session {
    /// A session of a scene loaded as `entry_name`, neither recording nor
    /// playing.
    pub(crate) fn new(timestep: FixedTimestep, knobs: Knobs, entry_name: String) -> Self {
        Self {
            timestep,
            knobs,
            entry_name,
            stats: Stats::default(),
            ticks_run: 0,
            recorder: None,
            playback: None,
        }
    }

    /// Counts a tick run.
    pub(crate) fn count_tick(&mut self) {
        self.ticks_run += 1;
    }

    /// Ends any recording or playback.
    pub(crate) fn stop_replays(&mut self) {
        self.recorder = None;
        self.playback = None;
    }

    /// Starts recording from the current tick.
    pub(crate) fn start_recording(&mut self) {
        self.playback = None;
        self.recorder = Some(Recorder {
            start: self.ticks_run,
            inputs: Vec::new(),
            commands: Vec::new(),
        });
    }

    /// Whether a recording is under way.
    pub fn is_recording(&self) -> bool {
        self.recorder.is_some()
    }

    /// Stops recording; the replay ends in the state of `final_hash`.
    pub(crate) fn stop_recording(&mut self, final_hash: u64) -> Option<Replay> {
        let r = self.recorder.take()?;
        Some(Replay {
            scene: self.entry_name.clone(),
            ticks: self.ticks_run - r.start,
            inputs: r.inputs,
            commands: r.commands,
            final_hash,
        })
    }

    /// Notes the input a tick is about to use, if it changed.
    pub(crate) fn record_input(&mut self, input: Input) {
        if let Some(r) = &mut self.recorder {
            let rel = self.ticks_run - r.start;
            if r.inputs.last().is_none_or(|(_, last)| *last != input) {
                r.inputs.push((rel, input));
            }
        }
    }

    /// Notes a command applied before the coming tick.
    pub(crate) fn record_command(&mut self, command: &Command) {
        if let Some(r) = &mut self.recorder {
            r.commands.push((self.ticks_run - r.start, command.clone()));
        }
    }

    /// Starts playing `replay` from the current tick.
    pub(crate) fn start_playback(&mut self, replay: Replay) {
        self.recorder = None;
        self.playback = Some(Playback {
            replay,
            start: self.ticks_run,
            next_input: 0,
            next_command: 0,
            input: Input::default(),
            result: None,
        });
    }

    /// Whether a replay is being played (or was played to its end).
    pub fn is_playing(&self) -> bool {
        self.playback.is_some()
    }

    /// Whether a playback reached its last tick (the loop then holds the
    /// final state).
    pub fn playback_finished(&self) -> bool {
        self.playback.as_ref().is_some_and(|p| p.result.is_some())
    }

    /// During or after a playback: `(ticks played, ticks recorded, final hash
    /// once finished, recorded hash)`.
    pub fn playback_status(&self) -> Option<(u64, u64, Option<u64>, u64)> {
        self.playback.as_ref().map(|p| {
            (
                self.ticks_run - p.start,
                p.replay.ticks,
                p.result,
                p.replay.final_hash,
            )
        })
    }

    /// In playback, the next recorded command due before the coming tick.
    pub(crate) fn next_replayed_command(&mut self) -> Option<Command> {
        let p = self.playback.as_mut()?;
        let rel = self.ticks_run - p.start;
        let (tick, command) = p.replay.commands.get(p.next_command)?;
        if *tick > rel {
            return None;
        }
        p.next_command += 1;
        Some(command.clone())
    }

    /// In playback, the recorded input of the coming tick. A recorded jump
    /// lasts one tick.
    pub(crate) fn replayed_input(&mut self) -> Option<Input> {
        let p = self.playback.as_mut()?;
        let rel = self.ticks_run - p.start;
        while let Some(&(tick, input)) = p.replay.inputs.get(p.next_input) {
            if tick > rel {
                break;
            }
            p.input = input;
            p.next_input += 1;
        }
        let input = p.input;
        p.input.jump = false;
        Some(input)
    }

    /// Whether a playback has just played its last tick.
    pub(crate) fn playback_due_to_end(&self) -> bool {
        self.playback
            .as_ref()
            .is_some_and(|p| p.result.is_none() && self.ticks_run - p.start >= p.replay.ticks)
    }

    /// Ends a playback in the state of `hash` and pauses the loop there.
    pub(crate) fn end_playback(&mut self, hash: u64) {
        if let Some(p) = &mut self.playback {
            p.result = Some(hash);
        }
        self.timestep.pause();
    }
}
