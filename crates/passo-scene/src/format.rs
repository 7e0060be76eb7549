//! The scene file format: what a RON scene may say, its defaults, and
//! parsing with precise errors (the allowed ranges are checked in
//! `validate`).

use crate::error::{SceneError, closest};
use crate::map_ref::PlatformPath;
use passo_physics::constants::{
    DEFAULT_DRAG_AREA, DEFAULT_FRICTION, DEFAULT_MAX_SPEED, DEFAULT_MIN_SPEED,
};
use passo_physics::glam::Vec2;
use passo_physics::{
    BodyKind, CentralGravity, CollisionFilter, ContactSettings, ForceForm, ForceZone, FrictionMix,
    Integrator, JointMotor, LinearDrag, QuadraticDrag, Shape, Spring, SurfaceFriction,
};
use ron::extensions::Extensions;
use serde::{Deserialize, Serialize};

/// Most bodies a scene may make (explicit and generated together).
pub const MAX_BODIES: usize = 1_000_000;

/// Most joints a scene may list.
pub const MAX_SCENE_JOINTS: usize = 1_000_000;

/// A whole scene file. Only `name` is required.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Shown in the demo's scene list.
    pub name: String,
    /// One or two sentences on what the scene shows. Default empty.
    #[serde(default)]
    pub description: String,
    /// Fixed ticks per second, in [1, 10000]. Default 60.
    #[serde(default = "default_rate")]
    pub rate_hz: f64,
    /// Time-stepping method. Default `SemiImplicitEuler`.
    #[serde(default)]
    pub integrator: Integrator,
    /// `Stable` (default) or `Explicit` drag and friction.
    #[serde(default)]
    pub force_form: ForceForm,
    /// The force models the scene uses; each is off unless listed.
    #[serde(default)]
    pub forces: Forces,
    /// Collisions and their solver settings (substeps, iterations, ...);
    /// absent means bodies never touch.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub collisions: Option<ContactSettings>,
    /// Below this speed a velocity snaps to zero, m/s, >= 0. Default 0.001.
    #[serde(default = "default_min_speed")]
    pub min_speed: f32,
    /// Speeds are clamped to this, m/s, > 0 (`inf` for none). Default 1000.
    #[serde(default = "default_max_speed")]
    pub max_speed: f32,
    /// Whether the world keeps each body's previous position, so a game
    /// can draw between ticks with `World::interpolated_position`. Default
    /// `false`.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub interpolation: bool,
    /// The region to show; absent fits every body.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<Camera>,
    /// Bodies listed one by one (at most [`MAX_BODIES`]).
    #[serde(default, deserialize_with = "at_most_max_bodies")]
    pub bodies: Vec<BodySpec>,
    /// Bodies made by pattern.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub generators: Vec<Generator>,
    /// Sloped ground: chains of one-sided segments that meet smoothly.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub chains: Vec<ChainSpec>,
    /// A level on a grid: a Tiled map or ASCII art (see [`TileMapRef`](crate::TileMapRef)).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tilemap: Option<crate::map_ref::TileMapRef>,
    /// Joints between named bodies (at most [`MAX_SCENE_JOINTS`]). They
    /// need `collisions`.
    #[serde(
        default,
        skip_serializing_if = "Vec::is_empty",
        deserialize_with = "at_most_max_joints"
    )]
    pub joints: Vec<JointSpec>,
}

/// A joint between two named bodies of the scene, or a named body and the
/// world.
///
/// ```ron
/// joints: [
///     // A rope from the ceiling: as long as the bodies are placed apart.
///     (a: "lamp", b: Some("ceiling"), kind: Rope()),
///     // A sliding door driven up at 1 m/s with at most 400 N.
///     (a: "frame", b: Some("door"), kind: Slider(axis: (0, 1), limits: Some((0, 2)),
///         motor: Some((speed: 1, max_force: 400)))),
/// ]
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointSpec {
    /// The first body's name.
    pub a: String,
    /// The second body's name, or none for the world (then `anchor_b` is a
    /// point of the world).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub b: Option<String>,
    /// Where the joint holds A: an offset from its centre, m. Default (0, 0).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub anchor_a: Vec2,
    /// Where it holds B: an offset from its centre, or a point of the world
    /// with no `b`. Default (0, 0).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub anchor_b: Vec2,
    /// What it holds.
    pub kind: JointSpecKind,
    /// Breaks above this force, N. Default: never.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub break_force: Option<f32>,
    /// The two bodies still collide with each other. Default false.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub collide: bool,
}

