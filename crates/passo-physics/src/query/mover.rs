//! A character mover: moves a kinematic body the way a platformer's player
//! moves, by shape casts rather than forces (as Rapier's character
//! controller and Box2D's mover do, for shapes that do not rotate).
//!
//! Each call of [`World::move_character`] takes the translation the game
//! wants this tick and:
//! 1. finds what it stands on now;
//! 2. adds the travel of the kinematic body it stands on (riding);
//! 3. is pushed along by a kinematic body that sweeps into it this step
//!    (however fast), then out of anything it overlaps;
//! 4. moves and slides: casts the shape along what is left of the
//!    translation, stops a skin width short of the first hit, and keeps
//!    the part of the motion along the surface; up to four times. On the
//!    ground and not jumping, the walk follows the ground instead: along
//!    each slope no steeper than `max_slope`, at the walking speed, and
//!    onto the next slope at a joint;
//! 5. climbs a step no higher than `max_step` that blocks it while on the
//!    ground (a static or kinematic one: a dynamic body is pushed);
//! 6. snaps down onto ground up to `snap_down` below, when it was on the
//!    ground and is not moving up, so it follows small drops instead of
//!    flying off them;
//! 7. on the ground, sets its feet exactly a skin above it;
//! 8. reports the ground (and the body it stands on), walls and ceilings.
//!
//! From step 2 on, every kinematic body is met where its velocity takes it
//! by the end of the step, where the character will be too: a lift it
//! lands on, rides or is pushed by is met where it will be, not a step
//! behind. So steer the platforms first each tick.
//!
//! The body is then steered to the place found with
//! [`set_kinematic_target`](World::set_kinematic_target), so the next
//! step moves it there and dynamic bodies it touches meet a moving body.
//! One-way platforms stop it only from their solid side, and not while it
//! drops through ([`World::drop_through`]). Dynamic bodies block it like
//! walls and are pushed with an impulse of at most `push_mass` times the
//! closing speed; the character's contacts never push them ahead of it
//! (see `contact::constraint::character_lead`).

use crate::constants::{LINEAR_SLOP, ONE_WAY_DEPTH};
use crate::geometry::manifold::collide;
use crate::query::Found;
use crate::{BodyId, PhysicsError, QueryFilter, Shape, World};
use glam::Vec2;

/// How a character moves: see [`World::move_character`].
///
/// A kinematic player walking right over a floor, with the game's own
/// gravity, one call a tick before the step:
///
/// ```
/// use passo_physics::{BodyDef, CharacterMover, Shape, World, glam::Vec2};
///
/// let mut world = World::default();
/// world.add_body(BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(40.0, 1.0))).unwrap();
/// let player = world
///     .add_body(BodyDef::new_kinematic(Vec2::new(0.0, 0.5), Shape::rect(0.4, 0.8), Vec2::ZERO))
///     .unwrap();
/// let mover = CharacterMover::default(); // 1 cm skin, 0.3 m steps
/// let dt = 1.0 / 60.0;
/// let mut velocity = Vec2::ZERO;
/// let mut on_ground = false;
/// for _ in 0..60 {
///     velocity.x = 3.0; // walk right at 3 m/s
///     velocity.y = if on_ground { 0.0 } else { velocity.y - 9.81 * dt };
///     let out = world.move_character(player, velocity * dt, &mover, dt).unwrap();
///     on_ground = out.on_ground;
///     world.step(dt);
/// }
/// let at = world.body(player).unwrap().position;
/// assert!(on_ground);
/// assert!((at.x - 3.0).abs() < 0.01, "3 m in 1 s, at {at}");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CharacterMover {
    /// Gap kept between the character and what it touches, metres, > 0.
    /// Default 0.01 (2 × the slop).
    pub skin: f32,
    /// Highest step climbed while walking on the ground, metres, >= 0 (a
    /// step up to `skin` higher is climbed too). Default 0.3.
    pub max_step: f32,
    /// Farthest drop followed while walking instead of leaving the ground,
    /// metres, >= 0. Default 0.3.
    pub snap_down: f32,
    /// Steepest slope that counts as ground, radians, in `[0, π/2]`:
    /// the character walks up and down it and stands on it. A steeper one
    /// is a wall for walking, and the character slides down it. Default
    /// 45° (`π/4`).
    pub max_slope: f32,
    /// On the ground, the walk follows the ground keeping its horizontal
    /// speed (`false`, the default: `translation.x` a tick is the
    /// distance across), or its speed along the ground (`true`: a walk up
    /// or down a slope covers the same distance along it as on the flat,
    /// as Godot's `floor_constant_speed`).
    pub constant_speed: bool,
    /// A character standing on a slope no steeper than `max_slope` stays
    /// put whatever the game's gravity (`true`, the default, as Godot's
    /// `floor_stop_on_slope`); with `false` the downward part of the
    /// translation slides it down the slope.
    pub stop_on_slope: bool,
    /// How hard the character pushes dynamic bodies it walks into: the mass,
    /// kilograms, >= 0, of the impulse per metre per second of closing
    /// speed (the speed it wants towards the body less the body's speed
    /// away). A body lighter than this is brought up to the character's
    /// speed, never past it. This push is the only one: the character's
    /// contacts never push a body ahead of it, so 0 pushes nothing.
    /// Default 20.
    pub push_mass: f32,
    /// Which bodies block it (sensors never do; the character itself is
    /// left out).
    pub filter: QueryFilter,
}

