//! The game of the `platformer` example, apart from its window: a level
//! made in the Tiled editor, a player moved by the character mover (walk,
//! run, jump, slide on ice, glide, wind; crushed by a moving body, it
//! starts again at the spawn point), coins
//! and a goal as sensors, and the game-feel helpers every platformer
//! writes by hand (they belong in a game, not in the physics): coyote
//! time, jump buffering and variable jump height.

use passo_physics::glam::Vec2;
use passo_physics::{Aabb, BodyDef, BodyId, BodyKind, CharacterMover, MoveOutcome, Shape, World};
use passo_scene::{BuiltScene, LevelArt, Platform, Scene, SceneBody};
use std::path::Path;

/// Walking speed, m/s.
pub const WALK_SPEED: f32 = 4.5;
/// Running speed, m/s.
pub const RUN_SPEED: f32 = 8.0;
/// Speed a jump starts with, m/s: up to v² / 2g = 1.7 m high.
pub const JUMP_SPEED: f32 = 5.8;
/// Gravity on the player, m/s².
pub const GRAVITY: f32 = 9.81;
/// How long after walking off an edge a jump still works, s.
pub const COYOTE_TIME: f32 = 0.1;
/// How long before landing a jump press is kept, s.
pub const JUMP_BUFFER: f32 = 0.1;
/// Releasing jump while rising keeps this much of the upward speed.
pub const JUMP_CUT: f32 = 0.4;
/// Fastest fall while gliding, m/s.
pub const GLIDE_FALL: f32 = 1.5;
/// Ice: how fast the walking speed follows the keys, per second (on
/// ground that is not ice the speed follows at once).
pub const ICE_GRIP: f32 = 2.0;
/// How fast the wind carries the player along +x while it blows, m/s
/// (half of it on the ground, where the feet hold).
pub const WIND_SPEED: f32 = 2.0;
/// The player's size, metres.
pub const PLAYER_SIZE: Vec2 = Vec2::new(0.4, 0.7);

/// The keys this tick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Keys {
    /// Walk left.
    pub left: bool,
    /// Walk right.
    pub right: bool,
    /// Run.
    pub run: bool,
    /// Jump is held.
    pub jump: bool,
    /// Glide (slow fall) is held.
    pub glide: bool,
    /// The wind blows (along +x).
    pub wind: bool,
}

/// The game.
pub struct Platformer {
    /// The level's world.
    pub world: World,
    /// Every body with its colour, for drawing.
    pub bodies: Vec<SceneBody>,
    /// How the level's cells look: tiles of the tileset image.
    pub art: LevelArt,
    /// The bodies of the level's cells, sorted: drawn as their tiles.
    pub cell_bodies: Vec<BodyId>,
    platforms: Vec<Platform>,
    /// The player's body (kinematic).
    pub player: BodyId,
    /// Where the player starts, and starts again once crushed.
    start: Vec2,
    /// Times the player was crushed (and started again).
    pub crushed: u32,
    mover: CharacterMover,
    /// What the last move reported: where the player stands now.
    last: MoveOutcome,
    velocity: Vec2,
    since_ground: f32,
    since_jump_press: f32,
    jump_was_held: bool,
    rising_from_jump: bool,
    /// Coins collected.
    pub coins: u32,
    /// Coins in the level.
    pub coins_total: u32,
    /// The box around the level's static bodies, metres: where the camera
    /// may look.
    pub bounds: Aabb,
    goal: Option<BodyId>,
    /// The tick the player reached the goal.
    pub reached: Option<u64>,
    /// Ticks played.
    pub tick: u64,
}

impl Platformer {
    /// Loads the level of a scene file and puts the player, a box, at its
    /// `player` spawn point.
    pub fn load(scene: &Path) -> Result<Self, String> {
        Self::load_with(scene, "player", Shape::rect(PLAYER_SIZE.x, PLAYER_SIZE.y))
    }

