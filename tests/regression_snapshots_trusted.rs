//! Snapshots were trusted in places: a warm-start impulse of -1 or NaN (or
//! out of order, which made the warm start differ on one thread and on the
//! pool), an infinite friction, a sleeping contact naming a shapeless body, a NaN
//! speed limit or a free list naming a slot twice got past `validate` and
//! panicked later or produced NaN positions or two bodies with one id. A
//! carried contact with a normal of 1e30 (which a reused contact is solved
//! with as it is) gave thousands of non-finite resets.
//! Every such edit is now refused with a message, and a step count near
//! `u64::MAX` steps on without overflowing.

use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, Shape, World, WorldSnapshot};
use passo_tests::add_ground;

const DT: f32 = 1.0 / 60.0;

/// A settled pile (contacts with impulses, sleeping contacts) and a freed
/// slot, as RON text.
fn snapshot_text() -> String {
    let mut world = World::default();
    add_ground(&mut world, 10.0);
    let gone = world
        .add_body(BodyDef::point_mass(Vec2::new(5.0, 5.0)))
        .unwrap();
    for i in 0..3 {
        world
            .add_body(BodyDef::new_dynamic(
                Vec2::new(0.0, 0.5 + i as f32),
                Shape::rect(1.0, 1.0),
            ))
            .unwrap();
    }
    world.remove_body(gone).unwrap();
    for _ in 0..90 {
        world.step(DT);
    }
    ron::to_string(&world.snapshot()).unwrap()
}

fn restore(text: &str) -> Result<World, String> {
    let snapshot: WorldSnapshot = ron::from_str(text).map_err(|e| e.to_string())?;
    World::from_snapshot(snapshot).map_err(|e| e.to_string())
}

/// The text with the first `from` replaced by `to` (which must be there).
fn edited(text: &str, edits: &[(&str, &str)]) -> String {
    let mut text = text.to_owned();
    for (from, to) in edits {
        assert!(text.contains(from), "{from} is in the snapshot");
        text = text.replacen(from, to, 1);
    }
    text
}

#[test]
fn each_untrusted_edit_is_refused_with_a_message() {
    let text = snapshot_text();
    assert!(restore(&text).is_ok(), "the unedited snapshot restores");
    let cases: &[(&str, &[(&str, &str)])] = &[
        (
            "a negative warm-start impulse",
            &[("normal_impulse:0.", "normal_impulse:-1.")],
        ),
        (
            "a NaN warm-start impulse",
            &[("normal_impulse:0.", "normal_impulse:NaN,x:0.")],
        ),
        (
            "an infinite static friction",
            &[("friction:[0.6]", "friction:[inf]")],
        ),
        (
            "a friction past MAX_FRICTION",
            &[("friction:[0.6,", "friction:[1e20,")],
        ),
        (
            "a sleeping contact with a shapeless body",
            &[
                ("shape:Some(Box(half_extents:(5.0,0.5)))", "shape:None"),
                ("shaped_static:1", "shaped_static:0"),
            ],
        ),
        (
            "a NaN speed limit",
            &[
                ("max_speed:None", "max_speed:Some(NaN)"),
                ("speed_overrides:0", "speed_overrides:1"),
            ],
        ),
        (
            "a subnormal mass",
            &[
                ("inv_mass:[1.0,", "inv_mass:[1e40,"),
                ("mass:1.0,", "mass:1e-40,"),
            ],
        ),
        ("a slot freed twice", &[("free:[1]", "free:[1,1]")]),
        (
            "a negative carried push",
            &[("push_impulse:0.0", "push_impulse:-1.0")],
        ),
        (
            "carried impulses out of order",
            &[(
                "key:((index:2,generation:0),(index:3,generation:0))",
                "key:((index:0,generation:0),(index:1,generation:0))",
            )],
        ),
        (
            "carried impulses naming the higher slot first",
            &[(
                "key:((index:3,generation:0),(index:4,generation:0))",
                "key:((index:4,generation:0),(index:3,generation:0))",
            )],
        ),
        (
            "a contact normal that is not a unit vector",
            &[("normal:(0.0,-1.0)", "normal:(0.0,-1e30)")],
        ),
        (
            "a negative contact friction",
            &[(
                "friction:0.6,normal_impulse",
                "friction:-0.6,normal_impulse",
            )],
        ),
        (
            "a contact of 200 points",
            &[("point_count:2", "point_count:200")],
        ),
        (
            "a NaN contact point",
            &[("points:((-0.5,0.0)", "points:((NaN,0.0)")],
        ),
        (
            "a NaN contact anchor",
            &[("anchor:(0.0,-1.0)", "anchor:(NaN,-1.0)")],
        ),
        (
            "a bouncy contact marked for reuse",
            &[(
                "restitution:0.0,impact_u:0.0,half_an_h:0.0,anchor:(0.0,-1.0)",
                "restitution:0.5,impact_u:0.0,half_an_h:0.0,anchor:(0.0,-1.0)",
            )],
        ),
        (
            "a contact seen farther apart than it is",
            &[(",lead:0.0)", ",lead:-0.5)")],
        ),
        (
            "a reused contact with a character's lead",
            &[("reusable:true,lead:0.0)", "reusable:true,lead:0.5)")],
        ),
        (
            "a static bullet",
            &[(
                "bullet:false,character:false,gravity_scale:1.0,min_speed:None,max_speed:None,user_data:0)]),speed_overrides",
                "bullet:true,character:false,gravity_scale:1.0,min_speed:None,max_speed:None,user_data:0)]),speed_overrides",
            )],
        ),
    ];
    for (what, edits) in cases {
        let text = edited(&text, edits);
        match restore(&text) {
            Ok(_) => panic!("{what}: restored"),
            Err(e) => assert!(
                e.contains("invalid world snapshot") || e.contains("must be"),
                "{what}: {e}"
            ),
        }
    }
}

