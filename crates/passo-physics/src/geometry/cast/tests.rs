//! Tests of `cast`.

use super::*;

fn circle(radius: f32) -> Shape {
    Shape::circle(radius)
}

fn rect(hx: f32, hy: f32) -> Shape {
    Shape::Box {
        half_extents: Vec2::new(hx, hy),
    }
}

/// The moving shape's position at the hit is within 1e-5 m of where
/// the closed form puts it, and the normal and point match.
#[track_caller]
fn assert_hit(
    hit: Option<CastHit>,
    start: Vec2,
    translation: Vec2,
    fraction: f64,
    normal: Vec2,
    point: Vec2,
) {
    let hit = hit.expect("a hit");
    let at = start + translation * hit.fraction;
    let expected = start.as_dvec2() + translation.as_dvec2() * fraction;
    assert!(
        (at.as_dvec2() - expected).length() < 1e-5,
        "position {at} at fraction {}, expected {expected} at {fraction}",
        hit.fraction
    );
    assert!(
        (hit.normal - normal).length() < 1e-5,
        "normal {}, expected {normal}",
        hit.normal
    );
    assert!(
        (hit.point - point).length() < 1e-5,
        "point {}, expected {point}",
        hit.point
    );
}

#[test]
fn circles_head_on() {
    // Centres 3 apart when touching: x = 3 of the 10 travelled.
    let (start, d) = (Vec2::ZERO, Vec2::new(10.0, 0.0));
    let hit = cast_shape(&circle(1.0), start, d, &circle(2.0), Vec2::new(6.0, 0.0));
    assert_hit(hit, start, d, 0.3, -Vec2::X, Vec2::new(4.0, 0.0));
}

#[test]
fn circles_oblique() {
    // Summed radius 1.5, path y = 0, target centre (5, 1): touching
    // when (x - 5)^2 + 1 = 1.5^2, first at x = 5 - sqrt(1.25).
    let (start, d) = (Vec2::ZERO, Vec2::new(10.0, 0.0));
    let target = Vec2::new(5.0, 1.0);
    let hit = cast_shape(&circle(0.5), start, d, &circle(1.0), target);
    let x = 5.0 - 1.25f64.sqrt();
    let normal = Vec2::new(-(1.25f32.sqrt()), -1.0) / 1.5;
    assert_hit(hit, start, d, x / 10.0, normal, target + normal);
}

#[test]
fn circle_hits_a_box_face() {
    // Box half extents (1, 2), circle radius 0.5: the left face of the
    // grown box is x = -1.5, reached at -5 + 8 t = -1.5, t = 0.4375,
    // where y = 2 t = 0.875 is within the face.
    let (start, d) = (Vec2::new(-5.0, 0.0), Vec2::new(8.0, 2.0));
    let hit = cast_shape(&circle(0.5), start, d, &rect(1.0, 2.0), Vec2::ZERO);
    assert_hit(hit, start, d, 0.4375, -Vec2::X, Vec2::new(-1.0, 0.875));
}

#[test]
fn circle_hits_a_box_corner() {
    // Box half extents (1, 0.5) at the origin, circle radius 1 starting
    // at the top-left corner (-1, 0.5) + (-2, 1.2), moving by (3, -1).
    // The grown box is entered through its left face x = -2 at t = 1/3,
    // where y = 1.7 - 1/3 > 0.5: the corner region. Relative to the
    // corner, |(-2 + 3t, 1.2 - t)|^2 = 1:
    //   10 t^2 - 14.4 t + 4.44 = 0,  t = (14.4 - sqrt(29.76)) / 20.
    let corner = Vec2::new(-1.0, 0.5);
    let start = corner + Vec2::new(-2.0, 1.2);
    let d = Vec2::new(3.0, -1.0);
    let t = (14.4 - 29.76f64.sqrt()) / 20.0;
    let rel = (Vec2::new(-2.0, 1.2).as_dvec2() + d.as_dvec2() * t).as_vec2();
    let hit = cast_shape(&circle(1.0), start, d, &rect(1.0, 0.5), Vec2::ZERO);
    assert_hit(hit, start, d, t, rel, corner);
    // Moved elsewhere, the same answer.
    let shift = Vec2::new(30.0, -7.0);
    let hit = cast_shape(&circle(1.0), start + shift, d, &rect(1.0, 0.5), shift);
    assert_hit(hit, start + shift, d, t, rel, corner + shift);
}

