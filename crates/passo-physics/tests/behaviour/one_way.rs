//! One-way platforms: solid from one side, open from every other.

use crate::support::add_ground;
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyId, CollisionFilter, Shape, World};

const DT: f32 = 1.0 / 60.0;
const UP: Vec2 = Vec2::Y;

/// A world with a one-way platform 4 m wide, 0.2 m thick, its top at y = 2,
/// and solid ground at y = 0.
fn world_with_platform(kind: &str) -> (World, BodyId) {
    let mut world = World::default();
    add_ground(&mut world, 40.0);
    let def = match kind {
        "kinematic" => {
            BodyDef::new_kinematic(Vec2::new(0.0, 1.9), Shape::rect(4.0, 0.2), Vec2::ZERO)
        }
        _ => BodyDef::new_static(Vec2::new(0.0, 1.9), Shape::rect(4.0, 0.2)),
    };
    let platform = world
        .add_body(BodyDef {
            one_way: Some(UP),
            ..def
        })
        .unwrap();
    (world, platform)
}

fn ball(world: &mut World, position: Vec2, velocity: Vec2) -> BodyId {
    world
        .add_body(BodyDef {
            position,
            velocity,
            shape: Some(Shape::circle(0.25)),
            ..Default::default()
        })
        .unwrap()
}

#[test]
fn a_body_moving_up_passes_through_with_its_velocity_unchanged_to_the_bit() {
    for kind in ["static", "kinematic"] {
        // From a crawl to speeds where continuous collision would make a
        // speculative contact from the platform's underside.
        // (5 m/s rises 1.27 m from y = 1.2: just past the top at y = 2.)
        for speed in [5.0, 8.0, 40.0, 200.0] {
            let (mut world, _) = world_with_platform(kind);
            let a = ball(&mut world, Vec2::new(0.0, 1.2), Vec2::new(0.3, speed));
            // The same ball in the same world without the platform.
            let mut open = World::default();
            open.add_body(BodyDef::new_static(
                Vec2::new(0.0, -0.5),
                Shape::rect(40.0, 1.0),
            ))
            .unwrap();
            let b = ball(&mut open, Vec2::new(0.0, 1.2), Vec2::new(0.3, speed));
            let mut passed = false;
            for _ in 0..30 {
                world.step(DT);
                open.step(DT);
                let (x, y) = (world.body(a).unwrap(), open.body(b).unwrap());
                // Until it comes back down onto the platform.
                if x.velocity.y < 0.0 && x.position.y < 2.6 {
                    break;
                }
                assert_eq!(x.velocity, y.velocity, "{kind}, {speed} m/s");
                assert_eq!(x.position, y.position, "{kind}, {speed} m/s");
                passed |= x.position.y - 0.25 > 2.0;
            }
            assert!(passed, "{kind}, {speed} m/s: went above the platform");
        }
    }
}

#[test]
fn a_body_falling_onto_it_from_above_lands_and_stands() {
    for kind in ["static", "kinematic"] {
        let (mut world, platform) = world_with_platform(kind);
        let a = ball(&mut world, Vec2::new(0.5, 5.0), Vec2::ZERO);
        for _ in 0..120 {
            world.step(DT);
        }
        let b = world.body(a).unwrap();
        assert!(
            (b.position.y - 2.25).abs() < 0.006,
            "{kind}: at {}",
            b.position.y
        );
        assert!(world.is_standing(a, 0.8), "{kind}");
        assert_eq!(world.standing_on(a, 0.8), Some(platform), "{kind}");
    }
}

#[test]
fn a_body_jumping_up_through_lands_on_top() {
    let (mut world, platform) = world_with_platform("static");
    let a = ball(&mut world, Vec2::new(0.0, 0.25), Vec2::new(0.0, 8.0));
    for _ in 0..180 {
        world.step(DT);
    }
    assert!((world.body(a).unwrap().position.y - 2.25).abs() < 0.006);
    assert_eq!(world.standing_on(a, 0.8), Some(platform));
}

