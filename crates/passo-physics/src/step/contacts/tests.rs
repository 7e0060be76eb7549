//! Tests of `contacts`.

use super::*;
use crate::{BodyDef, BodyKind, Shape};

/// A world of two boxes on the ground with the settings `tweak` makes.
fn world(tweak: impl Fn(&mut ContactSettings), kinematic: bool, bouncy: bool) -> World {
    let mut world = World::default();
    world
        .add_body(BodyDef::new_static(Vec2::ZERO, Shape::rect(10.0, 1.0)))
        .unwrap();
    for (x, kind) in [(0.0, BodyKind::Dynamic), (2.0, BodyKind::Kinematic)] {
        let kind = if kinematic { kind } else { BodyKind::Dynamic };
        let def = BodyDef {
            kind,
            position: Vec2::new(x, 1.0),
            shape: Some(Shape::rect(1.0, 1.0)),
            restitution: if bouncy { 0.5 } else { 0.0 },
            ..Default::default()
        };
        world.add_body(def).unwrap();
    }
    let mut settings = *world.settings();
    tweak(settings.contacts.as_mut().unwrap());
    world.set_settings(settings).unwrap();
    world
}

/// Every combination of the settings that add or drop stages: the
/// list keeps the stages' order, splits into the substep's stages on
/// the arrays, on the solver's copy and after, and holds exactly the
/// stages whose condition is met.
#[test]
fn the_stage_list_holds_what_the_settings_ask_for_in_order() {
    use ContactStage::*;
    let order = [
        IntegrateVelocities,
        HoldSleepers,
        HoldKinematic,
        WarmStart,
        Solve,
        PropagateShock,
        IntegratePositions,
        Relax,
        SweepFastBodies,
        Restitution,
        StoreSeparations,
        ClampSpeeds,
    ];
    let mut seen = std::collections::BTreeSet::new();
    for case in 0..128u32 {
        let bit = |k: u32| case & (1 << k) != 0;
        let (warm, relax, continuous, kinematic, bouncy) = (bit(0), bit(1), bit(2), bit(3), bit(4));
        let (shock, gravity) = (bit(5), bit(6));
        let mut w = world(
            |c| {
                c.warm_starting = warm;
                c.relax_iterations = if relax { 2 } else { 0 };
                c.continuous = continuous;
                c.shock_propagation = shock;
            },
            kinematic,
            bouncy,
        );
        if !gravity {
            let mut settings = *w.settings();
            settings.forces.gravity = None;
            w.set_settings(settings).unwrap();
        }
        let stages = w.contact_stages();
        let rank = |s: &ContactStage| order.iter().position(|o| o == s).unwrap();
        assert!(
            stages.windows(2).all(|p| rank(&p[0]) < rank(&p[1])),
            "{stages:?}"
        );
        let expect = |s: ContactStage, on: bool| {
            assert_eq!(stages.contains(&s), on, "case {case}: {s:?} in {stages:?}");
        };
        expect(WarmStart, warm);
        expect(Relax, relax);
        expect(SweepFastBodies, continuous);
        expect(HoldKinematic, kinematic);
        expect(Restitution, bouncy);
        expect(PropagateShock, shock && gravity);
        for s in [
            IntegrateVelocities,
            Solve,
            IntegratePositions,
            StoreSeparations,
        ] {
            expect(s, true);
        }
        let plan = SubstepPlan::new(&w, &w.contact_settings().unwrap(), 1.0, false, false);
        let (on_bodies, on_copy, after) = plan.stages.parts();
        assert!(
            on_bodies
                .iter()
                .all(|s| s.in_substep() && !s.on_solver_copy())
        );
        assert!(on_copy.iter().all(|s| s.in_substep() && s.on_solver_copy()));
        assert!(after.iter().all(|s| !s.in_substep()));
        assert_eq!([on_bodies, on_copy, after].concat(), stages);
        seen.extend(stages.iter().map(rank));
    }
    // Every stage but HoldSleepers (no body asleep here) was listed in
    // some case (ClampSpeeds by the default minimum-speed snap).
    assert_eq!(seen.len(), order.len() - 1);
}

#[test]
fn a_world_all_asleep_lists_no_substep_stage() {
    // Two boxes at rest fall asleep: the step runs no substep, and the
    // list says so, whatever the settings ask for.
    for warm in [false, true] {
        let mut w = world(
            |c| {
                c.warm_starting = warm;
                c.relax_iterations = 2;
                c.continuous = true;
                c.shock_propagation = true;
            },
            false,
            false,
        );
        let boxes: Vec<_> = w.bodies().filter(|b| b.kind == BodyKind::Dynamic).collect();
        let awake = w.contact_stages();
        assert!(awake.iter().any(|s| s.in_substep()), "{awake:?}");
        for _ in 0..300 {
            w.step(1.0 / 60.0);
        }
        assert!(boxes.iter().all(|b| w.is_asleep(b.id) == Some(true)));
        let stages = w.contact_stages();
        assert!(!stages.iter().any(|s| s.in_substep()), "{stages:?}");
        assert!(stages.contains(&ContactStage::StoreSeparations));
    }
}

#[test]
fn a_body_left_non_finite_is_put_back_where_the_step_began() {
    // Valid inputs keep every number finite (positions within
    // `MAX_COORDINATE`, speeds whose square is finite), so the guard is
    // tested on a world whose state is spoiled by hand after a step: body
    // 0's position, then body 1's velocity, non-finite, and one contact's
    // impulse NaN.
    for spoiled in [0, 1] {
        // Three boxes on the ground (an even number of them finite once
        // one is spoiled, which an exclusive or would count as none).
        let mut w = world(|_| {}, false, false);
        let third = BodyDef::new_dynamic(Vec2::new(-2.0, 1.0), Shape::rect(1.0, 1.0));
        w.add_body(third).unwrap();
        w.step(1.0 / 60.0);
        let mut cw = w.contacts.take().unwrap();
        let rows = cw.solved.rows.clone();
        assert!(rows.len() >= 2 && rows.iter().all(|r| r.normal_impulse > 0.0));
        let before: Vec<Vec2> = (0..3).map(|i| w.dynamic.pos.at(i)).collect();
        let moved: Vec<Vec2> = (0..3).map(|i| w.dynamic.vel.at(i)).collect();
        if spoiled == 0 {
            w.dynamic.pos.set(0, Vec2::new(f32::INFINITY, 1.0));
        } else {
            w.dynamic.vel.set(1, Vec2::new(0.0, f32::NAN));
        }
        cw.solved.rows[1].tangent_impulse = f32::NAN;
        assert_eq!(put_back_non_finite(&mut w.dynamic, &mut cw), 1);
        for i in 0..3 {
            let (p, v) = (w.dynamic.pos.at(i), w.dynamic.vel.at(i));
            if i == spoiled {
                assert_eq!((p, v), (cw.motion.start[i], Vec2::ZERO), "body {i}");
            } else {
                assert_eq!((p, v), (before[i], moved[i]), "body {i}");
            }
        }
        // The spoiled row starts again from nothing; the others keep theirs.
        let r = &cw.solved.rows[1];
        let zeroed = [
            r.normal_impulse,
            r.tangent_impulse,
            r.push_impulse,
            r.max_normal_impulse,
        ];
        assert_eq!(zeroed, [0.0; 4]);
        for (k, (now, was)) in cw.solved.rows.iter().zip(&rows).enumerate() {
            if k != 1 {
                assert_eq!(now, was, "row {k}");
            }
        }
        // Nothing left to put back.
        assert_eq!(put_back_non_finite(&mut w.dynamic, &mut cw), 0);
    }
}
