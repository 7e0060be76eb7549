//! Swept shapes: the time of impact of a shape moved in a straight line
//! against a shape that stays put, exact and in closed form.
//!
//! The Minkowski-sum view: shape A centred at `c` touches shape B exactly
//! when `c` lies on the boundary of B grown by A (B ⊕ −A, centred on B). So
//! sweeping A along `start + t * translation` is casting a ray of A's
//! centre against that grown shape:
//! - circle vs circle: a circle of the summed radius;
//! - circle vs box: the box grown by the radius, its corners rounded (a
//!   quarter circle of the radius about each corner);
//! - box vs circle: the same, seen from the circle (it moves by
//!   `-translation` relative to the box);
//! - box vs box: a box of the summed half extents.
//!
//! Rays are parametrised by the fraction `t` of the translation, never by
//! distance, so no direction is normalised: a tiny or huge translation gives
//! a defined answer, and the fraction comes out without a division by the
//! length.
//!
//! A hit means the path overlaps the target. A path that only grazes it
//! (touches without ever overlapping: tangent to a circle, sliding along a
//! face, meeting a corner point) is no hit, so a box sliding along the top
//! of flush tiles does not catch on the seams between them.

use crate::Shape;
use crate::geometry::manifold::collide;
use crate::geometry::segment::{Line, collide_line, ray_capsule};
use glam::Vec2;

/// The first contact of shape `moving`, starting at `start` and translated
/// by `translation`, with shape `target` at `target_pos` (which does not
/// move).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct CastHit {
    /// How far along the translation the first contact is, in [0, 1]: the
    /// moving shape is then at `start + fraction * translation`.
    pub fraction: f32,
    /// The contact point on the target's surface at that moment, world
    /// space, metres.
    pub point: Vec2,
    /// The target's outward unit normal at the contact, pointing from the
    /// target towards the moving shape.
    pub normal: Vec2,
}

/// The first contact of `moving`, swept from `start` by `translation`, with
/// `target` at `target_pos`, or `None` if the path does not overlap it.
///
/// - Already overlapping at `start`: fraction 0, with the normal along
///   which `moving` would leave and a point of the contact manifold.
/// - Touching at `start` (separation exactly 0): fraction 0 if the motion
///   goes into the target, `None` if it separates or slides along it.
/// - A zero translation is `None` unless already overlapping.
///
/// Every answer is finite for finite inputs, coincident centres included.
pub(crate) fn cast_shape(
    moving: &Shape,
    start: Vec2,
    translation: Vec2,
    target: &Shape,
    target_pos: Vec2,
) -> Option<CastHit> {
    let o = start - target_pos;
    let d = translation;
    if let Some(m) = collide(moving, start, target, target_pos, 0.0) {
        // `collide`'s normal points from A (moving) to B (target): flipped,
        // it is the direction in which the moving shape leaves.
        let normal = -m.normal;
        let enters = m.separation < 0.0 || touching_enters(moving, target, o, d, normal);
        return enters.then_some(CastHit {
            fraction: 0.0,
            point: m.points[0],
            normal,
        });
    }
    if d == Vec2::ZERO {
        return None;
    }
    // Each case gives (fraction, normal, contact point relative to the
    // target's centre).
    let (fraction, normal, point) = match (*moving, *target) {
        (Shape::Circle { radius: ra }, Shape::Circle { radius: rb }) => {
            let (t, n) = ray_circle(o, d, ra + rb)?;
            (t, n, n * rb)
        }
        (Shape::Circle { radius }, Shape::Box { half_extents }) => {
            ray_rounded_box(o, d, half_extents, radius)?
        }
        (Shape::Box { half_extents }, Shape::Circle { radius }) => {
            // Seen from the box, the circle starts at -o and moves by -d:
            // the relative positions along the way, and so the fraction,
            // are the same. The box's normal there points at the circle;
            // the circle's, towards the box, is its opposite.
            let (t, n, _) = ray_rounded_box(-o, -d, half_extents, radius)?;
            // The box's contact point (found with the box standing still)
            // moved by t * d lands on the circle's surface at -n * radius
            // from its centre; take it from there, exactly on the surface.
            (t, -n, -n * radius)
        }
        (Shape::Box { half_extents: ha }, Shape::Box { half_extents: hb }) => {
            ray_box_box(o, d, ha, hb)?
        }
        // A line standing still, the other shape moving onto it; or a line
        // moving onto the other shape, which is the other shape moving the
        // opposite way onto the line where it starts.
        (_, Shape::Segment { .. } | Shape::ChainSegment { .. } | Shape::Polygon(_)) => {
            if moving.is_level_only() {
                return None;
            }
            let (t, normal, point) = cast_level(moving.rounded(), start, d, target, target_pos)?;
            (t, normal, point - target_pos)
        }
        (Shape::Segment { .. } | Shape::ChainSegment { .. } | Shape::Polygon(_), _) => {
            let (t, normal, point) = cast_level(target.rounded(), target_pos, -d, moving, start)?;
            // That point moved with the target; back where the target is.
            (t, -normal, point + d * t - target_pos)
        }
        // A pair with a capsule: the Minkowski sum of two rounded boxes is
        // the rounded box of their cores' sum and their radii's sum.
        _ => {
            let ((ka, ra), (kb, rb)) = (moving.rounded(), target.rounded());
            let (t, normal, _) = ray_rounded_box(o, d, ka + kb, ra + rb)?;
            // On the target: its core's point nearest the moving shape's
            // centre, on the face the normal leaves by, out by its radius.
            let mut point = (o + d * t).clamp(-kb, kb);
            for axis in 0..2 {
                if normal[axis].abs() == 1.0 {
                    point[axis] = normal[axis] * kb[axis];
                }
            }
            (t, normal, point + normal * rb)
        }
    };
    Some(CastHit {
        fraction,
        point: target_pos + point,
        normal,
    })
}