    /// Loads the level of a scene file and puts a player of `shape` at its
    /// spawn point named `spawn`.
    pub fn load_with(scene: &Path, spawn: &str, shape: Shape) -> Result<Self, String> {
        let scene = Scene::load(scene).map_err(|e| e.to_string())?;
        let mut built: BuiltScene = scene.build().map_err(|e| e.to_string())?;
        let &(_, at) = built
            .spawns
            .iter()
            .find(|(name, _)| name == spawn)
            .ok_or_else(|| format!("the level has no `{spawn}` spawn point"))?;
        let mover = CharacterMover::default();
        let start = at + Vec2::new(0.0, shape.half_extents().y + mover.skin);
        let def = BodyDef::new_kinematic(start, shape, Vec2::ZERO);
        let player = built.world.add_body(def).map_err(|e| e.to_string())?;
        built.bodies.push(SceneBody {
            id: player,
            name: Some("player".into()),
            colour: passo_scene::Colour([0xe4, 0x6c, 0x3a, 0xff]),
        });
        let goal = built.body_named("goal");
        let coins_total = built
            .bodies
            .iter()
            .filter(|b| b.name.as_deref().is_some_and(|n| n.starts_with("coin")))
            .count() as u32;
        let bounds = built
            .world
            .bodies()
            .filter(|b| b.kind == BodyKind::Static)
            .filter_map(|b| Some(Aabb::from_centre(b.position, b.shape?.half_extents())))
            .reduce(|a, b| a.union(&b))
            .ok_or("the level has no static bodies")?;
        let mut cell_bodies = built.cell_bodies;
        cell_bodies.sort();
        Ok(Self {
            world: built.world,
            bodies: built.bodies,
            art: built.art,
            cell_bodies,
            platforms: built.platforms,
            player,
            start,
            crushed: 0,
            mover,
            last: MoveOutcome::default(),
            velocity: Vec2::ZERO,
            since_ground: f32::INFINITY,
            since_jump_press: f32::INFINITY,
            jump_was_held: false,
            rising_from_jump: false,
            coins: 0,
            coins_total,
            bounds,
            goal,
            reached: None,
            tick: 0,
        })
    }

    /// The player's position, metres.
    pub fn player_position(&self) -> Vec2 {
        self.world
            .body(self.player)
            .map_or(Vec2::ZERO, |b| b.position)
    }

    /// Seconds played.
    pub fn seconds(&self, dt: f32) -> f32 {
        self.tick as f32 * dt
    }

    /// One fixed tick of `dt` seconds with `keys` held.
    pub fn update(&mut self, keys: Keys, dt: f32) {
        self.tick += 1;
        let t_end = self.tick as f64 * f64::from(dt);
        BuiltScene::drive_platforms(&self.platforms, &mut self.world, t_end, dt);
        // Where the player stands: the last move says (it ended where the
        // step put the player).
        let now = self.last;
        let on_ice = now
            .ground
            .and_then(|g| self.world.body(g))
            .is_some_and(|g| g.friction < 0.1);
        // Coyote time and jump buffering.
        self.since_ground = if now.on_ground {
            0.0
        } else {
            self.since_ground + dt
        };
        let pressed = keys.jump && !self.jump_was_held;
        self.jump_was_held = keys.jump;
        self.since_jump_press = if pressed {
            0.0
        } else {
            self.since_jump_press + dt
        };
        let dir = f32::from(u8::from(keys.right)) - f32::from(u8::from(keys.left));
        let target = dir * if keys.run { RUN_SPEED } else { WALK_SPEED };
        self.velocity.x = if on_ice {
            // Ice: the speed follows the keys slowly.
            self.velocity.x + (target - self.velocity.x) * (ICE_GRIP * dt).min(1.0)
        } else {
            target
        };
        if now.on_ground && self.velocity.y <= 0.0 {
            self.velocity.y = 0.0;
            self.rising_from_jump = false;
        } else {
            self.velocity.y -= GRAVITY * dt;
        }
        if self.since_jump_press <= JUMP_BUFFER && self.since_ground <= COYOTE_TIME {
            self.velocity.y = JUMP_SPEED;
            self.since_jump_press = f32::INFINITY;
            self.since_ground = f32::INFINITY;
            self.rising_from_jump = true;
        }
        // Variable jump height: letting go of jump while rising cuts it.
        if self.rising_from_jump && !keys.jump && self.velocity.y > 0.0 {
            self.velocity.y *= JUMP_CUT;
            self.rising_from_jump = false;
        }
        if keys.glide && self.velocity.y < -GLIDE_FALL {
            self.velocity.y = -GLIDE_FALL;
        }
        let mut translation = self.velocity * dt;
        if keys.wind {
            let hold = if now.on_ground { 0.5 } else { 1.0 };
            translation.x += WIND_SPEED * hold * dt;
        }
        if let Ok(out) = self
            .world
            .move_character(self.player, translation, &self.mover, dt)
        {
            self.last = out;
            if out.ceiling.is_some() && self.velocity.y > 0.0 {
                self.velocity.y = 0.0;
            }
            if out.wall.is_some() && !on_ice {
                self.velocity.x = 0.0;
            }
            if out.crushed.is_some() {
                self.start_again();
            }
        }
        self.world.step(dt);
        self.collect();
    }