impl Default for CharacterMover {
    fn default() -> Self {
        Self {
            skin: 2.0 * LINEAR_SLOP,
            max_step: 0.3,
            snap_down: 0.3,
            max_slope: std::f32::consts::FRAC_PI_4,
            constant_speed: false,
            stop_on_slope: true,
            push_mass: 20.0,
            filter: QueryFilter::solid(),
        }
    }
}

impl CharacterMover {
    fn validate(&self) -> Result<(), PhysicsError> {
        crate::error::positive("CharacterMover::skin", self.skin)?;
        crate::error::non_negative("CharacterMover::max_step", self.max_step)?;
        crate::error::non_negative("CharacterMover::snap_down", self.snap_down)?;
        crate::error::finite("CharacterMover::max_slope", self.max_slope)?;
        if !(0.0..=std::f32::consts::FRAC_PI_2).contains(&self.max_slope) {
            return Err(PhysicsError::OutOfRange {
                what: "CharacterMover::max_slope",
                value: self.max_slope,
                allowed: "in [0, π/2] radians",
            });
        }
        crate::error::non_negative("CharacterMover::push_mass", self.push_mass)?;
        Ok(())
    }
}

/// What a move did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MoveOutcome {
    /// Where the character will be after the next step, metres.
    pub position: Vec2,
    /// The translation it will make (the wanted one, slid, stepped,
    /// snapped and carried by its platform).
    pub translation: Vec2,
    /// It stands on ground after the move, its feet exactly
    /// [`skin`](CharacterMover::skin) above it. Never while the
    /// translation asked for moves it up (a jump).
    pub on_ground: bool,
    /// The body it stands on.
    pub ground: Option<BodyId>,
    /// The normal of the ground it stands on (zero off the ground).
    pub ground_normal: Vec2,
    /// The velocity of the ground it stands on: a moving platform's (zero
    /// for static ground and off the ground). A game adds it to the
    /// character's own when it jumps or walks off, to carry the platform's
    /// momentum.
    pub ground_velocity: Vec2,
    /// A wall stopped part of the motion ([`wall`](Self::wall) names it).
    pub on_wall: bool,
    /// A ceiling stopped part of the motion ([`ceiling`](Self::ceiling)
    /// names it).
    pub on_ceiling: bool,
    /// A wall stopped part of the motion: the body.
    pub wall: Option<BodyId>,
    /// A ceiling stopped part of the motion: the body.
    pub ceiling: Option<BodyId>,
    /// How far it climbed a step, metres (0 if it did not).
    pub stepped: f32,
    /// Dynamic bodies it pushed.
    pub pushed: u32,
    /// A kinematic body pressed into it with no room left to get out of
    /// the way (a lift come down onto a character standing on the floor, a
    /// moving wall pressing it against another, in the air or not, a lift
    /// carrying it into a ceiling): the body. The character is left where
    /// it is, overlapped; a game usually treats this as the character
    /// being crushed.
    pub crushed: Option<BodyId>,
}

/// The first thing a cast meets.
#[derive(Clone, Copy, Debug)]
struct Hit {
    fraction: f32,
    normal: Vec2,
    body: BodyId,
    /// The body's index in the dynamic arrays, if it is dynamic (not
    /// kinematic): it can be pushed.
    pushable: Option<usize>,
}

