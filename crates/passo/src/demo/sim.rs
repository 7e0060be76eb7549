//! The demo's simulation: one or more worlds driven by the fixed-timestep
//! loop, the player's controls, the panel's knobs and the plotted history.
//! Nothing here touches a window, so tests drive it with exact frame times.

use super::replay::{Command, Playback, Recorder, Replay};
use anyhow::Result;
use glam::Vec2;
use passo_loop::{FixedTimestep, Frame};
use passo_physics::{
    Aabb, BodyDef, BodyId, BodyKind, ForceModels, Integrator, QuadraticDrag, Shape, Spring, World,
    WorldSettings,
};
use passo_scene::{Colour, Generator, Scene, SceneBody, SceneFile};
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;
use std::time::{Duration, Instant};

/// Samples kept for the plot: 10 s at 60 Hz.
const HISTORY: usize = 600;

/// One world of the demo, drawn at `offset`.
#[derive(Debug)]
pub struct Lane {
    /// Shown under the lane when there are several.
    pub label: String,
    /// The world.
    pub world: World,
    /// Names and colours, sorted by id.
    pub bodies: Vec<SceneBody>,
    /// Where the lane is drawn, metres.
    pub offset: Vec2,
    /// Each dynamic body's drag area as the scene gave it, for the drag-area
    /// slider (a multiplier).
    base_drag: Vec<(BodyId, f32)>,
}

/// The keys held or pressed this frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Input {
    /// Walk left (A or Left).
    pub left: bool,
    /// Walk right (D or Right).
    pub right: bool,
    /// Run instead of walking (Shift).
    pub run: bool,
    /// Glide: open a large drag area (hold G).
    pub glide: bool,
    /// Jump (Space) was pressed since the last tick.
    pub jump: bool,
}

/// Values of the panel's sliders, applied to every lane when changed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Knobs {
    /// Vertical gravity, m/s² (0 turns gravity off).
    pub gravity: f32,
    /// Friction coefficient of every dynamic body.
    pub friction: f32,
    /// Air density, kg/m³ (0 turns quadratic drag off).
    pub density: f32,
    /// Multiplier of every body's drag area.
    pub drag_scale: f32,
    /// Restitution of every dynamic body.
    pub restitution: f32,
    /// Minimum speed, m/s.
    pub min_speed: f32,
    /// Maximum speed, m/s.
    pub max_speed: f32,
    /// Wind on.
    pub wind: bool,
    /// Wind speed along +x, m/s.
    pub wind_speed: f32,
    /// Continuous collision on.
    pub continuous: bool,
    /// Sleeping on (resting islands are not solved until woken).
    #[serde(default = "yes")]
    pub sleeping: bool,
}

fn yes() -> bool {
    true
}

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

/// Plotted values over the last ten seconds.
#[derive(Clone, Debug, Default)]
pub struct History {
    /// What is plotted.
    pub title: String,
    /// Simulated time of each sample, seconds.
    pub time: VecDeque<f32>,
    /// Named series, one value per sample.
    pub series: Vec<(String, VecDeque<f32>)>,
    /// Named horizontal reference lines (closed-form values).
    pub lines: Vec<(String, f32)>,
}

impl History {
    fn push(&mut self, t: f32, values: &[f32]) {
        if self.time.len() == HISTORY {
            self.time.pop_front();
            for (_, s) in &mut self.series {
                s.pop_front();
            }
        }
        self.time.push_back(t);
        for ((_, s), v) in self.series.iter_mut().zip(values) {
            s.push_back(*v);
        }
    }
}

/// What the plot shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum PlotKind {
    /// Total energy of each lane.
    Energy,
    /// Speed of each dynamic body, with its terminal speed as a line.
    DragRace,
}

/// A running demo scene.
#[derive(Debug)]
pub struct Sim {
    /// Scene name.
    pub name: String,
    /// One-line description.
    pub description: String,
    /// The worlds (several only for side-by-side comparisons).
    pub lanes: Vec<Lane>,
    /// The fixed-timestep loop.
    pub timestep: FixedTimestep,
    /// The region to show at first.
    pub bounds: Aabb,
    /// The body the keyboard moves, in lane 0.
    pub player: Option<BodyId>,
    /// The panel's sliders.
    pub knobs: Knobs,
    /// Whether each lane has its own integrator (the integrator picker is off).
    pub fixed_integrators: bool,
    /// The last frame.
    pub stats: Stats,
    /// The plot.
    pub history: History,
    /// The scene file, to rebuild (reset, body count) from.
    pub file: Option<SceneFile>,
    plot: PlotKind,
    /// Game input for the next tick (jump is consumed by it).
    input: Input,
    /// The name the scene was loaded by (for replays).
    pub entry_name: String,
    /// Ticks run since the scene was loaded.
    ticks_run: u64,
    recorder: Option<Recorder>,
    playback: Option<Playback>,
}

