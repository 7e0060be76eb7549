//! The game both netplay examples play: the playground with two players,
//! a state that is a world snapshot and a tick, and the GGRS glue that
//! saves, loads and advances it. GGRS asks for a save every frame, and on
//! a rollback for a load and several advances within the frame, so the
//! game keeps no state outside what it saves, and every advance depends
//! only on the state and the inputs.

use ggrs::{Config, GgrsRequest, PredictRepeatLast};
use passo_physics::glam::Vec2;
use passo_physics::{BodyId, StateHasher, World, WorldSnapshot};
use passo_scene::{BuiltScene, Platform, Scene};
use std::fmt::Debug;
use std::hash::Hash;
use std::marker::PhantomData;

/// One player's input for a tick: bit 0 left, bit 1 right, bit 2 jump.
pub type Input = u8;

/// The bits an [`Input`] may set: left, right and jump.
pub const KEYS: Input = 0b111;

/// Checks the inputs GGRS hands the game for a tick: a peer that sends
/// bits no key makes (a bug, or garbage on the wire that happened to
/// decode) is named in an error rather than played.
pub fn check_inputs(inputs: &[Input]) -> Result<(), String> {
    match inputs.iter().position(|&input| input & !KEYS != 0) {
        None => Ok(()),
        Some(player) => Err(format!(
            "player {player} sent the input {:#010b}: only the bits {KEYS:#05b} \
             (left, right, jump) are keys",
            inputs[player]
        )),
    }
}

/// The game's GGRS configuration over a transport whose peers have
/// addresses `A`: a `SocketAddr` over UDP (`passo_examples::netplay::
/// Netplay`), a WebRTC peer id in a browser. An input is a [`Input`]; a
/// save is the world and the game's tick.
pub struct Netplay<A>(PhantomData<A>);

impl<A: Clone + PartialEq + Eq + Hash + Debug + Send + Sync + 'static> Config for Netplay<A> {
    type Input = Input;
    type InputPredictor = PredictRepeatLast;
    /// What a save holds: the world and the game's tick.
    type State = (WorldSnapshot, u64);
    type Address = A;
}

/// A GGRS configuration this game plays under: its inputs and its saved
/// state; the address is the transport's (a UDP address natively, a WebRTC
/// peer in a browser).
pub trait Rollback: Config<Input = Input, State = (WorldSnapshot, u64)> {}

impl<C: Config<Input = Input, State = (WorldSnapshot, u64)>> Rollback for C {}

/// The game: the playground scene (`assets/scenes/playground.ron`: ground,
/// ice, walls, platforms, a moving platform and a one-way lift on paths, a
/// crate and a ball) with a second player beside the first, and the tick
/// it is at.
pub struct Game {
    /// The physics.
    pub world: World,
    /// The two players' bodies.
    pub players: [BodyId; 2],
    /// The kinematic bodies on paths, driven by the tick.
    pub platforms: Vec<Platform>,
    /// Ticks simulated.
    pub tick: u64,
}

/// The fixed step, seconds.
pub const DT: f32 = 1.0 / 60.0;

impl Game {
    /// The game at tick 0.
    pub fn new() -> Self {
        let scene = Scene::parse(
            include_str!("../../../assets/scenes/playground.ron"),
            "playground.ron",
        )
        .expect("the shipped playground is valid");
        let built = scene.build().expect("the shipped playground builds");
        let first = built
            .body_named("player")
            .expect("the playground has a player");
        let mut world = built.world;
        let mut second = world.body(first).expect("the player exists").to_def();
        second.position = Vec2::new(0.0, 0.8);
        let second = world.add_body(second).expect("valid second player");
        Self {
            world,
            players: [first, second],
            platforms: built.platforms,
            tick: 0,
        }
    }

    /// One tick with both players' inputs.
    pub fn advance(&mut self, inputs: [Input; 2]) {
        for (&player, input) in self.players.iter().zip(inputs) {
            let left = f32::from(input & 1);
            let right = f32::from((input >> 1) & 1);
            self.world
                .apply_force(player, Vec2::new((right - left) * 1500.0, 0.0));
            if input & 4 != 0 && self.world.is_standing(player, 0.8) {
                self.world.apply_impulse(player, Vec2::new(0.0, 70.0 * 6.0));
            }
        }
        // The platforms' clock is the tick: saved with it, so a rollback
        // puts them back too.
        let t_end = (self.tick + 1) as f64 * f64::from(DT);
        BuiltScene::drive_platforms(&self.platforms, &mut self.world, t_end, DT);
        self.world.step(DT);
        self.tick += 1;
    }

