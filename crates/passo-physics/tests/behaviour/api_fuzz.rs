//! A stateful property test of the public physics API: random sequences of
//! adding, removing, changing, pushing, stepping, snapshotting, restoring
//! and querying, with random values that include NaN, infinities,
//! subnormals, zero and huge numbers. Whatever the sequence, nothing panics
//! (`step` is only given valid timesteps: its assert is documented), no
//! body ever holds a non-finite value, and a snapshot restored into a fresh
//! world steps to the same hash as the world it came from.
//!
//! `cargo test -p passo-physics --test behaviour api_fuzz` runs 2 000 sequences; the
//! long run (a million operations) is
//! `PROPTEST_CASES=40000 cargo test --release -p passo-physics --test behaviour api_fuzz`.

use passo_physics::glam::Vec2;
use passo_physics::{
    BodyDef, BodyId, BodyKind, CollisionFilter, FrictionMix, QueryFilter, Shape, World,
    WorldSettings,
};
use proptest::prelude::*;

/// Any `f32` a game might send by mistake, and ordinary ones.
fn any_value() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -50.0f32..50.0,
        1 => Just(f32::NAN),
        1 => Just(f32::INFINITY),
        1 => Just(f32::NEG_INFINITY),
        1 => Just(1e-40f32),
        1 => Just(0.0f32),
        1 => Just(-0.0f32),
        1 => Just(3e38f32),
        1 => Just(-1e30f32),
        1 => Just(1e20f32),
    ]
}

fn any_vec() -> impl Strategy<Value = Vec2> {
    (any_value(), any_value()).prop_map(|(x, y)| Vec2::new(x, y))
}

/// Mostly sensible vectors, now and then a wild one.
fn vec_mostly_sane() -> impl Strategy<Value = Vec2> {
    prop_oneof![
        6 => (-20.0f32..20.0, -5.0f32..20.0).prop_map(|(x, y)| Vec2::new(x, y)),
        1 => any_vec(),
    ]
}

fn any_shape() -> impl Strategy<Value = Option<Shape>> {
    prop_oneof![
        1 => Just(None),
        3 => (0.05f32..2.0).prop_map(|r| Some(Shape::circle(r))),
        3 => (0.05f32..4.0, 0.05f32..2.0).prop_map(|(w, h)| Some(Shape::rect(w, h))),
        1 => any_value().prop_map(|r| Some(Shape::circle(r))),
        1 => (any_value(), any_value()).prop_map(|(w, h)| Some(Shape::rect(w, h))),
    ]
}

#[derive(Clone, Debug)]
enum Op {
    Add {
        kind: u8,
        position: Vec2,
        velocity: Vec2,
        mass: f32,
        shape: Option<Shape>,
        friction: f32,
        restitution: f32,
        one_way: bool,
        sensor: bool,
    },
    Remove(usize),
    SetVelocity(usize, Vec2),
    SetPosition(usize, Vec2),
    ApplyForce(usize, Vec2),
    ApplyImpulse(usize, Vec2),
    ApplyFriction(usize, f32, f32),
    SetFriction(usize, f32),
    SetRestitution(usize, f32),
    SetDragArea(usize, f32),
    SetFilter(usize, u32, u32),
    SetOneWay(usize, Option<Vec2>),
    SetSensor(usize, bool),
    SetBullet(usize, bool),
    SetFrictionMix(usize, u8),
    DropThrough(usize, f32),
    KinematicTarget(usize, Vec2, f32),
    Wake(usize),
    Step(f32),
    Snapshot,
    Restore,
    Ray(Vec2, Vec2, f32),
    Cast(Option<Shape>, Vec2, Vec2),
    Point(Vec2),
    ContactsOf(usize),
    Interpolated(usize, f32),
    ToggleSleeping,
}