/// The colour a spawned body gets, by count.
const SPAWN_COLOURS: [[u8; 4]; 4] = [
    [0xf0, 0xc8, 0x50, 0xff],
    [0xf0, 0x78, 0x78, 0xff],
    [0x78, 0xd0, 0xf0, 0xff],
    [0xb0, 0xf0, 0x78, 0xff],
];

impl Sim {
    /// A demo of a scene file.
    pub fn from_scene(scene: &Scene) -> Result<Self> {
        let built = scene.build()?;
        let file = scene.file.clone();
        let f = &file.forces;
        let first = built.world.bodies().find(|b| b.kind == BodyKind::Dynamic);
        let knobs = Knobs {
            gravity: f.gravity.map_or(0.0, |g| g.y),
            friction: first.map_or(0.6, |b| b.friction),
            density: f.quadratic_drag.map_or(0.0, |d| d.density),
            drag_scale: 1.0,
            restitution: first.map_or(0.0, |b| b.restitution),
            min_speed: file.min_speed,
            max_speed: file.max_speed.min(1000.0),
            wind: f.wind != Vec2::ZERO,
            wind_speed: if f.wind.x != 0.0 { f.wind.x } else { 8.0 },
            continuous: file.collisions.is_none_or(|c| c.continuous),
            sleeping: file.collisions.is_none_or(|c| c.sleeping),
        };
        let player = built.body_named("player");
        let plot = if file.name == "Drag race" {
            PlotKind::DragRace
        } else {
            PlotKind::Energy
        };
        let lane = Lane::new(String::new(), built.world, built.bodies, Vec2::ZERO);
        let mut sim = Self {
            name: file.name.clone(),
            description: file.description.clone(),
            lanes: vec![lane],
            timestep: FixedTimestep::from_hz(file.rate_hz)?,
            bounds: built.camera,
            player,
            knobs,
            fixed_integrators: false,
            stats: Stats::default(),
            history: History::default(),
            entry_name: file.name.to_lowercase().replace(' ', "_"),
            file: Some(file),
            plot,
            input: Input::default(),
            ticks_run: 0,
            recorder: None,
            playback: None,
        };
        sim.set_interpolation(true);
        sim.reset_history();
        Ok(sim)
    }