    /// A checksum of what the players see, without allocating: every
    /// body's position and velocity bits ([`World::state_hash`]) and the
    /// tick. State that does not show (warm-start impulses, sleep timers,
    /// a force model's own counters) is not in it; it shows as soon as it
    /// moves a body, which is when GGRS's comparison catches it.
    pub fn checksum(&self) -> u128 {
        let mut h = StateHasher::new();
        h.write_u64(self.world.state_hash());
        h.write_u64(self.tick);
        u128::from(h.finish())
    }

    /// Carries out GGRS's requests in order.
    pub fn handle<C: Rollback>(&mut self, requests: Vec<GgrsRequest<C>>) -> Result<(), String> {
        requests.into_iter().try_for_each(|r| self.handle_one(r))
    }

    /// [`handle`](Self::handle), keeping a record: each tick it advances
    /// to, up to tick `keep`, has its checksum written at `checksums[t -
    /// 1]` (a tick simulated again after a rollback overwrites it).
    /// Returns how many rollbacks (loads) the requests held.
    pub fn handle_recording<C: Rollback>(
        &mut self,
        requests: Vec<GgrsRequest<C>>,
        checksums: &mut Vec<u128>,
        keep: u64,
    ) -> Result<usize, String> {
        let mut rollbacks = 0;
        for request in requests {
            let advance = matches!(request, GgrsRequest::AdvanceFrame { .. });
            rollbacks += usize::from(matches!(request, GgrsRequest::LoadGameState { .. }));
            self.handle_one(request)?;
            if advance && self.tick <= keep {
                let t = self.tick as usize;
                checksums.resize(checksums.len().max(t), 0);
                checksums[t - 1] = self.checksum();
            }
        }
        Ok(rollbacks)
    }

    /// Carries out one GGRS request: save, load or advance. An advance
    /// whose inputs set bits no key makes is refused (see
    /// [`check_inputs`]): the session should end with that error.
    pub fn handle_one<C: Rollback>(&mut self, request: GgrsRequest<C>) -> Result<(), String> {
        match request {
            GgrsRequest::SaveGameState { cell, frame } => {
                let state = (self.world.snapshot(), self.tick);
                cell.save(frame, Some(state), Some(self.checksum()));
            }
            GgrsRequest::LoadGameState { cell, .. } => {
                let (snapshot, tick) = cell.load().ok_or("GGRS loaded an empty cell")?;
                self.world
                    .restore_from(&snapshot)
                    .map_err(|e| e.to_string())?;
                self.tick = tick;
            }
            GgrsRequest::AdvanceFrame { inputs } => {
                let inputs: Vec<Input> = inputs.iter().map(|&(input, _)| input).collect();
                check_inputs(&inputs)?;
                let [a, b] = inputs[..] else {
                    return Err(format!("GGRS gave {} inputs for 2 players", inputs.len()));
                };
                self.advance([a, b]);
            }
        }
        Ok(())
    }
}

impl Default for Game {
    fn default() -> Self {
        Self::new()
    }
}

/// Player `player`'s scripted input at `frame`: walking, turning, jumping.
pub fn scripted_input(player: usize, frame: u64) -> Input {
    let phase = (frame / 40 + player as u64 * 3) % 6;
    let walk = match phase {
        0 | 1 => 2, // right
        3 | 4 => 1, // left
        _ => 0,
    };
    let jump = if (frame + player as u64 * 17).is_multiple_of(55) {
        4
    } else {
        0
    };
    walk | jump
}

/// The same inputs run straight, with no rollback: the reference a sync
/// test and networked peers must reach.
pub fn straight_run(frames: u64) -> u128 {
    straight_checksums(frames)
        .last()
        .copied()
        .unwrap_or_else(|| Game::new().checksum())
}

/// The checksum after each tick of a straight run (`[t]` after `t + 1`
/// ticks).
pub fn straight_checksums(frames: u64) -> Vec<u128> {
    let mut game = Game::new();
    (0..frames)
        .map(|frame| {
            game.advance([scripted_input(0, frame), scripted_input(1, frame)]);
            game.checksum()
        })
        .collect()
}