fn op() -> impl Strategy<Value = Op> {
    let body = 0usize..64;
    prop_oneof![
        6 => (0u8..3, vec_mostly_sane(), vec_mostly_sane(), prop_oneof![4 => 0.1f32..10.0, 1 => any_value()],
              any_shape(), prop_oneof![3 => 0.0f32..1.0, 1 => any_value()],
              prop_oneof![3 => 0.0f32..1.0, 1 => any_value()], any::<bool>(), prop::bool::weighted(0.1))
            .prop_map(|(kind, position, velocity, mass, shape, friction, restitution, one_way, sensor)| Op::Add {
                kind, position, velocity, mass, shape, friction, restitution, one_way, sensor,
            }),
        1 => body.clone().prop_map(Op::Remove),
        2 => (body.clone(), any_vec()).prop_map(|(b, v)| Op::SetVelocity(b, v)),
        1 => (body.clone(), vec_mostly_sane()).prop_map(|(b, v)| Op::SetPosition(b, v)),
        2 => (body.clone(), any_vec()).prop_map(|(b, v)| Op::ApplyForce(b, v)),
        2 => (body.clone(), any_vec()).prop_map(|(b, v)| Op::ApplyImpulse(b, v)),
        1 => (body.clone(), any_value(), any_value()).prop_map(|(b, m, n)| Op::ApplyFriction(b, m, n)),
        1 => (body.clone(), any_value()).prop_map(|(b, f)| Op::SetFriction(b, f)),
        1 => (body.clone(), any_value()).prop_map(|(b, e)| Op::SetRestitution(b, e)),
        1 => (body.clone(), any_value()).prop_map(|(b, a)| Op::SetDragArea(b, a)),
        1 => (body.clone(), 0u32..4, 0u32..4).prop_map(|(b, l, m)| Op::SetFilter(b, l, m)),
        1 => (body.clone(), prop::option::of(any_vec())).prop_map(|(b, n)| Op::SetOneWay(b, n)),
        1 => (body.clone(), any::<bool>()).prop_map(|(b, s)| Op::SetSensor(b, s)),
        1 => (body.clone(), any::<bool>()).prop_map(|(b, s)| Op::SetBullet(b, s)),
        1 => (body.clone(), 0u8..5).prop_map(|(b, m)| Op::SetFrictionMix(b, m)),
        1 => (body.clone(), any_value()).prop_map(|(b, s)| Op::DropThrough(b, s)),
        1 => (body.clone(), any_vec(), any_value()).prop_map(|(b, t, dt)| Op::KinematicTarget(b, t, dt)),
        1 => body.clone().prop_map(Op::Wake),
        8 => prop_oneof![Just(1.0f32 / 60.0), Just(1.0 / 240.0), Just(0.1), 1e-6f32..0.05].prop_map(Op::Step),
        1 => Just(Op::Snapshot),
        1 => Just(Op::Restore),
        1 => (any_vec(), any_vec(), any_value()).prop_map(|(o, d, m)| Op::Ray(o, d, m)),
        1 => (any_shape(), any_vec(), any_vec()).prop_map(|(s, a, t)| Op::Cast(s, a, t)),
        1 => any_vec().prop_map(Op::Point),
        1 => body.clone().prop_map(Op::ContactsOf),
        1 => (body, any_value()).prop_map(|(b, a)| Op::Interpolated(b, a)),
        1 => Just(Op::ToggleSleeping),
    ]
}

/// The body a random index names, if any body lives.
fn pick(ids: &[BodyId], i: usize) -> Option<BodyId> {
    (!ids.is_empty()).then(|| ids[i % ids.len()])
}

fn assert_finite(world: &World) -> Result<(), TestCaseError> {
    for b in world.bodies() {
        prop_assert!(
            b.position.is_finite() && b.velocity.is_finite() && b.force.is_finite(),
            "{b:?}"
        );
        if b.kind == BodyKind::Dynamic {
            prop_assert!(b.mass.is_finite() && b.mass > 0.0, "{b:?}");
        }
        prop_assert!(b.friction.is_finite() && (0.0..=1.0).contains(&b.restitution));
    }
    Ok(())
}

