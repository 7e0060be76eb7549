//! Collision shapes: circles, axis-aligned boxes and capsules for every
//! body; segments and chain segments (sloped ground) for static and
//! kinematic ones. Bodies do not rotate.

use glam::Vec2;

/// The shape of a body, centred on its position.
///
/// Bodies do not rotate, so a box stays axis-aligned.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Shape {
    /// A circle (disc) of the given radius, metres.
    Circle {
        /// Radius, metres, > 0.
        radius: f32,
    },
    /// An axis-aligned box with the given half extents, metres.
    Box {
        /// Half the width and half the height, metres, both > 0.
        half_extents: Vec2,
    },
    /// A capsule: two half-circles of `radius` joined by a box, upright or
    /// lying down (it does not rotate). The usual shape of a character: it
    /// slides over the seams and corners a box catches on. Make one with
    /// [`Shape::capsule`].
    Capsule {
        /// Half the straight part between the half-circles' centres,
        /// metres: `(0, h)` for an upright capsule, `(h, 0)` for a lying
        /// one, `h >= 0` (one component is zero).
        half_segment: Vec2,
        /// Radius of the half-circles, metres, > 0.
        radius: f32,
    },
    /// A line segment from `position - half` to `position + half`, solid
    /// from both sides: a thin sloped wall or ramp. Static and kinematic
    /// bodies only (it has no area, so no mass).
    Segment {
        /// Half the segment: from its middle (the body's position) to its
        /// second end, metres; not zero.
        half: Vec2,
    },
    /// One segment of a chain (see [`World::add_chain`](crate::World::add_chain)):
    /// the segment from `position - half` to `position + half`, solid from
    /// one side only, the right of its direction (ground drawn left to
    /// right is solid below), and smooth where it meets its neighbours:
    /// nothing catches on a joint between two segments of a chain. Static
    /// and kinematic bodies only.
    ChainSegment {
        /// Half the segment, as for [`Segment`](Self::Segment).
        half: Vec2,
        /// The chain's point before this segment's first end, relative to
        /// the body's position; `None` where the chain starts.
        before: Option<Vec2>,
        /// The chain's point after this segment's second end, relative to
        /// the body's position; `None` where the chain ends.
        after: Option<Vec2>,
    },
    /// A convex polygon of up to 8 vertices about the body's position
    /// ([`ConvexPolygon::new`]): a rock, a ramp, a wedge. Static and
    /// kinematic bodies only.
    Polygon(ConvexPolygon),
}

impl Shape {
    /// A circle of the given radius, metres.
    pub const fn circle(radius: f32) -> Self {
        Self::Circle { radius }
    }

    /// A box of the given full width and height, metres (the [`Box`]
    /// variant stores half of each: `Shape::rect(2.0, 1.0)` has half
    /// extents `(1.0, 0.5)`).
    ///
    /// [`Box`]: Self::Box
    pub fn rect(width: f32, height: f32) -> Self {
        Self::Box {
            half_extents: Vec2::new(width * 0.5, height * 0.5),
        }
    }

    /// A box of the given half width and half height, metres (what the
    /// [`Box`](Self::Box) variant stores).
    pub const fn from_half_extents(half_width: f32, half_height: f32) -> Self {
        Self::Box {
            half_extents: Vec2::new(half_width, half_height),
        }
    }

    /// A capsule filling a `width` × `height` box, metres: upright when
    /// it is taller than wide (its radius half the width), lying down
    /// otherwise. `Shape::capsule(0.4, 0.8)` is a character 0.8 m tall
    /// with round ends of radius 0.2 m.
    pub fn capsule(width: f32, height: f32) -> Self {
        let radius = 0.5 * width.min(height);
        let half_segment = if height >= width {
            Vec2::new(0.0, 0.5 * height - radius)
        } else {
            Vec2::new(0.5 * width - radius, 0.0)
        };
        Self::Capsule {
            half_segment,
            radius,
        }
    }

    /// A segment between two points relative to the body's position; the
    /// body's position should be their middle: `Shape::segment(a, b)`
    /// ends at `position + (b - a) / 2` and `position - (b - a) / 2`.
    pub fn segment(a: Vec2, b: Vec2) -> Self {
        Self::Segment {
            half: 0.5 * (b - a),
        }
    }

    /// Whether the shape is a line (a segment or a chain segment).
    pub fn is_line(&self) -> bool {
        matches!(self, Self::Segment { .. } | Self::ChainSegment { .. })
    }