#[test]
fn a_step_count_at_the_end_of_u64_steps_on_without_overflow() {
    let text = edited(
        &snapshot_text(),
        &[("steps:90", "steps:18446744073709551615")],
    );
    let mut world = restore(&text).unwrap();
    world.step(DT);
    world.step(DT);
    assert_eq!(world.stats().steps, u64::MAX);
    assert!(world.bodies().all(|b| b.position.is_finite()));
    // Queries follow the bodies although the count no longer changes: a
    // ray finds a falling ball where it is now, as a fresh copy does.
    let ball = world
        .add_body(BodyDef::new_dynamic(
            Vec2::new(20.0, 5.0),
            Shape::circle(0.2),
        ))
        .unwrap();
    let up = |w: &World| {
        w.ray_cast(Vec2::new(20.0, 3.0), Vec2::new(0.0, 1.0), 1.0)
            .map(|hit| hit.body)
    };
    assert_eq!(up(&world), None);
    let mut hits = 0;
    for _ in 0..60 {
        world.step(DT);
        let copy = World::from_snapshot(world.snapshot()).unwrap();
        assert_eq!(up(&world), up(&copy));
        hits += usize::from(up(&world) == Some(ball));
    }
    assert!(hits > 3, "the ball fell past the ray: {hits} ticks");
}

#[test]
fn subnormal_and_out_of_range_materials_are_refused_where_they_enter() {
    let mut world = World::default();
    let err = world
        .add_body(BodyDef::point_mass(Vec2::ZERO).with_mass(1e-40))
        .unwrap_err()
        .to_string();
    assert!(err.contains("BodyDef::mass"), "{err}");
    assert!(
        world
            .add_body(BodyDef::new_static(Vec2::ZERO, Shape::circle(1.0)).with_friction(1e20))
            .is_err()
    );
    // Two touching bodies at the largest friction step without a panic.
    world
        .add_body(
            BodyDef::new_static(Vec2::new(0.0, -0.5), Shape::rect(10.0, 1.0))
                .with_friction(passo_physics::constants::MAX_FRICTION),
        )
        .unwrap();
    let b = world
        .add_body(
            BodyDef::new_dynamic(Vec2::new(0.0, 0.5), Shape::rect(1.0, 1.0))
                .with_friction(passo_physics::constants::MAX_FRICTION)
                .with_velocity(Vec2::new(5.0, 0.0)),
        )
        .unwrap();
    world.set_friction(b, 1e20);
    assert_eq!(world.stats().rejected_inputs, 1);
    for _ in 0..60 {
        world.step(DT);
    }
    assert!(world.body(b).unwrap().velocity.is_finite());
    // A scene with a density that gives a subnormal mass names the body.
    let scene = passo_scene::Scene::parse(
        "(name: \"t\", bodies: [(shape: Circle(radius: 1e-20), density: 1e-5)])",
        "t.ron",
    );
    let err = scene
        .and_then(|s| s.build().map(|_| ()))
        .unwrap_err()
        .to_string();
    assert!(err.contains("bodies[0]"), "{err}");
}

#[test]
fn a_kinematic_speed_past_the_limit_is_refused_and_counters_saturate() {
    let mut world = World::default();
    let lift = world
        .add_body(BodyDef {
            kind: passo_physics::BodyKind::Kinematic,
            velocity: Vec2::new(3.0, 0.0),
            shape: Some(Shape::rect(2.0, 0.5)),
            ..BodyDef::default()
        })
        .unwrap();
    world.step(DT);
    let text = ron::to_string(&world.snapshot()).unwrap();
    assert!(restore(&text).is_ok());
    // 3e38 m/s has no finite square (the step would carry the platform
    // to an infinite position in a few ticks).
    let fast = edited(&text, &[("vel:[(3.0,0.0)]", "vel:[(3e38,0.0)]")]);
    let err = restore(&fast).map(|_| ()).unwrap_err();
    assert!(
        err.contains("dynamic body 0") && err.contains("its square"),
        "{err}"
    );
    // A kinematic body faster than `max_speed` restores: `set_settings`
    // may lower the limit below a platform already going (a world's own
    // snapshot was refused then).
    let mut slower = World::from_snapshot(ron::from_str(&text).unwrap()).unwrap();
    let settings = passo_physics::WorldSettings {
        max_speed: 2.0,
        ..*slower.settings()
    };
    slower.set_settings(settings).unwrap();
    let copy = World::from_snapshot(slower.snapshot()).unwrap();
    assert_eq!(copy.body(lift).unwrap().velocity, Vec2::new(3.0, 0.0));
    // Counters at their end saturate instead of overflowing.
    let text = edited(
        &text,
        &[
            ("rejected_inputs:0", "rejected_inputs:18446744073709551615"),
            (
                "non_finite_resets:0",
                "non_finite_resets:18446744073709551615",
            ),
        ],
    );
    let mut world = restore(&text).unwrap();
    world.set_velocity(lift, Vec2::new(f32::NAN, 0.0));
    world.step(DT);
    let stats = world.stats();
    assert_eq!(
        (stats.rejected_inputs, stats.non_finite_resets),
        (u64::MAX, u64::MAX)
    );
}