fn run(ops: &[Op]) -> Result<(), TestCaseError> {
    let mut world = World::new(WorldSettings {
        interpolation: true,
        ..Default::default()
    })
    .unwrap();
    let mut ids: Vec<BodyId> = Vec::new();
    let mut saved = None;
    for op in ops {
        match op.clone() {
            Op::Add {
                kind,
                position,
                velocity,
                mass,
                shape,
                friction,
                restitution,
                one_way,
                sensor,
            } => {
                let kind =
                    [BodyKind::Dynamic, BodyKind::Static, BodyKind::Kinematic][kind as usize];
                let def = BodyDef {
                    kind,
                    position,
                    velocity,
                    mass,
                    shape,
                    friction,
                    restitution,
                    sensor,
                    one_way: (one_way && kind != BodyKind::Dynamic).then_some(Vec2::Y),
                    ..Default::default()
                };
                if let Ok(id) = world.add_body(def) {
                    ids.push(id);
                }
            }
            Op::Remove(i) => {
                if let Some(id) = pick(&ids, i) {
                    prop_assert!(world.remove_body(id).is_some());
                    ids.retain(|&x| x != id);
                    prop_assert!(world.body(id).is_none());
                }
            }
            Op::SetVelocity(i, v) => {
                if let Some(id) = pick(&ids, i) {
                    world.set_velocity(id, v);
                }
            }
            Op::SetPosition(i, p) => {
                if let Some(id) = pick(&ids, i) {
                    world.set_position(id, p);
                }
            }
            Op::ApplyForce(i, f) => {
                if let Some(id) = pick(&ids, i) {
                    world.apply_force(id, f);
                }
            }
            Op::ApplyImpulse(i, j) => {
                if let Some(id) = pick(&ids, i) {
                    world.apply_impulse(id, j);
                }
            }
            Op::ApplyFriction(i, mu, n) => {
                if let Some(id) = pick(&ids, i) {
                    world.apply_friction(id, mu, n);
                }
            }
            Op::SetFriction(i, mu) => {
                if let Some(id) = pick(&ids, i) {
                    world.set_friction(id, mu);
                }
            }
            Op::SetRestitution(i, e) => {
                if let Some(id) = pick(&ids, i) {
                    let _ = world.set_restitution(id, e);
                }
            }
            Op::SetDragArea(i, a) => {
                if let Some(id) = pick(&ids, i) {
                    let _ = world.set_drag_area(id, a);
                }
            }
            Op::SetFilter(i, layers, mask) => {
                if let Some(id) = pick(&ids, i) {
                    world
                        .set_filter(id, CollisionFilter { layers, mask })
                        .unwrap();
                }
            }
            Op::SetOneWay(i, n) => {
                if let Some(id) = pick(&ids, i) {
                    let _ = world.set_one_way(id, n);
                }
            }
            Op::SetSensor(i, s) => {
                if let Some(id) = pick(&ids, i) {
                    world.set_sensor(id, s).unwrap();
                }
            }
            Op::SetBullet(i, s) => {
                if let Some(id) = pick(&ids, i) {
                    let dynamic = world.body(id).unwrap().kind == BodyKind::Dynamic;
                    prop_assert_eq!(world.set_bullet(id, s).is_ok(), dynamic || !s);
                }
            }
            Op::SetFrictionMix(i, m) => {
                if let Some(id) = pick(&ids, i) {
                    let mix = [
                        FrictionMix::GeometricMean,
                        FrictionMix::Average,
                        FrictionMix::Min,
                        FrictionMix::Multiply,
                        FrictionMix::Max,
                    ][m as usize];
                    world.set_friction_mix(id, mix).unwrap();
                }
            }
            Op::DropThrough(i, s) => {
                if let Some(id) = pick(&ids, i) {
                    world.drop_through(id, s);
                }
            }
            Op::KinematicTarget(i, t, dt) => {
                if let Some(id) = pick(&ids, i) {
                    world.set_kinematic_target(id, t, dt);
                }
            }
            Op::Wake(i) => {
                if let Some(id) = pick(&ids, i) {
                    world.wake(id).unwrap();
                }
            }
            Op::Step(dt) => world.step(dt),
            Op::Snapshot => saved = Some(world.snapshot()),
            Op::Restore => {
                if let Some(snapshot) = &saved {
                    world.restore(snapshot.clone()).unwrap();
                    ids.retain(|&id| world.contains(id));
                    for b in world.bodies() {
                        if !ids.contains(&b.id) {
                            ids.push(b.id);
                        }
                    }
                }
            }
            Op::Ray(origin, dir, max) => {
                if let Some(hit) = world.ray_cast(origin, dir, max) {
                    prop_assert!(hit.distance.is_finite() && hit.point.is_finite());
                }
                let _ = world.ray_cast_with(origin, dir, max, &QueryFilter::solid());
            }
            Op::Cast(shape, start, translation) => {
                if let Some(shape) = shape
                    && let Some(hit) =
                        world.cast_shape(&shape, start, translation, &QueryFilter::default())
                {
                    prop_assert!((0.0..=1.0).contains(&hit.fraction), "{hit:?}");
                }
            }
            Op::Point(p) => {
                let _ = world.query_point(p);
            }
            Op::ContactsOf(i) => {
                if let Some(id) = pick(&ids, i) {
                    for c in world.contacts_of(id) {
                        prop_assert_eq!(c.a, id);
                    }
                    let _ = world.is_standing(id, 0.8);
                }
            }
            Op::Interpolated(i, alpha) => {
                if let Some(id) = pick(&ids, i) {
                    let p = world.interpolated_position(id, alpha).unwrap();
                    prop_assert!(p.is_finite(), "alpha {alpha}: {p}");
                }
            }
            Op::ToggleSleeping => {
                let mut settings = *world.settings();
                if let Some(c) = &mut settings.contacts {
                    c.sleeping = !c.sleeping;
                }
                world.set_settings(settings).unwrap();
            }
        }
        assert_finite(&world)?;
    }
    // A snapshot restored into a fresh world steps to the same bits.
    let mut copy = World::from_snapshot(world.snapshot()).unwrap();
    for _ in 0..20 {
        world.step(1.0 / 60.0);
        copy.step(1.0 / 60.0);
    }
    prop_assert_eq!(world.state_hash(), copy.state_hash());
    assert_finite(&world)?;
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 2_000,
        max_shrink_iters: 2_000,
        ..ProptestConfig::default()
    })]

    #[test]
    fn no_sequence_of_calls_panics_or_stores_a_non_finite_value(
        ops in prop::collection::vec(op(), 1..60)
    ) {
        run(&ops)?;
    }
}