    /// Whether only static and kinematic bodies may have the shape: a
    /// line (it has no area), or a polygon (level geometry; moving bodies
    /// are circles, boxes and capsules).
    pub fn is_level_only(&self) -> bool {
        self.is_line() || matches!(self, Self::Polygon(_))
    }

    /// A convex polygon through `points`, relative to the body's position
    /// (see [`ConvexPolygon::new`]).
    ///
    /// # Errors
    /// As [`ConvexPolygon::new`].
    pub fn polygon(points: &[Vec2]) -> Result<Self, crate::PhysicsError> {
        ConvexPolygon::new(points).map(Self::Polygon)
    }

    /// Area in square metres (used to derive mass from density).
    pub fn area(&self) -> f32 {
        match *self {
            Self::Segment { .. } | Self::ChainSegment { .. } => 0.0,
            Self::Polygon(polygon) => polygon.area(),
            Self::Circle { radius } => std::f32::consts::PI * radius * radius,
            Self::Box { half_extents } => 4.0 * half_extents.x * half_extents.y,
            Self::Capsule {
                half_segment,
                radius,
            } => {
                let length = 2.0 * (half_segment.x + half_segment.y);
                std::f32::consts::PI * radius * radius + 2.0 * radius * length
            }
        }
    }

    /// Half extents of the shape's bounding box, metres.
    pub fn half_extents(&self) -> Vec2 {
        match *self {
            Self::Circle { radius } => Vec2::splat(radius),
            Self::Box { half_extents } => half_extents,
            Self::Capsule {
                half_segment,
                radius,
            } => half_segment + Vec2::splat(radius),
            Self::Segment { half } | Self::ChainSegment { half, .. } => half.abs(),
            Self::Polygon(polygon) => polygon.half_extents(),
        }
    }

    /// The shape as a box of half extents `core` grown by `radius` all
    /// round (a rounded box): a circle has no core, a box no radius, and
    /// a capsule's core is its straight part. Every pair of shapes with a
    /// capsule collides and casts in this form.
    #[inline(always)]
    pub(crate) fn rounded(&self) -> (Vec2, f32) {
        match *self {
            Self::Circle { radius } => (Vec2::ZERO, radius),
            Self::Box { half_extents } => (half_extents, 0.0),
            Self::Capsule {
                half_segment,
                radius,
            } => (half_segment, radius),
            // Not a rounded box: every pair with a line has its own case
            // first. As a thin box it is at least the right size.
            Self::Segment { half } | Self::ChainSegment { half, .. } => (half.abs(), 0.0),
            Self::Polygon(polygon) => (polygon.half_extents(), 0.0),
        }
    }

    /// Checks that every size is finite and strictly positive.
    pub(crate) fn validate(&self) -> Result<(), crate::PhysicsError> {
        match *self {
            Self::Circle { radius } => size("Shape::Circle::radius", radius)?,
            Self::Box { half_extents } => {
                size("Shape::Box::half_extents.x", half_extents.x)?;
                size("Shape::Box::half_extents.y", half_extents.y)?
            }
            Self::Capsule {
                half_segment,
                radius,
            } => {
                size("Shape::Capsule::radius", radius)?;
                for (what, value) in [
                    ("Shape::Capsule::half_segment.x", half_segment.x),
                    ("Shape::Capsule::half_segment.y", half_segment.y),
                ] {
                    crate::error::non_negative(what, value)?;
                    size(what, value.max(f32::MIN_POSITIVE))?;
                }
                if half_segment.x > 0.0 && half_segment.y > 0.0 {
                    return Err(crate::PhysicsError::OutOfRange {
                        what: "Shape::Capsule::half_segment",
                        value: half_segment.x.min(half_segment.y),
                        allowed: "one component 0: upright (0, h) or lying (h, 0)",
                    });
                }
                0.0
            }
            Self::Segment { half } => line("Shape::Segment::half", half)?,
            Self::ChainSegment {
                half,
                before,
                after,
            } => {
                line("Shape::ChainSegment::half", half)?;
                for (what, point) in [
                    ("Shape::ChainSegment::before", before),
                    ("Shape::ChainSegment::after", after),
                ] {
                    if let Some(point) = point {
                        crate::error::finite_vec(what, point)?;
                        size(what, point.abs().max_element().max(f32::MIN_POSITIVE))?;
                    }
                }
                0.0
            }
            // Checked when made.
            Self::Polygon(_) => 0.0,
        };
        Ok(())
    }
}