fn is_zero(v: &Vec2) -> bool {
    *v == Vec2::ZERO
}

/// What a scene joint holds. A length left out is the distance between the
/// anchors as the bodies are placed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum JointSpecKind {
    /// A rigid rod.
    Rod {
        /// Length, m. Default: as placed.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        length: Option<f32>,
    },
    /// A rope: at most `length` apart, free to come closer.
    Rope {
        /// Longest, m. Default: as placed.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        length: Option<f32>,
    },
    /// A spring toward `length`, with optional limits.
    Spring {
        /// Rest length, m. Default: as placed.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        length: Option<f32>,
        /// Frequency, Hz, >= 0.
        hertz: f32,
        /// Damping ratio, >= 0. Default 0.
        #[serde(default)]
        damping_ratio: f32,
        /// Shortest and longest, m. Default: none.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        limits: Option<(f32, f32)>,
    },
    /// A slider along `axis`.
    Slider {
        /// The direction of travel.
        axis: Vec2,
        /// Least and most travel, m. Default: none.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        limits: Option<(f32, f32)>,
        /// A motor. Default: none.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        motor: Option<JointMotor>,
    },
    /// The bodies held as placed, rigidly or by a spring.
    Weld {
        /// A spring's frequency, Hz; 0 (the default) is rigid.
        #[serde(default)]
        hertz: f32,
        /// Its damping ratio. Default 0.
        #[serde(default)]
        damping_ratio: f32,
    },
}

/// Reads `joints`, refusing the list as soon as it holds more than
/// [`MAX_SCENE_JOINTS`].
fn at_most_max_joints<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<JointSpec>, D::Error> {
    at_most(d, MAX_SCENE_JOINTS, "joints")
}

/// Reads `bodies`, refusing the list as soon as it holds more than
/// [`MAX_BODIES`]: a file of ten million `()` (30 MB) took 1.5 GB to read
/// before its count was checked.
fn at_most_max_bodies<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<BodySpec>, D::Error> {
    at_most(d, MAX_BODIES, "bodies")
}

/// Reads the list `what`, refusing it as soon as it holds more than `max`
/// entries (before reading the rest).
fn at_most<'de, D, T>(d: D, max: usize, what: &'static str) -> Result<Vec<T>, D::Error>
where
    D: serde::Deserializer<'de>,
    T: Deserialize<'de>,
{
    struct Bounded<T> {
        max: usize,
        what: &'static str,
        entries: std::marker::PhantomData<T>,
    }
    impl<'de, T: Deserialize<'de>> serde::de::Visitor<'de> for Bounded<T> {
        type Value = Vec<T>;

        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            write!(f, "a list of at most {} {}", self.max, self.what)
        }

        fn visit_seq<A: serde::de::SeqAccess<'de>>(
            self,
            mut seq: A,
        ) -> Result<Self::Value, A::Error> {
            let (max, what) = (self.max, self.what);
            let mut entries = Vec::new();
            while let Some(entry) = seq.next_element()? {
                if entries.len() == max {
                    return Err(serde::de::Error::custom(format!(
                        "`{what}` lists more than {max} {what}; at most {max} are allowed"
                    )));
                }
                entries.push(entry);
            }
            Ok(entries)
        }
    }
    d.deserialize_seq(Bounded {
        max,
        what,
        entries: std::marker::PhantomData,
    })
}

fn default_rate() -> f64 {
    60.0
}
fn default_min_speed() -> f32 {
    DEFAULT_MIN_SPEED
}
fn default_max_speed() -> f32 {
    DEFAULT_MAX_SPEED
}