/// Whether shapes that touch (separation exactly 0, `o` the moving centre
/// relative to the target's, `normal` out of the target) overlap as soon
/// as the moving one moves by `d`.
fn touching_enters(moving: &Shape, target: &Shape, o: Vec2, d: Vec2, normal: Vec2) -> bool {
    match (*moving, *target) {
        // The Minkowski box has corners: at a corner both faces are
        // touched, and the motion must go in through both (moving along
        // one face from the corner only slides).
        (Shape::Box { half_extents: ha }, Shape::Box { half_extents: hb }) => {
            let h = ha + hb;
            (0..2).all(|axis| o[axis].abs() < h[axis] || o[axis] * d[axis] < 0.0)
        }
        // The grown shape is smooth (round corners): in through the tangent.
        _ => d.dot(normal) < 0.0,
    }
}

/// The first `t` in [0, 1] at which `o + t d` enters the disc of radius
/// `r` about the origin, and the outward normal there; `None` if the path
/// misses, only grazes, or stops short of it.
fn ray_circle(o: Vec2, d: Vec2, r: f32) -> Option<(f32, Vec2)> {
    // |o + t d|^2 = r^2  <=>  a t^2 + 2 b t + c = 0 with a = d.d, b = o.d,
    // c = o.o - r^2. From outside (c > 0) the path enters only heading
    // inwards (b < 0) and crossing the circle rather than touching it
    // (discriminant b^2 - a c > 0).
    // - Written so, the discriminant subtracts two numbers of size
    //   |o|^2 |d|^2 and loses most digits when the path nearly grazes a
    //   small circle from afar. Lagrange's identity (o.d)^2 + (o x d)^2 =
    //   |o|^2 |d|^2 turns it into a r^2 - (o x d)^2: (|d| r)^2 against
    //   (|d| times the path's distance from the centre)^2, numbers of the
    //   circle's size.
    // - The first root (-b - sqrt(disc)) / a loses its digits when c is
    //   small (starting near the surface), so take it as
    //   c / (-b + sqrt(disc)) (the roots multiply to c / a): a sum of two
    //   positives, never 0/0.
    let a = d.length_squared();
    let b = o.dot(d);
    let c = o.length_squared() - r * r;
    let t = if c > 0.0 {
        let cross = o.perp_dot(d);
        let disc = a * (r * r) - cross * cross;
        if disc > 0.0 {
            c / (-b + disc.sqrt())
        } else {
            // Passing by, or tangent: never inside.
            f32::INFINITY
        }
    } else {
        // On the circle (or inside by rounding).
        0.0
    };
    // Comparisons false for NaN (from non-finite input) give `None` too.
    (b < 0.0 && t <= 1.0).then(|| (t, (o + d * t).normalize_or(Vec2::Y)))
}