#[test]
fn a_body_partly_inside_when_it_starts_to_fall_goes_on_through() {
    let (mut world, _) = world_with_platform("static");
    // Its bottom 12 cm below the platform's top, at rest.
    let a = ball(&mut world, Vec2::new(0.0, 2.13), Vec2::ZERO);
    for _ in 0..120 {
        world.step(DT);
    }
    let y = world.body(a).unwrap().position.y;
    assert!((y - 0.25).abs() < 0.006, "fell to the ground: {y}");
}

#[test]
fn a_body_coming_from_the_side_passes_through() {
    let (mut world, _) = world_with_platform("static");
    // 30 m/s for 0.2 s: 6 m to the right, 0.2 m lower.
    let a = ball(&mut world, Vec2::new(-3.0, 1.9), Vec2::new(30.0, 0.0));
    for _ in 0..12 {
        world.step(DT);
    }
    assert!(
        world.body(a).unwrap().position.x > 2.5,
        "through the platform"
    );
}

#[test]
fn drop_through_lets_a_standing_body_fall_to_the_ground() {
    let (mut world, platform) = world_with_platform("static");
    let a = ball(&mut world, Vec2::new(0.0, 2.25), Vec2::ZERO);
    for _ in 0..60 {
        world.step(DT);
    }
    assert_eq!(world.standing_on(a, 0.8), Some(platform));
    world.drop_through(a, 0.25);
    for _ in 0..120 {
        world.step(DT);
    }
    let y = world.body(a).unwrap().position.y;
    assert!((y - 0.25).abs() < 0.006, "on the ground: {y}");
    assert!(world.try_drop_through(a, -1.0).is_err());
}

/// Sets `a` just above the platform, falling at 3 m/s onto it, and steps
/// 40 ticks; returns whether the platform then holds it.
fn lands_on_the_platform(world: &mut World, a: BodyId, platform: BodyId) -> bool {
    world.set_position(a, Vec2::new(0.0, 2.3));
    world.set_velocity(a, Vec2::new(0.0, -3.0));
    for _ in 0..40 {
        world.step(DT);
    }
    world.standing_on(a, 0.8) == Some(platform)
}

#[test]
fn drop_through_lasts_its_time_then_the_platform_holds_the_same_body_again() {
    // The timer counts down by dt each step: it runs out in the step that
    // takes it to zero, ceil(seconds / dt) steps after the call.
    for seconds in [0.2f32, 0.5, 1.0] {
        let ticks = (seconds / DT).ceil() as usize;
        // While the time runs, the body passes through from above every
        // time it meets the platform: set back above it three ticks before
        // the end of its time, it falls through again.
        let (mut world, _) = world_with_platform("static");
        let a = ball(&mut world, Vec2::new(0.0, 2.25), Vec2::ZERO);
        world.drop_through(a, seconds);
        for _ in 0..ticks - 3 {
            world.step(DT);
        }
        world.set_position(a, Vec2::new(0.0, 2.3));
        world.set_velocity(a, Vec2::new(0.0, -3.0));
        // It enters the platform before the time runs out, and a body
        // still inside then goes on through.
        for _ in 0..60 {
            world.step(DT);
        }
        let y = world.body(a).unwrap().position.y;
        assert!(
            (y - 0.25).abs() < 0.01,
            "{seconds} s: through the platform to the ground: {y}"
        );
        // Once it ran out, the same body lands on the platform.
        let (mut world, platform) = world_with_platform("static");
        let a = ball(&mut world, Vec2::new(0.0, 2.25), Vec2::ZERO);
        world.drop_through(a, seconds);
        for _ in 0..ticks {
            world.step(DT);
        }
        assert!(
            lands_on_the_platform(&mut world, a, platform),
            "{seconds} s: held again after {ticks} ticks"
        );
        // A drop-through of 0 seconds ends one early.
        let (mut world, platform) = world_with_platform("static");
        let a = ball(&mut world, Vec2::new(0.0, 2.25), Vec2::ZERO);
        world.drop_through(a, seconds);
        world.step(DT);
        world.drop_through(a, 0.0);
        assert!(
            lands_on_the_platform(&mut world, a, platform),
            "{seconds} s, ended"
        );
    }
}