/// Force models. Unlike the physics API (gravity on by default), a scene
/// switches on only what it lists.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Forces {
    /// Gravitational acceleration, m/s², e.g. `(0, -9.81)`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gravity: Option<Vec2>,
    /// Quadratic drag, `(density: 1.225)` kg/m³.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub quadratic_drag: Option<QuadraticDrag>,
    /// Linear drag, `(coefficient: b)` kg/s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub linear_drag: Option<LinearDrag>,
    /// Air velocity (wind) that both drags act relative to, m/s. Default (0, 0).
    pub wind: Vec2,
    /// Top-down friction, `(gravity: 9.81)` m/s².
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surface_friction: Option<SurfaceFriction>,
    /// A constant force on every dynamic body, N.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub force_field: Option<Vec2>,
    /// A spring to an anchor, `(anchor: (x, y), stiffness: k)`, N/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spring: Option<Spring>,
    /// Attraction to a centre, `(centre: (x, y), gm: GM)`, m³/s².
    #[serde(skip_serializing_if = "Option::is_none")]
    pub central_gravity: Option<CentralGravity>,
}

/// The region the camera shows at first, metres.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    /// Lower-left corner.
    pub min: Vec2,
    /// Upper-right corner.
    pub max: Vec2,
}

/// A chain of segments in a scene: static ground that slopes (see
/// `passo_physics::ChainDef`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChainSpec {
    /// A name for the demo and for game code, given to every segment.
    /// Default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The points, metres, in order: solid on the right of the way they
    /// go (ground drawn left to right is solid below). At least 2.
    pub points: Vec<Vec2>,
    /// Whether the last point joins the first. Default `false`.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub closed: bool,
    /// `Static` (default) or `Kinematic`.
    #[serde(default = "static_kind")]
    pub kind: BodyKind,
    /// Friction and restitution (drag does not apply). Default as a body's.
    #[serde(default)]
    pub material: Material,
    /// sRGB colour. Default: the static grey.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub colour: Option<Colour>,
}

fn static_kind() -> BodyKind {
    BodyKind::Static
}

/// Material of a body.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Material {
    /// Bounciness in [0, 1]. Default 0.
    pub restitution: f32,
    /// Friction coefficient, >= 0. Default 0.6.
    pub friction: f32,
    /// Drag area `Cd A`, m², >= 0. Default 0.1.
    pub drag_area: f32,
    /// How the friction combines with another body's in a contact:
    /// `GeometricMean` (default), `Average`, `Min` (ice), `Multiply` or
    /// `Max`; the later rule of the two bodies wins.
    #[serde(skip_serializing_if = "is_default_mix")]
    pub friction_mix: FrictionMix,
}

fn is_default_mix(mix: &FrictionMix) -> bool {
    *mix == FrictionMix::default()
}

impl Default for Material {
    fn default() -> Self {
        Self {
            restitution: 0.0,
            friction: DEFAULT_FRICTION,
            drag_area: DEFAULT_DRAG_AREA,
            friction_mix: FrictionMix::default(),
        }
    }
}

/// An sRGB colour with alpha, written `"#rrggbb"` or `"#rrggbbaa"`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Colour(pub [u8; 4]);

impl Colour {
    /// Parses `#rrggbb` or `#rrggbbaa`.
    pub fn parse(text: &str) -> Option<Self> {
        let hex = text.strip_prefix('#')?;
        // Hex digits only (`from_str_radix` would take a `+` sign too).
        if !(hex.len() == 6 || hex.len() == 8) || !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
            return None;
        }
        let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok();
        let alpha = if hex.len() == 8 { byte(6)? } else { 255 };
        Some(Self([byte(0)?, byte(2)?, byte(4)?, alpha]))
    }

    /// `#rrggbb`, or `#rrggbbaa` when not opaque.
    pub fn to_hex(self) -> String {
        let [r, g, b, a] = self.0;
        if a == 255 {
            format!("#{r:02x}{g:02x}{b:02x}")
        } else {
            format!("#{r:02x}{g:02x}{b:02x}{a:02x}")
        }
    }
}

impl Serialize for Colour {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.to_hex())
    }
}

impl<'de> Deserialize<'de> for Colour {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let text = String::deserialize(d)?;
        Self::parse(&text).ok_or_else(|| {
            serde::de::Error::custom(format!(
                "colour must be \"#rrggbb\" or \"#rrggbbaa\" (hex digits), got {text:?}"
            ))
        })
    }
}

