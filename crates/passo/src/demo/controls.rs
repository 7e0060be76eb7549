//! What the player and the panel control: the keys held this tick
//! ([`Input`]), the panel's sliders ([`Knobs`]), and the two controllers
//! of the player: forces on a dynamic body (the playground's physics
//! player), or the character mover on a kinematic one (a level's player,
//! made at its `player` spawn point).

use glam::Vec2;
use passo_physics::constants::DEFAULT_MAX_SPEED;
use passo_physics::{
    BodyDef, BodyId, BodyKind, CharacterMover, QuadraticDrag, Shape, World, WorldSettings,
};
use passo_scene::{BuiltScene, Colour, SceneBody};
use serde::{Deserialize, Serialize};
use std::ops::RangeInclusive;

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

/// The wind slider's speed in a scene without wind, m/s along +x.
const CALM_WIND_SPEED: f32 = 8.0;

impl Knobs {
    /// The max-speed slider's range, m/s: it tops out at the library's
    /// default cap, and a scene without a cap shows that.
    pub const MAX_SPEED_RANGE: RangeInclusive<f32> = 1.0..=DEFAULT_MAX_SPEED;

    /// The sliders as `world` is set up: its force models and speed limits,
    /// and the friction and restitution of its first dynamic body (the
    /// library's [`BodyDef`] defaults without one).
    pub fn of(world: &World) -> Self {
        let s = world.settings();
        let f = &s.forces;
        let def = BodyDef::default();
        let first = world.bodies().find(|b| b.kind == BodyKind::Dynamic);
        Self {
            gravity: f.gravity.map_or(0.0, |g| g.y),
            friction: first.map_or(def.friction, |b| b.friction),
            density: f.quadratic_drag.map_or(0.0, |d| d.density),
            drag_scale: 1.0,
            restitution: first.map_or(def.restitution, |b| b.restitution),
            min_speed: s.min_speed,
            max_speed: s.max_speed.min(*Self::MAX_SPEED_RANGE.end()),
            wind: f.air_velocity != Vec2::ZERO,
            wind_speed: if f.air_velocity.x != 0.0 {
                f.air_velocity.x
            } else {
                CALM_WIND_SPEED
            },
            continuous: s.contacts.is_none_or(|c| c.continuous),
            sleeping: s.contacts.is_none_or(|c| c.sleeping),
        }
    }

    /// Whether every slider value is finite (as the panel's sliders always
    /// are; a replay file could say otherwise).
    pub fn is_finite(&self) -> bool {
        [
            self.gravity,
            self.friction,
            self.density,
            self.drag_scale,
            self.restitution,
            self.min_speed,
            self.max_speed,
            self.wind_speed,
        ]
        .iter()
        .all(|v| v.is_finite())
    }

    /// `settings` with the sliders' force models, speed limits and contact
    /// switches.
    pub fn applied_to(&self, settings: WorldSettings) -> WorldSettings {
        let mut s = settings;
        s.forces.gravity = (self.gravity != 0.0).then_some(Vec2::new(0.0, self.gravity));
        s.forces.quadratic_drag = (self.density > 0.0).then_some(QuadraticDrag {
            density: self.density,
        });
        s.forces.air_velocity = if self.wind {
            Vec2::new(self.wind_speed, 0.0)
        } else {
            Vec2::ZERO
        };
        s.min_speed = self.min_speed;
        s.max_speed = self.max_speed;
        if let Some(c) = &mut s.contacts {
            c.continuous = self.continuous;
            c.sleeping = self.sleeping;
        }
        s
    }
}

/// Target walking speed, m/s.
const WALK_SPEED: f32 = 4.5;
/// Target running speed, m/s.
const RUN_SPEED: f32 = 9.0;
/// Acceleration beyond what kinetic friction takes, m/s².
const WALK_ACCELERATION: f32 = 8.0;
/// Time to close the gap to the target speed, s (before the force cap).
const WALK_RESPONSE: f32 = 0.15;
/// Upward speed a jump gives, m/s.
const JUMP_SPEED: f32 = 6.5;
/// Steepest support that counts as standing, radians from up (0.8 rad,
/// about 46°).
const MAX_STANDING_SLOPE: f32 = 0.8;
/// Drag-area multiplier while gliding.
const GLIDE_DRAG: f32 = 40.0;