#[test]
fn box_hits_a_box_face_and_a_corner_prefers_y() {
    // Summed half extents (2.5, 1.5): the top face y = 1.5 at
    // 5 - 10 t = 1.5, t = 0.35, where x = 0.35. The shared stretch of
    // face is [0.35 - 0.5, 0.35 + 0.5].
    let (start, d) = (Vec2::new(0.0, 5.0), Vec2::new(1.0, -10.0));
    let hit = cast_shape(&rect(0.5, 0.5), start, d, &rect(2.0, 1.0), Vec2::ZERO);
    assert_hit(hit, start, d, 0.35, Vec2::Y, Vec2::new(0.35, 1.0));

    // From the left: x = -2.5 at -4 + 3 t, t = 0.5, y = 0.5.
    let (start, d) = (Vec2::new(-4.0, 0.0), Vec2::new(3.0, 1.0));
    let hit = cast_shape(&rect(0.5, 0.5), start, d, &rect(2.0, 1.0), Vec2::ZERO);
    assert_hit(hit, start, d, 0.5, -Vec2::X, Vec2::new(-2.0, 0.5));

    // Corner to corner: both faces at t = 0.5; the top face wins.
    let (start, d) = (Vec2::new(-3.5, 2.5), Vec2::new(2.0, -2.0));
    let hit = cast_shape(&rect(0.5, 0.5), start, d, &rect(2.0, 1.0), Vec2::ZERO);
    assert_hit(hit, start, d, 0.5, Vec2::Y, Vec2::new(-2.0, 1.0));
}

#[test]
fn box_hits_a_circle_on_its_face_and_its_corner() {
    // The box's right face reaches the circle's left point x = -1 when
    // the box is at x = -2: t = 0.3. The normal is the circle's, out
    // towards the box.
    let (start, d) = (Vec2::new(-5.0, 0.0), Vec2::new(10.0, 0.0));
    let target = Vec2::new(0.0, 0.2);
    let hit = cast_shape(&rect(1.0, 0.5), start, d, &circle(1.0), target);
    assert_hit(hit, start, d, 0.3, -Vec2::X, Vec2::new(-1.0, 0.2));

    // The box's top-right corner (x + 1, 1) meets the circle of radius
    // 1 at (0, 1.6) when (x + 1)^2 + 0.6^2 = 1: x = -1.8, t = 0.55.
    let (start, d) = (Vec2::new(-4.0, 0.0), Vec2::new(4.0, 0.0));
    let target = Vec2::new(0.0, 1.6);
    let hit = cast_shape(&rect(1.0, 1.0), start, d, &circle(1.0), target);
    assert_hit(
        hit,
        start,
        d,
        0.55,
        Vec2::new(-0.8, -0.6),
        Vec2::new(-0.8, 1.0),
    );
}

