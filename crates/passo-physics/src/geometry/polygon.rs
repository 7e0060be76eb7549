//! Convex polygons (static and kinematic level geometry) against the
//! shapes that move, all seen as rounded boxes (see [`Shape::rounded`]).
//! A polygon is its edges: apart, the nearest edge gives the contact (its
//! nearest features, as a segment's do); overlapping, the separating axis
//! of least overlap among the edges' normals and x and y.

use crate::geometry::segment::{Line, LineContact, closest_features, contact_points};
use crate::geometry::shape::ConvexPolygon;
use glam::Vec2;

/// The edges of `poly` at `p`, as lines (each from a vertex to the next).
pub(crate) fn edges(poly: &ConvexPolygon, p: Vec2) -> impl Iterator<Item = Line> + '_ {
    let v = poly.vertices();
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

/// Whether `point` is inside (or on) `poly` at `p`.
pub(crate) fn contains(poly: &ConvexPolygon, p: Vec2, point: Vec2) -> bool {
    edges(poly, p).all(|e| (point - e.a).dot(e.normal()) <= 0.0)
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
    for edge in edges(poly, p) {
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
        for e in edges(poly, p) {
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