#[test]
fn a_platform_can_be_made_one_way_and_a_filter_changed_after_creation() {
    let mut world = World::default();
    let slab = world
        .add_body(BodyDef::new_static(
            Vec2::new(0.0, 1.9),
            Shape::rect(4.0, 0.2),
        ))
        .unwrap();
    add_ground(&mut world, 40.0);
    let a = ball(&mut world, Vec2::new(0.0, 0.25), Vec2::new(0.0, 8.0));
    world.step(DT);
    for _ in 0..10 {
        world.step(DT);
    }
    assert!(
        world.body(a).unwrap().position.y < 1.8,
        "solid: it hits the underside"
    );
    world.set_one_way(slab, Some(Vec2::new(0.0, 3.0))).unwrap();
    assert_eq!(world.body(slab).unwrap().one_way, Some(UP), "normalised");
    world.set_velocity(a, Vec2::new(0.0, 8.0));
    for _ in 0..120 {
        world.step(DT);
    }
    assert_eq!(
        world.standing_on(a, 0.8),
        Some(slab),
        "one-way: up through, then on it"
    );
    // A filter that no longer touches the platform's layer: it falls.
    world
        .set_filter(
            a,
            CollisionFilter {
                layers: 2,
                mask: !1 | 1,
            },
        )
        .unwrap();
    world
        .set_filter(
            slab,
            CollisionFilter {
                layers: 4,
                mask: !2,
            },
        )
        .unwrap();
    for _ in 0..120 {
        world.step(DT);
    }
    assert!((world.body(a).unwrap().position.y - 0.25).abs() < 0.006);
    // Dynamic bodies cannot be one-way; zero normals are refused.
    assert!(world.set_one_way(a, Some(UP)).is_err());
    assert!(world.set_one_way(slab, Some(Vec2::ZERO)).is_err());
    // Any other finite normal is a direction, however long or short (its
    // length overflowed or rounded to zero, and it was refused as zero).
    let platform =
        |normal| BodyDef::new_static(Vec2::ZERO, Shape::rect(1.0, 0.2)).with_one_way(normal);
    for (normal, unit) in [
        (Vec2::new(0.0, 3e38), UP),
        (Vec2::new(3e38, 3e38), Vec2::ONE.normalize()),
        (Vec2::new(1e-30, 1e-30), Vec2::ONE.normalize()),
        (Vec2::new(0.0, 1e-45), UP),
    ] {
        let id = world.add_body(platform(normal)).unwrap();
        assert_eq!(world.body(id).unwrap().one_way, Some(unit), "{normal}");
        world.set_one_way(id, Some(-normal)).unwrap();
        assert_eq!(world.body(id).unwrap().one_way, Some(-unit), "{normal}");
    }
    assert!(
        world
            .add_body(BodyDef {
                one_way: Some(UP),
                ..BodyDef::point_mass(Vec2::ZERO)
            })
            .is_err()
    );
}

#[test]
fn one_way_platforms_and_drop_through_survive_a_snapshot() {
    let (mut world, _) = world_with_platform("kinematic");
    let a = ball(&mut world, Vec2::new(0.0, 2.25), Vec2::ZERO);
    for _ in 0..30 {
        world.step(DT);
    }
    world.drop_through(a, 0.2);
    world.step(DT);
    let mut copy = World::from_snapshot(world.snapshot()).unwrap();
    for _ in 0..90 {
        world.step(DT);
        copy.step(DT);
    }
    assert_eq!(world.state_hash(), copy.state_hash());
    assert!(copy.body(a).unwrap().position.y < 1.0, "it dropped through");
}

/// A world with continuous collision off (contacts reach 2 cm) and solid
/// ground at y = 0.
fn without_sweeps() -> World {
    use passo_physics::{ContactSettings, WorldSettings};
    let settings = WorldSettings {
        contacts: Some(ContactSettings {
            continuous: false,
            ..Default::default()
        }),
        ..Default::default()
    };
    let mut world = World::new(settings).unwrap();
    add_ground(&mut world, 40.0);
    world
}

