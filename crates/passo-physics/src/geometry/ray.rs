//! Rays against one shape: the first point a ray from `origin` meets on a
//! circle, a box or a capsule at `p`, and whether a point is inside one
//! (the world's ray and point queries use them).

use crate::Shape;
use glam::Vec2;

/// Whether a point is inside (or on) a shape at `p`.
pub(crate) fn shape_contains(shape: &Shape, p: Vec2, point: Vec2) -> bool {
    match *shape {
        Shape::Circle { radius } => (point - p).length_squared() <= radius * radius,
        Shape::Box { half_extents } => (point - p).abs().cmple(half_extents).all(),
        Shape::Capsule {
            half_segment,
            radius,
        } => {
            let local = point - p;
            (local - local.clamp(-half_segment, half_segment)).length_squared() <= radius * radius
        }
        // No area: no point is inside.
        Shape::Segment { .. } | Shape::ChainSegment { .. } => false,
        Shape::Polygon(polygon) => crate::geometry::polygon::contains(&polygon, p, point),
    }
}

/// The first hit of the ray `origin + t dir` (`dir` a unit vector, `t` in
/// `[0, max_t]`) with a shape at `p`: `(t, outward normal)`. A ray starting
/// inside a shape hits it at `t = 0` with the normal opposing `dir`.
pub(crate) fn ray_shape(
    shape: &Shape,
    p: Vec2,
    origin: Vec2,
    dir: Vec2,
    max_t: f32,
) -> Option<(f32, Vec2)> {
    if shape_contains(shape, p, origin) {
        return Some((0.0, -dir));
    }
    match *shape {
        Shape::Segment { .. } | Shape::ChainSegment { .. } => {
            let line = crate::geometry::segment::Line::of(shape, p)?;
            crate::geometry::segment::ray_line(&line, origin, dir, max_t)
        }
        // Its first edge along the ray (the origin is outside).
        Shape::Polygon(polygon) => crate::geometry::polygon::edges(&polygon, p)
            .filter_map(|e| crate::geometry::segment::ray_line(&e, origin, dir, max_t))
            .min_by(|x, y| x.0.total_cmp(&y.0)),
        Shape::Capsule {
            half_segment,
            radius,
        } => {
            // The box between the half-circles' centres, as wide as the
            // capsule, and the two half-circles' full circles: the first
            // hit on any of them (the origin is outside them all).
            let across = if half_segment.x > 0.0 {
                Vec2::new(0.0, radius)
            } else {
                Vec2::new(radius, 0.0)
            };
            let parts = [
                (
                    Shape::Box {
                        half_extents: half_segment + across,
                    },
                    p,
                ),
                (Shape::Circle { radius }, p + half_segment),
                (Shape::Circle { radius }, p - half_segment),
            ];
            parts
                .iter()
                .filter_map(|(part, at)| ray_shape(part, *at, origin, dir, max_t))
                .min_by(|x, y| x.0.total_cmp(&y.0))
        }
        Shape::Circle { radius } => {
            // |o + t d - c|^2 = r^2 with |d| = 1: t^2 + 2 b t + c = 0, in
            // the forms of `cast::ray_circle` that keep their digits from
            // afar (written as b^2 - c, the discriminant subtracted two
            // numbers of the distance squared: 300 m from a 5 cm circle it
            // lost the radius, and the hit came back at the centre with a
            // zero normal):
            // - the discriminant as r^2 - q^2, with q the line's distance
            //   from the centre (Lagrange's identity);
            // - the first root as -b - sqrt(disc) from afar, and as
            //   c / (-b + sqrt(disc)) near the circle, where the first
            //   form cancels (c, the distance squared less r^2, is small
            //   there, and overflows only from afar);
            // - the normal from q and the discriminant, not from the hit
            //   point less the centre.
            // The origin is outside (else `shape_contains`): heading away
            // (b > 0), the ray misses.
            let m = origin - p;
            let b = m.dot(dir);
            let q = m.dot(dir.perp());
            let disc = radius * radius - q * q;
            if disc < 0.0 || b > 0.0 {
                return None;
            }
            let root = disc.sqrt();
            let t = if -b > 2.0 * root {
                -b - root
            } else {
                (m.length_squared() - radius * radius) / (-b + root)
            };
            let normal = (dir.perp() * q - dir * root) / radius;
            (t >= 0.0 && t <= max_t).then_some((t, normal))
        }
        Shape::Box { half_extents } => {
            // Slabs: the latest entry over both axes is the hit. It starts
            // below zero, so an origin on a face (rounded just outside the
            // box) takes that face's normal: starting at zero, it met the
            // face at t = 0 and returned a zero normal.
            let lo = p - half_extents;
            let hi = p + half_extents;
            let mut t_enter = f32::NEG_INFINITY;
            let mut t_exit = max_t;
            let mut normal = Vec2::ZERO;
            for axis in 0..2 {
                if dir[axis] == 0.0 {
                    if origin[axis] < lo[axis] || origin[axis] > hi[axis] {
                        return None;
                    }
                    continue;
                }
                let inv = 1.0 / dir[axis];
                let (mut t0, mut t1) = (
                    (lo[axis] - origin[axis]) * inv,
                    (hi[axis] - origin[axis]) * inv,
                );
                let mut n = Vec2::ZERO;
                n[axis] = -1.0;
                if t0 > t1 {
                    std::mem::swap(&mut t0, &mut t1);
                    n[axis] = 1.0;
                }
                if t0 > t_enter {
                    t_enter = t0;
                    normal = n;
                }
                t_exit = t_exit.min(t1);
                if t_enter > t_exit {
                    return None;
                }
            }
            // Behind the origin, or (rounding) started inside.
            (t_exit >= 0.0).then_some((t_enter.max(0.0), normal))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rays_hit_circles_and_boxes_at_the_right_distance() {
        // A unit circle 5 m along x from the origin, the ray along +x.
        let at_circle = |centre: Vec2, max_t: f32| {
            ray_shape(&Shape::circle(1.0), centre, Vec2::ZERO, Vec2::X, max_t)
        };
        let (t, n) = at_circle(Vec2::new(5.0, 0.0), 10.0).unwrap();
        assert!((t - 4.0).abs() < 1e-6);
        assert_eq!(n, -Vec2::X);
        assert!(at_circle(Vec2::new(5.0, 0.0), 3.0).is_none());
        assert!(at_circle(Vec2::new(5.0, 2.0), 10.0).is_none());

        let wall = Shape::rect(1.0, 6.0);
        let dir = Vec2::new(1.0, 1.0).normalize();
        let (t, n) = ray_shape(&wall, Vec2::new(3.0, 0.0), Vec2::ZERO, dir, 10.0).unwrap();
        assert!((t - 2.5 * 2f32.sqrt()).abs() < 1e-5);
        assert_eq!(n, -Vec2::X);
        let (t, n) = ray_shape(
            &wall,
            Vec2::new(3.0, 0.0),
            Vec2::new(3.0, 6.0),
            -Vec2::Y,
            10.0,
        )
        .unwrap();
        assert_eq!((t, n), (3.0, Vec2::Y));
        assert!(ray_shape(&wall, Vec2::new(3.0, 0.0), Vec2::ZERO, -Vec2::X, 10.0).is_none());
    }

    #[test]
    fn a_ray_from_a_box_face_hits_it_at_zero_with_the_face_normal() {
        // 1.9 + 0.1 rounds the top to just above 2, and the origin on it
        // to just outside: the hit came back with a zero normal.
        for (centre, half) in [(1.9, 0.1), (0.3, 0.7), (-4.1, 2.1)] {
            let shape = Shape::from_half_extents(2.0, half);
            let p = Vec2::new(0.5, centre);
            for x in [-1.5, 0.0, 1.7] {
                let top = Vec2::new(x, centre + half);
                let (t, n) = ray_shape(&shape, p, top, -Vec2::Y, 5.0).unwrap();
                assert_eq!((t, n), (0.0, Vec2::Y), "{centre} {half} {x}");
                let bottom = Vec2::new(x, centre - half);
                let (t, n) = ray_shape(&shape, p, bottom, Vec2::Y, 5.0).unwrap();
                assert_eq!((t, n), (0.0, -Vec2::Y), "{centre} {half} {x}");
            }
            // Behind the ray: no hit.
            let below = Vec2::new(0.0, centre - half - 1.0);
            assert!(ray_shape(&shape, p, below, -Vec2::Y, 5.0).is_none());
        }
    }
}
