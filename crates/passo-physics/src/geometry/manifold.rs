//! Narrow phase: the contact manifold between two shapes.
//!
//! Every function takes shape A at `pa` and shape B at `pb` and returns the
//! normal pointing from A to B, the separation along it (negative when the
//! shapes overlap: minus the penetration depth), and the contact points.
//! Results are exact for touching, separated and overlapping shapes, and
//! defined when one contains the other or the centres coincide: the normal
//! then falls back to +y (up), never NaN.

use crate::Shape;
use glam::Vec2;

/// Where two shapes touch or would touch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Manifold {
    /// Unit normal from A to B.
    pub normal: Vec2,
    /// Distance between the shapes along `normal`, metres; negative when
    /// they overlap (its magnitude is then the penetration depth).
    pub separation: f32,
    /// Contact points in world space; `point_count` of them are valid.
    pub points: [Vec2; 2],
    /// 1 or 2.
    pub point_count: u8,
}

impl Manifold {
    pub(crate) fn one(normal: Vec2, separation: f32, point: Vec2) -> Self {
        Self {
            normal,
            separation,
            points: [point, point],
            point_count: 1,
        }
    }

    /// The valid contact points.
    pub fn points(&self) -> &[Vec2] {
        &self.points[..usize::from(self.point_count)]
    }

    /// The same contact seen from B: normal reversed, points unchanged.
    pub fn flipped(mut self) -> Self {
        self.normal = -self.normal;
        self
    }
}

/// The manifold of two shapes, or `None` if they are farther apart than
/// `margin` metres (a speculative contact is kept up to that distance).
#[inline]
pub fn collide(sa: &Shape, pa: Vec2, sb: &Shape, pb: Vec2, margin: f32) -> Option<Manifold> {
    collide_shapes(sa, pa, sb, pb, margin)
}

/// [`collide`], inlined into the narrow phase's loop over the pairs
/// (through [`collide_seamless`]): the manifold is then built in registers
/// rather than returned through memory.
#[inline(always)]
fn collide_shapes(sa: &Shape, pa: Vec2, sb: &Shape, pb: Vec2, margin: f32) -> Option<Manifold> {
    let m = match (*sa, *sb) {
        (Shape::Circle { radius: ra }, Shape::Circle { radius: rb }) => {
            circle_circle(pa, ra, pb, rb)
        }
        (Shape::Box { half_extents: ha }, Shape::Box { half_extents: hb }) => {
            box_box(pa, ha, pb, hb)
        }
        (Shape::Box { half_extents }, Shape::Circle { radius }) => {
            box_circle(pa, half_extents, pb, radius)
        }
        (Shape::Circle { radius }, Shape::Box { half_extents }) => {
            box_circle(pb, half_extents, pa, radius).flipped()
        }
        // A pair with a line (a segment or chain segment) or a polygon.
        (Shape::Segment { .. } | Shape::ChainSegment { .. } | Shape::Polygon(_), _)
        | (_, Shape::Segment { .. } | Shape::ChainSegment { .. } | Shape::Polygon(_)) => {
            return with_line(sa, pa, sb, pb, margin);
        }
        // A pair with a capsule: two rounded boxes.
        _ => rounded_rounded(pa, sa.rounded(), pb, sb.rounded(), Faces::default()),
    };
    (m.separation <= margin).then_some(m)
}

/// The faces of a static box that another static box covers (bits of
/// [`Faces::LEFT`], ...): a body meeting the box there is meeting the
/// neighbour's surface, so a contact never takes its normal through a
/// covered face. This is how flush boxes and tiles make seamless ground:
/// the joint between two boxes with the same top is no edge to catch on.
/// (Box2D solves the same "ghost collisions" on chain shapes with one-sided
/// edges and their neighbouring vertices.)
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Faces(pub u8);

impl Faces {
    pub(crate) const LEFT: u8 = 1;
    pub(crate) const RIGHT: u8 = 2;
    pub(crate) const BOTTOM: u8 = 4;
    pub(crate) const TOP: u8 = 8;

    /// Whether the face whose outward normal is `sign` along `axis` (0 = x,
    /// 1 = y) is covered.
    #[inline(always)]
    pub(crate) fn covered(self, axis: usize, sign: f32) -> bool {
        let bit = match (axis, sign > 0.0) {
            (0, false) => Self::LEFT,
            (0, true) => Self::RIGHT,
            (_, false) => Self::BOTTOM,
            (_, true) => Self::TOP,
        };
        self.0 & bit != 0
    }

    /// Whether `normal` (out of the box) leaves through a covered face:
    /// anything arriving along it came through the neighbour first.
    pub(crate) fn covers(self, normal: Vec2) -> bool {
        (normal.x != 0.0 && self.covered(0, normal.x))
            || (normal.y != 0.0 && self.covered(1, normal.y))
    }

