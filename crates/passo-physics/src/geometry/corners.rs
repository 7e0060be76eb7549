//! Which face a moving body meets where shapes meet at a corner or a
//! step: rules applied to the plain manifold (see `manifold`) in the
//! narrow phase, with the bodies' motion over the step.
//!
//! - [`over_a_step`]: a body closing on another while level with its face
//!   to within the slop meets that face (it climbs a step no higher than
//!   bodies sink into each other), so seams between boxes laid side by
//!   side are smooth.
//! - [`beyond_corner`]: two bodies beyond each other's corner take the
//!   axis whose gap their motion closes last.

use crate::Shape;
use crate::geometry::manifold::{Faces, Manifold};
use glam::Vec2;

/// For two bodies beyond each other's corner, the contact along the axis
/// whose gap the relative motion closes last, the face they would first
/// meet on:
/// - two boxes apart along both axes;
/// - a circle whose centre lies beyond both faces of a box at one corner,
///   apart from the box along at least one axis, whose path this step
///   (`closing` over `dt`) stays clear of that corner, and which meets that
///   face's plane, if at all, with its centre level with the face (else it
///   would meet the corner first, and the corner's own normal stands).
///
/// `None` for other shapes and places, when no motion tells (neither gap
/// closes, or both close at once), or when that face of B is covered (see
/// [`Faces`]). `closing` gives B's velocity relative to A's (asked only for
/// bodies beyond a corner, which most pairs are not).
///
/// The contact a step keeps acts as a plane for the whole step. Along the
/// axis of the larger gap, or a corner's normal, a box or circle falling
/// past a ledge's corner with a few centimetres to spare met a plane it
/// never reaches and stopped or was knocked aside beside the ledge; along
/// the axis whose gap does not close it meets the plane of the ledge's side.
#[inline(always)]
pub(crate) fn beyond_corner(
    sa: &Shape,
    pa: Vec2,
    sb: &Shape,
    pb: Vec2,
    closing: impl FnOnce() -> Vec2,
    dt: f32,
    faces_b: Faces,
) -> Option<Manifold> {
    let (ha, hb) = (sa.half_extents(), sb.half_extents());
    let d = pb - pa;
    let gap = d.abs() - (ha + hb);
    // For a circle and a box: the circle's radius, and its centre and
    // velocity relative to the box's.
    let (closing, circle) = match (*sa, *sb) {
        (Shape::Box { .. }, Shape::Box { .. }) if gap.x > 0.0 && gap.y > 0.0 => (closing(), None),
        (Shape::Circle { radius }, Shape::Box { half_extents: h }) if beyond(d, h, gap) => {
            let closing = closing();
            (closing, Some((radius, -d, -closing, h)))
        }
        (Shape::Box { half_extents: h }, Shape::Circle { radius }) if beyond(d, h, gap) => {
            let closing = closing();
            (closing, Some((radius, d, closing, h)))
        }
        _ => return None,
    };
    // How soon each gap closes (at once if the bodies overlap along it):
    // B moving towards A along the axis.
    let entry = |k: usize| {
        let speed = -closing[k] * d[k].signum();
        if gap[k] <= 0.0 {
            0.0
        } else if speed > 0.0 {
            gap[k] / speed
        } else {
            f32::INFINITY
        }
    };
    let (tx, ty) = (entry(0), entry(1));
    if tx == ty {
        return None;
    }
    let (axis, when) = if tx > ty { (0, tx) } else { (1, ty) };
    let sign = d[axis].signum();
    if gap[axis] <= 0.0 || faces_b.covered(axis, -sign) {
        return None;
    }
    if let Some((radius, centre, velocity, h)) = circle {
        let corner = centre.signum() * h;
        // Its path this step stays farther than its radius from the corner.
        let speed_sq = velocity.length_squared();
        let t = if speed_sq > 0.0 {
            (-(centre - corner).dot(velocity) / speed_sq).clamp(0.0, dt)
        } else {
            0.0
        };
        if (centre - corner + velocity * t).length() <= radius {
            return None;
        }
        // It meets the face's plane, if ever, level with the face.
        let other = 1 - axis;
        if when.is_finite() && (centre[other] + velocity[other] * when).abs() > h[other] {
            return None;
        }
    }
    let mut normal = Vec2::ZERO;
    normal[axis] = sign;
    // Midway between the two along the axis, and between their centres
    // along the other.
    let mut point = (pa + pb) * 0.5;
    point[axis] = pa[axis] + sign * (ha[axis] + 0.5 * gap[axis]);
    Some(Manifold::one(normal, gap[axis], point))
}