/// The character during one move.
struct Walker<'a> {
    world: &'a World,
    shape: Shape,
    mover: &'a CharacterMover,
    filter: QueryFilter,
    dropping: bool,
    /// Seconds to the end of the step: kinematic bodies are seen where
    /// they will be then (`position + velocity * dt`), as the character
    /// will be. `None`: where they are now (to find what it stands on).
    ahead: Option<f32>,
    /// The farthest a kinematic body travels this step (queries grow by
    /// it, so each is found where it will be).
    reach: f32,
    /// A body left out of the casts (the platform carrying it, during the
    /// carry).
    ignored: Option<BodyId>,
    /// The least upward part of a normal that is ground: `cos(max_slope)`.
    ground_cos: f32,
}

impl Walker<'_> {
    /// Where a found body is met: a kinematic one where it will be after
    /// the step (unless the walker looks at now).
    fn place(&self, f: &Found<'_>) -> Vec2 {
        match (self.ahead, f.dynamic) {
            (Some(dt), Some(i)) if f.meta.kinematic => {
                f.position + self.world.dynamic.vel.at(i) * dt
            }
            _ => f.position,
        }
    }

    /// Calls `f` with every candidate near `area` (grown by the kinematic
    /// bodies' travel, so each is found where it will be).
    fn near(&self, area: &crate::Aabb, mut f: impl FnMut(Found<'_>)) {
        let grow = if self.ahead.is_some() {
            self.reach
        } else {
            0.0
        };
        self.world
            .candidates(&area.grown(grow), &self.filter, |found| {
                if Some(found.id) != self.ignored {
                    f(found);
                }
            });
    }

    /// Whether the character at `at` stands on one-way body `f`'s solid
    /// side: not dropping through, and either clear of it or inside it no
    /// deeper than [`ONE_WAY_DEPTH`] plus how far the body rises into it
    /// this step, with the way out along the solid side (as the contacts
    /// of a body landing on it; a lift going up carries it).
    fn on_solid_side(&self, at: Vec2, f: &Found<'_>, solid: Vec2) -> bool {
        if self.dropping {
            return false;
        }
        let place = self.place(f);
        let Some(m) = collide(&self.shape, at, &f.shape, place, 0.0) else {
            return true;
        };
        let rise = (place - f.position).dot(solid).max(0.0);
        // `m.normal` points from the character to the body.
        -m.normal.dot(solid) > 0.0 && m.separation >= -(ONE_WAY_DEPTH + rise)
    }

    /// The first body `shape` meets moving from `from` by `by`: one-way
    /// platforms only from their solid side (and not while dropping
    /// through), and nothing it overlaps at the start (the push out deals
    /// with those).
    fn cast(&self, from: Vec2, by: Vec2) -> Option<Hit> {
        if by == Vec2::ZERO {
            return None;
        }
        let swept = self.swept(from, by);
        let mut best: Option<Hit> = None;
        self.near(&swept, |f: Found<'_>| {
            let at = self.place(&f);
            let Some(hit) = crate::geometry::cast::cast_shape(&self.shape, from, by, &f.shape, at)
            else {
                return;
            };
            if let Some(solid) = f.meta.one_way {
                // From its solid side only: a body inside it deeper than a
                // landing goes through (and one touching it stays on it).
                if hit.normal.dot(solid) <= 0.0 || !self.on_solid_side(from, &f, solid) {
                    return;
                }
            } else if hit.fraction == 0.0 && self.overlaps(from, &f) {
                return;
            }
            let pushable = f.dynamic.filter(|_| !f.meta.kinematic);
            let candidate = Hit {
                fraction: hit.fraction,
                normal: hit.normal,
                body: f.id,
                pushable,
            };
            // (A tie is one body met twice at once: a chain's two segments
            // at their shared vertex. Either segment's normal will do.)
            if best.is_none_or(|b| (hit.fraction, f.id) < (b.fraction, b.body)) {
                best = Some(candidate);
            }
        });
        best
    }

    /// Whether the character moving in a straight line from `from` by `by`
    /// would pass through a dynamic (not kinematic) body.
    fn cuts_dynamic(&self, from: Vec2, by: Vec2) -> bool {
        let swept = self.swept(from, by);
        let mut cuts = false;
        self.near(&swept, |f: Found<'_>| {
            if f.dynamic.is_some() && !f.meta.kinematic && !cuts {
                cuts =
                    crate::geometry::cast::cast_shape(&self.shape, from, by, &f.shape, f.position)
                        // (`<= 0.0` is untested: it differs only for a line
                        // starting inside the body and moving exactly along
                        // its side, and the push out has moved the
                        // character out of it sideways by then.)
                        .is_some_and(|hit| hit.fraction < 1.0 && hit.normal.dot(by) < 0.0);
            }
        });
        cuts
    }

    /// The box the character's shape covers moving from `from` by `by`.
    fn swept(&self, from: Vec2, by: Vec2) -> crate::Aabb {
        let half = self.shape.half_extents();
        crate::Aabb::from_centre(from, half).union(&crate::Aabb::from_centre(from + by, half))
    }

    /// Whether the character at `at` overlaps `f` (deeper than touching).
    fn overlaps(&self, at: Vec2, f: &Found<'_>) -> bool {
        collide(&self.shape, at, &f.shape, self.place(f), 0.0).is_some_and(|m| m.separation < 0.0)
    }

    /// Moves from `from` by `by` as far as the first hit allows, a skin
    /// short of it. Returns where it got and the hit.
    fn advance(&self, from: Vec2, by: Vec2) -> (Vec2, Option<Hit>) {
        match self.cast(from, by) {
            None => (from + by, None),
            Some(hit) => {
                let length = by.length();
                // The skin measured along the normal: moving at a slant
                // to the surface, back off more along the motion.
                let along = (-by.dot(hit.normal) / length).max(0.1);
                let fraction = (hit.fraction - self.mover.skin / (length * along)).max(0.0);
                (from + by * fraction, Some(hit))
            }
        }
    }

    /// [`advance`](Self::advance) through `body` (a platform carrying the
    /// character, a body pushing it), which moves along with it: where it
    /// got.
    fn advance_past(&mut self, body: BodyId, from: Vec2, by: Vec2) -> Vec2 {
        self.ignored = Some(body);
        let (to, _) = self.advance(from, by);
        self.ignored = None;
        to
    }

    /// Pushes the character at `at` out of every solid body it overlaps
    /// (one-way platforms only when it is on their solid side), a few
    /// rounds.
    fn push_out(&self, mut at: Vec2) -> Vec2 {
        for _ in 0..4 {
            let mut deepest: Option<(f32, Vec2)> = None;
            let area = crate::Aabb::from_centre(at, self.shape.half_extents());
            self.near(&area, |f: Found<'_>| {
                if let Some(solid) = f.meta.one_way
                    && !self.on_solid_side(at, &f, solid)
                {
                    return;
                }
                if let Some(m) = collide(&self.shape, at, &f.shape, self.place(&f), 0.0)
                    && m.separation < 0.0
                    // (Of two exactly as deep, the first found goes first;
                    // the next round takes the other.)
                    && deepest.is_none_or(|(s, _)| m.separation < s)
                {
                    // `m.normal` points from the character to the body.
                    deepest = Some((m.separation, -m.normal));
                }
            });
            let Some((separation, normal)) = deepest else {
                break;
            };
            at += normal * (-separation + self.mover.skin);
        }
        at
    }

    /// How far the kinematic bodies that sweep into the character this step
    /// push it, the character having started at `start` and been carried
    /// to `at` (riding): each body's travel is taken relative to that
    /// carry, from the character's start. The first one met (the earliest
    /// along its travel, then the lowest id) pushes it along the face that
    /// meets it for the rest of that travel, to a skin in front of where
    /// the body ends: one ending clear of the character passed through it
    /// (faster than it is wide), and one ending inside it would push it out
    /// on whichever side is nearer, or into what blocks that side. A body
    /// ending under it no higher than `max_step` above its feet, with the
    /// push out lifting it on top (a low-lipped platform), is left to the
    /// push out, which scoops it up, as are bodies it overlaps already and
    /// one-way platforms. Returns the body and the push, or `None`.
    fn swept_by_kinematic(&self, start: Vec2, at: Vec2) -> Option<(BodyId, Vec2)> {
        let dt = self.ahead?;
        let carried = at - start;
        let area = self.swept(start, carried);
        let mut first: Option<(f32, BodyId, Vec2)> = None;
        self.near(&area, |f: Found<'_>| {
            let Some(i) = f
                .dynamic
                .filter(|_| f.meta.kinematic && f.meta.one_way.is_none())
            else {
                return;
            };
            let travel = self.world.dynamic.vel.at(i) * dt - carried;
            let Some(hit) =
                crate::geometry::cast::cast_shape(&f.shape, f.position, travel, &self.shape, start)
            else {
                return;
            };
            if hit.fraction == 0.0 {
                return;
            }
            // `hit.normal` points out of the character towards the body.
            let away = -hit.normal;
            // A body no higher than a step ending under the character, whose
            // push out lifts it on top, scoops it up as a step climbed;
            // every other is swept.
            let place = self.place(&f);
            // (A body that ends exactly touching is met by rounding either
            // way.)
            let lifts = collide(&self.shape, at, &f.shape, place, 0.0)
                .is_some_and(|m| m.separation < 0.0 && -m.normal.y >= self.ground_cos);
            let rise = place.y + f.shape.half_extents().y - (at.y - self.shape.half_extents().y);
            if lifts && rise <= self.mover.max_step {
                return;
            }
            let push = away * ((1.0 - hit.fraction) * travel.dot(away) + self.mover.skin);
            // (Each body is found once, and no two share an id: `<=` would
            // choose the same.)
            if first.is_none_or(|(t, id, _)| (hit.fraction, f.id) < (t, id)) {
                first = Some((hit.fraction, f.id, push));
            }
        });
        first.map(|(_, body, push)| (body, push))
    }

    /// Calls `f` with each kinematic body (not one-way) the character at
    /// `at` overlaps by more than the skin where the body ends the step:
    /// the body, where it is met, and the way out of it (the character's
    /// shortest move out of the overlap).
    fn kinematic_inside(&self, at: Vec2, mut f: impl FnMut(&Found<'_>, Vec2, Vec2)) {
        let area = crate::Aabb::from_centre(at, self.shape.half_extents());
        self.near(&area, |found: Found<'_>| {
            let kinematic = found.dynamic.is_some() && found.meta.kinematic;
            if !kinematic || found.meta.one_way.is_some() {
                return;
            }
            let place = self.place(&found);
            // (At exactly the skin, in or out: rounding decides either way.)
            if let Some(m) = collide(&self.shape, at, &found.shape, place, 0.0)
                && m.separation < -self.mover.skin
            {
                // `m.normal` points from the character to the body.
                f(&found, place, m.normal * m.separation);
            }
        });
    }

    /// The kinematic body (not one-way) that overlaps the character at
    /// `at` from above by more than the skin where it ends the step, the
    /// character standing on ground there: it has no room (a lift come
    /// down onto it). The lowest id of several.
    fn crushing(&self, at: Vec2) -> Option<BodyId> {
        self.ground(at, 2.0 * self.mover.skin)?;
        let mut crusher: Option<BodyId> = None;
        self.kinematic_inside(at, |f, place, _| {
            // Its underside above the feet, however deep it is in, or its
            // top higher than a step: a body down at the feet no higher than
            // `max_step` (a low platform sliding in under them, a thin lift
            // come down to the floor) is climbed on top instead.
            let feet = at.y - self.shape.half_extents().y;
            let (h, skin) = (f.shape.half_extents().y, self.mover.skin);
            // (Exactly at either height, either answer will do.)
            let above =
                place.y - h > feet + skin || place.y + h > feet + self.mover.max_step + skin;
            // (Each body is found once: `<=` would choose the same.)
            if above && crusher.is_none_or(|c| f.id < c) {
                crusher = Some(f.id);
            }
        });
        crusher
    }

    /// The kinematic body (not one-way) that overlaps the character at
    /// `at` by more than the skin with no way out: moving the character
    /// out of it, along the way out of the overlap, meets something that
    /// does not give way (a wall, the floor, a ceiling; not a dynamic
    /// body). A wall pressing it sideways against another, in the air or
    /// on the ground, or a platform lifting it into a ceiling. The lowest
    /// id of several.
    fn squeezing(&mut self, at: Vec2) -> Option<BodyId> {
        let mut inside: Vec<(BodyId, Vec2)> = Vec::new();
        self.kinematic_inside(at, |f, _, way_out| inside.push((f.id, way_out)));
        inside.sort_by_key(|&(id, _)| id);
        let ignored = self.ignored;
        let mut squeezer = None;
        for (id, way_out) in inside {
            self.ignored = Some(id);
            let blocked = self
                .cast(at, way_out)
                // (A way out that ends exactly touching is taken by rounding
                // either way.)
                .is_some_and(|hit| hit.fraction < 1.0 && hit.pushable.is_none());
            if blocked {
                squeezer = Some(id);
                break;
            }
        }
        self.ignored = ignored;
        squeezer
    }

    /// The ground within `reach` below `at`: the hit, if its normal is
    /// ground enough.
    fn ground(&self, at: Vec2, reach: f32) -> Option<Hit> {
        self.cast(at, Vec2::new(0.0, -reach))
            .filter(|h| h.normal.y >= self.ground_cos)
    }
}

