//! The peer comparison: the same rain of circles in Passo and in rapier2d,
//! in one run, on one thread each.
//!
//! Like for like: the same bodies (radius 0.1 m, 0.1 kg) and walls, dt =
//! 1/60 s, gravity 9.81 m/s², restitution 0, friction 0.6 (both engines
//! combine two equal coefficients to the same value), 4 substeps each
//! (rapier's default `num_solver_iterations` = 4 with one PGS and one
//! stabilisation pass each; Passo's defaults: 4 substeps, each with one pass, the shock
//! propagation pass and one relax pass).
//! Rotations are locked in rapier (Passo's bodies do not rotate), CCD is off
//! in rapier (Passo's speculative contacts are always on). Sleeping is off
//! in both engines for the main comparison; two more columns let both
//! sleep. Penetration is measured the same way for both: Passo's exact
//! geometry at the final positions.
//!
//! With the `box2d` feature, Box2D v3 (through `boxdd`, built from source)
//! runs the same rain too, in the same run: fixed rotation, sleeping off
//! for its main column, 4 substeps, friction 0.6, restitution 0, and its
//! own default contact recycling (`BOX2D_RECYCLE_DISTANCE=0` turns it off,
//! any other distance in metres sets it).
//!
//! With the `parallel` feature, one more column: Passo awake on both cores
//! (its thread pool), the same ticks as the one-thread columns, so that it
//! compares with Box2D's one-thread time of the same run.
//!
//! Run: `cargo run --release -p passo-benches --features rapier --bin peer [N | pN ...]`
//! (N: a rain of N circles; pN: a pyramid of base N; gridN: Box2D's joint
//! grid of N × N without rotation, rods between centres, which rapier's
//! columns leave out (`–`); `--features rapier,box2d`
//! or `rapier,box2d-avx2` for the Box2D columns, and `parallel` for the
//! pool's column).

#[cfg(feature = "box2d")]
use passo_benches::box2d;
use passo_benches::{density_of, pyramid_world, rain_world, time_steps, with_sleeping};
use passo_physics::{BodyKind, Shape, World};
use rapier2d::prelude::*;

struct Rapier {
    world: PhysicsWorld,
    handles: Vec<(passo_physics::BodyId, RigidBodyHandle)>,
}

/// The same bodies as a Passo world, in rapier.
fn rapier_copy(passo: &World, sleep: bool) -> Rapier {
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::new(0.0, -9.81);
    world.integration_parameters.dt = 1.0 / 60.0;
    let mut handles = Vec::new();
    for b in passo.bodies() {
        let rb = match b.kind {
            BodyKind::Static => RigidBodyBuilder::fixed(),
            BodyKind::Kinematic => RigidBodyBuilder::kinematic_velocity_based()
                .linvel(Vector::new(b.velocity.x, b.velocity.y)),
            BodyKind::Dynamic => RigidBodyBuilder::dynamic()
                .lock_rotations()
                .can_sleep(sleep),
        }
        .translation(Vector::new(b.position.x, b.position.y))
        .build();
        let handle = world.bodies.insert(rb);
        let collider = match b.shape.expect("benchmark bodies have shapes") {
            Shape::Circle { radius } => ColliderBuilder::ball(radius),
            Shape::Box { half_extents } => ColliderBuilder::cuboid(half_extents.x, half_extents.y),
            Shape::Capsule {
                half_segment,
                radius,
            } if half_segment.x > 0.0 => ColliderBuilder::capsule_x(half_segment.x, radius),
            Shape::Capsule {
                half_segment,
                radius,
            } => ColliderBuilder::capsule_y(half_segment.y, radius),
            // rapier2d's segments are solid from both sides.
            Shape::Segment { half } | Shape::ChainSegment { half, .. } => {
                ColliderBuilder::segment((-half).to_array().into(), half.to_array().into())
            }
            Shape::Polygon(polygon) => {
                let points: Vec<_> = polygon
                    .vertices()
                    .iter()
                    .map(|v| v.to_array().into())
                    .collect();
                ColliderBuilder::convex_polyline(points).expect("a convex polygon")
            }
        }
        .friction(0.6)
        .restitution(0.0)
        .density(density_of(&b))
        .build();
        world
            .colliders
            .insert_with_parent(collider, handle, &mut world.bodies);
        handles.push((b.id, handle));
    }
    Rapier { world, handles }
}