    /// The faces of box `a` that the boxes `neighbours` cover together:
    /// each face that some of them lie flush against (or across), within
    /// `tolerance` metres, and whose whole length their spans cover with
    /// no gap wider than the tolerance. A face of a tall tile whose
    /// neighbour is two shorter tiles, one on the other, is covered as if
    /// by one. `spans` is scratch space.
    pub(crate) fn covered_by_all(
        a: &crate::Aabb,
        neighbours: &[crate::Aabb],
        tolerance: f32,
        spans: &mut Vec<(f32, f32)>,
    ) -> u8 {
        let t = tolerance;
        // (face, whether `b` lies flush against or across it, the axis
        // along the face)
        type Against = fn(&crate::Aabb, &crate::Aabb, f32) -> bool;
        let faces: [(u8, Against, usize); 4] = [
            (
                Self::RIGHT,
                |a, b, t| b.min.x <= a.max.x + t && b.max.x >= a.max.x + 2.0 * t,
                1,
            ),
            (
                Self::LEFT,
                |a, b, t| b.max.x >= a.min.x - t && b.min.x <= a.min.x - 2.0 * t,
                1,
            ),
            (
                Self::TOP,
                |a, b, t| b.min.y <= a.max.y + t && b.max.y >= a.max.y + 2.0 * t,
                0,
            ),
            (
                Self::BOTTOM,
                |a, b, t| b.max.y >= a.min.y - t && b.min.y <= a.min.y - 2.0 * t,
                0,
            ),
        ];
        let mut covered = 0;
        for (bit, against, axis) in faces {
            spans.clear();
            spans.extend(
                neighbours
                    .iter()
                    .filter(|b| against(a, b, t))
                    .map(|b| (b.min[axis], b.max[axis]))
                    .filter(|&span| Self::lies_along(a, span, axis, t)),
            );
            spans.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
            // Walk the spans in order: how far along the face is covered
            // without a gap.
            let mut reach = a.min[axis] + t;
            for &(lo, hi) in spans.iter() {
                if lo > reach + t {
                    break;
                }
                reach = reach.max(hi);
            }
            // (Some neighbour must lie against the face: a face no longer
            // than the tolerances, 1 cm, would pass the test with none.)
            if !spans.is_empty() && reach >= a.max[axis] - t {
                covered |= bit;
            }
        }
        covered
    }

    /// Whether a neighbour spanning `lo..hi` along `axis` lies along a face
    /// of box `a` on that axis: it overlaps the face by more than the
    /// tolerance `t` (or by half a face shorter than that). A floor under
    /// a box lies against its sides' lines too, but covers nothing of them.
    fn lies_along(a: &crate::Aabb, (lo, hi): (f32, f32), axis: usize, t: f32) -> bool {
        let (from, to) = (a.min[axis], a.max[axis]);
        hi.min(to) - lo.max(from) > t.min(0.5 * (to - from))
    }

    /// The faces of box `a` that box `b` covers: `b` lies flush against (or
    /// across) the face, within `tolerance` metres, along all of it.
    pub(crate) fn covered_by(a: &crate::Aabb, b: &crate::Aabb, tolerance: f32) -> u8 {
        let t = tolerance;
        let spans_y = b.min.y <= a.min.y + t
            && b.max.y >= a.max.y - t
            && Self::lies_along(a, (b.min.y, b.max.y), 1, t);
        let spans_x = b.min.x <= a.min.x + t
            && b.max.x >= a.max.x - t
            && Self::lies_along(a, (b.min.x, b.max.x), 0, t);
        let mut faces = 0;
        if spans_y && b.min.x <= a.max.x + t && b.max.x >= a.max.x + 2.0 * t {
            faces |= Self::RIGHT;
        }
        if spans_y && b.max.x >= a.min.x - t && b.min.x <= a.min.x - 2.0 * t {
            faces |= Self::LEFT;
        }
        if spans_x && b.min.y <= a.max.y + t && b.max.y >= a.max.y + 2.0 * t {
            faces |= Self::TOP;
        }
        if spans_x && b.max.y >= a.min.y - t && b.min.y <= a.min.y - 2.0 * t {
            faces |= Self::BOTTOM;
        }
        faces
    }
}