    /// The same spring under each integrator side by side: a 1 kg body on
    /// a spring of period 1 s, started 1.5 m from rest.
    pub fn integrators() -> Self {
        let colours = [
            [0xe4, 0x6c, 0x3a, 0xff],
            [0x5c, 0xb8, 0x5c, 0xff],
            [0x3a, 0x8e, 0xe4, 0xff],
            [0xa3, 0x5c, 0xd6, 0xff],
        ];
        let lanes = Integrator::ALL
            .iter()
            .zip(colours)
            .enumerate()
            .map(|(i, (&integrator, colour))| {
                let mut world = World::new(WorldSettings {
                    forces: ForceModels {
                        gravity: None,
                        spring: Some(Spring {
                            anchor: Vec2::ZERO,
                            stiffness: (2.0 * std::f32::consts::PI).powi(2),
                        }),
                        ..ForceModels::none()
                    },
                    integrator,
                    min_speed: 0.0,
                    interpolation: true,
                    // The bob swings through its anchor: nothing collides.
                    contacts: None,
                    ..Default::default()
                })
                .expect("valid settings");
                let anchor = world
                    .add_body(BodyDef::fixed(Vec2::ZERO, Shape::circle(0.08)))
                    .expect("valid anchor");
                let bob = world
                    .add_body(BodyDef {
                        position: Vec2::new(0.0, 1.5),
                        shape: Some(Shape::circle(0.2)),
                        ..Default::default()
                    })
                    .expect("valid body");
                let bodies = vec![
                    SceneBody {
                        id: anchor,
                        name: Some("anchor".into()),
                        colour: Colour([0x9a, 0x9e, 0xa8, 0xff]),
                    },
                    SceneBody {
                        id: bob,
                        name: Some(integrator.name().into()),
                        colour: Colour(colour),
                    },
                ];
                Lane::new(
                    integrator.name().to_owned(),
                    world,
                    bodies,
                    Vec2::new(i as f32 * 3.0 - 4.5, 0.0),
                )
            })
            .collect();
        let mut sim = Self {
            name: "Integrators".into(),
            description:
                "One spring (period 1 s) under each integrator: explicit Euler gains energy, \
                          semi-implicit Euler keeps it bounded, Verlet and RK4 follow the cosine."
                    .into(),
            lanes,
            timestep: FixedTimestep::from_hz(60.0).expect("60 Hz is valid"),
            bounds: Aabb {
                min: Vec2::new(-6.5, -3.0),
                max: Vec2::new(6.5, 3.0),
            },
            player: None,
            knobs: Knobs {
                gravity: 0.0,
                friction: 0.6,
                density: 0.0,
                drag_scale: 1.0,
                restitution: 0.0,
                min_speed: 0.0,
                max_speed: 1000.0,
                wind: false,
                wind_speed: 8.0,
                continuous: true,
                sleeping: true,
            },
            fixed_integrators: true,
            stats: Stats::default(),
            history: History::default(),
            file: None,
            plot: PlotKind::Energy,
            input: Input::default(),
            entry_name: "integrators".into(),
            ticks_run: 0,
            recorder: None,
            playback: None,
        };
        sim.reset_history();
        sim
    }

    fn reset_history(&mut self) {
        self.history = match self.plot {
            PlotKind::Energy => History {
                title: "total energy (J)".into(),
                series: self
                    .lanes
                    .iter()
                    .map(|l| {
                        (
                            if l.label.is_empty() {
                                "energy".into()
                            } else {
                                l.label.clone()
                            },
                            VecDeque::new(),
                        )
                    })
                    .collect(),
                ..Default::default()
            },
            PlotKind::DragRace => {
                let lane = &self.lanes[0];
                History {
                    title: "speed (m/s); lines: terminal speed".into(),
                    series: lane
                        .bodies
                        .iter()
                        .filter(|b| {
                            lane.world
                                .body(b.id)
                                .is_some_and(|b| b.kind == BodyKind::Dynamic)
                        })
                        .map(|b| (b.name.clone().unwrap_or_default(), VecDeque::new()))
                        .collect(),
                    ..Default::default()
                }
            }
        };
        self.update_reference_lines();
    }

    /// Terminal speeds `sqrt(2 m g / (rho Cd A))` of the drag race's bodies.
    fn update_reference_lines(&mut self) {
        if self.plot != PlotKind::DragRace {
            return;
        }
        let lane = &self.lanes[0];
        let (g, rho) = (self.knobs.gravity.abs(), self.knobs.density);
        self.history.lines = lane
            .world
            .bodies()
            .filter(|b| b.kind == BodyKind::Dynamic)
            .map(|b| {
                let vt = (2.0 * b.mass * g / (rho * b.drag_area)).sqrt();
                (format!("{:.1} m/s", vt), vt)
            })
            .filter(|(_, v)| v.is_finite())
            .collect();
    }

    /// The game input for the coming ticks.
    pub fn set_input(&mut self, input: Input) {
        let jump = self.input.jump || input.jump;
        self.input = Input { jump, ..input };
    }