/// One body. Everything has a default: `()` is a 1 kg dynamic point mass at
/// the origin.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BodySpec {
    /// A name for the demo and for game code. Default none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// `Dynamic` (default), `Static` or `Kinematic` (moved by its
    /// `velocity` alone: a moving platform).
    pub kind: BodyKind,
    /// `Circle(radius: r)` or `Box(half_extents: (hx, hy))`, metres. Default
    /// none: a point mass that touches nothing.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shape: Option<Shape>,
    /// Mass, kg, > 0. Give `mass` or `density`, not both. Default 1 kg.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mass: Option<f32>,
    /// Area density, kg/m², > 0: mass = density × shape area.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub density: Option<f32>,
    /// Position of the centre, m (an offset from the pattern's place in a
    /// generator). Default (0, 0).
    pub position: Vec2,
    /// Velocity, m/s. Default (0, 0).
    pub velocity: Vec2,
    /// Restitution, friction and drag area.
    pub material: Material,
    /// Drawing colour. Default: grey for static bodies, a palette colour
    /// for dynamic ones.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub colour: Option<Colour>,
    /// A sensor reports overlaps and pushes nothing. Default false.
    pub sensor: bool,
    /// A one-way platform (static or kinematic): the outward normal of its
    /// solid side, e.g. `(0, 1)`. Default none (solid from every side).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub one_way: Option<Vec2>,
    /// A dynamic body swept against every other body when it moves faster
    /// than its contacts reach (a projectile). Default false.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub bullet: bool,
    /// A kinematic body's back-and-forth path (a moving platform, a lift).
    /// Default none (it keeps its `velocity`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub path: Option<PlatformPath>,
    /// Collision layers and mask. Default: layer 1, collides with all.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub filter: Option<CollisionFilter>,
    /// Own minimum speed, m/s, >= 0. Default: the scene's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_speed: Option<f32>,
    /// Own maximum speed, m/s, > 0. Default: the scene's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_speed: Option<f32>,
    /// A conveyor belt: the velocity its surface moves at, m/s; what
    /// touches it is carried along. Default none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub conveyor: Option<Vec2>,
    /// Share of the scene's gravity, in [-1000, 1000]. Default 1.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gravity_scale: Option<f32>,
    /// Makes a sensor box a force zone: its own gravity, wind, drag or a
    /// liquid, e.g. `zone: Some((liquid: Some((density: 6, drag: 3))))`.
    /// Default none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub zone: Option<ForceZone>,
}

/// Patterns that make many bodies from one template `body`, whose
/// `position` is added to each generated place.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Generator {
    /// `columns × rows` bodies, the first at `origin`, `spacing` apart.
    Grid {
        /// Centre of the first body, m.
        origin: Vec2,
        /// Bodies per row, >= 1.
        columns: u32,
        /// Rows, >= 1.
        rows: u32,
        /// Distance between centres along x and y, m.
        spacing: Vec2,
        /// The template.
        body: BodySpec,
    },
    /// A pyramid of `base` bodies at the bottom, one fewer per row, resting
    /// on `origin` (the bottom centre). Bodies are placed edge to edge by
    /// their shape's size plus `gap`.
    Pyramid {
        /// Bodies in the bottom row, >= 1.
        base: u32,
        /// Bottom centre of the pyramid, m.
        origin: Vec2,
        /// Horizontal gap between neighbours, m, >= 0. Default 0.
        #[serde(default)]
        gap: f32,
        /// The template (needs a shape).
        body: BodySpec,
    },
    /// `count` bodies on a grid of `columns` columns from `origin`,
    /// `spacing` apart, each moved by a random offset of up to `jitter` m
    /// along x and y (seeded: the same seed gives the same scene).
    Rain {
        /// Number of bodies.
        count: u32,
        /// Centre of the first place, m.
        origin: Vec2,
        /// Places per row, >= 1.
        columns: u32,
        /// Distance between places, m.
        spacing: Vec2,
        /// Largest random offset, m, >= 0. Default 0.
        #[serde(default)]
        jitter: f32,
        /// Random seed. Default 1.
        #[serde(default = "default_seed")]
        seed: u64,
        /// The template.
        body: BodySpec,
    },
}

fn default_seed() -> u64 {
    1
}

impl Generator {
    /// How many bodies the pattern makes.
    pub fn count(&self) -> u64 {
        match self {
            Self::Grid { columns, rows, .. } => u64::from(*columns) * u64::from(*rows),
            Self::Pyramid { base, .. } => u64::from(*base) * (u64::from(*base) + 1) / 2,
            Self::Rain { count, .. } => u64::from(*count),
        }
    }
}

