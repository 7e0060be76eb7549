//! Segments and chain segments (sloped static and kinematic geometry)
//! against the shapes that move: circles, boxes and capsules, all seen as
//! rounded boxes (see [`Shape::rounded`]). Contacts, casts and rays.
//!
//! A chain segment is solid from one side, the right of its direction,
//! and its normal points to the other (the open side). Where two segments
//! of a chain meet, a contact never takes a normal the joint does not
//! allow, so nothing catches on it (Box2D's chain shapes do the same with
//! "ghost" vertices):
//! - a body whose nearest point on a segment is its first end, where a
//!   segment comes before it, is left to that segment, which owns the
//!   joint;
//! - at its second end, where a segment follows, a segment keeps the
//!   contact only at a convex joint (a crest, or a flat one), and only
//!   with a normal between its own and the next segment's; at a valley
//!   the next segment's face is met first.

use crate::Shape;
use glam::Vec2;

/// A contact with a line: as [`Manifold`](crate::Manifold), which is built
/// from it (the manifold module comes after this one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LineContact {
    /// Unit normal from the line to the shape.
    pub normal: Vec2,
    /// Distance between the surfaces along `normal` (negative: overlap).
    pub separation: f32,
    /// One or two points, midway between the surfaces.
    pub points: [Vec2; 2],
    /// 1 or 2.
    pub point_count: u8,
}

impl LineContact {
    pub(crate) fn one(normal: Vec2, separation: f32, point: Vec2) -> Self {
        Self {
            normal,
            separation,
            points: [point, point],
            point_count: 1,
        }
    }
}

/// A segment in world space, with a chain segment's neighbours.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Line {
    pub a: Vec2,
    pub b: Vec2,
    /// One-sided, with neighbours (a chain segment).
    pub chain: bool,
    /// The chain's point before `a`, if any.
    pub before: Option<Vec2>,
    /// The chain's point after `b`, if any.
    pub after: Option<Vec2>,
}

impl Line {
    /// The line of a segment or chain segment at `p`; `None` for other
    /// shapes.
    #[inline]
    pub(crate) fn of(shape: &Shape, p: Vec2) -> Option<Self> {
        match *shape {
            Shape::Segment { half } => Some(Self {
                a: p - half,
                b: p + half,
                chain: false,
                before: None,
                after: None,
            }),
            Shape::ChainSegment {
                half,
                before,
                after,
            } => Some(Self {
                a: p - half,
                b: p + half,
                chain: true,
                before: before.map(|q| p + q),
                after: after.map(|q| p + q),
            }),
            _ => None,
        }
    }

    /// Unit direction from `a` to `b`.
    fn direction(&self) -> Vec2 {
        (self.b - self.a).normalize_or(Vec2::X)
    }

    /// The unit normal on the open side (the left of `a → b`).
    pub(crate) fn normal(&self) -> Vec2 {
        self.direction().perp()
    }

    /// Whether a chain segment lets a contact whose nearest point on it is
    /// at parameter `t` (0 at `a`, 1 at `b`) take normal `m` (see the
    /// module's rules). A plain segment allows every normal.
    fn allows(&self, t: f32, m: Vec2) -> bool {
        if !self.chain {
            return true;
        }
        if t <= 0.0 && self.before.is_some() {
            return false;
        }
        if t >= 1.0
            && let Some(after) = self.after
        {
            let (u, next) = (self.direction(), (after - self.b).normalize_or(Vec2::ZERO));
            // Turning left is a valley: the next face is met first.
            // (Within rounding of the next segment's normal still counts:
            // just past a flat joint the next segment's face holds it too.)
            let convex = u.perp_dot(next) <= 0.0;
            return convex && m.dot(next) <= 1e-4;
        }
        true
    }
}

