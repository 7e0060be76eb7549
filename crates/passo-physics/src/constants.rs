//! Tuning constants, each with its unit, a typical value and what breaks if it changes.

use glam::Vec2;

/// Standard gravity, metres per second², y up: `(0, -9.81)`.
///
/// The weight of a body is `m * DEFAULT_GRAVITY`.
pub const DEFAULT_GRAVITY: Vec2 = Vec2::new(0.0, -9.81);

/// Density of air at sea level and 15 °C, kilograms per cubic metre.
///
/// Used by quadratic drag `-1/2 rho |v|^2 (Cd A) v_hat`.
pub const AIR_DENSITY: f32 = 1.225;

/// Default minimum speed, metres per second: below it a body's velocity snaps
/// to exactly `(0, 0)` wherever the speed limits act: at the end of the step,
/// and in every substep of the contact step.
///
/// One millimetre per second is invisible at any zoom a game uses and far
/// above the subnormal range: velocities that decay under drag would
/// otherwise end up as subnormal floats, on which the same integration
/// loop runs several times slower. Keep it well under the speed gravity adds in one
/// (sub)step, `g dt / substeps` (0.041 m/s at 60 Hz with the default four
/// substeps; `g dt` without contacts): a body slower than the minimum at the
/// apex of a jump is snapped to rest there, and gravity alone never lifts
/// its speed back over the minimum, so it hangs in the air for good. 0 turns
/// the snap off.
pub const DEFAULT_MIN_SPEED: f32 = 1.0e-3;

/// Default maximum speed, metres per second: a faster body is scaled back to
/// exactly this speed at the end of the step.
///
/// 1000 m/s is faster than any game object that should stay visible, and low
/// enough that a runaway force never overflows a position. Set
/// `f32::INFINITY` to turn the clamp off.
pub const DEFAULT_MAX_SPEED: f32 = 1000.0;

/// Default drag area `Cd * A` of a body, square metres.
///
/// 0.1 m² gives a 1 kg body a terminal speed of 12.7 m/s in air, a lively
/// value for games. 0 makes a body ignore quadratic drag.
pub const DEFAULT_DRAG_AREA: f32 = 0.1;

/// Default friction coefficient `mu` of a body (dimensionless), as in Box2D.
pub const DEFAULT_FRICTION: f32 = 0.6;

/// Largest friction coefficient a body may have: 1000. Real materials stay
/// below 2; the bound keeps `mu * normal impulse` (the friction row's
/// limit) finite for any finite impulse, where two coefficients of 1e20
/// would overflow it to infinity and the limit to NaN.
pub const MAX_FRICTION: f32 = 1.0e3;

/// Farthest a body may be placed from the origin along either axis,
/// metres: 10⁷ (10 000 km). `f32` positions there are 1 m apart, far too
/// coarse for contacts (keep play within a few kilometres: the guide's
/// "Bad input and limits"), and the broad phase's cell indices stay well
/// inside `i32` for any body size. Positions beyond it are refused where
/// they enter (definitions, `set_position`, kinematic targets); a body
/// that flies past it keeps flying, and a snapshot of it loads back (a
/// restored position need only be finite).
pub const MAX_COORDINATE: f32 = 1.0e7;

/// Longest step [`World::step`](crate::World::step) takes, seconds: an
/// hour. Far past any game's step (a fixed-timestep loop runs at 1 Hz or
/// more), and short enough that no finite velocity (its square is finite,
/// so under 2e19 m/s) moves a body from the world's coordinates to an
/// infinite position in fewer than 10¹⁵ steps. A step of 1e38 s sent
/// bodies to infinity in one.
pub const MAX_STEP: f32 = 3600.0;

/// Largest radius or half extent a shape may have, metres: 10⁶.
pub const MAX_SHAPE_SIZE: f32 = 1.0e6;

/// Largest mass a dynamic body may have, kilograms: 10³⁰ (half the Sun).
/// A contact impulse is a mass times a speed; above this, one against a
/// body at the maximum speed could overflow `f32`, and the inverse mass
/// would be subnormal (3e38 kg has 3.3e-39 1/kg), which turns a push into
/// an infinity. Use a static or kinematic body for anything immovable.
pub const MAX_MASS: f32 = 1.0e30;

/// Largest drag area `Cd A` a body may have, square metres: 10⁶ (a square
/// kilometre). Far above any game body; it keeps drag terms finite.
pub const MAX_DRAG_AREA: f32 = 1.0e6;

/// Default surface gravity for top-down friction, metres per second²: the
/// normal force on a body resting on the plane is `m * 9.81`.
pub const DEFAULT_SURFACE_GRAVITY: f32 = 9.81;

/// Allowed penetration, metres: 5 mm (Box2D's `linear slop`).
///
/// Overlap up to this depth is left alone by position correction, so a
/// resting contact does not jitter between touching and apart; deeper
/// overlap is pushed out. Smaller values make stacks jitter, larger values
/// make overlap visible. Also the tolerance for "touching".
pub const LINEAR_SLOP: f32 = 0.005;

/// How far two touching bodies may move relative to each other before
/// their contact is found afresh, metres: the default of
/// [`ContactSettings::reuse_distance`](crate::ContactSettings::reuse_distance),
/// [`LINEAR_SLOP`]. Box2D v3 reuses within ten times its slop; here ten
/// times saved no more time than this (BENCHMARKS.md, "Why the code is
/// shaped this way").
pub const REUSE_DISTANCE: f32 = LINEAR_SLOP;