#[test]
fn without_continuous_collision_a_body_falling_onto_it_lands_as_on_a_solid_one() {
    // With continuous collision off, contacts reach 2 cm: a box falling
    // from 5 to 50 cm was first seen deeper than a landing and went
    // through, 1 to 7 times in 10, where a solid platform held every time.
    for drop in [0.05f32, 0.1, 0.2, 0.5, 2.0] {
        for i in 0..10 {
            let mut world = without_sweeps();
            let platform = BodyDef::new_static(Vec2::new(0.0, 1.9), Shape::rect(6.0, 0.2));
            world.add_body(platform.with_one_way(UP)).unwrap();
            let y = 2.4 + drop + 0.01 * i as f32;
            let b = world
                .add_body(BodyDef::new_dynamic(
                    Vec2::new(0.0, y),
                    Shape::rect(0.8, 0.8),
                ))
                .unwrap();
            for _ in 0..120 {
                world.step(DT);
            }
            let y = world.body(b).unwrap().position.y;
            assert!(
                (y - 2.4).abs() < 0.01,
                "from {drop} m (+{i} cm): at y = {y}"
            );
        }
    }
}

#[test]
fn a_body_standing_on_it_holds_when_a_heavier_one_lands_on_top() {
    // A 1 kg box stands on the platform; a box of 5 to 20 kg lands on it.
    // The light box sinks a little, as on a solid platform, and used to
    // drop through with the heavy one once it sank deeper than a landing.
    let run = |one_way: bool, mass: f32, drop: f32| {
        let mut world = World::default();
        add_ground(&mut world, 40.0);
        let platform = BodyDef::new_static(Vec2::new(0.0, 1.9), Shape::rect(4.0, 0.2));
        world
            .add_body(BodyDef {
                one_way: one_way.then_some(UP),
                ..platform
            })
            .unwrap();
        let light = world
            .add_body(BodyDef::new_dynamic(
                Vec2::new(0.0, 2.4),
                Shape::rect(0.8, 0.8),
            ))
            .unwrap();
        let heavy = BodyDef::new_dynamic(Vec2::new(0.0, 3.3 + drop), Shape::rect(1.0, 1.0));
        world.add_body(heavy.with_mass(mass)).unwrap();
        let mut lowest = f32::INFINITY;
        for _ in 0..240 {
            world.step(DT);
            lowest = lowest.min(world.body(light).unwrap().position.y);
        }
        (lowest, world.body(light).unwrap().position.y)
    };
    for (mass, drop) in [(5.0f32, 3.0f32), (10.0, 3.0), (10.0, 5.0), (20.0, 0.5)] {
        let (lowest, end) = run(true, mass, drop);
        let (solid_lowest, solid_end) = run(false, mass, drop);
        let case = format!("{mass} kg from {drop} m");
        assert!(lowest > 2.4 - 0.05, "{case}: sank to {lowest}");
        assert!(
            (lowest - solid_lowest).abs() < 1e-3,
            "{case}: {lowest}, solid {solid_lowest}"
        );
        assert!(
            (end - solid_end).abs() < 1e-3,
            "{case}: ends at {end}, solid {solid_end}"
        );
    }
}