/// [`collide`] with static shape B's covered faces: a normal that would
/// leave B through a covered face leaves through the other axis's face
/// instead. With no covered face this is exactly [`collide`]. (Inlined
/// into the narrow phase, with the one copy of [`collide`] it calls.)
#[inline(always)]
pub(crate) fn collide_seamless(
    sa: &Shape,
    pa: Vec2,
    sb: &Shape,
    pb: Vec2,
    margin: f32,
    faces_b: Faces,
) -> Option<Manifold> {
    let m = match (*sa, *sb) {
        (Shape::Box { half_extents: ha }, Shape::Box { half_extents: hb }) if faces_b.0 != 0 => {
            box_box_faces(pa, ha, pb, hb, faces_b)
        }
        (Shape::Circle { radius }, Shape::Box { half_extents }) if faces_b.0 != 0 => {
            box_circle_faces(pb, half_extents, pa, radius, faces_b).flipped()
        }
        (Shape::Capsule { .. }, Shape::Box { .. }) if faces_b.0 != 0 => {
            rounded_rounded(pa, sa.rounded(), pb, sb.rounded(), faces_b)
        }
        _ => return collide_shapes(sa, pa, sb, pb, margin),
    };
    (m.separation <= margin).then_some(m)
}

/// A pair with a line or a polygon: its contact with the other shape, seen
/// from A. Two such shapes never touch (only static and kinematic bodies
/// have them).
#[inline(never)]
fn with_line(sa: &Shape, pa: Vec2, sb: &Shape, pb: Vec2, margin: f32) -> Option<Manifold> {
    use crate::geometry::segment::{Line, collide_line};
    let manifold = |c: crate::geometry::segment::LineContact| Manifold {
        normal: c.normal,
        separation: c.separation,
        points: c.points,
        point_count: c.point_count,
    };
    use crate::geometry::polygon::collide_polygon;
    // Level geometry never meets level geometry (only static and
    // kinematic bodies have it).
    if sa.is_level_only() && sb.is_level_only() {
        return None;
    }
    let m = match (sa, sb) {
        (Shape::Polygon(polygon), _) => manifold(collide_polygon(polygon, pa, sb.rounded(), pb)),
        (_, Shape::Polygon(polygon)) => {
            manifold(collide_polygon(polygon, pb, sa.rounded(), pa)).flipped()
        }
        _ => match (Line::of(sa, pa), Line::of(sb, pb)) {
            (Some(line), None) => manifold(collide_line(&line, sb.rounded(), pb)?),
            (None, Some(line)) => manifold(collide_line(&line, sa.rounded(), pa)?).flipped(),
            _ => return None,
        },
    };
    (m.separation <= margin).then_some(m)
}

/// Two circles: along the line of centres.
pub(crate) fn circle_circle(pa: Vec2, ra: f32, pb: Vec2, rb: f32) -> Manifold {
    let d = pb - pa;
    let dist = d.length();
    let normal = if dist > 0.0 { d / dist } else { Vec2::Y };
    let separation = dist - ra - rb;
    // Midway between the two surfaces.
    let point = pa + normal * (ra + 0.5 * separation);
    Manifold::one(normal, separation, point)
}

/// Two axis-aligned boxes: along the axis of least overlap (most
/// separation); on a tie, the y axis. Two points span the shared face.
#[inline(always)]
pub(crate) fn box_box(pa: Vec2, ha: Vec2, pb: Vec2, hb: Vec2) -> Manifold {
    box_box_faces(pa, ha, pb, hb, Faces::default())
}

/// [`box_box`] where B's covered faces are not crossed.
// Inlined into its callers (the box-box case of `collide`, through
// `box_box`, and of `collide_seamless`), and with them into the narrow
// phase, where a call cost the pairs loop a fifth of its time.
#[inline(always)]
fn box_box_faces(pa: Vec2, ha: Vec2, pb: Vec2, hb: Vec2, faces_b: Faces) -> Manifold {
    let d = pb - pa;
    let overlap = ha + hb - d.abs();
    let sign_of = |axis: usize| if d[axis] < 0.0 { -1.0 } else { 1.0 };
    // Axis 0 = x, 1 = y; ties go to y so stacks get vertical normals. The
    // normal points from A to B, so it leaves B through B's face on the
    // `-sign` side.
    let mut axis = if overlap.x < overlap.y { 0 } else { 1 };
    let other = 1 - axis;
    // Leaving through a covered face, the boxes meet across the other
    // axis instead: a box crossing the joint of two flush boxes is beside
    // the second by less than it sinks into the top they share. Only while
    // that is a contact's depth: with the smaller box more than halfway
    // across the other axis, it lies on whatever covers the face (a coat
    // flush on it, a lift passing through), and pushing it out sideways
    // would shove it by its own width.
    let shallow = overlap[other] < ha[other].min(hb[other]);
    if faces_b.covered(axis, -sign_of(axis)) && !faces_b.covered(other, -sign_of(other)) && shallow
    {
        axis = other;
    }
    let tangent_axis = 1 - axis;
    let sign = sign_of(axis);
    let mut normal = Vec2::ZERO;
    normal[axis] = sign;
    let separation = -overlap[axis];

    // The face midway between A's face and B's face, along the normal axis.
    let face = 0.5 * ((pa[axis] + sign * ha[axis]) + (pb[axis] - sign * hb[axis]));
    let lo = (pa[tangent_axis] - ha[tangent_axis]).max(pb[tangent_axis] - hb[tangent_axis]);
    let hi = (pa[tangent_axis] + ha[tangent_axis]).min(pb[tangent_axis] + hb[tangent_axis]);
    face_points(normal, separation, axis, face, lo, hi)
}