/// A move of `by` on ground whose normal is `normal` (pointing up): its
/// walk across, `by.x`, along the ground, keeping the horizontal distance
/// or with `constant_speed` the distance along the ground; and its fall,
/// `by.y`, left out where the character stops on slopes, else slid down
/// the ground.
fn along_ground(by: Vec2, normal: Vec2, mover: &CharacterMover) -> Vec2 {
    // Along the ground, towards +x.
    let tangent = Vec2::new(normal.y, -normal.x);
    let walk = if mover.constant_speed {
        tangent * by.x
    } else {
        tangent * (by.x / tangent.x)
    };
    if mover.stop_on_slope {
        return walk;
    }
    let fall = Vec2::new(0.0, by.y);
    // (Only the part across the slope decides where it ends: the snap to
    // the ground sets the height.)
    walk + fall - normal * fall.dot(normal)
}

impl World {
    /// Moves character `id` (a kinematic body with a shape) by `translation`
    /// over the next step of `dt` seconds, sliding along what it meets,
    /// climbing steps, following small drops and riding platforms (see
    /// the [`mover`](crate::CharacterMover) settings), and steers it
    /// there with [`set_kinematic_target`](Self::set_kinematic_target).
    /// Call it once per tick before [`step`](Self::step), and after
    /// steering this tick's platforms: kinematic bodies are met where their
    /// velocity takes them by the end of the step, so a platform steered
    /// after the call is met a step late (a rider lags a sideways
    /// platform, sinks into a lift going up, or is thrown off one that
    /// turns back).
    ///
    /// A kinematic body that sweeps into the character this step (steered
    /// before the call) pushes it along to a skin in front of where the
    /// body ends, however fast it goes. One that presses into it with no
    /// room left (down onto it on the floor, against a wall, up into a
    /// ceiling) crushes it: [`MoveOutcome::crushed`] names it, and the
    /// character stays where it is.
    ///
    /// Limits: a round bottom (a capsule's, a circle's) rolls up a
    /// block's corner once the corner is under it within `max_slope`,
    /// so at speed it may top blocks higher than `max_step` (use a box for
    /// exact step heights), and climbing a step it moves at least its
    /// radius forward; walking off a dynamic body's edge the character
    /// falls rather than snaps down.
    ///
    /// ```
    /// use passo_physics::{BodyDef, CharacterMover, Shape, TileMap, BodyKind, World, glam::Vec2};
    /// let mut world = World::default();
    /// let level = TileMap::from_ascii("
    ///     ..........
    ///     .......###
    ///     ##########", Vec2::splat(0.25), Vec2::ZERO).unwrap();
    /// world.add_tile_map(&level, BodyKind::Static).unwrap();
    /// let player = world
    ///     .add_body(BodyDef::new_kinematic(Vec2::new(0.5, 0.5 + 0.01), Shape::rect(0.3, 0.5), Vec2::ZERO))
    ///     .unwrap();
    /// let mover = CharacterMover::default();
    /// for _ in 0..30 {
    ///     // Walk right at 3 m/s and fall at 5 m/s.
    ///     world.move_character(player, Vec2::new(3.0, -5.0) / 60.0, &mover, 1.0 / 60.0).unwrap();
    ///     world.step(1.0 / 60.0);
    /// }
    /// // In half a second it walked 1.5 m and climbed the 0.25 m step.
    /// let p = world.body(player).unwrap().position;
    /// assert!((p.x - 2.0).abs() < 0.05, "{p}");
    /// assert!((p.y - (0.5 + 0.25 + 0.01)).abs() < 0.02, "{p}");
    /// ```
    ///
    /// # Errors
    /// A stale id, a body that is not kinematic or has no shape, a
    /// non-finite translation, `dt` not > 0, or settings out of range.
    pub fn move_character(
        &mut self,
        id: BodyId,
        translation: Vec2,
        mover: &CharacterMover,
        dt: f32,
    ) -> Result<MoveOutcome, PhysicsError> {
        mover.validate()?;
        crate::error::finite_vec("translation", translation)?;
        crate::error::positive("dt", dt)?;
        let body = self.body(id).ok_or(PhysicsError::StaleBody(id))?;
        let (Some(shape), crate::BodyKind::Kinematic) = (body.shape, body.kind) else {
            return Err(PhysicsError::OutOfRange {
                what: "move_character body",
                value: 0.0,
                allowed: "a kinematic body with a shape",
            });
        };
        let i = self
            .dynamic_index(id)?
            .expect("a kinematic body is in the dynamic arrays");
        // How far any kinematic body goes this step: the queries reach that
        // much farther. (Farther would find the same, only slower.)
        let b = &self.dynamic;
        let reach = b
            .kinematic
            .iter()
            .map(|&k| b.vel.at(k as usize).length() * dt)
            .fold(0.0, f32::max);
        let mut walker = Walker {
            world: self,
            shape,
            mover,
            filter: mover.filter.excluding(id),
            dropping: self.dynamic.meta[i].drop_through > 0.0,
            ahead: None,
            reach,
            ignored: None,
            ground_cos: libm::cosf(mover.max_slope),
        };
        let mut out = MoveOutcome::default();
        // What it stands on now, where everything is now.
        let under = walker.ground(body.position, 2.0 * mover.skin);
        // From here on every kinematic body is seen where it will be after
        // the step, as the character will be: a platform it lands on or is
        // carried past is met there, not a step behind.
        walker.ahead = Some(dt);
        // Riding: the platform under it carries it first (through nothing
        // else; the platform itself moves along with it).
        let mut at = body.position;
        if let Some(ground) = under
            && let Some(b) = self.body(ground.body)
            && b.kind == crate::BodyKind::Kinematic
        {
            at = walker.advance_past(ground.body, at, b.velocity * dt);
        }
        if let Some((pusher, push)) = walker.swept_by_kinematic(body.position, at) {
            // Through anything in the way but the pusher, which ends
            // behind it.
            at = walker.advance_past(pusher, at, push);
        }
        // Crushed: left where it stands, not pushed out through the body
        // that crushes it (once that body is past its middle, the way out
        // was up through it, on top).
        out.crushed = walker.crushing(at).or_else(|| walker.squeezing(at));
        walker.ignored = out.crushed;
        at = walker.push_out(at);
        walker.ignored = None;
        let mut pushes: Vec<(usize, Vec2, f32)> = Vec::new();
        // On the ground and not jumping, the walk follows the ground: up
        // and down slopes as on the flat, and standing still on a slope
        // it stays put.
        let walking = under.is_some() && translation.y <= 0.0;
        let mut remaining = match under {
            Some(ground) if walking => along_ground(translation, ground.normal, mover),
            _ => translation,
        };
        for _ in 0..4 {
            // (What is left below a micrometre changes nothing seen.)
            if remaining.length_squared() < 1e-12 {
                break;
            }
            let (next, hit) = walker.advance(at, remaining);
            let Some(hit) = hit else {
                at = next;
                break;
            };
            let moved = next - at;
            let left = remaining - moved;
            // (A slope at exactly `max_slope` is ground or wall by
            // rounding.)
            let is_wall = hit.normal.y.abs() < walker.ground_cos;
            // A step is static or kinematic: a dynamic body in the way is
            // pushed, not climbed.
            if is_wall
                && hit.pushable.is_none()
                && under.is_some()
                // (With none, a step up could rise the skin at most, and
                // the feet, a skin up, clear anything that low.)
                && mover.max_step > 0.0
                && let Some((stepped_to, height)) = self.step_up(&walker, next, left)
            {
                at = stepped_to;
                out.stepped = out.stepped.max(height);
                remaining = Vec2::ZERO;
                continue;
            }
            if hit.normal.y <= -walker.ground_cos {
                out.ceiling = Some(hit.body);
            } else if is_wall {
                out.wall = Some(hit.body);
            }
            // Walking into a dynamic body pushes it, once per move, up to
            // the speed this leg of the move wanted towards it.
            // (A cast hits only what the move closes on: never exactly 0.)
            let wanted = -remaining.dot(hit.normal) / dt;
            if let (Some(j), true) = (hit.pushable, wanted > 0.0 && mover.push_mass > 0.0)
                && !pushes.iter().any(|p| p.0 == j)
            {
                pushes.push((j, -hit.normal, wanted));
            }
            at = next;
            remaining = if walking && hit.normal.y >= walker.ground_cos {
                // Onto ground of another slope: along it, at the same pace.
                along_ground(left, hit.normal, mover)
            } else {
                left - hit.normal * left.dot(hit.normal)
            };
        }
        // Following a small drop: it walked off an edge, not jumped. The
        // step moves it in a straight line, so not while that line would
        // cut the corner of a dynamic body (walking off a crate): the
        // crate, caught between it and the ground, would be launched. It
        // falls instead.
        // The ground and the gap down to it.
        let probe = 2.0 * mover.skin;
        let mut ground = walker.ground(at, probe).map(|h| (h, h.fraction * probe));
        if ground.is_none()
            && under.is_some()
            && translation.y <= 0.0
            // (With none, the snap would reach no farther than the probe.)
            && mover.snap_down > 0.0
            && let Some(hit) = walker.ground(at, mover.snap_down + mover.skin)
        {
            let gap = hit.fraction * (mover.snap_down + mover.skin);
            let snapped = Vec2::new(at.x, at.y - (gap - mover.skin).max(0.0));
            if !walker.cuts_dynamic(body.position, snapped - body.position) {
                at = snapped;
                ground = Some((hit, gap.min(mover.skin)));
            }
        }
        // On the ground: the feet exactly a skin above it. A fall that ends
        // nearer than the probe's reach lands (it reported ground above
        // the floor, at the full fall speed), and creeping down by the
        // game's gravity each tick no longer sinks it into the skin. Not
        // while it moves up by its own motion (a jump leaves the ground).
        if translation.y > 0.0 {
            ground = None;
        } else if let Some((_, gap)) = ground {
            // Up by a cast: under a ceiling nearer than the skin, only as
            // far as the ceiling lets it.
            at = if gap >= mover.skin {
                at - Vec2::new(0.0, gap - mover.skin)
            } else {
                walker.advance(at, Vec2::new(0.0, mover.skin - gap)).0
            };
        }
        let ground = ground.map(|(hit, _)| hit);
        out.on_ground = ground.is_some();
        out.ground = ground.map(|h| h.body);
        if let Some(hit) = ground {
            out.ground_normal = hit.normal;
            out.ground_velocity = self.body(hit.body).map_or(Vec2::ZERO, |b| {
                if b.kind == crate::BodyKind::Static {
                    Vec2::ZERO
                } else {
                    b.velocity
                }
            });
        }
        out.on_wall = out.wall.is_some();
        out.on_ceiling = out.ceiling.is_some();
        out.position = at;
        out.translation = at - body.position;
        for (j, direction, wanted) in pushes {
            let target = self.dynamic.meta[j].id;
            // By the closing speed: a body already moving away as fast as
            // the character walks gets nothing more. At most push_mass of
            // impulse per m/s: a light body is pushed up to the speed the
            // character walks, never faster.
            let closing = wanted - self.dynamic.vel.at(j).dot(direction);
            if closing <= 0.0 {
                continue;
            }
            out.pushed += 1;
            let mass = self.dynamic.meta[j].mass.min(mover.push_mass);
            let _ = self.try_apply_impulse(target, direction * (closing * mass));
        }
        // Its contacts now stop what comes at it but push nothing ahead of
        // it: the push above is the whole push (see `character_lead`).
        self.dynamic.meta[i].character = true;
        self.try_set_kinematic_target(id, at, dt)?;
        Ok(out)
    }