#[test]
fn solid_queries_meet_a_one_way_platform_only_from_its_solid_side() {
    use passo_physics::QueryFilter;
    let (world, platform) = world_with_platform("static");
    let ground = |hit: Option<BodyId>| hit.is_some_and(|b| b != platform);
    let solid = QueryFilter::solid();
    let every_side = QueryFilter::default();
    // Across the platform and past both ends.
    for k in 0..=20 {
        let x = -2.47 + 0.25 * k as f32;
        let over = x.abs() < 2.0;
        let down = |filter| world.ray_cast_with(Vec2::new(x, 5.0), -UP, 10.0, filter);
        let up = |filter| world.ray_cast_with(Vec2::new(x, 0.5), UP, 10.0, filter);
        // From above it stops both; from below only a query that sees every side.
        for filter in [&solid, &every_side] {
            let hit = down(filter).unwrap();
            if over {
                assert_eq!(hit.body, platform, "x = {x}");
                assert!((hit.distance - 3.0).abs() < 1e-5, "x = {x}: {hit:?}");
            } else {
                assert!(ground(Some(hit.body)), "x = {x}");
            }
        }
        assert_eq!(up(&solid), None, "x = {x}");
        assert_eq!(
            up(&every_side).map(|h| h.body),
            over.then_some(platform),
            "x = {x}"
        );
        // A box cast up from under it (a head under a ledge).
        let head = Shape::rect(0.4, 0.4);
        let cast = |filter| world.cast_shape(&head, Vec2::new(x, 1.0), UP * 3.0, filter);
        assert!(cast(&solid).is_none(), "x = {x}");
        let expected = (x.abs() < 2.2).then_some(platform);
        assert_eq!(cast(&every_side).map(|h| h.body), expected, "x = {x}");
        // Started inside it, a ray goes through to the ground.
        if over {
            let inside = Vec2::new(x, 1.9);
            let hit = world.ray_cast_with(inside, -UP, 10.0, &solid).unwrap();
            assert!(
                ground(Some(hit.body)) && (hit.distance - 1.9).abs() < 1e-5,
                "{hit:?}"
            );
            let hit = world.ray_cast_with(inside, -UP, 10.0, &every_side).unwrap();
            assert_eq!((hit.body, hit.distance), (platform, 0.0));
        }
        // A box resting on top (within a landing's depth) is stopped at once.
        if over {
            let resting = Vec2::new(x, 2.2 - 0.5 * passo_physics::constants::ONE_WAY_DEPTH);
            let hit = world.cast_shape(&head, resting, -UP, &solid).unwrap();
            assert_eq!((hit.body, hit.fraction), (platform, 0.0), "x = {x}");
        }
    }
}

#[test]
fn a_dropping_body_s_own_queries_pass_through_one_way_platforms() {
    use passo_physics::QueryFilter;
    let (mut world, platform) = world_with_platform("static");
    let player = ball(&mut world, Vec2::new(0.0, 2.25), Vec2::ZERO);
    let filter = QueryFilter::solid().excluding(player);
    let ground_ray = |world: &World| {
        world
            .ray_cast_with(Vec2::new(0.0, 2.0), -UP, 5.0, &filter)
            .map(|h| (h.body, h.distance))
    };
    // Standing on it, the ray from its feet (on the top face) is stopped
    // there.
    assert_eq!(ground_ray(&world), Some((platform, 0.0)));
    world.drop_through(player, 0.5);
    let (body, distance) = ground_ray(&world).unwrap();
    assert!(
        body != platform && (distance - 2.0).abs() < 1e-5,
        "{body:?} {distance}"
    );
    // Another body's queries still meet it.
    let other = QueryFilter::solid();
    assert_eq!(
        world
            .ray_cast_with(Vec2::new(1.0, 3.0), -UP, 5.0, &other)
            .map(|h| h.body),
        Some(platform)
    );
    // Once the time is up it stops the player's queries again.
    for _ in 0..40 {
        world.step(DT);
    }
    world.set_position(player, Vec2::new(0.0, 3.0));
    assert_eq!(ground_ray(&world).map(|h| h.0), Some(platform));
}

#[test]
fn without_continuous_collision_a_body_falling_onto_a_moving_lift_lands_on_it() {
    // The same falls onto a one-way lift rising at 1.5 m/s or sinking at
    // 0.5 m/s: how deep a landing may first be seen depends on how fast
    // the two close, the lift's motion with the box's.
    for lift in [1.5f32, -0.5] {
        for drop in [0.05f32, 0.2, 0.5, 2.0] {
            for i in 0..5 {
                let mut world = without_sweeps();
                let velocity = Vec2::new(0.0, lift);
                let def =
                    BodyDef::new_kinematic(Vec2::new(0.0, 1.9), Shape::rect(6.0, 0.2), velocity);
                let platform = world.add_body(def.with_one_way(UP)).unwrap();
                let y = 2.4 + drop + 0.01 * i as f32;
                let def = BodyDef::new_dynamic(Vec2::new(0.0, y), Shape::rect(0.8, 0.8));
                let b = world.add_body(def).unwrap();
                for _ in 0..60 {
                    world.step(DT);
                }
                let top = world.body(platform).unwrap().position.y + 0.1;
                let y = world.body(b).unwrap().position.y;
                assert!(
                    (y - 0.4 - top).abs() < 0.01,
                    "lift {lift} m/s, from {drop} m (+{i} cm): {} m above its top",
                    y - 0.4 - top
                );
            }
        }
    }
}