/// A manifold with `normal` along `axis` whose points lie on the line
/// `axis = face`: the two ends of the stretch `lo..hi` along the other
/// axis, or one point midway where the stretch is empty (corner to
/// corner, or an edge on a single point).
#[inline(always)]
fn face_points(
    normal: Vec2,
    separation: f32,
    axis: usize,
    face: f32,
    lo: f32,
    hi: f32,
) -> Manifold {
    let point_at = |t: f32| {
        let mut p = Vec2::ZERO;
        p[axis] = face;
        p[1 - axis] = t;
        p
    };
    if lo < hi {
        Manifold {
            normal,
            separation,
            points: [point_at(lo), point_at(hi)],
            point_count: 2,
        }
    } else {
        Manifold::one(normal, separation, point_at(0.5 * (lo + hi)))
    }
}

/// A box (A) and a circle (B): from the closest point of the box to the
/// circle's centre; a centre inside the box leaves through the nearest face.
pub(crate) fn box_circle(pa: Vec2, ha: Vec2, pb: Vec2, rb: f32) -> Manifold {
    box_circle_faces(pa, ha, pb, rb, Faces::default())
}

/// [`box_circle`] where A's covered faces are not crossed: a circle beyond
/// a corner whose one face is covered meets the other face's plane, and a
/// centre inside leaves through an uncovered face.
fn box_circle_faces(pa: Vec2, ha: Vec2, pb: Vec2, rb: f32, faces_a: Faces) -> Manifold {
    let local = pb - pa;
    let closest = local.clamp(-ha, ha);
    let d = local - closest;
    let dist_sq = d.length_squared();
    let sign_of = |axis: usize| if local[axis] < 0.0 { -1.0 } else { 1.0 };
    if d.x != 0.0 && d.y != 0.0 {
        // Beyond a corner: if exactly one of its faces is covered, the
        // circle meets the other face's plane.
        let covered = [
            faces_a.covered(0, sign_of(0)),
            faces_a.covered(1, sign_of(1)),
        ];
        if covered[0] != covered[1] {
            let axis = if covered[0] { 1 } else { 0 };
            let mut normal = Vec2::ZERO;
            normal[axis] = sign_of(axis);
            let mut point = closest;
            point[axis] = sign_of(axis) * ha[axis];
            return Manifold::one(normal, d[axis].abs() - rb, pa + point);
        }
    }
    if dist_sq > 0.0 {
        let dist = dist_sq.sqrt();
        let normal = d / dist;
        Manifold::one(normal, dist - rb, pa + closest)
    } else {
        // Centre inside (or on) the box: push out through the nearest face;
        // on a tie prefer y, then the positive side.
        let to_face = ha - local.abs();
        let mut axis = if to_face.x < to_face.y { 0 } else { 1 };
        let other = 1 - axis;
        if faces_a.covered(axis, sign_of(axis)) && !faces_a.covered(other, sign_of(other)) {
            axis = other;
        }
        let depth = to_face[axis];
        let mut normal = Vec2::ZERO;
        normal[axis] = sign_of(axis);
        let mut point = local;
        point[axis] = normal[axis] * ha[axis];
        Manifold::one(normal, -depth - rb, pa + point)
    }
}