    /// Crushed: the player starts again at the spawn point, at rest.
    fn start_again(&mut self) {
        self.crushed += 1;
        // Where it is, at rest: a kinematic body keeps the velocity the
        // mover steered it with.
        self.world.set_position(self.player, self.start);
        self.world.set_velocity(self.player, Vec2::ZERO);
        self.velocity = Vec2::ZERO;
        self.rising_from_jump = false;
        self.last = MoveOutcome::default();
    }

    /// Coins the player touches are taken; the goal is noted.
    fn collect(&mut self) {
        let touched: Vec<BodyId> = self
            .world
            .sensor_overlaps()
            .iter()
            .filter(|p| p.visitor == self.player)
            .map(|p| p.sensor)
            .collect();
        for sensor in touched {
            if Some(sensor) == self.goal {
                self.reached.get_or_insert(self.tick);
            } else if self.is_coin(sensor) && self.world.remove_body(sensor).is_some() {
                self.coins += 1;
            }
        }
    }

    fn is_coin(&self, id: BodyId) -> bool {
        self.bodies
            .iter()
            .any(|b| b.id == id && b.name.as_deref().is_some_and(|n| n.starts_with("coin")))
    }

    /// Scripted keys that play the level to its goal: run right, and jump
    /// when a wall is in the way.
    pub fn autopilot(&self) -> Keys {
        let at = self.player_position();
        let blocked = self
            .world
            .cast_shape(
                &Shape::rect(PLAYER_SIZE.x, PLAYER_SIZE.y),
                at,
                Vec2::new(0.3, 0.0),
                &passo_physics::QueryFilter::solid().excluding(self.player),
            )
            .is_some_and(|hit| hit.normal.x < -0.5);
        Keys {
            right: true,
            jump: blocked,
            ..Keys::default()
        }
    }
}

/// Where a camera showing `view` (width, height in metres) looks next: a
/// tenth of the way from `centre` towards `player`, so it follows a little
/// behind, then moved so the view stays inside `bounds`. Along an axis
/// where the level is smaller than the view, the level is centred.
pub fn follow_camera(centre: Vec2, player: Vec2, view: Vec2, bounds: Aabb) -> Vec2 {
    let wanted = centre + (player - centre) * 0.1;
    let clamp_axis = |c: f32, half: f32, lo: f32, hi: f32| {
        if hi - lo <= 2.0 * half {
            0.5 * (lo + hi)
        } else {
            c.clamp(lo + half, hi - half)
        }
    };
    let half = 0.5 * view;
    Vec2::new(
        clamp_axis(wanted.x, half.x, bounds.min.x, bounds.max.x),
        clamp_axis(wanted.y, half.y, bounds.min.y, bounds.max.y),
    )
}