/// A body closing on B along one axis while level with B's face along the
/// other to within `tolerance` (overlapping it, or apart, by no more): B's
/// face along that other axis, as if the step between them were not there.
///
/// Contacts let bodies sink into each other by up to the slop, so a box or
/// circle sliding across boxes laid side by side meets the next box's side
/// a few millimetres below its top: a box stopped dead at the seam, and a
/// circle was thrown up by the corner at every seam. A step no higher than
/// the tolerance is climbed instead: the contact takes the face the body
/// rests against, and the push lifts it by what lies beyond the slop. A
/// body held a hair above its floor meets the next top the same way, not
/// the side below it.
///
/// Only while B closes on A along the other axis (`closing` gives B's
/// velocity relative to A's; a body moving off a ledge still falls); where
/// both axes qualify, the face the body closes on more slowly (it slides
/// along it: gravity alone does not turn a slide into a fall past a
/// ledge); only where B's face is open (see [`Faces`]); and only where the
/// plain contact would take another face (for two boxes the other axis,
/// the smaller overlap; for a circle beyond a box's corner the corner's
/// normal). `None` otherwise, and for two circles.
#[inline(always)]
pub(crate) fn over_a_step(
    sa: &Shape,
    pa: Vec2,
    sb: &Shape,
    pb: Vec2,
    closing: impl FnOnce() -> Vec2,
    tolerance: f32,
    faces_b: Faces,
) -> Option<Manifold> {
    // Two boxes take a step only when even the larger overlap of their
    // bounding boxes is within it: one test, inlined into the narrow
    // phase, sends back most pairs of a pile (a resting box overlaps its
    // support by half its width or more along the other axis); the rest
    // is out of line.
    match (*sa, *sb) {
        // Round ends roll over a step's edge, and flush boxes' seams are
        // closed by their covered faces.
        (Shape::Circle { .. }, Shape::Circle { .. }) => None,
        (Shape::Capsule { .. }, _) | (_, Shape::Capsule { .. }) => None,
        // A chain's joints are smooth already.
        (a, b) if a.is_level_only() || b.is_level_only() => None,
        (Shape::Box { half_extents: ha }, Shape::Box { half_extents: hb })
            if (ha + hb - (pb - pa).abs()).max_element() > tolerance =>
        {
            None
        }
        _ => step_face(sa, pa, sb, pb, closing(), tolerance, faces_b),
    }
}

/// [`over_a_step`] past its first test, with B's velocity relative to A's.
#[inline(never)]
fn step_face(
    sa: &Shape,
    pa: Vec2,
    sb: &Shape,
    pb: Vec2,
    closing: Vec2,
    tolerance: f32,
    faces_b: Faces,
) -> Option<Manifold> {
    let d = pb - pa;
    // The box's half extents when the other shape is a circle.
    let circle_and_box = match (*sa, *sb) {
        (Shape::Circle { .. }, Shape::Box { half_extents: h })
        | (Shape::Box { half_extents: h }, Shape::Circle { .. }) => Some(h),
        _ => None,
    };
    // The bounding boxes' overlap along each axis (negative: apart).
    let (ha, hb) = (sa.half_extents(), sb.half_extents());
    let overlap = ha + hb - d.abs();
    let sign = |axis: usize| if d[axis] < 0.0 { -1.0 } else { 1.0 };
    // How fast B closes on A along an axis.
    let closes = |axis: usize| -closing[axis] * sign(axis);
    // A step along axis `k`: level with B's face to within the tolerance
    // either way, the face open, and B closing on A along the other axis.
    let step = |k: usize| {
        overlap[k].abs() <= tolerance && !faces_b.covered(k, -sign(k)) && closes(1 - k) > 0.0
    };
    // On both: the face the body moves along rather than into, the one it
    // closes on more slowly (y on a tie): a body sliding onto the next box
    // with gravity pulling it down meets the top, one falling past a ledge
    // the side.
    let k = match (step(0), step(1)) {
        (false, false) => return None,
        (true, true) => usize::from(closes(1) <= closes(0)),
        (x, _) => usize::from(!x),
    };
    // Only where the plain contact would take another face: for two
    // boxes, the other axis (the smaller overlap, y on a tie); for a
    // circle, the corner's normal.
    let plain_takes_k = match circle_and_box {
        None => (k == 0) == (overlap.x < overlap.y),
        Some(h) => !(d.x.abs() > h.x && d.y.abs() > h.y),
    };
    if plain_takes_k {
        return None;
    }
    let mut normal = Vec2::ZERO;
    normal[k] = sign(k);
    // Midway between the two along the step's axis, and between their
    // centres along the other.
    let mut point = (pa + pb) * 0.5;
    point[k] = pa[k] + sign(k) * (ha[k] - 0.5 * overlap[k]);
    Some(Manifold::one(normal, -overlap[k], point))
}