/// Parses scene text, turning RON errors into messages with line, column
/// and field.
pub(crate) fn parse(text: &str, source: &str) -> Result<SceneFile, SceneError> {
    ron::Options::default()
        .with_default_extension(Extensions::IMPLICIT_SOME)
        .from_str(text)
        .map_err(|e| syntax_error(&e, text, source))
}

fn syntax_error(e: &ron::error::SpannedError, text: &str, source: &str) -> SceneError {
    use ron::Error as E;
    let start = e.span.start;
    let within = |outer: &Option<String>| {
        outer
            .as_ref()
            .map(|o| format!(" in `{o}`"))
            .unwrap_or_default()
    };
    let (field, message) = match &e.code {
        E::NoSuchStructField {
            expected,
            found,
            outer,
        } => {
            let hint = match closest(found, expected) {
                Some(best) => format!("did you mean `{best}`? "),
                None => String::new(),
            };
            (
                Some(found.clone()),
                format!(
                    "unknown field `{found}`{}; {hint}valid fields: {}",
                    within(outer),
                    expected.join(", ")
                ),
            )
        }
        E::NoSuchEnumVariant {
            expected,
            found,
            outer,
        } => {
            let hint = match closest(found, expected) {
                Some(best) => format!("did you mean `{best}`? "),
                None => String::new(),
            };
            (
                field_before(text, start.line, start.col),
                format!(
                    "unknown variant `{found}`{}; {hint}valid variants: {}",
                    within(outer),
                    expected.join(", ")
                ),
            )
        }
        E::MissingStructField { field, outer } => (
            Some((*field).to_owned()),
            format!("missing field `{field}`{}", within(outer)),
        ),
        E::DuplicateStructField { field, outer } => (
            Some((*field).to_owned()),
            format!("field `{field}` given twice{}", within(outer)),
        ),
        other => (field_before(text, start.line, start.col), other.to_string()),
    };
    SceneError::Syntax {
        source_name: source.to_owned(),
        line: start.line,
        column: start.col,
        field,
        message,
    }
}

/// The last `identifier:` before a 1-based line and column: the field whose
/// value was being read.
fn field_before(text: &str, line: usize, col: usize) -> Option<String> {
    let mut offset = 0;
    for (i, l) in text.split_inclusive('\n').enumerate() {
        if i + 1 == line {
            offset += l
                .char_indices()
                .nth(col.saturating_sub(1))
                .map_or(l.len(), |(b, _)| b);
            break;
        }
        offset += l.len();
    }
    let before = &text[..offset.min(text.len())];
    let bytes = before.as_bytes();
    let mut i = bytes.len();
    while i > 0 {
        i -= 1;
        if bytes[i] != b':' {
            continue;
        }
        let mut end = i;
        while end > 0 && bytes[end - 1].is_ascii_whitespace() {
            end -= 1;
        }
        let mut begin = end;
        while begin > 0 && (bytes[begin - 1].is_ascii_alphanumeric() || bytes[begin - 1] == b'_') {
            begin -= 1;
        }
        if begin < end && !bytes[begin].is_ascii_digit() {
            return Some(before[begin..end].to_owned());
        }
    }
    None
}