/// A segment's half: finite, not zero, each component at most
/// [`MAX_SHAPE_SIZE`](crate::constants::MAX_SHAPE_SIZE).
fn line(what: &'static str, half: Vec2) -> Result<f32, crate::PhysicsError> {
    crate::error::finite_vec(what, half)?;
    size(what, half.length())
}

/// A size: finite, > 0 and at most [`MAX_SHAPE_SIZE`](crate::constants::MAX_SHAPE_SIZE).
fn size(what: &'static str, value: f32) -> Result<f32, crate::PhysicsError> {
    crate::error::positive(what, value)?;
    if value <= crate::constants::MAX_SHAPE_SIZE {
        Ok(value)
    } else {
        Err(crate::PhysicsError::OutOfRange {
            what,
            value,
            allowed: "at most 1e6 m (MAX_SHAPE_SIZE)",
        })
    }
}

/// Most vertices a polygon has.
pub const MAX_POLYGON_VERTICES: usize = 8;

/// A convex polygon of 3 to [`MAX_POLYGON_VERTICES`] vertices,
/// counter-clockwise, relative to its body's position. Make one with
/// [`ConvexPolygon::new`], which checks it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(try_from = "Vec<Vec2>", into = "Vec<Vec2>")
)]
pub struct ConvexPolygon {
    vertices: [Vec2; MAX_POLYGON_VERTICES],
    count: u8,
}

impl ConvexPolygon {
    /// The polygon through `points` (relative to the body's position), in
    /// either order: stored counter-clockwise.
    ///
    /// # Errors
    /// Fewer than 3 or more than 8 points, a point that is not finite or
    /// farther than [`MAX_SHAPE_SIZE`](crate::constants::MAX_SHAPE_SIZE)
    /// from the position, two points the same, three in a line, or a
    /// polygon that is not convex.
    pub fn new(points: &[Vec2]) -> Result<Self, crate::PhysicsError> {
        let bad = |allowed: &'static str, value: f32| crate::PhysicsError::OutOfRange {
            what: "ConvexPolygon points",
            value,
            allowed,
        };
        let n = points.len();
        if !(3..=MAX_POLYGON_VERTICES).contains(&n) {
            return Err(bad("3 to 8 points", n as f32));
        }
        for p in points {
            crate::error::finite_vec("ConvexPolygon points", *p)?;
            if p.abs().max_element() > crate::constants::MAX_SHAPE_SIZE {
                return Err(bad(
                    "within 1e6 m of the position (MAX_SHAPE_SIZE)",
                    p.abs().max_element(),
                ));
            }
        }
        let mut vertices = [Vec2::ZERO; MAX_POLYGON_VERTICES];
        vertices[..n].copy_from_slice(points);
        // Counter-clockwise: every turn to the left.
        let area: f32 = (0..n)
            .map(|i| vertices[i].perp_dot(vertices[(i + 1) % n]))
            .sum();
        if area < 0.0 {
            vertices[..n].reverse();
        }
        let turn = |i: usize| {
            let (a, b, c) = (vertices[i], vertices[(i + 1) % n], vertices[(i + 2) % n]);
            (b - a).perp_dot(c - b)
        };
        for i in 0..n {
            if vertices[i] == vertices[(i + 1) % n] {
                return Err(bad("no two points the same", i as f32));
            }
            let t = turn(i);
            if t <= 0.0 {
                return Err(bad("convex, with no three points in a line", i as f32));
            }
        }
        Ok(Self {
            vertices,
            count: n as u8,
        })
    }

    /// The vertices, counter-clockwise, relative to the body's position.
    pub fn vertices(&self) -> &[Vec2] {
        &self.vertices[..usize::from(self.count)]
    }

    /// Area, square metres.
    pub fn area(&self) -> f32 {
        let v = self.vertices();
        0.5 * (0..v.len())
            .map(|i| v[i].perp_dot(v[(i + 1) % v.len()]))
            .sum::<f32>()
    }

    /// Half extents of the box about the body's position that holds it.
    pub fn half_extents(&self) -> Vec2 {
        self.vertices()
            .iter()
            .fold(Vec2::ZERO, |h, v| h.max(v.abs()))
    }
}

impl TryFrom<Vec<Vec2>> for ConvexPolygon {
    type Error = crate::PhysicsError;

    fn try_from(points: Vec<Vec2>) -> Result<Self, Self::Error> {
        Self::new(&points)
    }
}

impl From<ConvexPolygon> for Vec<Vec2> {
    fn from(polygon: ConvexPolygon) -> Self {
        polygon.vertices().to_vec()
    }
}