    /// Climbs a step blocking a walk of `left` from `at`: up at most
    /// `max_step`, forward, then down onto ground. Returns where it ends and
    /// how high it climbed, or `None` if there is no step to climb there.
    fn step_up(&self, walker: &Walker<'_>, at: Vec2, left: Vec2) -> Option<(Vec2, f32)> {
        let mover = walker.mover;
        // (Below a micrometre across, no walk is blocked by a step.)
        if left.x.abs() < 1e-6 {
            return None;
        }
        // Forward by what is left of the walk, but at least two skins: the
        // character stopped a skin short of the step's face, and a slow
        // walk's few millimetres would not carry it over the edge. A round
        // bottom (a capsule's, a circle's) goes on until its lowest point
        // is over the step's top: resting on the edge it would roll back.
        let (_, radius) = walker.shape.rounded();
        // (A skin less would do as well: a corner a skin from the lowest
        // point is ground to a round bottom.)
        let least = (2.0 * mover.skin).max(radius + mover.skin);
        let forward = Vec2::new(left.x.signum() * left.x.abs().max(least), 0.0);
        let (up, _) = walker.advance(at, Vec2::new(0.0, mover.max_step + mover.skin));
        let (ahead, blocked) = walker.advance(up, forward);
        // (An early out: were it left out, a wall blocking the forward
        // move at once leaves the landing on the ground it left, and the
        // height check below refuses the climb.)
        if blocked.is_some() && (ahead.x - up.x).abs() < mover.skin {
            return None; // still blocked: a wall, not a step
        }
        // (A skin more or less finds the same landing: the step's top
        // lies well inside.)
        let fall = up.y - at.y + mover.skin;
        let landing = walker.ground(ahead, fall)?;
        let drop = landing.fraction * fall - mover.skin;
        let end = Vec2::new(ahead.x, ahead.y - drop.max(0.0));
        let height = end.y - at.y;
        // (A climb of no height is refused by the early out above first.)
        (height > 0.0 && height <= mover.max_step + mover.skin).then_some((end, height))
    }
}