/// Max penetration of rapier's final state, by Passo's exact geometry.
fn rapier_penetration(passo: &World, rapier: &Rapier) -> f32 {
    let mut copy = passo.clone();
    for &(id, handle) in &rapier.handles {
        let t = rapier.world.bodies[handle].translation();
        copy.set_position(id, passo_physics::glam::Vec2::new(t.x, t.y));
    }
    copy.max_penetration()
}

/// Box2D v3 through `boxdd`.
fn main() {
    // A bad setting is refused before anything runs.
    #[cfg(feature = "box2d")]
    box2d::recycle_distance();
    // `N`: a rain of N circles; `pN`: a pyramid of base N.
    let mut scenes: Vec<(String, World)> = std::env::args()
        .skip(1)
        .filter_map(|a| match a.strip_prefix('p') {
            Some(base) => base
                .parse()
                .ok()
                .map(|b| (format!("pyramid {b}"), pyramid_world(b))),
            // `hillsN`: a rain of N onto ground of 1000 segments;
            // `hillboxesN`: onto as many boxes.
            None if a.starts_with("hillboxes") => a["hillboxes".len()..].parse().ok().map(|n| {
                (
                    format!("rain {n} on 1000 boxes"),
                    passo_benches::rain_on_hills(n, true),
                )
            }),
            // `bridgeN`: a bridge of N planks on rods.
            None if a.starts_with("bridge") => a["bridge".len()..].parse().ok().map(|n| {
                (
                    format!("bridge of {n} planks"),
                    passo_benches::bridge_world(n),
                )
            }),
            // `gridN`: Box2D's joint grid, N × N, without rotation.
            None if a.starts_with("grid") => a["grid".len()..].parse().ok().map(|n| {
                (
                    format!("joint grid {n} × {n}"),
                    passo_benches::joint_grid(n),
                )
            }),
            None if a.starts_with("hills") => a["hills".len()..].parse().ok().map(|n| {
                (
                    format!("rain {n} on 1000 segments"),
                    passo_benches::rain_on_hills(n, false),
                )
            }),
            None => a.parse().ok().map(|n| (format!("rain {n}"), rain_world(n))),
        })
        .collect();
    if scenes.is_empty() {
        scenes = vec![
            ("rain 1000".into(), rain_world(1000)),
            ("rain 10000".into(), rain_world(10_000)),
        ];
    }
    let ticks = 300;
    // Each engine runs three times, interleaved, and the median run is
    // kept: the machine is shared, and a single run can be off by 20 %.
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    println!(
        "| scene | Passo ms/step (awake) | rapier2d ms/step (awake) | speed-up | Passo max penetration | rapier2d max penetration | Passo ms/step (sleeping on) | rapier2d ms/step (sleeping on) |{}{}",
        if cfg!(feature = "box2d") {
            " Box2D v3 ms/step (awake) | Box2D v3 max penetration | Box2D v3 ms/step (sleeping on) |"
        } else {
            ""
        },
        if cfg!(feature = "parallel") {
            " Passo ms/step (awake, both cores) |"
        } else {
            ""
        }
    );
    println!(
        "|---:|---:|---:|---:|---:|---:|---:|---:|{}{}",
        if cfg!(feature = "box2d") {
            "---:|---:|---:|"
        } else {
            ""
        },
        if cfg!(feature = "parallel") {
            "---:|"
        } else {
            ""
        }
    );
    for (n, start) in scenes {
        // One thread for every Passo column but the pool's.
        let mut start = start;
        start.set_parallel(false);
        let awake_start = with_sleeping(&start, false);
        let (mut p, mut ps, mut r, mut s) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut pool = Vec::<f64>::new();
        let (mut passo_pen, mut rapier_pen) = (0.0, 0.0);
        // How far the bridge hangs (with joints only).
        #[cfg_attr(not(feature = "box2d"), allow(unused_mut))]
        let (mut passo_sag, mut box2d_sag) = (0.0f32, None::<f32>);
        // Filled only with the Box2D columns.
        #[cfg_attr(not(feature = "box2d"), allow(unused_mut))]
        let (mut b, mut bs, mut box2d_pen) = (Vec::<f64>::new(), Vec::<f64>::new(), 0.0f32);
        for _ in 0..3 {
            #[cfg(feature = "box2d")]
            {
                let mut awake = box2d::copy(&start, false);
                b.push(time_steps(ticks, || awake.step()).mean_ms);
                box2d_pen = awake.penetration(&start);
                box2d_sag = Some(passo_benches::sag(&start, &awake.state(&start)));
                let mut sleepy = box2d::copy(&start, true);
                bs.push(time_steps(ticks, || sleepy.step()).mean_ms);
            }
            let mut passo = awake_start.clone();
            p.push(time_steps(ticks, || passo.step(1.0 / 60.0)).mean_ms);
            passo_pen = passo.max_penetration();
            passo_sag = passo_benches::sag(&start, &passo);
            if cfg!(feature = "parallel") {
                let mut passo = awake_start.clone();
                passo.set_parallel(true);
                pool.push(time_steps(ticks, || passo.step(1.0 / 60.0)).mean_ms);
            }
            let mut passo_sleepy = start.clone();
            ps.push(time_steps(ticks, || passo_sleepy.step(1.0 / 60.0)).mean_ms);
            // The rapier columns carry no joints over: a scene with joints
            // has none.
            if start.joint_len() > 0 {
                continue;
            }
            let mut awake = rapier_copy(&start, false);
            r.push(time_steps(ticks, || awake.world.step()).mean_ms);
            rapier_pen = rapier_penetration(&start, &awake);
            let mut sleepy = rapier_copy(&start, true);
            s.push(time_steps(ticks, || sleepy.world.step()).mean_ms);
        }
        let (p, ps) = (median(p), median(ps));
        let (r, s) = if r.is_empty() {
            (f64::NAN, f64::NAN)
        } else {
            (median(r), median(s))
        };
        let box2d = if b.is_empty() {
            String::new()
        } else {
            let (b, bs) = (median(b), median(bs));
            format!(" {} | {:.1} mm | {} |", ms(b), box2d_pen * 1e3, ms(bs))
        };
        let pool = if pool.is_empty() {
            String::new()
        } else {
            format!(" {} |", ms(median(pool)))
        };
        let or_dash = |v: f64, text: String| if v.is_nan() { "–".to_owned() } else { text };
        println!(
            "| {n} | {} | {} | {} | {:.1} mm | {} | {} | {} |{box2d}{pool}",
            ms(p),
            or_dash(r, ms(r)),
            or_dash(r, format!("{:.2}×", r / p)),
            passo_pen * 1e3,
            or_dash(r, format!("{:.1} mm", rapier_pen * 1e3)),
            ms(ps),
            or_dash(s, ms(s)),
        );
        if start.joint_len() > 0 {
            let box2d =
                box2d_sag.map_or(String::new(), |s| format!(", Box2D v3 {:.1} mm", s * 1e3));
            eprintln!("{n}: sags {:.1} mm in Passo{box2d}", passo_sag * 1e3);
        }
    }
}

/// Milliseconds to three significant figures (two decimals from 1 ms on):
/// a ratio of two sub-millisecond times read from the table is then good
/// to a percent.
fn ms(v: f64) -> String {
    if v < 1.0 {
        format!("{v:.3}")
    } else {
        format!("{v:.2}")
    }
}