/// Whether a circle's centre, `d` from the centre of a box of half extents
/// `h` (either way), lies beyond both of the box's faces at a corner, with
/// their bounding boxes `gap` apart along some axis.
#[inline(always)]
fn beyond(d: Vec2, h: Vec2, gap: Vec2) -> bool {
    d.x.abs() > h.x && d.y.abs() > h.y && (gap.x > 0.0 || gap.y > 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::manifold::{box_box, box_circle};

    #[test]
    fn a_step_no_higher_than_the_tolerance_is_met_on_its_top_while_closing() {
        let (tol, none) = (0.005, Faces::default());
        // A 0.4 m box sliding right, 3 mm below the top of box B (1 m),
        // 2 cm short of B's left face.
        let (sa, pa) = (Shape::rect(0.4, 0.4), Vec2::new(-0.72, 0.697));
        let (sb, pb) = (Shape::rect(1.0, 1.0), Vec2::ZERO);
        let right = || Vec2::new(-3.0, 0.0); // B closes on A
        let left = || Vec2::new(3.0, 0.0);
        // The plain contact is B's side, 2 cm away.
        let plain = box_box(pa, Vec2::splat(0.2), pb, Vec2::splat(0.5));
        assert_eq!(plain.normal, Vec2::X);
        let m = over_a_step(&sa, pa, &sb, pb, right, tol, none).unwrap();
        assert_eq!(m.normal, Vec2::NEG_Y);
        assert!((m.separation + 0.003).abs() < 1e-6, "{m:?}");
        // Moving away, standing still, a step above the tolerance, or B's
        // top covered: the plain contact stands.
        assert_eq!(over_a_step(&sa, pa, &sb, pb, left, tol, none), None);
        assert_eq!(
            over_a_step(&sa, pa, &sb, pb, || Vec2::ZERO, tol, none),
            None
        );
        let low = pa - Vec2::new(0.0, 0.01);
        assert_eq!(over_a_step(&sa, low, &sb, pb, right, tol, none), None);
        // Hovering 3 mm above the top (a body the speculative contact holds
        // a hair above its floor): the top too, 3 mm away, not the side.
        let above = pa + Vec2::new(0.0, 0.006);
        let m = over_a_step(&sa, above, &sb, pb, right, tol, none).unwrap();
        assert_eq!(m.normal, Vec2::NEG_Y);
        assert!((m.separation - 0.003).abs() < 1e-6, "{m:?}");
        let top = Faces(Faces::TOP);
        assert_eq!(over_a_step(&sa, pa, &sb, pb, right, tol, top), None);
        // B as A, and A as B: the same face, the normal reversed.
        let swapped = over_a_step(&sb, pb, &sa, pa, left, tol, none).unwrap();
        assert_eq!(swapped.normal, Vec2::Y);
        // Sliding (3 m/s) onto a box whose top is level with its bottom,
        // just past B's side (7 µm), gravity closing at 0.16 m/s: the plain
        // contact, B's top, stands (it took B's side, and a body sliding
        // from a one-way platform onto solid ground stopped dead there).
        // Falling past B's side with 3 mm to spare: the side.
        let (sd, pd) = (Shape::rect(0.6, 1.0), Vec2::new(-0.8 + 7e-6, 1.0));
        let slide = || Vec2::new(-3.0, 0.16);
        assert_eq!(
            box_box(pd, Vec2::new(0.3, 0.5), pb, Vec2::splat(0.5)).normal,
            Vec2::NEG_Y
        );
        assert_eq!(over_a_step(&sd, pd, &sb, pb, slide, tol, none), None);
        let past = Vec2::new(-0.8 + 0.003, 1.2);
        let fall = || Vec2::new(0.0, 10.0);
        let m = over_a_step(&sd, past, &sb, pb, fall, tol, none).unwrap();
        assert_eq!(m.normal, Vec2::X);
        // Side by side and flush (a row of a pyramid): the contact already
        // takes the shallow axis, x; nothing changes.
        let beside = Vec2::new(-1.0, 0.0);
        assert_eq!(over_a_step(&sb, beside, &sb, pb, right, tol, none), None);

        // A circle of 0.2 m sunk 3 mm, its centre beyond B's top-left
        // corner: the corner's normal would throw it up and back.
        let (sc, pc) = (Shape::circle(0.2), Vec2::new(-0.52, 0.697));
        let corner = box_circle(pb, Vec2::splat(0.5), pc, 0.2).flipped();
        assert!(corner.normal.x > 0.09, "{corner:?}");
        let m = over_a_step(&sc, pc, &sb, pb, right, tol, none).unwrap();
        assert_eq!(m.normal, Vec2::NEG_Y);
        assert!((m.separation + 0.003).abs() < 1e-6, "{m:?}");
        assert_eq!(over_a_step(&sc, pc, &sb, pb, left, tol, none), None);
        // Two circles: never.
        let pd = Vec2::new(0.39, 0.0);
        assert_eq!(
            over_a_step(&sc, pd, &sc, Vec2::ZERO, right, 0.02, none),
            None
        );
    }
}