#[test]
fn grazing_paths_miss() {
    // Passing 1 mm outside the summed radius.
    let hit = cast_shape(
        &circle(1.0),
        Vec2::new(-5.0, 3.001),
        Vec2::new(10.0, 0.0),
        &circle(2.0),
        Vec2::ZERO,
    );
    assert_eq!(hit, None);
    // Through the grown box's square corner, 1 cm outside the rounded
    // one: the closest approach to the corner (1, 1) is 1.01.
    let closest = Vec2::ONE + Vec2::ONE.normalize() * 1.01;
    let d = Vec2::new(6.0, -6.0);
    let start = closest - 0.5 * d;
    assert_eq!(
        cast_shape(&circle(1.0), start, d, &rect(1.0, 1.0), Vec2::ZERO),
        None
    );
    // And the box seen against that circle.
    assert_eq!(
        cast_shape(&rect(1.0, 1.0), Vec2::ZERO, -d, &circle(1.0), start),
        None
    );
    // A box level with the top of another, sliding across it: the
    // seam between flush tiles catches nothing.
    let hit = cast_shape(
        &rect(0.5, 0.5),
        Vec2::new(-5.0, 1.5),
        Vec2::new(10.0, 0.0),
        &rect(1.0, 1.0),
        Vec2::ZERO,
    );
    assert_eq!(hit, None);
    // A box passing just above another.
    let hit = cast_shape(
        &rect(0.5, 0.5),
        Vec2::new(-5.0, 1.501),
        Vec2::new(10.0, -0.0005),
        &rect(1.0, 1.0),
        Vec2::ZERO,
    );
    assert_eq!(hit, None);
}

#[test]
fn starting_overlapped_is_fraction_zero_leaving_the_way_collide_says() {
    // A circle sunk into the top of a box leaves upwards.
    let hit = cast_shape(
        &circle(0.5),
        Vec2::new(0.0, 0.8),
        Vec2::new(1.0, 0.0),
        &rect(1.0, 1.0),
        Vec2::ZERO,
    )
    .unwrap();
    assert_eq!(hit.fraction, 0.0);
    assert_eq!(hit.normal, Vec2::Y);
    assert!((hit.point - Vec2::new(0.0, 1.0)).length() < 1e-6);
    // With no translation, and with coincident centres: defined, out
    // of the box's nearest face or, for a tie, `collide`'s +y from A
    // to B, flipped.
    for (a, b, normal) in [
        (circle(1.0), circle(2.0), -Vec2::Y),
        (circle(1.0), rect(1.0, 2.0), Vec2::X),
        (rect(1.0, 2.0), circle(1.0), -Vec2::X),
        (rect(1.0, 2.0), rect(2.0, 1.0), -Vec2::Y),
    ] {
        let hit = cast_shape(&a, Vec2::ONE, Vec2::ZERO, &b, Vec2::ONE).unwrap();
        assert_eq!((hit.fraction, hit.normal), (0.0, normal), "{a:?} {b:?}");
        assert!(hit.point.is_finite());
    }
}

#[test]
fn starting_touching_moving_away_or_along_is_none_moving_in_is_zero() {
    let (a, b) = (circle(1.0), circle(1.0));
    let target = Vec2::new(2.0, 0.0);
    assert_eq!(cast_shape(&a, Vec2::ZERO, -Vec2::X, &b, target), None);
    assert_eq!(cast_shape(&a, Vec2::ZERO, Vec2::Y, &b, target), None);
    assert_eq!(cast_shape(&a, Vec2::ZERO, Vec2::ZERO, &b, target), None);
    let hit = cast_shape(&a, Vec2::ZERO, Vec2::new(1.0, 1.0), &b, target).unwrap();
    assert_eq!((hit.fraction, hit.normal), (0.0, -Vec2::X));
    assert_eq!(hit.point, Vec2::new(1.0, 0.0));

    // A circle resting on a box.
    let (c, floor) = (circle(0.5), rect(2.0, 1.0));
    let on_top = Vec2::new(0.3, 1.5);
    assert_eq!(cast_shape(&c, on_top, Vec2::Y, &floor, Vec2::ZERO), None);
    assert_eq!(cast_shape(&c, on_top, Vec2::X, &floor, Vec2::ZERO), None);
    let hit = cast_shape(&c, on_top, -Vec2::Y, &floor, Vec2::ZERO).unwrap();
    assert_eq!((hit.fraction, hit.normal), (0.0, Vec2::Y));

    // A box resting on a box, and one touching it corner to corner.
    let (small, big) = (rect(0.5, 0.5), rect(1.0, 1.0));
    let resting = Vec2::new(0.2, 1.5);
    assert_eq!(cast_shape(&small, resting, Vec2::X, &big, Vec2::ZERO), None);
    assert_eq!(cast_shape(&small, resting, Vec2::Y, &big, Vec2::ZERO), None);
    let hit = cast_shape(&small, resting, -Vec2::Y, &big, Vec2::ZERO).unwrap();
    assert_eq!((hit.fraction, hit.normal), (0.0, Vec2::Y));
    let corner = Vec2::new(1.5, 1.5);
    assert_eq!(cast_shape(&small, corner, -Vec2::X, &big, Vec2::ZERO), None);
    assert_eq!(cast_shape(&small, corner, -Vec2::Y, &big, Vec2::ZERO), None);
    let hit = cast_shape(&small, corner, -Vec2::ONE, &big, Vec2::ZERO).unwrap();
    assert_eq!((hit.fraction, hit.normal), (0.0, Vec2::Y));
}