    /// Advances by one rendered frame of `frame_time`: the loop decides how
    /// many fixed ticks run.
    pub fn frame(&mut self, frame_time: Duration) -> Frame {
        let frame = self.timestep.advance(frame_time);
        let started = Instant::now();
        for _ in frame.tick_numbers() {
            // A finished playback holds its final state.
            if self.playback.as_ref().is_some_and(|p| p.result.is_some()) {
                break;
            }
            self.tick();
        }
        self.stats = Stats {
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
        self.before_tick();
        let dt = self.timestep.dt();
        self.control_player();
        for lane in &mut self.lanes {
            lane.world.step(dt);
        }
        let t = (self.timestep.tick() as f64 * self.timestep.step().as_secs_f64()) as f32;
        let values: Vec<f32> = match self.plot {
            PlotKind::Energy => self
                .lanes
                .iter()
                .map(|l| l.world.total_energy() as f32)
                .collect(),
            PlotKind::DragRace => {
                let world = &self.lanes[0].world;
                world
                    .bodies()
                    .filter(|b| b.kind == BodyKind::Dynamic)
                    .map(|b| b.velocity.length())
                    .collect()
            }
        };
        self.history.push(t, &values);
        self.ticks_run += 1;
        self.after_tick();
    }

    /// In playback, applies the commands due and takes the recorded input;
    /// when recording, notes the input used.
    fn before_tick(&mut self) {
        if let Some(mut p) = self.playback.take() {
            let rel = self.ticks_run - p.start;
            while let Some((tick, command)) = p.replay.commands.get(p.next_command).cloned() {
                if tick > rel {
                    break;
                }
                p.next_command += 1;
                if let Err(e) = self.apply(&command) {
                    log::warn!("replayed command failed: {e:#}");
                }
            }
            while let Some(&(tick, input)) = p.replay.inputs.get(p.next_input) {
                if tick > rel {
                    break;
                }
                p.input = input;
                p.next_input += 1;
            }
            self.input = p.input;
            // A recorded jump lasts one tick.
            p.input.jump = false;
            self.playback = Some(p);
        }
        let input = self.input;
        if let Some(r) = &mut self.recorder {
            let rel = self.ticks_run - r.start;
            if r.inputs.last().is_none_or(|(_, last)| *last != input) {
                r.inputs.push((rel, input));
            }
        }
    }

    /// Ends a playback after its last tick, keeping the final hash.
    fn after_tick(&mut self) {
        let done = self
            .playback
            .as_ref()
            .is_some_and(|p| p.result.is_none() && self.ticks_run - p.start >= p.replay.ticks);
        if done {
            let hash = self.state_hash();
            if let Some(p) = &mut self.playback {
                p.result = Some(hash);
            }
            self.timestep.pause();
        }
    }

    /// A 64-bit hash of every lane's state (see `World::state_hash`).
    pub fn state_hash(&self) -> u64 {
        self.lanes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, l| {
            (h ^ l.world.state_hash()).wrapping_mul(0x0000_0100_0000_01b3)
        })
    }

    /// Applies a command from the player or the panel, recording it when
    /// recording. In playback, live commands are ignored.
    pub fn command(&mut self, command: Command) -> Result<()> {
        if self.playback.is_some() {
            return Ok(());
        }
        if let Some(r) = &mut self.recorder {
            r.commands.push((self.ticks_run - r.start, command.clone()));
        }
        self.apply(&command)
    }

    fn apply(&mut self, command: &Command) -> Result<()> {
        match command {
            Command::Spawn { at, round } => {
                self.spawn(Vec2::from_array(*at), *round);
            }
            Command::Fling {
                index,
                generation,
                velocity,
            } => {
                let id = self.lanes[0]
                    .world
                    .bodies()
                    .map(|b| b.id)
                    .find(|id| id.index() == *index && id.generation() == *generation);
                if let Some(id) = id {
                    self.fling(id, Vec2::from_array(*velocity));
                }
            }
            Command::Knobs {
                knobs,
                friction,
                restitution,
                drag,
            } => {
                self.knobs = *knobs;
                self.apply_knobs();
                if *friction {
                    self.apply_friction();
                }
                if *restitution {
                    self.apply_restitution();
                }
                if *drag {
                    self.apply_drag_scale();
                }
            }
            Command::Rate(hz) => self.timestep.set_hz(*hz)?,
            Command::Integrator(integrator) => self.set_integrator(*integrator),
            Command::Reset => self.reset()?,
            Command::RainCount(n) => self.set_rain_count(*n)?,
        }
        Ok(())
    }

    /// Starts recording from the scene's first state (the scene restarts).
    pub fn start_recording(&mut self) -> Result<()> {
        self.playback = None;
        self.recorder = None;
        self.reset()?;
        self.recorder = Some(Recorder {
            start: self.ticks_run,
            inputs: Vec::new(),
            commands: Vec::new(),
        });
        Ok(())
    }

    /// Whether a recording is under way.
    pub fn is_recording(&self) -> bool {
        self.recorder.is_some()
    }