/// The first `t` in [0, 1] at which `o + t d` enters the box `[-h, h]`,
/// and the outward normal of the face it enters through (zero if it starts
/// inside); `None` if the path misses, only grazes (slides along a face,
/// meets a corner point) or stops short of it.
fn ray_box(o: Vec2, d: Vec2, h: Vec2) -> Option<(f32, Vec2)> {
    // Slabs: along each axis the path is strictly inside |o + t d| < h for
    // t in an open interval (near, far). The box is entered at the latest
    // near time, if that comes before the earliest far time; the axis of
    // that latest entry is the face. On a tie (a corner) take y, as
    // `manifold` does.
    let mut near = [f32::NEG_INFINITY; 2];
    let mut far = f32::INFINITY;
    for axis in 0..2 {
        if d[axis] == 0.0 {
            // Parallel to the slab: inside it throughout or never.
            if o[axis].abs() >= h[axis] {
                return None;
            }
            continue;
        }
        // Divide, not multiply by 1 / d: a subnormal d makes 1 / d infinite
        // and 0 * inf NaN.
        let side = h[axis].copysign(d[axis]);
        near[axis] = (-side - o[axis]) / d[axis];
        far = far.min((side - o[axis]) / d[axis]);
    }
    let axis = if near[0] > near[1] { 0 } else { 1 };
    let t = near[axis].max(0.0);
    let mut normal = Vec2::ZERO;
    if near[axis] >= 0.0 {
        normal[axis] = -(1.0f32.copysign(d[axis]));
    }
    (t < far && t <= 1.0).then_some((t, normal))
}

/// The first contact of a rounded box (core `k`, radius `r`) starting at
/// `o` and moving by `d` with `line`, for `t` in `[0, 1]`: `(t, normal
/// out of the line, point)`. Exact: the line's ends meeting the rounded
/// box, and the core's corners (grown by `r`) meeting the line. The
/// shapes are apart at `o`. A hit the line does not allow (behind a chain
/// segment, at a joint its neighbour owns) is no hit.
/// [`cast_line`] against a line or a polygon (`level`, at `at`): a
/// polygon is met first at one of its edges.
fn cast_level(
    rounded: (Vec2, f32),
    o: Vec2,
    d: Vec2,
    level: &Shape,
    at: Vec2,
) -> Option<(f32, Vec2, Vec2)> {
    match level {
        Shape::Polygon(polygon) => crate::geometry::polygon::edges(polygon, at)
            .filter_map(|edge| cast_line(rounded, o, d, &edge))
            .min_by(|x, y| x.0.total_cmp(&y.0)),
        _ => cast_line(rounded, o, d, &Line::of(level, at)?),
    }
}

pub(crate) fn cast_line(
    (k, r): (Vec2, f32),
    o: Vec2,
    d: Vec2,
    line: &Line,
) -> Option<(f32, Vec2, Vec2)> {
    let mut best: Option<f32> = None;
    let mut consider = |t: Option<f32>| {
        if let Some(t) = t
            && (0.0..=1.0).contains(&t)
            && best.is_none_or(|b| t < b)
        {
            best = Some(t);
        }
    };
    // An end of the line, moving by -d relative to the shape, into it.
    for end in [line.a, line.b] {
        consider(ray_rounded_box(end - o, -d, k, r).map(|(t, ..)| t));
    }
    // A corner of the core (a circle of radius r) into the line.
    for corner in [
        Vec2::new(-1.0, -1.0),
        Vec2::new(1.0, -1.0),
        Vec2::new(1.0, 1.0),
        Vec2::new(-1.0, 1.0),
    ] {
        consider(ray_capsule(o + k * corner, d, line.a, line.b, r));
    }
    let t = best?;
    let m = collide_line(line, (k, r), o + d * t)?;
    (d.dot(m.normal) < 0.0).then_some((t, m.normal, m.points[0]))
}