/// The contact between `line` (A) and a rounded box (B: core half
/// extents `k`, radius `r`) centred at `c`: the normal points from the
/// line to the shape. `None` where a chain segment allows no contact: the
/// centre behind it, or a joint its neighbour owns.
pub(crate) fn collide_line(line: &Line, (k, r): (Vec2, f32), c: Vec2) -> Option<LineContact> {
    let n = line.normal();
    let ahead = (c - line.a).dot(n);
    if line.chain && ahead < 0.0 {
        return None;
    }
    let (ab, length_sq) = (line.b - line.a, (line.b - line.a).length_squared());
    let nearest = closest_features(line, k, c);
    let (m, separation, t) = match nearest {
        Some((distance, normal, t)) if distance > 0.0 => (normal, distance - r, t),
        // The core touches or crosses the line: out along the face normal
        // (either side for a plain segment), or along x or y past a free
        // end if that is shallower (where a chain goes on, its next
        // segment's face is the way out).
        _ => {
            let side = if line.chain || ahead >= 0.0 { n } else { -n };
            let mut best = (side, ahead.abs() - support(k, side) - r);
            if line.before.is_none() || line.after.is_none() {
                let mid = 0.5 * (line.a + line.b);
                for axis in 0..2 {
                    let sign = if c[axis] < mid[axis] { -1.0 } else { 1.0 };
                    let (lo, hi) = (
                        line.a[axis].min(line.b[axis]),
                        line.a[axis].max(line.b[axis]),
                    );
                    let s = if sign > 0.0 {
                        (c[axis] - k[axis] - r) - hi
                    } else {
                        lo - (c[axis] + k[axis] + r)
                    };
                    if s > best.1 {
                        let mut normal = Vec2::ZERO;
                        normal[axis] = sign;
                        best = (normal, s);
                    }
                }
            }
            let t = ((c - line.a).dot(ab) / length_sq).clamp(0.0, 1.0);
            (best.0, best.1, t.clamp(f32::EPSILON, 1.0 - f32::EPSILON))
        }
    };
    if !line.allows(t, m) {
        return None;
    }
    Some(contact_points(line, k, r, c, m, separation))
}

/// The nearest points of the line and the core box `[c - k, c + k]` when
/// they do not meet: `(distance, unit normal from the line to the core,
/// parameter of the point on the line)`. The normal comes from the
/// features that meet, not from the points' difference, which rounding
/// turns any way when they nearly touch: the line's normal where a corner
/// faces the inside of the line, an axis where an end faces a side of the
/// core. Only an end facing a corner takes the direction between them.
/// `None` when the line crosses or touches the core, or an end nearly
/// touches a corner.
pub(crate) fn closest_features(line: &Line, k: Vec2, c: Vec2) -> Option<(f32, Vec2, f32)> {
    let (a, b) = (line.a, line.b);
    let ab = b - a;
    if crosses_box(a, ab, c, k) {
        return None;
    }
    // The side the centre is on (a chain's open side): a corner nearly on
    // the line is on it, whichever side rounding puts it.
    let n = line.normal();
    let side = if line.chain || (c - a).dot(n) >= 0.0 {
        n
    } else {
        -n
    };
    let mut best: Option<(f32, Vec2, f32)> = None;
    let mut consider = |distance: f32, normal: Option<Vec2>, t: f32| {
        if best.is_none_or(|(d, ..)| distance < d) {
            best = normal.map(|normal| (distance, normal, t));
            if best.is_none() {
                // A corner against an end, too close to tell the way.
                best = Some((distance, Vec2::NAN, t));
            }
        }
    };
    // The core's corners against the line first: where an end is as near
    // (a body right over a joint), the face's normal wins.
    let length_sq = ab.length_squared();
    for corner in [
        Vec2::new(-1.0, -1.0),
        Vec2::new(1.0, -1.0),
        Vec2::new(1.0, 1.0),
        Vec2::new(-1.0, 1.0),
    ] {
        let q = c + k * corner;
        let t = ((q - a).dot(ab) / length_sq).clamp(0.0, 1.0);
        let delta = q - (a + ab * t);
        let distance = delta.length();
        let normal = if t > 0.0 && t < 1.0 {
            Some(side)
        } else {
            (distance > 1e-4).then(|| delta / distance)
        };
        consider(distance, normal, t);
    }
    // The line's ends against the core.
    for (end, t) in [(a, 0.0), (b, 1.0)] {
        let q = end.clamp(c - k, c + k);
        let delta = q - end;
        let distance = delta.length();
        let normal = match (delta.x != 0.0, delta.y != 0.0) {
            (true, false) => Some(Vec2::new(delta.x.signum(), 0.0)),
            (false, true) => Some(Vec2::new(0.0, delta.y.signum())),
            _ => (distance > 1e-4).then(|| delta / distance),
        };
        consider(distance, normal, t);
    }
    best.filter(|(_, normal, _)| !normal.is_nan())
}

/// Whether the segment from `a` along `ab` meets the closed box `[c - k,
/// c + k]` (slabs).
fn crosses_box(a: Vec2, ab: Vec2, c: Vec2, k: Vec2) -> bool {
    let (mut lo, mut hi) = (0.0f32, 1.0f32);
    for axis in 0..2 {
        let (min, max) = (c[axis] - k[axis], c[axis] + k[axis]);
        if ab[axis] == 0.0 {
            if a[axis] < min || a[axis] > max {
                return false;
            }
            continue;
        }
        let (t0, t1) = ((min - a[axis]) / ab[axis], (max - a[axis]) / ab[axis]);
        lo = lo.max(t0.min(t1));
        hi = hi.min(t0.max(t1));
        if lo > hi {
            return false;
        }
    }
    true
}

/// How far the box `[-k, k]` reaches along unit `n`.
fn support(k: Vec2, n: Vec2) -> f32 {
    k.x * n.x.abs() + k.y * n.y.abs()
}