/// Distance below which contacts are kept before bodies touch, metres:
/// 4 × [`LINEAR_SLOP`] = 2 cm, as in Box2D. Together with each body's
/// travel this step (up to [`SPECULATIVE_REACH`]) it makes contacts
/// speculative, so nothing passes through a thin wall: a wall (static,
/// kinematic or asleep) is met in any direction, two awake dynamic bodies
/// as far as each moves towards the other along the pair's normal.
pub const SPECULATIVE_DISTANCE: f32 = 4.0 * LINEAR_SLOP;

/// How far along its travel a body's speculative contacts reach, in its
/// own smallest half extent: 4 (40 cm for a circle of radius 0.1 m).
///
/// A body's contacts are looked for as far as it can move this step, but
/// no farther than this, so the pairs of a scene stay bounded however fast
/// its bodies move or however long its step (5 000 circles at 100–500 m/s
/// in a box, a rain at 1 Hz). A body that moves farther is swept along its
/// path against static and kinematic bodies (and, as a bullet, against
/// every body) and stopped at its first impact: see
/// [`BodyDef::bullet`](crate::BodyDef::bullet).
pub const SPECULATIVE_REACH: f32 = 4.0;

/// How deep a body may sit in a one-way platform, metres, and still land
/// on it: 2 × [`LINEAR_SLOP`] = 1 cm. A resting body sits up to the slop
/// deep; one deeper was coming through (from below, or dropping through)
/// and goes on through instead of popping up. Raising it makes bodies that
/// jumped nearly through snap up onto the platform.
pub const ONE_WAY_DEPTH: f32 = 2.0 * LINEAR_SLOP;

/// Overlap, metres, that makes a pile deep: 6 × [`LINEAR_SLOP`] = 3 cm,
/// deeper than a resting pile or an ordinary impact gets (a rain of 10 000
/// circles landing peaks at 18 mm).
///
/// In a pile (bodies joined by contacts) holding a contact this deep, each
/// contact's push out of overlap carries on from one substep and step to
/// the next, so the push spreads through the whole pile: 10 000 circles
/// spawned on one spot are apart (no overlap over 1 cm) in about 5 s
/// instead of over 15 s. In every other pile the push starts from nothing
/// each substep, which lets piles come to rest.
pub const DEEP_OVERLAP: f32 = 6.0 * LINEAR_SLOP;

/// Default substeps of a step when contacts are solved: 4. Each substep
/// integrates forces, solves contacts and moves bodies with `dt / 4`; more
/// substeps make tall stacks and large mass ratios stiffer.
pub const DEFAULT_SUBSTEPS: u32 = 4;

/// Default fraction of overlap (beyond the slop) removed per substep: 0.2.
///
/// Higher values separate overlapping bodies faster but let deep piles
/// overshoot and jitter; lower values leave overlap visible for longer.
pub const POSITION_CORRECTION: f32 = 0.2;

/// Default cap on the speed at which overlapping bodies are pushed apart,
/// metres per second: 3. Deep overlap is removed at most this fast, so it
/// takes a few steps instead of one violent jump.
pub const CONTACT_PUSH_SPEED: f32 = 3.0;

/// Default restitution threshold, metres per second: 1. Slower impacts do
/// not bounce, so bouncy bodies come to rest.
pub const RESTITUTION_THRESHOLD: f32 = 1.0;

/// Bodies slower than this, metres per second, count as resting for
/// sleeping: 0.05. Well above the minimum-speed snap (a settled pile sits
/// at exactly zero) and below any motion a player would notice stopping.
pub const SLEEP_SPEED: f32 = 0.05;

/// Seconds every body of an island must rest before it sleeps: 0.5. Long
/// enough that a ball at the top of its bounce or a box changing direction
/// does not stop in mid-air.
pub const TIME_TO_SLEEP: f32 = 0.5;

/// Worlds with at least this many dynamic bodies (or contact pairs) run
/// their per-body stages, broad-phase pair search and narrow phase on
/// rayon's thread pool, with the `parallel` feature. Below it the cost of
/// handing work to threads outweighs the gain. Results are the same bits
/// either way. (Public for tests that check thread counts.)
#[doc(hidden)]
pub const PARALLEL_MIN_ITEMS: usize = 4096;

/// Bodies (or pairs) per parallel task at least: large enough that
/// handing out a task costs little against the work in it. (The loops of
/// `parallel::for_chunks`, over bodies, contacts or pairs, make larger
/// tasks in large worlds: about two a thread.)
#[doc(hidden)]
pub const PARALLEL_CHUNK: usize = 1024;

/// Stiffness of a rigid joint's position correction, hertz: 60, as in
/// Box2D v3, and never above a quarter of the substep rate (a joint of a
/// 60 Hz step with four substeps corrects at 60 Hz, one with one substep
/// at 15 Hz).
///
/// A joint's velocity constraint is exact; its drift is removed by a
/// spring of this frequency during the solve passes and the spring is
/// taken out again in the relax passes (as the contacts' push is), so it
/// adds no energy. Higher corrects faster and rings; lower lets a chain
/// sag and stretch under a heavy load.
pub const JOINT_HERTZ: f32 = 60.0;

/// Damping ratio of a rigid joint's position correction: 2, as in
/// Box2D v3 (over-damped: the drift goes without bounce).
pub const JOINT_DAMPING_RATIO: f32 = 2.0;

/// Most joints a world holds: 2^24 (16 777 216), as many as bodies can be
/// paired in a grid of 4 096 × 4 096. A snapshot from a file holding more is
/// refused before anything is allocated for them.
pub const MAX_JOINTS: usize = 1 << 24;

/// Largest gravity scale a body may have, either way: 1000 (a body under a
/// thousand times the world's gravity, 9.8 km/s² on Earth's).
pub const MAX_GRAVITY_SCALE: f32 = 1000.0;