    /// Stops recording; the replay reproduces the state hash of now.
    pub fn stop_recording(&mut self) -> Option<Replay> {
        let r = self.recorder.take()?;
        Some(Replay {
            scene: self.entry_name.clone(),
            ticks: self.ticks_run - r.start,
            inputs: r.inputs,
            commands: r.commands,
            final_hash: self.state_hash(),
        })
    }

    /// Plays `replay` from the scene's first state: its inputs and commands
    /// replace the live ones until its last tick, when the loop pauses.
    pub fn start_playback(&mut self, replay: Replay) -> Result<()> {
        self.recorder = None;
        self.playback = None;
        self.reset()?;
        self.playback = Some(Playback {
            replay,
            start: self.ticks_run,
            next_input: 0,
            next_command: 0,
            input: Input::default(),
            result: None,
        });
        Ok(())
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

    /// Walk and run by pushing against friction, jump only when standing,
    /// glide with a large drag area.
    fn control_player(&mut self) {
        let Some(player) = self.player else { return };
        let jump = std::mem::replace(&mut self.input.jump, false);
        let world = &mut self.lanes[0].world;
        let Some(body) = world.body(player) else {
            return;
        };
        let m = body.mass;
        let standing = world.is_standing(player, 0.8);
        let dir = f32::from(u8::from(self.input.right)) - f32::from(u8::from(self.input.left));
        if dir != 0.0 {
            let target = dir * if self.input.run { 9.0 } else { 4.5 };
            // Enough to overcome kinetic friction and accelerate at 8 m/s².
            let g = self.knobs.gravity.abs();
            let max = m * (body.friction * g + 8.0);
            let push = (m * (target - body.velocity.x) / 0.15).clamp(-max, max);
            let _ = world.apply_force(player, Vec2::new(push, 0.0));
        }
        if jump && standing {
            let _ = world.apply_impulse(player, Vec2::new(0.0, m * 6.5));
        }
        let lane = &self.lanes[0];
        if let Some(&(_, base)) = lane.base_drag.iter().find(|(id, _)| *id == player) {
            let open = self.input.glide && !standing;
            let area = base * self.knobs.drag_scale * if open { 40.0 } else { 1.0 };
            let _ = self.lanes[0].world.set_drag_area(player, area);
        }
    }

    /// Applies the sliders to every lane.
    pub fn apply_knobs(&mut self) {
        let k = self.knobs;
        for lane in &mut self.lanes {
            let mut s = *lane.world.settings();
            s.forces.gravity = (k.gravity != 0.0).then_some(Vec2::new(0.0, k.gravity));
            s.forces.quadratic_drag =
                (k.density > 0.0).then_some(QuadraticDrag { density: k.density });
            s.forces.air_velocity = if k.wind {
                Vec2::new(k.wind_speed, 0.0)
            } else {
                Vec2::ZERO
            };
            s.min_speed = k.min_speed;
            s.max_speed = k.max_speed;
            if let Some(c) = &mut s.contacts {
                c.continuous = k.continuous;
                c.sleeping = k.sleeping;
            }
            if let Err(e) = lane.world.set_settings(s) {
                log::warn!("slider value refused: {e}");
            }
        }
        self.update_reference_lines();
    }

    /// Sets the friction of every dynamic body.
    pub fn apply_friction(&mut self) {
        let mu = self.knobs.friction;
        self.for_each_dynamic(|w, id| w.set_friction(id, mu));
    }

    /// Sets the restitution of every dynamic body.
    pub fn apply_restitution(&mut self) {
        let e = self.knobs.restitution;
        self.for_each_dynamic(|w, id| w.set_restitution(id, e));
    }

    /// Scales every dynamic body's scene drag area.
    pub fn apply_drag_scale(&mut self) {
        let scale = self.knobs.drag_scale;
        for lane in &mut self.lanes {
            for &(id, base) in &lane.base_drag {
                let _ = lane.world.set_drag_area(id, base * scale);
            }
        }
        self.update_reference_lines();
    }

    fn for_each_dynamic(
        &mut self,
        mut f: impl FnMut(&mut World, BodyId) -> Result<(), passo_physics::PhysicsError>,
    ) {
        for lane in &mut self.lanes {
            let ids: Vec<BodyId> = lane
                .world
                .bodies()
                .filter(|b| b.kind == BodyKind::Dynamic)
                .map(|b| b.id)
                .collect();
            for id in ids {
                if let Err(e) = f(&mut lane.world, id) {
                    log::warn!("slider value refused: {e}");
                }
            }
        }
    }

    /// The integrator of every lane (unless each lane has its own).
    pub fn set_integrator(&mut self, integrator: Integrator) {
        if self.fixed_integrators {
            return;
        }
        for lane in &mut self.lanes {
            let s = WorldSettings {
                integrator,
                ..*lane.world.settings()
            };
            let _ = lane.world.set_settings(s);
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
            let s = WorldSettings {
                interpolation: on,
                ..*lane.world.settings()
            };
            let _ = lane.world.set_settings(s);
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

    /// Sets a body's velocity (a fling).
    pub fn fling(&mut self, id: BodyId, velocity: Vec2) {
        if let Err(e) = self.lanes[0].world.set_velocity(id, velocity) {
            log::warn!("fling refused: {e}");
        }
    }

    /// Adds a body at a world point: a circle or a box of 0.6 m.
    pub fn spawn(&mut self, at: Vec2, round: bool) -> Option<BodyId> {
        let lane = &mut self.lanes[0];
        let shape = if round {
            Shape::circle(0.3)
        } else {
            Shape::rect(0.6, 0.6)
        };
        let def = BodyDef {
            position: at - lane.offset,
            shape: Some(shape),
            mass: shape.area() * 2.0,
            friction: self.knobs.friction,
            restitution: self.knobs.restitution,
            ..Default::default()
        };
        let id = lane.world.add_body(def).ok()?;
        let colour = Colour(SPAWN_COLOURS[lane.bodies.len() % SPAWN_COLOURS.len()]);
        let at = lane.bodies.partition_point(|b| b.id < id);
        lane.bodies.insert(
            at,
            SceneBody {
                id,
                name: None,
                colour,
            },
        );
        lane.base_drag.push((id, def.drag_area));
        Some(id)
    }

    /// Number of bodies of the scene's rain generator, if it has one.
    pub fn rain_count(&self) -> Option<u32> {
        self.file.as_ref()?.generators.iter().find_map(|g| match g {
            Generator::Rain { count, .. } => Some(*count),
            _ => None,
        })
    }

    /// Rebuilds the scene with another rain count.
    pub fn set_rain_count(&mut self, n: u32) -> Result<()> {
        let Some(mut file) = self.file.clone() else {
            return Ok(());
        };
        for g in &mut file.generators {
            if let Generator::Rain { count, .. } = g {
                *count = n.max(1);
            }
        }
        self.rebuild(file)
    }

    /// Restarts the scene from its file, keeping rate, pause and sliders.
    pub fn reset(&mut self) -> Result<()> {
        match self.file.clone() {
            Some(file) => self.rebuild(file),
            None => {
                let mut fresh = Self::integrators();
                fresh.knobs = self.knobs;
                fresh.timestep = self.timestep.clone();
                fresh.ticks_run = self.ticks_run;
                fresh.recorder = self.recorder.take();
                fresh.playback = self.playback.take();
                *self = fresh;
                Ok(())
            }
        }
    }

    fn rebuild(&mut self, file: SceneFile) -> Result<()> {
        let scene = Scene {
            file,
            source: self.name.clone(),
        };
        scene.file.validate(&scene.source)?;
        let mut fresh = Self::from_scene(&scene)?;
        fresh.timestep = self.timestep.clone();
        fresh.timestep.reset_accumulator();
        let interpolation = self.interpolation();
        let integrator = self.integrator();
        fresh.knobs = self.knobs;
        fresh.apply_knobs();
        fresh.set_integrator(integrator);
        fresh.set_interpolation(interpolation);
        fresh.entry_name = std::mem::take(&mut self.entry_name);
        fresh.ticks_run = self.ticks_run;
        fresh.recorder = self.recorder.take();
        fresh.playback = self.playback.take();
        *self = fresh;
        Ok(())
    }
}

impl Lane {
    fn new(label: String, world: World, bodies: Vec<SceneBody>, offset: Vec2) -> Self {
        let base_drag = world
            .bodies()
            .filter(|b| b.kind == BodyKind::Dynamic)
            .map(|b| (b.id, b.drag_area))
            .collect();
        Self {
            label,
            world,
            bodies,
            offset,
            base_drag,
        }
    }
}