/// The manifold with normal `m` and `separation`: the core's points
/// nearest the line along `m` (a whole side where `m` is along an axis,
/// clipped to the line), each midway between the two surfaces.
pub(crate) fn contact_points(
    line: &Line,
    k: Vec2,
    r: f32,
    c: Vec2,
    m: Vec2,
    separation: f32,
) -> LineContact {
    let sign = |x: f32| {
        if x > 0.0 {
            1.0
        } else if x < 0.0 {
            -1.0
        } else {
            0.0
        }
    };
    let base = c - k * Vec2::new(sign(m.x), sign(m.y));
    // Along the line, where its surface is under a point of the core.
    let ab = line.b - line.a;
    let length_sq = ab.length_squared();
    let under = |q: Vec2| ((q - line.a).dot(ab) / length_sq).clamp(0.0, 1.0);
    let at = |q: Vec2| q - m * (r + 0.5 * separation);
    let side = if m.x == 0.0 && k.x > 0.0 {
        Some(Vec2::new(k.x, 0.0))
    } else if m.y == 0.0 && k.y > 0.0 {
        Some(Vec2::new(0.0, k.y))
    } else {
        None
    };
    if let Some(e) = side
        && ab.dot(e) != 0.0
        && m.dot(line.normal()).abs() > 0.999_999
    {
        // A side of the core parallel to the line: its stretch over the
        // line.
        let (q0, q1) = (base - e, base + e);
        let (t0, t1) = (under(q0), under(q1));
        let (u0, u1) = (
            ((q0 - line.a).dot(ab)) / length_sq,
            ((q1 - line.a).dot(ab)) / length_sq,
        );
        let along = |t: f32| q0 + (q1 - q0) * ((t - u0) / (u1 - u0));
        let (p0, p1) = (at(along(t0)), at(along(t1)));
        if (p1 - p0).length_squared() > 0.0 {
            return LineContact {
                normal: m,
                separation,
                points: [p0, p1],
                point_count: 2,
            };
        }
        return LineContact::one(m, separation, p0);
    }
    LineContact::one(m, separation, at(base))
}

/// The first `t` in `[0, 1]` at which `o + t d` comes within `r` of the
/// segment `a b` (enters the capsule around it); `None` if it never does
/// or starts inside.
pub(crate) fn ray_capsule(o: Vec2, d: Vec2, a: Vec2, b: Vec2, r: f32) -> Option<f32> {
    let ab = b - a;
    let length = ab.length();
    let u = ab / length;
    let n = u.perp();
    // In the segment's frame: along it and across it.
    let (along, across) = ((o - a).dot(u), (o - a).dot(n));
    let (d_along, d_across) = (d.dot(u), d.dot(n));
    let mut best: Option<f32> = None;
    // The band: |across| <= r and 0 <= along <= length.
    if d_across != 0.0 {
        let face = if across > 0.0 { r } else { -r };
        let t = (face - across) / d_across;
        let s = along + d_along * t;
        if t >= 0.0 && (0.0..=length).contains(&s) && across.abs() >= r {
            best = Some(t);
        }
    }
    // The ends' circles.
    for end in [a, b] {
        if let Some(t) = ray_circle(o - end, d, r) {
            best = Some(best.map_or(t, |b| b.min(t)));
        }
    }
    best
}

/// The first `t >= 0` at which `o + t d` enters the disc of radius `r`
/// about the origin (`o` outside; a radius of 0 never).
fn ray_circle(o: Vec2, d: Vec2, r: f32) -> Option<f32> {
    let (a, b, c) = (d.dot(d), o.dot(d), o.dot(o) - r * r);
    if r <= 0.0 || c < 0.0 || b >= 0.0 || a == 0.0 {
        return None;
    }
    let disc = b * b - a * c;
    (disc > 0.0).then(|| c / (-b + disc.sqrt()))
}

/// The first hit of the ray `origin + t dir` (`dir` a unit vector, `t` in
/// `[0, max_t]`) with `line`: `(t, normal towards the origin)`. A chain
/// segment is hit only from its open side.
pub(crate) fn ray_line(line: &Line, origin: Vec2, dir: Vec2, max_t: f32) -> Option<(f32, Vec2)> {
    let ab = line.b - line.a;
    let denom = dir.perp_dot(ab);
    if denom == 0.0 {
        return None;
    }
    let ao = line.a - origin;
    let t = ao.perp_dot(ab) / denom;
    let s = ao.perp_dot(dir) / denom;
    if !(0.0..=max_t).contains(&t) || !(0.0..=1.0).contains(&s) {
        return None;
    }
    let n = line.normal();
    let facing = if dir.dot(n) < 0.0 { n } else { -n };
    if line.chain && facing != n {
        return None;
    }
    Some((t, facing))
}