/// Two rounded boxes (see [`Shape::rounded`]): A with core half extents
/// and radius `(ka, ra)` at `pa`, B with `(kb, rb)` at `pb`. Beyond a
/// corner of the cores (apart along both axes) the normal joins the two
/// nearest core corners; otherwise it is the axis along which the cores
/// are farthest apart (least overlap; on a tie, y), and up to two points
/// span the stretch where the cores face each other. B's covered faces
/// (a static box's, see [`Faces`]) are never crossed: beyond a corner
/// with one face covered, A meets the other face's plane, and the axis
/// through a covered face gives way to the other.
fn rounded_rounded(
    pa: Vec2,
    (ka, ra): (Vec2, f32),
    pb: Vec2,
    (kb, rb): (Vec2, f32),
    faces_b: Faces,
) -> Manifold {
    let d = pb - pa;
    let gap = d.abs() - (ka + kb);
    let sign_of = |axis: usize| if d[axis] < 0.0 { -1.0 } else { 1.0 };
    let sign = Vec2::new(sign_of(0), sign_of(1));
    let radii = ra + rb;
    // The normal leaves B through its face on the `-sign` side.
    let covered = [faces_b.covered(0, -sign.x), faces_b.covered(1, -sign.y)];
    if gap.x > 0.0 && gap.y > 0.0 && covered[0] == covered[1] {
        // From A's nearest core corner to B's.
        let between = gap * sign;
        let length = between.length();
        let normal = between / length;
        let corner = pa + ka * sign;
        let separation = length - radii;
        return Manifold::one(
            normal,
            separation,
            corner + normal * (ra + 0.5 * separation),
        );
    }
    let mut axis = if gap.x > gap.y { 0 } else { 1 };
    let other = 1 - axis;
    if covered[axis] && !covered[other] {
        axis = other;
    }
    let tangent = 1 - axis;
    let mut normal = Vec2::ZERO;
    normal[axis] = sign[axis];
    let separation = gap[axis] - radii;
    // Midway between A's surface and B's, along the normal.
    let face = 0.5
        * ((pa[axis] + sign[axis] * (ka[axis] + ra)) + (pb[axis] - sign[axis] * (kb[axis] + rb)));
    let lo = (pa[tangent] - ka[tangent]).max(pb[tangent] - kb[tangent]);
    let hi = (pa[tangent] + ka[tangent]).min(pb[tangent] + kb[tangent]);
    face_points(normal, separation, axis, face, lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec2, b: Vec2) -> bool {
        (a - b).length() < 1e-6
    }

    #[test]
    fn circles_touching_separated_overlapping_and_coincident() {
        let touching = circle_circle(Vec2::ZERO, 1.0, Vec2::new(3.0, 0.0), 2.0);
        assert_eq!((touching.normal, touching.separation), (Vec2::X, 0.0));
        assert!(close(touching.points[0], Vec2::new(1.0, 0.0)));

        let apart = circle_circle(Vec2::ZERO, 1.0, Vec2::new(0.0, -5.0), 1.0);
        assert_eq!((apart.normal, apart.separation), (-Vec2::Y, 3.0));

        let overlap = circle_circle(Vec2::ZERO, 1.0, Vec2::new(3.0, 4.0), 4.5);
        assert!(close(overlap.normal, Vec2::new(0.6, 0.8)));
        assert!((overlap.separation + 0.5).abs() < 1e-6);

        let same = circle_circle(Vec2::ONE, 1.0, Vec2::ONE, 0.5);
        assert_eq!((same.normal, same.separation), (Vec2::Y, -1.5));
        assert!(same.points[0].is_finite());
    }

    #[test]
    fn boxes_use_the_axis_of_least_overlap_with_two_face_points() {
        // B resting on A, offset by half a width: a vertical normal and the
        // shared stretch of face as the two points.
        let m = box_box(
            Vec2::ZERO,
            Vec2::splat(0.5),
            Vec2::new(0.5, 0.99),
            Vec2::splat(0.5),
        );
        assert_eq!(m.normal, Vec2::Y);
        assert!((m.separation + 0.01).abs() < 1e-6);
        assert_eq!(m.point_count, 2);
        assert!(close(m.points[0], Vec2::new(0.0, 0.495)));
        assert!(close(m.points[1], Vec2::new(0.5, 0.495)));

        let side = box_box(
            Vec2::ZERO,
            Vec2::splat(0.5),
            Vec2::new(-1.2, 0.1),
            Vec2::splat(0.5),
        );
        assert_eq!(side.normal, -Vec2::X);
        assert!((side.separation - 0.2).abs() < 1e-6);

        // Contained and coincident: defined, up by convention.
        let inside = box_box(Vec2::ZERO, Vec2::splat(2.0), Vec2::ZERO, Vec2::splat(0.5));
        assert_eq!((inside.normal, inside.separation), (Vec2::Y, -2.5));
        // A box below: down.
        let below = box_box(
            Vec2::ZERO,
            Vec2::new(2.0, 0.5),
            Vec2::new(0.0, -0.9),
            Vec2::splat(0.5),
        );
        assert_eq!(below.normal, -Vec2::Y);
    }

    #[test]
    fn box_circle_outside_corner_face_and_inside() {
        let h = Vec2::new(2.0, 1.0);
        let above = box_circle(Vec2::ZERO, h, Vec2::new(0.5, 1.5), 0.5);
        assert_eq!((above.normal, above.separation), (Vec2::Y, 0.0));
        assert!(close(above.points[0], Vec2::new(0.5, 1.0)));

        let corner = box_circle(Vec2::ZERO, h, Vec2::new(5.0, 5.0), 1.0);
        assert!(close(corner.normal, Vec2::new(0.6, 0.8)));
        assert!((corner.separation - 4.0).abs() < 1e-6);

        let inside = box_circle(Vec2::ZERO, h, Vec2::new(1.8, 0.0), 0.5);
        assert_eq!(inside.normal, Vec2::X);
        assert!((inside.separation + 0.7).abs() < 1e-6);

        let centre = box_circle(Vec2::ZERO, Vec2::splat(1.0), Vec2::ZERO, 0.5);
        assert_eq!((centre.normal, centre.separation), (Vec2::Y, -1.5));

        // The circle-first order flips the normal.
        let m = collide(
            &Shape::circle(0.5),
            Vec2::new(0.5, 1.5),
            &Shape::Box { half_extents: h },
            Vec2::ZERO,
            0.0,
        )
        .unwrap();
        assert_eq!(m.normal, -Vec2::Y);
    }

    #[test]
    fn margin_keeps_speculative_contacts_and_drops_far_ones() {
        let a = Shape::circle(1.0);
        assert!(collide(&a, Vec2::ZERO, &a, Vec2::new(2.5, 0.0), 0.5).is_some());
        assert!(collide(&a, Vec2::ZERO, &a, Vec2::new(2.6, 0.0), 0.5).is_none());
    }

    #[test]
    fn flush_neighbours_cover_faces_and_a_wall_on_the_ground_covers_one() {
        use crate::Aabb;
        let a = Aabb::from_centre(Vec2::new(0.0, 0.0), Vec2::splat(0.5));
        let right = Aabb::from_centre(Vec2::new(1.0, 0.0), Vec2::splat(0.5));
        let lower = Aabb::from_centre(Vec2::new(1.0, -0.001), Vec2::splat(0.5));
        let above = Aabb::from_centre(Vec2::new(0.0, 1.0), Vec2::splat(0.5));
        let ground = Aabb::from_centre(Vec2::new(0.0, -1.0), Vec2::new(5.0, 0.5));
        let t = crate::constants::LINEAR_SLOP;
        assert_eq!(Faces::covered_by(&a, &right, t), Faces::RIGHT);
        assert_eq!(Faces::covered_by(&right, &a, t), Faces::LEFT);
        assert_eq!(
            Faces::covered_by(&a, &lower, t),
            Faces::RIGHT,
            "1 mm is within the slop"
        );
        assert_eq!(Faces::covered_by(&a, &above, t), Faces::TOP);
        // A box on the ground: its bottom is covered, the ground's top is not
        // (the box covers only part of it).
        assert_eq!(Faces::covered_by(&a, &ground, t), Faces::BOTTOM);
        assert_eq!(Faces::covered_by(&ground, &a, t), 0);
        // A gap wider than the slop covers nothing.
        let apart = Aabb::from_centre(Vec2::new(1.02, 0.0), Vec2::splat(0.5));
        assert_eq!(Faces::covered_by(&a, &apart, t), 0);
    }

    #[test]
    fn neighbours_cover_a_face_together_but_not_across_a_gap() {
        use crate::Aabb;
        let t = crate::constants::LINEAR_SLOP;
        let mut spans = Vec::new();
        // A tile two cells tall with two one-cell tiles stacked on its right.
        let tall = Aabb::from_centre(Vec2::ZERO, Vec2::new(0.5, 1.0));
        let low = Aabb::from_centre(Vec2::new(1.0, -0.5), Vec2::splat(0.5));
        let high = Aabb::from_centre(Vec2::new(1.0, 0.5), Vec2::splat(0.5));
        assert_eq!(Faces::covered_by(&tall, &low, t), 0, "neither alone");
        assert_eq!(
            Faces::covered_by_all(&tall, &[high, low], t, &mut spans),
            Faces::RIGHT
        );
        // A 1 cm gap between them is wider than the slop: the face is open.
        let high_up = Aabb::from_centre(Vec2::new(1.0, 0.51), Vec2::splat(0.49));
        assert_eq!(
            Faces::covered_by_all(&tall, &[low, high_up], t, &mut spans),
            0
        );
        // One neighbour alone gives what covered_by gives.
        let right = Aabb::from_centre(Vec2::new(1.0, 0.0), Vec2::splat(1.0));
        assert_eq!(
            Faces::covered_by_all(&tall, &[right], t, &mut spans),
            Faces::covered_by(&tall, &right, t)
        );
        // A box 1 cm on a side with no neighbour covers nothing (its faces
        // are no longer than the tolerances, and passed the walk with no
        // span at all: fast bodies went through it).
        for side in [0.01, 0.005, 1e-4] {
            let tiny = Aabb::from_centre(Vec2::ZERO, Vec2::splat(side / 2.0));
            assert_eq!(Faces::covered_by_all(&tiny, &[], t, &mut spans), 0);
            // Standing on a floor, it is covered below and nowhere else
            // (the floor lies against its sides' lines, not along them).
            let h = side / 2.0;
            let floor = Aabb::from_centre(Vec2::new(0.0, -h - 0.5), Vec2::new(5.0, 0.5));
            assert_eq!(
                Faces::covered_by_all(&tiny, &[floor], t, &mut spans),
                Faces::BOTTOM,
                "{side}"
            );
            assert_eq!(Faces::covered_by(&tiny, &floor, t), Faces::BOTTOM, "{side}");
            // A neighbour as tall, flush on its right (and at least the
            // 1 cm deep a cover needs), covers that face.
            let right = Aabb::from_centre(Vec2::new(h + 0.5, 0.0), Vec2::new(0.5, h));
            assert_eq!(
                Faces::covered_by_all(&tiny, &[floor, right], t, &mut spans),
                Faces::BOTTOM | Faces::RIGHT,
                "{side}"
            );
        }
    }

    #[test]
    fn a_covered_face_turns_the_normal_to_the_open_face() {
        // A box sunk 4 cm into the tile left of tile B crosses 2 cm past
        // B's left face, which that tile covers.
        let faces = Faces(Faces::LEFT);
        let (pa, ha) = (Vec2::new(-0.78, 0.26), Vec2::splat(0.3));
        let (pb, hb) = (Vec2::new(0.0, -0.5), Vec2::splat(0.5));
        // Uncovered, the least overlap (2 cm along x) would push A back
        // out through the side; covered, the normal is the top's.
        assert_eq!(box_box(pa, ha, pb, hb).normal, Vec2::X);
        let m = box_box_faces(pa, ha, pb, hb, faces);
        assert_eq!(m.normal, Vec2::new(0.0, -1.0));
        assert!((m.separation + 0.04).abs() < 1e-6);
        // A circle beyond B's top-left corner meets B's top plane.
        let m = box_circle_faces(pb, hb, Vec2::new(-0.55, 0.3), 0.3, faces);
        assert_eq!(m.normal, Vec2::Y);
        assert!((m.separation - (0.3 - 0.3)).abs() < 1e-6);
        // Nothing covered: exactly the plain functions.
        assert_eq!(
            box_box_faces(pa, ha, pb, hb, Faces::default()),
            box_box(pa, ha, pb, hb)
        );
    }

    /// Within 1e-5 m.
    fn near(a: Vec2, b: Vec2) -> bool {
        (a - b).length() < 1e-5
    }

    #[test]
    fn capsule_pairs_against_their_closed_forms() {
        let capsule = Shape::capsule(0.4, 1.2); // radius 0.2, half segment (0, 0.4)
        let lying = Shape::capsule(1.2, 0.4); // half segment (0.4, 0)
        let floor = Shape::rect(4.0, 1.0);
        let at = |x: f32, y: f32| Vec2::new(x, y);
        // Standing on a floor 1 mm up: its lower half-circle, one point
        // midway under its centre.
        let m = collide(&floor, at(0.0, -0.5), &capsule, at(0.3, 0.601), 1.0).unwrap();
        assert_eq!(m.normal, Vec2::Y);
        assert!(
            (m.separation - 0.001).abs() < 1e-5 && m.point_count == 1,
            "{m:?}"
        );
        assert!(near(m.points[0], at(0.3, 0.0005)), "{m:?}");
        // Against a wall: the straight side, two points spanning it.
        let wall = Shape::rect(1.0, 4.0);
        let m = collide(&capsule, at(0.0, 0.5), &wall, at(0.7, 0.0), 1.0).unwrap();
        assert_eq!(m.normal, Vec2::X);
        assert!(m.separation.abs() < 1e-5 && m.point_count == 2, "{m:?}");
        assert!(
            near(m.points[0], at(0.2, 0.1)) && near(m.points[1], at(0.2, 0.9)),
            "{m:?}"
        );
        // A circle off its top end, at 45°: from the end's centre.
        let ball = Shape::circle(0.1);
        let m = collide(&capsule, at(0.0, 0.0), &ball, at(0.3, 0.7), 1.0).unwrap();
        let to = at(0.3, 0.3);
        assert!(near(m.normal, to.normalize()), "{m:?}");
        assert!((m.separation - (to.length() - 0.3)).abs() < 1e-5, "{m:?}");
        let surface_a = at(0.0, 0.4) + m.normal * 0.2;
        assert!(
            near(m.points[0], surface_a + m.normal * 0.5 * m.separation),
            "{m:?}"
        );
        // Upright against lying, corner to corner: between the segments'
        // nearest ends.
        let m = collide(&capsule, at(0.0, 0.0), &lying, at(1.0, 1.0), 1.0).unwrap();
        let between = at(1.0 - 0.4, 1.0 - 0.4);
        assert!(near(m.normal, between.normalize()), "{m:?}");
        assert!(
            (m.separation - (between.length() - 0.4)).abs() < 1e-5,
            "{m:?}"
        );
        // Two upright capsules overlapping side by side by 5 cm.
        let m = collide(&capsule, at(0.0, 0.0), &capsule, at(0.35, 0.2), 1.0).unwrap();
        assert_eq!(m.normal, Vec2::X);
        assert!((m.separation + 0.05).abs() < 1e-5, "{m:?}");
        assert!(
            near(m.points[0], at(0.175, -0.2)) && near(m.points[1], at(0.175, 0.4)),
            "{m:?}"
        );
        // Flipped pairs: the same contact seen from the other side.
        let ab = collide(&capsule, at(0.1, 0.2), &floor, at(0.0, -0.8), 1.0).unwrap();
        let ba = collide(&floor, at(0.0, -0.8), &capsule, at(0.1, 0.2), 1.0).unwrap();
        assert_eq!(ab.normal, -ba.normal);
        assert!((ab.separation - ba.separation).abs() < 1e-6);
    }

    #[test]
    fn capsules_contained_and_coincident_give_defined_contacts() {
        let capsule = Shape::capsule(0.4, 1.2);
        for other in [
            Shape::circle(0.05),
            Shape::rect(0.1, 0.1),
            Shape::capsule(0.2, 0.6),
        ] {
            for offset in [Vec2::ZERO, Vec2::new(0.0, 0.3), Vec2::new(0.05, -0.2)] {
                let m = collide(&capsule, Vec2::ZERO, &other, offset, 0.0).unwrap();
                assert!(
                    (m.normal.length() - 1.0).abs() < 1e-6,
                    "{other:?} {offset}: {m:?}"
                );
                assert!(m.separation < 0.0 && m.points().iter().all(|p| p.is_finite()));
                // Moved out along the normal by the depth, they touch.
                let out = offset - m.normal * m.separation;
                let touching = collide(&capsule, Vec2::ZERO, &other, out, 1.0).unwrap();
                assert!(
                    touching.separation.abs() < 1e-5,
                    "{other:?} {offset}: {touching:?}"
                );
            }
        }
    }

    #[test]
    fn random_separated_capsule_pairs_are_apart_by_their_true_distance() {
        // The distance between two rounded boxes is the distance from one
        // centre to the box of both cores, less both radii; the points lie
        // midway between the surfaces.
        let mut seed = 0x5eed_u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1);
            (seed >> 40) as f32 / (1u64 << 24) as f32
        };
        for case in 0..2000 {
            let shape = |pick: f32, w: f32, h: f32| match (pick * 3.0) as u32 {
                0 => Shape::circle(0.5 * w),
                1 => Shape::rect(w, h),
                _ => Shape::capsule(w, h),
            };
            let a = shape(next(), 0.1 + 2.0 * next(), 0.1 + 2.0 * next());
            let mut b = shape(next(), 0.1 + 2.0 * next(), 0.1 + 2.0 * next());
            if !matches!(a, Shape::Capsule { .. }) {
                b = Shape::capsule(0.1 + 2.0 * next(), 0.1 + 2.0 * next());
            }
            let pb = Vec2::new(8.0 * next() - 4.0, 8.0 * next() - 4.0);
            let ((ka, ra), (kb, rb)) = (a.rounded(), b.rounded());
            let e = pb.abs() - (ka + kb);
            let outside = e.max(Vec2::ZERO).length() + e.max_element().min(0.0);
            let distance = outside - (ra + rb);
            if distance <= 0.0 {
                continue;
            }
            let m = collide(&a, Vec2::ZERO, &b, pb, f32::INFINITY).unwrap();
            assert!(
                (m.separation - distance).abs() < 1e-5,
                "case {case}: {a:?} {b:?} at {pb}: {m:?}"
            );
            // Each point is half the separation from each surface.
            for p in m.points() {
                let from_a = (*p - p.clamp(-ka, ka)).length() - ra;
                assert!(
                    (from_a - 0.5 * m.separation).abs() < 1e-4,
                    "case {case}: {m:?}"
                );
            }
        }
    }
}