#[test]
fn stopping_short_or_not_moving_is_none() {
    // Touching would take x = 3 of the way; the translation is 2.9.
    let hit = cast_shape(
        &circle(1.0),
        Vec2::ZERO,
        Vec2::new(2.9, 0.0),
        &circle(2.0),
        Vec2::new(6.0, 0.0),
    );
    assert_eq!(hit, None);
    let hit = cast_shape(
        &rect(0.5, 0.5),
        Vec2::new(0.0, 5.0),
        Vec2::new(0.0, -3.4),
        &rect(2.0, 1.0),
        Vec2::ZERO,
    );
    assert_eq!(hit, None);
    for (a, b) in [
        (circle(1.0), circle(1.0)),
        (circle(1.0), rect(1.0, 1.0)),
        (rect(1.0, 1.0), circle(1.0)),
        (rect(1.0, 1.0), rect(1.0, 1.0)),
    ] {
        assert_eq!(
            cast_shape(&a, Vec2::ZERO, Vec2::ZERO, &b, Vec2::X * 3.0),
            None
        );
    }
}

#[test]
fn tiny_and_huge_translations_stay_finite() {
    let shapes = [circle(1.0), rect(1.0, 0.5)];
    let half_height = |s: &Shape| s.half_extents().y;
    for a in &shapes {
        for b in &shapes {
            // A standing on top of B, touching (separation exactly 0).
            let top = half_height(a) + half_height(b);
            let touching = Vec2::new(0.0, top);
            // Into B, however little: a hit at once, out of B's top.
            for d in [
                Vec2::new(0.0, -1e-30),
                Vec2::new(1e-44, -1e-44),
                Vec2::new(0.0, -1e18),
            ] {
                let hit = cast_shape(a, touching, d, b, Vec2::ZERO)
                    .unwrap_or_else(|| panic!("{a:?} on {b:?} moved by {d}"));
                assert_eq!((hit.fraction, hit.normal), (0.0, Vec2::Y), "{d}");
                assert!(hit.point.is_finite(), "{d}");
                assert!((hit.point.y - half_height(b)).abs() < 1e-6, "{d}");
                assert!(hit.point.x.abs() <= 1.0, "{d}");
            }
            // Along B's top or away from it: no hit.
            for d in [
                Vec2::new(1e-30, 0.0),
                Vec2::new(-1e-44, 0.0),
                Vec2::new(1e30, 1e-30),
                Vec2::new(0.0, 1e-44),
            ] {
                assert_eq!(cast_shape(a, touching, d, b, Vec2::ZERO), None, "{d}");
            }
            // One step of f32 above touching: a tiny move down stops short,
            // a move of a micrometre hits after that step.
            let above = Vec2::new(0.0, top.next_up());
            let gap = f64::from(above.y) - f64::from(top);
            assert_eq!(
                cast_shape(a, above, Vec2::new(0.0, -1e-30), b, Vec2::ZERO),
                None
            );
            let d = Vec2::new(0.0, -1e-6);
            let hit = cast_shape(a, above, d, b, Vec2::ZERO).expect("a hit");
            let want = gap / 1e-6;
            assert!(
                (f64::from(hit.fraction) - want).abs() < 1e-3,
                "fraction {} for {want}",
                hit.fraction
            );
            assert_eq!(hit.normal, Vec2::Y);
            // Straight down from 5 m by 1e18 m: hits at a tiny fraction.
            let hit =
                cast_shape(a, Vec2::new(0.0, 5.0), Vec2::new(0.0, -1e18), b, Vec2::ZERO).unwrap();
            assert!(hit.fraction > 0.0 && hit.fraction < 1e-17);
            assert_eq!(hit.normal, Vec2::Y);
        }
    }
}