/// A circle of radius `r` at `o` moved by `d` against the box `[-h, h]`:
/// `(t, normal, contact point on the box)`, both relative to the box's
/// centre.
fn ray_rounded_box(o: Vec2, d: Vec2, h: Vec2, r: f32) -> Option<(f32, Vec2, Vec2)> {
    // The centre touches the box at distance r from it: the box grown by r
    // with a quarter circle of radius r about each corner. Cast against the
    // grown box with square corners first. Entering through a face (within
    // the box's extent along it) is the hit. Entering in a corner square
    // (beyond the box on both axes), the hit if any is on that corner's
    // circle: leaving that square towards the box crosses a side of the
    // square that lies within r of the corner, so a path that misses the
    // corner's circle misses the rounded box altogether.
    let (t, normal) = ray_box(o, d, h + Vec2::splat(r))?;
    let q = o + d * t;
    if q.abs().cmpgt(h).all() {
        let corner = h.copysign(q);
        let (t, normal) = ray_circle(o - corner, d, r)?;
        return Some((t, normal, corner));
    }
    if normal == Vec2::ZERO {
        // Inside the rounded box by rounding only (`collide` found the
        // shapes apart): touching the face nearest to the outside.
        let normal = face_normal(q, h);
        return (d.dot(normal) < 0.0).then(|| (0.0, normal, on_face(q, h, normal)));
    }
    Some((t, normal, on_face(q, h, normal)))
}

/// A box with half extents `ha` at `o` moved by `d` against the box `[-hb,
/// hb]`: a ray against their Minkowski sum, the box `[-(ha + hb), ha +
/// hb]`. Returns `(t, face normal, contact point on the target)`: the
/// middle of the stretch of face the two boxes share.
fn ray_box_box(o: Vec2, d: Vec2, ha: Vec2, hb: Vec2) -> Option<(f32, Vec2, Vec2)> {
    let (t, mut normal) = ray_box(o, d, ha + hb)?;
    let q = o + d * t;
    if normal == Vec2::ZERO {
        // Starting inside is an overlap, which `collide` reports with the
        // same arithmetic, so this is unreachable; still defined.
        normal = face_normal(q, ha + hb);
    }
    let axis = if normal.x != 0.0 { 0 } else { 1 };
    let tangent = 1 - axis;
    let lo = (q[tangent] - ha[tangent]).max(-hb[tangent]);
    let hi = (q[tangent] + ha[tangent]).min(hb[tangent]);
    let mut point = Vec2::ZERO;
    point[axis] = normal[axis] * hb[axis];
    point[tangent] = (0.5 * (lo + hi)).clamp(-hb[tangent], hb[tangent]);
    Some((t, normal, point))
}

/// The outward normal of the face of `[-h, h]` that `q` is farthest
/// outside of (or nearest to leaving through); y on a tie.
fn face_normal(q: Vec2, h: Vec2) -> Vec2 {
    let excess = q.abs() - h;
    let axis = if excess.x > excess.y { 0 } else { 1 };
    let mut normal = Vec2::ZERO;
    normal[axis] = 1.0f32.copysign(q[axis]);
    normal
}

/// The point of the face of `[-h, h]` with outward `normal` (axis-aligned)
/// nearest to `q`.
fn on_face(q: Vec2, h: Vec2, normal: Vec2) -> Vec2 {
    let mut point = q.clamp(-h, h);
    let axis = if normal.x != 0.0 { 0 } else { 1 };
    point[axis] = normal[axis] * h[axis];
    point
}

#[cfg(test)]
mod tests;