/// Moves the player: walk and run by pushing against friction, jump only
/// when standing, glide with a large drag area (`base_drag`, the body's
/// scene drag area, scaled by the drag slider). Consumes a pending jump.
pub(crate) fn drive_player(
    world: &mut World,
    player: BodyId,
    input: &mut Input,
    knobs: &Knobs,
    base_drag: Option<f32>,
) {
    let jump = std::mem::replace(&mut input.jump, false);
    let Some(body) = world.body(player) else {
        return;
    };
    let m = body.mass;
    let standing = world.is_standing(player, MAX_STANDING_SLOPE);
    let dir = f32::from(u8::from(input.right)) - f32::from(u8::from(input.left));
    if dir != 0.0 {
        let target = dir * if input.run { RUN_SPEED } else { WALK_SPEED };
        // Enough to overcome kinetic friction and accelerate.
        let g = knobs.gravity.abs();
        let max = m * (body.friction * g + WALK_ACCELERATION);
        let push = (m * (target - body.velocity.x) / WALK_RESPONSE).clamp(-max, max);
        world.apply_force(player, Vec2::new(push, 0.0));
    }
    if jump && standing {
        world.apply_impulse(player, Vec2::new(0.0, m * JUMP_SPEED));
    }
    if let Some(base) = base_drag {
        let open = input.glide && !standing;
        let area = base * knobs.drag_scale * if open { GLIDE_DRAG } else { 1.0 };
        let _ = world.set_drag_area(player, area);
    }
}

/// The character's size, metres: a little narrower than a 0.5 m tile and
/// shorter than two.
const CHARACTER_SIZE: Vec2 = Vec2::new(0.4, 0.7);
/// Fastest fall of a gliding character, m/s.
const GLIDE_FALL_SPEED: f32 = 1.5;
/// The character's colour (sRGB).
const CHARACTER_COLOUR: Colour = Colour([0xe4, 0x6c, 0x3a, 0xff]);

/// Adds a kinematic character named `player` at the scene's `player`
/// spawn point, if it has one; returns it.
pub(crate) fn add_character(built: &mut BuiltScene) -> Option<BodyId> {
    let &(_, at) = built.spawns.iter().find(|(name, _)| name == "player")?;
    let skin = CharacterMover::default().skin;
    let def = BodyDef::new_kinematic(
        at + Vec2::new(0.0, 0.5 * CHARACTER_SIZE.y + skin),
        Shape::rect(CHARACTER_SIZE.x, CHARACTER_SIZE.y),
        Vec2::ZERO,
    );
    add_named(built, def, "player", CHARACTER_COLOUR)
}

/// Adds a body to a built scene with its name and colour.
fn add_named(built: &mut BuiltScene, def: BodyDef, name: &str, colour: Colour) -> Option<BodyId> {
    let id = built.world.add_body(def).ok()?;
    built.bodies.push(SceneBody {
        id,
        name: Some(name.into()),
        colour,
    });
    Some(id)
}

/// Adds a dynamic physics player at the scene's `physics player` spawn
/// point, the character's size, if it has one; returns it.
pub(crate) fn add_physics_player(built: &mut BuiltScene) -> Option<BodyId> {
    let &(_, at) = built
        .spawns
        .iter()
        .find(|(name, _)| name == "physics player")?;
    let def = BodyDef {
        mass: 70.0,
        friction: 0.8,
        drag_area: 0.5,
        ..BodyDef::new_dynamic(
            at + Vec2::new(0.0, 0.5 * CHARACTER_SIZE.y),
            Shape::rect(CHARACTER_SIZE.x, CHARACTER_SIZE.y),
        )
    };
    add_named(built, def, "physics player", PHYSICS_PLAYER_COLOUR)
}

/// The physics player's colour beside the character (sRGB).
const PHYSICS_PLAYER_COLOUR: Colour = Colour([0x3a, 0x8e, 0xe4, 0xff]);

/// Whether `player` is moved by the character mover (a kinematic body).
pub(crate) fn is_character(world: &World, player: BodyId) -> bool {
    world
        .body(player)
        .is_some_and(|b| b.kind == BodyKind::Kinematic)
}

/// Moves a kinematic character with the character mover: walk and run at
/// their speeds, jump from the ground, fall under the gravity slider,
/// glide slowly down while G is held. Its own velocity (the last tick's
/// motion, which the world keeps) is the only state, so rewinding and
/// replays need nothing else. Consumes a pending jump.
pub(crate) fn drive_character(
    world: &mut World,
    player: BodyId,
    input: &mut Input,
    knobs: &Knobs,
    dt: f32,
) {
    let jump = std::mem::replace(&mut input.jump, false);
    let Some(body) = world.body(player) else {
        return;
    };
    let mover = CharacterMover::default();
    // Where it stands now.
    let Ok(now) = world.move_character(player, Vec2::ZERO, &mover, dt) else {
        return;
    };
    let dir = f32::from(u8::from(input.right)) - f32::from(u8::from(input.left));
    let mut v = body.velocity;
    v.x = dir * if input.run { RUN_SPEED } else { WALK_SPEED };
    if now.on_ground {
        v.y = if jump { JUMP_SPEED } else { 0.0 };
    } else {
        v.y += knobs.gravity * dt;
        if now.ceiling.is_some() {
            v.y = v.y.min(0.0);
        }
        if input.glide {
            v.y = v.y.max(-GLIDE_FALL_SPEED);
        }
    }
    let _ = world.move_character(player, v * dt, &mover, dt);
}