/// A tiny deterministic generator (Knuth's MMIX LCG), uniform in [0, 1).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }

    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next()
    }

    fn vec(&mut self, lo: f32, hi: f32) -> Vec2 {
        Vec2::new(self.range(lo, hi), self.range(lo, hi))
    }

    fn shape(&mut self) -> Shape {
        let pick = self.next();
        if pick < 0.35 {
            circle(self.range(0.1, 2.0))
        } else if pick < 0.7 {
            Shape::Box {
                half_extents: self.vec(0.1, 2.0),
            }
        } else {
            let size = self.vec(0.2, 4.0);
            Shape::capsule(size.x, size.y)
        }
    }
}

fn separation(a: &Shape, pa: Vec2, b: &Shape, pb: Vec2) -> f32 {
    collide(a, pa, b, pb, f32::INFINITY).unwrap().separation
}

/// Distance from `point` to the boundary of `shape` at `p`.
fn off_surface(shape: &Shape, p: Vec2, point: Vec2) -> f32 {
    match *shape {
        Shape::Circle { radius } => ((point - p).length() - radius).abs(),
        Shape::Box { half_extents } => box_distance(point - p, half_extents).abs(),
        Shape::Capsule {
            half_segment,
            radius,
        } => (box_distance(point - p, half_segment) - radius).abs(),
        Shape::Segment { half } | Shape::ChainSegment { half, .. } => {
            let local = point - p;
            let t = (local.dot(half) / half.length_squared()).clamp(-1.0, 1.0);
            (local - half * t).length()
        }
        // The nearest edge.
        Shape::Polygon(polygon) => {
            let v = polygon.vertices();
            (0..v.len())
                .map(|i| {
                    let (a, b) = (p + v[i], p + v[(i + 1) % v.len()]);
                    let t = ((point - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
                    (point - (a + (b - a) * t)).length()
                })
                .fold(f32::INFINITY, f32::min)
        }
    }
}

/// Signed distance from `local` to the box `[-h, h]` (negative inside).
fn box_distance(local: Vec2, h: Vec2) -> f32 {
    let e = local.abs() - h;
    if e.cmple(Vec2::ZERO).all() {
        e.max_element()
    } else {
        e.max(Vec2::ZERO).length()
    }
}

#[test]
fn random_casts_touch_at_the_hit_and_never_overlap_before_it_or_on_a_miss() {
    let mut rng = Lcg(0x5eed_ca57);
    let (mut hits, mut at_zero, mut misses) = (0, 0, 0);
    for case in 0..20_000 {
        let (a, b) = (rng.shape(), rng.shape());
        let target = rng.vec(-3.0, 3.0);
        let mut start = rng.vec(-8.0, 8.0);
        let mut d = match case % 4 {
            // Aimed at the target, give or take.
            0 | 1 => (target - start) * rng.range(0.0, 2.0) + rng.vec(-2.0, 2.0),
            _ => rng.vec(-12.0, 12.0),
        };
        match case % 16 {
            // Axis-aligned motion (parallel slabs).
            3 => d.y = 0.0,
            7 => d.x = 0.0,
            // Level with the target's top, sliding sideways.
            11 => {
                start.y = target.y + a.half_extents().y + b.half_extents().y;
                d.y = 0.0;
            }
            13 => d = Vec2::ZERO,
            15 => start = target,
            _ => {}
        }
        let context = format!("case {case}: {a:?} at {start} by {d}, {b:?} at {target}");
        match cast_shape(&a, start, d, &b, target) {
            Some(hit) => {
                assert!((0.0..=1.0).contains(&hit.fraction), "{context}: {hit:?}");
                assert!(hit.point.is_finite(), "{context}: {hit:?}");
                assert!(
                    (hit.normal.length() - 1.0).abs() < 1e-5,
                    "{context}: {hit:?}"
                );
                let m = collide(&a, start, &b, target, f32::INFINITY).unwrap();
                if m.separation < 0.0 {
                    assert_eq!(hit.fraction, 0.0, "{context}");
                    assert_eq!(hit.normal, -m.normal, "{context}");
                    at_zero += 1;
                    continue;
                }
                hits += 1;
                let at = start + d * hit.fraction;
                let s = separation(&a, at, &b, target);
                assert!(s.abs() < 1e-4, "{context}: {hit:?}, separation {s}");
                if hit.fraction > 0.01 {
                    let before = start + d * (hit.fraction - 0.01);
                    let s = separation(&a, before, &b, target);
                    assert!(s > -1e-4, "{context}: {hit:?}, before {s}");
                }
                // The point is on both surfaces, the motion goes in
                // against the normal, and backing off along it parts
                // the shapes.
                let on_b = off_surface(&b, target, hit.point);
                let on_a = off_surface(&a, at, hit.point);
                assert!(on_a < 1e-4 && on_b < 1e-4, "{context}: {hit:?}");
                assert!(d.dot(hit.normal) <= 0.0, "{context}: {hit:?}");
                let s = separation(&a, at + hit.normal * 1e-3, &b, target);
                assert!(s > 5e-4, "{context}: {hit:?}, backed off {s}");
            }
            None => {
                misses += 1;
                for i in 0..64 {
                    let p = start + d * (i as f32 / 63.0);
                    let s = separation(&a, p, &b, target);
                    assert!(s > -1e-4, "{context}: missed, but at {p} {s}");
                }
            }
        }
    }
    // Every branch is exercised.
    assert!(hits > 2000 && at_zero > 1000 && misses > 2000);
}

#[test]
fn random_casts_onto_segments_touch_at_the_hit_and_never_pass_through_one() {
    let mut rng = Lcg(0x5e9_0e17);
    let (mut hits, mut misses) = (0, 0);
    for case in 0..20_000 {
        let a = rng.shape();
        let half = rng.vec(-3.0, 3.0);
        let chain = case % 2 == 1;
        let b = if chain {
            Shape::ChainSegment {
                half,
                before: None,
                after: None,
            }
        } else {
            Shape::Segment { half }
        };
        let target = rng.vec(-3.0, 3.0);
        let start = rng.vec(-8.0, 8.0);
        let mut d = match case % 4 {
            0 | 1 => (target - start) * rng.range(0.0, 2.0) + rng.vec(-2.0, 2.0),
            _ => rng.vec(-12.0, 12.0),
        };
        if case % 16 == 3 {
            d.y = 0.0;
        }
        let context = format!("case {case}: {a:?} at {start} by {d}, {b:?} at {target}");
        let sep = |p: Vec2| collide(&a, p, &b, target, f32::INFINITY).map(|m| m.separation);
        if sep(start).is_some_and(|s| s < 0.0) {
            continue;
        }
        // A chain segment is passed from behind (once the centre is past
        // its line, it is pushed out in front, as Box2D's chains do).
        let behind = chain && (start - (target - half)).dot(half.perp()) < 0.0;
        if cast_onto_level(&a, start, d, &b, target, !behind, &context) {
            hits += 1;
        } else {
            misses += 1;
        }
    }
    assert!(hits > 2000 && misses > 2000, "{hits} hits, {misses} misses");
}

#[test]
fn random_casts_onto_polygons_touch_at_the_hit_and_never_pass_through_one() {
    let mut rng = Lcg(0x901_760);
    let (mut hits, mut misses) = (0, 0);
    for case in 0..20_000 {
        let a = rng.shape();
        // A regular polygon of 3 to 8 sides, squashed and turned.
        let sides = 3 + (rng.next() * 6.0) as usize;
        let (radius, squash, turn) = (
            rng.range(0.3, 3.0),
            rng.range(0.3, 1.0),
            rng.range(0.0, 6.3),
        );
        let points: Vec<Vec2> = (0..sides)
            .map(|i| {
                let angle = turn + std::f32::consts::TAU * i as f32 / sides as f32;
                let p = Vec2::from_angle(angle) * radius;
                Vec2::new(p.x, p.y * squash)
            })
            .collect();
        let b = Shape::polygon(&points).unwrap();
        let target = rng.vec(-3.0, 3.0);
        let start = rng.vec(-8.0, 8.0);
        let d = match case % 4 {
            0 | 1 => (target - start) * rng.range(0.0, 2.0) + rng.vec(-2.0, 2.0),
            _ => rng.vec(-12.0, 12.0),
        };
        let context = format!("case {case}: {a:?} at {start} by {d}, {b:?} at {target}");
        let sep = |p: Vec2| collide(&a, p, &b, target, f32::INFINITY).map(|m| m.separation);
        if sep(start).is_some_and(|s| s < 0.0) {
            continue;
        }
        if cast_onto_level(&a, start, d, &b, target, true, &context) {
            hits += 1;
        } else {
            misses += 1;
        }
    }
    assert!(hits > 2000 && misses > 2000, "{hits} hits, {misses} misses");
}

/// Casts `a` from `start` by `d` onto level geometry `b` at `target`
/// (apart at the start) and checks the answer: a hit touches, with a unit
/// normal against the motion, overlaps nothing just before it, and its
/// point is on `a`; a miss (checked if `check_miss`) overlaps nowhere on
/// the way. Returns whether it hit.
fn cast_onto_level(
    a: &Shape,
    start: Vec2,
    d: Vec2,
    b: &Shape,
    target: Vec2,
    check_miss: bool,
    context: &str,
) -> bool {
    let sep = |p: Vec2| collide(a, p, b, target, f32::INFINITY).map(|m| m.separation);
    let Some(hit) = cast_shape(a, start, d, b, target) else {
        if check_miss {
            for i in 0..64 {
                let p = start + d * (i as f32 / 63.0);
                let s = sep(p);
                assert!(
                    s.is_none_or(|s| s > -1e-4),
                    "{context}: missed, but at {p} {s:?}"
                );
            }
        }
        return false;
    };
    assert!((0.0..=1.0).contains(&hit.fraction), "{context}: {hit:?}");
    assert!(
        (hit.normal.length() - 1.0).abs() < 1e-5,
        "{context}: {hit:?}"
    );
    assert!(d.dot(hit.normal) <= 0.0, "{context}: {hit:?}");
    let at = start + d * hit.fraction;
    let s = sep(at).unwrap_or_else(|| panic!("{context}: no contact at the hit"));
    assert!(s.abs() < 1e-4, "{context}: {hit:?}, separation {s}");
    if hit.fraction > 0.01 {
        let before = sep(start + d * (hit.fraction - 0.01));
        assert!(
            before.is_none_or(|s| s > -1e-4),
            "{context}: {hit:?} {before:?}"
        );
    }
    assert!(off_surface(a, at, hit.point) < 1e-4, "{context}: {hit:?}");
    true
}