/// The scene as pretty RON, readable back by [`parse`].
pub(crate) fn to_ron(file: &SceneFile) -> String {
    let config = ron::ser::PrettyConfig::new()
        .struct_names(false)
        .extensions(Extensions::IMPLICIT_SOME);
    ron::ser::to_string_pretty(file, config).expect("a scene always serializes")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error(text: &str) -> String {
        crate::Scene::parse(text, "test.ron")
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn the_smallest_scene_takes_every_default() {
        let scene = crate::Scene::parse("(name: \"empty\")", "test.ron").unwrap();
        assert_eq!(scene.file.rate_hz, 60.0);
        assert_eq!(scene.file.forces, Forces::default());
        assert!(scene.file.collisions.is_none());
        assert!(scene.file.bodies.is_empty());
    }

    #[test]
    fn syntax_errors_name_line_column_and_field() {
        let text = "(\n    name: \"x\",\n    rate_hz: 60,\n    bodies: [(mass: \"heavy\")],\n)";
        assert_eq!(
            error(text),
            "test.ron:4:20: in field `mass`: Expected float"
        );
        let text = "(\n  name: \"x\",\n  bodies: [(position: (0, 1)]\n)";
        let msg = error(text);
        assert!(msg.starts_with("test.ron:3:"), "{msg}");
    }

    #[test]
    fn unknown_fields_suggest_the_closest_valid_one() {
        let msg = error("(name: \"x\", bodies: [(mas: 2)])");
        assert!(msg.contains("unknown field `mas`"), "{msg}");
        assert!(msg.contains("did you mean `mass`?"), "{msg}");
        assert!(msg.starts_with("test.ron:1:"), "{msg}");
        let msg = error("(name: \"x\", rate: 30)");
        assert!(msg.contains("did you mean `rate_hz`?"), "{msg}");
        let msg = error("(name: \"x\", integrator: Rk5)");
        assert!(msg.contains("unknown variant `Rk5`"), "{msg}");
        assert!(msg.contains("did you mean `Rk4`?"), "{msg}");
        assert!(error("(description: \"no name\")").contains("missing field `name`"));
    }

    #[test]
    fn values_out_of_range_name_the_field_and_the_range() {
        // One body more than a scene may have, each `()`: refused while read.
        let many = format!("(name: \"x\", bodies: [{}])", "(),".repeat(MAX_BODIES + 1));
        let cases = [
            (
                "(name: \"x\", rate_hz: 0)",
                "`rate_hz` must be in [1, 10000] Hz, got 0.0",
            ),
            (
                "(name: \"x\", rate_hz: 1e-300)",
                "`rate_hz` must be in [1, 10000] Hz, got 1e-300",
            ),
            (
                "(name: \"x\", bodies: [(), (mass: -1)])",
                "`bodies[1].mass` must be > 0 kg, got -1",
            ),
            (
                "(name: \"x\", bodies: [(shape: Circle(radius: 0))])",
                "`bodies[0].shape.radius` must be > 0 m, got 0",
            ),
            (
                "(name: \"x\", bodies: [(material: (restitution: 1.5))])",
                "`bodies[0].material.restitution` must be in [0, 1], got 1.5",
            ),
            (
                "(name: \"x\", bodies: [(position: (inf, 0))])",
                "`bodies[0].position` must be finite, got (inf, 0)",
            ),
            (
                "(name: \"x\", bodies: [(mass: NaN)])",
                "`bodies[0].mass` must be finite (> 0 kg), got NaN",
            ),
            (
                "(name: \"x\", bodies: [(mass: 1, density: 2)])",
                "`bodies[0]` gives both `mass` and `density`; give one",
            ),
            (
                "(name: \"x\", collisions: (substeps: 0))",
                "`collisions.substeps` must be in [1, 64], got 0",
            ),
            (
                "(name: \"x\", collisions: (substeps: 65))",
                "`collisions.substeps` must be in [1, 64], got 65",
            ),
            (
                "(name: \"x\", generators: [Grid(origin: (0,0), columns: 0, rows: 1, spacing: (1,1), body: ())])",
                "`generators[0].columns` must be >= 1, got 0",
            ),
            (
                "(name: \"x\", generators: [Rain(origin: (0,0), count: 4000000000, columns: 10, spacing: (1,1), body: ())])",
                "`generators` make 4000000000 bodies; at most 1000000 are allowed",
            ),
            (
                &many,
                "`bodies` lists more than 1000000 bodies; at most 1000000 are allowed",
            ),
            (
                "(name: \"x\", bodies: [(colour: \"red\")])",
                "test.ron:1:32: in field `colour`: colour must be \"#rrggbb\" or \"#rrggbbaa\" (hex digits), got \"red\"",
            ),
        ];
        for (text, want) in cases {
            let msg = error(text);
            assert!(msg.ends_with(want), "{text}\n  got:  {msg}\n  want: {want}");
        }
    }

    #[test]
    fn colours_parse_and_print_as_hex() {
        assert_eq!(Colour::parse("#ff8000"), Some(Colour([255, 128, 0, 255])));
        assert_eq!(Colour::parse("#ff800080"), Some(Colour([255, 128, 0, 128])));
        assert_eq!(Colour([1, 2, 3, 255]).to_hex(), "#010203");
        for bad in [
            "ff8000",
            "#ff80",
            "#gg8000",
            "#ff8000ff00",
            "#ééé",
            "#+f+f+f",
            "#-1-1-1",
        ] {
            assert_eq!(Colour::parse(bad), None, "{bad}");
        }
    }
}
