//! Convex polygons (static and kinematic level geometry) against the
//! shapes that move, all seen as rounded boxes (see [`Shape::rounded`]).
//! A polygon is its edges: apart, the nearest edge gives the contact (its
//! nearest features, as a segment's do); overlapping, the separating axis
//! of least overlap among the edges' normals and x and y.

use crate::geometry::segment::{Line, LineContact, closest_features, contact_points};
use glam::Vec2;

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

    /// Its edges at `p`, as lines (each from a vertex to the next).
    pub(crate) fn edges(&self, p: Vec2) -> impl Iterator<Item = Line> + '_ {
        let v = self.vertices();
        (0..v.len()).map(move |i| Line {
            // Counter-clockwise, so the open side (the left of a → b) is
            // inside: each edge runs backwards, to face out.
            a: p + v[(i + 1) % v.len()],
            b: p + v[i],
            chain: false,
            before: None,
            after: None,
        })
    }

    /// Whether `point` is inside (or on) the polygon at `p`.
    pub(crate) fn contains(&self, p: Vec2, point: Vec2) -> bool {
        self.edges(p).all(|e| (point - e.a).dot(e.normal()) <= 0.0)
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

/// The contact between polygon `poly` at `p` (A) and a rounded box (B:
/// core half extents `k`, radius `r`) centred at `c`; the normal points
/// from the polygon to the shape.
pub(crate) fn collide_polygon(
    poly: &ConvexPolygon,
    p: Vec2,
    (k, r): (Vec2, f32),
    c: Vec2,
) -> LineContact {
    // The separating axis of least overlap between the polygon and the
    // core: each edge's outward normal, then x and y.
    let mut best: Option<(f32, Vec2, Option<Line>)> = None;
    let mut consider = |s: f32, n: Vec2, edge: Option<Line>| {
        if best.is_none_or(|(b, ..)| s > b) {
            best = Some((s, n, edge));
        }
    };
    for edge in poly.edges(p) {
        let n = edge.normal();
        let reach = k.x * n.x.abs() + k.y * n.y.abs();
        consider((c - edge.a).dot(n) - reach, n, Some(edge));
    }
    let v = poly.vertices();
    for axis in 0..2 {
        let (lo, hi) = v
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), q| {
                (lo.min(p[axis] + q[axis]), hi.max(p[axis] + q[axis]))
            });
        let mut n = Vec2::ZERO;
        if c[axis] >= 0.5 * (lo + hi) {
            n[axis] = 1.0;
            consider(c[axis] - k[axis] - hi, n, None);
        } else {
            n[axis] = -1.0;
            consider(lo - (c[axis] + k[axis]), n, None);
        }
    }
    let (axis_separation, n, edge) = best.expect("a polygon has edges");
    if axis_separation > 0.0 {
        // Apart: the nearest edge, by its nearest features (an edge the
        // core touches, within rounding, leaves it to the axis).
        let mut nearest: Option<(f32, Vec2, Line)> = None;
        let mut touching = false;
        for e in poly.edges(p) {
            match closest_features(&e, k, c) {
                None => touching = true,
                Some((d, m, _)) if nearest.is_none_or(|(b, ..)| d < b) => nearest = Some((d, m, e)),
                Some(_) => {}
            }
        }
        if let (Some((distance, m, e)), false) = (nearest, touching) {
            return contact_points(&e, k, r, c, m, distance - r);
        }
    }
    match edge {
        Some(e) => contact_points(&e, k, r, c, n, axis_separation - r),
        // Along x or y: the polygon's vertex deepest into the shape.
        None => {
            let deepest = v
                .iter()
                .map(|q| p + *q)
                .max_by(|x, y| x.dot(n).total_cmp(&y.dot(n)))
                .expect("a polygon has vertices");
            let separation = axis_separation - r;
            LineContact::one(n, separation, deepest + n * (0.5 * separation))
        }
    }
}
