//! Tests of `colouring`.

use super::*;
use crate::body::collider::ColliderRef;
use crate::columns::Columns;
use crate::solver::lanes::RESTING;
use crate::solver::scalar::BodyState;
use glam::Vec2;

fn row(a: u32, b: Option<u32>, inv_mass_b: f32) -> Constraint {
    Constraint {
        a,
        b: b.map_or(ColliderRef::fixed(0), ColliderRef::dynamic),
        normal: Vec2::Y,
        base_separation: 0.0,
        inv_mass_a: 1.0,
        inv_mass_b,
        mass: 0.5,
        friction: 0.5,
        normal_impulse: 1.0,
        tangent_impulse: 0.0,
        push_impulse: 0.0,
        max_normal_impulse: 1.0,
        tangent_speed: 0.0,
    }
}

/// No two contacts of a colour move the same body.
fn assert_colours_share_no_moved_body(c: &Colouring, bodies: usize) {
    for range in &c.colours {
        let mut moved = vec![false; bodies];
        for k in &c.blocks[range.clone()] {
            for l in 0..LANES {
                let sides = [
                    (k.a[l], k.write_a[l], k.inv_mass_a[l]),
                    (k.b[l], k.write_b[l], k.inv_mass_b[l]),
                ];
                for (body, write, inv_mass) in sides {
                    let moves = body != NONE && inv_mass > 0.0;
                    assert_eq!(write, if moves { body } else { NONE });
                    if moves {
                        assert!(!moved[body as usize], "body {body} twice in a colour");
                        moved[body as usize] = true;
                    }
                }
            }
        }
    }
}

#[test]
fn a_chain_is_solved_link_after_link_and_a_floor_of_resting_bodies_in_two_colours() {
    // A chain 0-1-2-3-4: each link after the one before, as in the list.
    let chain: Vec<_> = (0..4).map(|i| row(i, Some(i + 1), 1.0)).collect();
    let mut c = Colouring {
        switches: TestSwitches {
            blocks_always: true,
            ..TestSwitches::default()
        },
        ..Colouring::default()
    };
    c.build(&chain, 0..chain.len(), 5, &[]);
    assert_eq!(c.colour_of, [0, 1, 2, 3]);
    assert_colours_share_no_moved_body(&c, 5);
    // Ten bodies each on the ground and on a kinematic body 10: the
    // ground and the kinematic body are only read.
    let floor: Vec<_> = (0..10)
        .flat_map(|i| [row(i, None, 0.0), row(i, Some(10), 0.0)])
        .collect();
    c.build(&floor, 0..floor.len(), 11, &[]);
    assert_eq!(c.colour_count(), 2, "each body's two contacts, two colours");
    assert_eq!(
        c.blocks.len(),
        2 * 10usize.div_ceil(LANES),
        "ten contacts a colour"
    );
    assert_colours_share_no_moved_body(&c, 11);
    // A chain longer than the colours wraps round.
    let long: Vec<_> = (0..200).map(|i| row(i, Some(i + 1), 1.0)).collect();
    c.build(&long, 0..long.len(), 201, &[]);
    assert_eq!(c.colour_of[COLOURS - 1], (COLOURS - 1) as u8);
    assert_eq!(c.colour_of[COLOURS], 0);
    assert_colours_share_no_moved_body(&c, 201);
}

#[test]
fn rows_moving_the_same_bodies_again_take_the_last_colours_and_give_the_same_blocks() {
    // A pile: each body on the ground, on the one below, and beside a
    // neighbour; more contacts than colours on body 0, so some overflow.
    let mut rows: Vec<_> = (0..300)
        .map(|i| row(i % 40, Some(40 + i % 7), 1.0))
        .collect();
    rows.extend((0..40).map(|i| row(i, None, 0.0)));
    rows.extend((1..200).map(|i| row(0, Some(100 + i), 1.0)));
    let fresh = |rows: &[Constraint], picked: &[usize]| {
        let mut c = Colouring {
            switches: TestSwitches {
                blocks_always: true,
                ..TestSwitches::default()
            },
            ..Colouring::default()
        };
        c.build(rows, picked.iter().copied(), 300, &[]);
        c
    };
    let assert_same = |kept: &Colouring, fresh: &Colouring| {
        assert_eq!(kept.blocks, fresh.blocks);
        assert_eq!(kept.colours, fresh.colours);
        assert_eq!(kept.colour_of, fresh.colour_of);
        assert_eq!(kept.overflow, fresh.overflow);
        assert_eq!(kept.overflow_rows, fresh.overflow_rows);
    };
    let all: Vec<usize> = (0..rows.len()).collect();
    let mut kept = fresh(&rows, &all);
    assert!(!kept.overflow.is_empty() && !kept.blocks.is_empty());
    let padded = |c: &Colouring| c.blocks.iter().any(|k| k.row.contains(&NONE));
    assert!(padded(&kept), "some block has padding lanes");
    // The step's passes, which the next build's blocks are kept from.
    let params = SolverParams::for_tests();
    let vel: Vec<_> = (0..300).map(|i| Vec2::new(0.01 * i as f32, -1.0)).collect();
    let mut state = crate::solver::scalar::BodyState::of(&vel);
    let delta = vec![Vec2::new(0.0, -0.001); 300];
    let mut bodies = SolverBodies {
        state: &mut state,
        delta: &delta,
        deep: &[],
    };
    kept.run(&mut bodies, &Pass::Begin(params, true));
    kept.run(&mut bodies, &Pass::solve(&params, true));
    kept.run(&mut bodies, &Pass::relax(&params));
    // The next step: the same bodies, other impulses and normals.
    for (k, r) in rows.iter_mut().enumerate() {
        r.normal_impulse = k as f32;
        r.normal = Vec2::new(0.6, 0.8);
    }
    kept.build(&rows, all.iter().copied(), 300, &[]);
    assert_eq!(kept.reused, 1, "the colours were taken");
    let again = fresh(&rows, &all);
    assert_same(&kept, &again);
    // A body that falls asleep is only read now: new colours.
    rows[5].inv_mass_b = 0.0;
    kept.build(&rows, all.iter().copied(), 300, &[]);
    assert_eq!(kept.reused, 1, "coloured anew");
    assert_same(&kept, &fresh(&rows, &all));
    assert_ne!(kept.colour_of, again.colour_of);
    // A row gone, at the end (an overflow row) or in the middle (a
    // coloured one), or another one gone instead (as many blocks, other
    // lanes taken): new colours too.
    for gone in [rows.len() - 1, 3, 4] {
        let picked: Vec<usize> = all.iter().copied().filter(|&i| i != gone).collect();
        kept.build(&rows, picked.iter().copied(), 300, &[]);
        assert_eq!(kept.reused, 1, "coloured anew");
        assert_same(&kept, &fresh(&rows, &picked));
    }
    // Mostly padding (a stack, solved one by one): the same again.
    let stack: Vec<_> = (0..10).map(|i| row(i, Some(i + 1), 1.0)).collect();
    let mut one_by_one = Colouring::default();
    one_by_one.build(&stack, 0..stack.len(), 11, &[]);
    assert!(one_by_one.blocks.is_empty());
    let first = one_by_one.overflow_rows.clone();
    one_by_one.build(&stack, 0..stack.len(), 11, &[]);
    assert_eq!(one_by_one.reused, 1);
    assert!(one_by_one.blocks.is_empty() && one_by_one.colours.is_empty());
    assert_eq!(one_by_one.overflow_rows, first);
}

#[test]
fn a_body_with_more_contacts_than_colours_overflows_and_all_come_back() {
    // Body 0 touches 200 others: COLOURS coloured, the rest left over.
    let mut rows: Vec<_> = (1..=200).map(|i| row(0, Some(i), 1.0)).collect();
    let mut c = Colouring {
        switches: TestSwitches {
            blocks_always: true,
            ..TestSwitches::default()
        },
        ..Colouring::default()
    };
    c.build(&rows, 0..rows.len(), 201, &[]);
    assert_eq!(c.colour_count(), COLOURS);
    assert_eq!(c.overflow.len(), 200 - COLOURS);
    assert_colours_share_no_moved_body(&c, 201);
    // Every row comes back from its lane or from the overflow.
    for (k, block) in c.blocks.iter_mut().enumerate() {
        for l in 0..LANES {
            block.normal_impulse[l] = (k * LANES + l) as f32 + 10.0;
        }
    }
    for o in &mut c.overflow {
        o.normal_impulse = -1.0;
    }
    c.store(&mut rows);
    let mut seen: Vec<_> = rows.iter().map(|r| r.normal_impulse).collect();
    assert_eq!(seen.iter().filter(|&&n| n == -1.0).count(), 200 - COLOURS);
    seen.retain(|&n| n != -1.0);
    seen.sort_by(f32::total_cmp);
    seen.dedup();
    assert_eq!(seen.len(), COLOURS, "each coloured row written once");
}

#[test]
fn a_stack_is_solved_one_by_one_and_a_floor_in_blocks() {
    // A stack: one contact a colour, blocks mostly padding.
    let stack: Vec<_> = (0..10).map(|i| row(i, Some(i + 1), 1.0)).collect();
    let mut c = Colouring::default();
    c.build(&stack, 0..stack.len(), 11, &[]);
    assert!(c.blocks.is_empty());
    assert_eq!(c.overflow, stack, "all of it, in the list's order");
    // A floor of bodies side by side: full blocks.
    let floor: Vec<_> = (0..16).map(|i| row(i, None, 0.0)).collect();
    c.build(&floor, 0..floor.len(), 16, &[]);
    assert_eq!(c.blocks.len(), 16 / LANES);
    assert!(c.overflow.is_empty());
}

#[test]
fn a_replayed_warm_start_gives_the_velocities_of_a_pass_over_the_contacts() {
    use crate::solver::motion::{Motion, Start};
    // Four boxes and the ground, in blocks (a chain) and, with
    // `blocks_always` off, one by one: both paths.
    let rows = vec![
        row(0, None, 0.0),
        Constraint {
            normal: Vec2::new(0.6, 0.8),
            base_separation: 0.01,
            ..row(0, Some(1), 1.0)
        },
        Constraint {
            normal: Vec2::X,
            friction: 0.2,
            tangent_impulse: 0.1,
            ..row(2, Some(1), 0.5)
        },
        Constraint {
            base_separation: -0.02,
            ..row(3, Some(2), 1.0)
        },
    ];
    let vel0 = [
        Vec2::new(0.3, -2.0),
        Vec2::new(-1.0, 0.5),
        Vec2::new(0.2, 0.1),
        Vec2::new(0.5, -1.5),
    ];
    let params = SolverParams::for_tests();
    for blocks_always in [true, false] {
        let mut colouring = Colouring {
            switches: TestSwitches {
                blocks_always,
                ..TestSwitches::default()
            },
            ..Colouring::default()
        };
        colouring.build(&rows, 0..rows.len(), 4, &[]);
        // A substep that keeps each body's velocity change.
        let mut motion = Motion::default();
        let columns = |v: [Vec2; 4]| v.into_iter().collect::<Columns>();
        motion.begin(columns([Vec2::ZERO; 4]).view());
        motion.load(columns(vel0).view(), Start::Track, false, None);
        colouring.run(&mut motion.bodies(), &Pass::Begin(params, false));
        for _ in 0..2 {
            colouring.run(&mut motion.bodies(), &Pass::solve(&params, true));
        }
        colouring.run(&mut motion.bodies(), &Pass::relax(&params));
        let mut vel = columns(vel0);
        motion.unload(vel.view_mut(), true, false, None);
        // The next substep's velocities before its warm start.
        let next: Columns = vel.iter().map(|v| v + Vec2::new(0.0, -0.04)).collect();
        // Warm started by a pass over the contacts...
        let (mut passed, mut replayed) = (motion.clone(), motion);
        let mut passed_colouring = colouring.clone();
        passed.load(next.view(), Start::Plain, false, None);
        passed_colouring.run(&mut passed.bodies(), &Pass::Begin(params, false));
        // ...and by the replay, with a pass that only clears the push.
        replayed.load(next.view(), Start::Replay, false, None);
        let (mut fresh, mut fresh_colouring) = (replayed.clone(), colouring.clone());
        let clear = SolverParams {
            warm_starting: false,
            ..params
        };
        colouring.run(&mut replayed.bodies(), &Pass::Begin(clear, false));
        // The first pass with the push after the clearing gives the bits
        // of a pass that starts each push from zero itself.
        let mut cleared = (replayed.clone(), colouring.clone());
        cleared
            .1
            .run(&mut cleared.0.bodies(), &Pass::solve(&params, true));
        fresh_colouring.run(&mut fresh.bodies(), &Pass::fresh(&params));
        assert_eq!(fresh.state, cleared.0.state);
        let (mut a, mut b) = (rows.clone(), rows.clone());
        fresh_colouring.store(&mut a);
        cleared.1.store(&mut b);
        assert_eq!(a, b);
        for (a, b) in passed.state.iter().zip(&replayed.state) {
            assert!(
                (a.vel - b.vel).length() < 1e-5,
                "{:?} against {:?} (blocks: {blocks_always})",
                a.vel,
                b.vel
            );
            assert_eq!(b.push, Vec2::ZERO);
        }
        let moved: f32 = passed.state[..4]
            .iter()
            .zip(next.iter())
            .map(|(s, v)| s.vel.distance(v))
            .sum();
        assert!(moved > 0.1, "the warm start moved the bodies");
        let mut stored = rows.clone();
        colouring.store(&mut stored);
        assert!(stored.iter().all(|c| c.push_impulse == 0.0), "push cleared");
    }
}

/// A pass of [`wide_and_scalar`], run by the blocks and by the scalar
/// solver.
#[derive(Clone, Copy)]
enum Step {
    /// The warm start pass (the blocks then measure the separations).
    Begin,
    /// A Gauss-Seidel pass, with the push or without.
    Solve(bool),
    /// The first pass with the push of a replayed substep: each push
    /// impulse from zero.
    Fresh,
    /// The bodies moved on (to twice their displacement and 1 mm by 2 mm
    /// more; each push slot then holds the displacement, as the position
    /// stage leaves it), then the relax stage's first pass.
    Relax,
}

/// What the position stage leaves: the bodies displaced by `delta`, and
/// each state's push slot holding the displacement (the rest state after
/// the bodies untouched).
fn move_on<'a>(bodies: &mut SolverBodies<'a>, delta: &'a [Vec2]) {
    for (s, &d) in bodies.state.iter_mut().zip(delta) {
        s.push = d;
    }
    bodies.delta = delta;
}

/// Runs `steps` over `rows` (bodies starting at `vel0`, displaced by
/// `delta`, `deep` as for [`Colouring::build`]) in blocks and in the
/// scalar solver in the list's order, checks that both give the same bits
/// (velocities, pushes and every impulse) and returns the scalar solver's
/// velocities and pushes, and rows.
fn wide_and_scalar(
    rows: &[Constraint],
    (vel0, delta, deep): (&[Vec2], &[Vec2], &[bool]),
    params: &SolverParams,
    steps: &[Step],
) -> (Vec<Vec2>, Vec<Vec2>, Vec<Constraint>) {
    let mut colouring = Colouring {
        switches: TestSwitches {
            blocks_always: true,
            ..TestSwitches::default()
        },
        ..Colouring::default()
    };
    colouring.build(rows, 0..rows.len(), vel0.len(), deep);
    assert!(colouring.overflow.is_empty(), "every contact in a block");
    let moved_on: Vec<Vec2> = delta
        .iter()
        .map(|&d| d * 2.0 + Vec2::new(0.001, -0.002))
        .collect();
    let mut scalar_rows = rows.to_vec();
    let mut state = BodyState::of(vel0);
    let mut bodies = SolverBodies {
        state: &mut state,
        delta,
        deep,
    };
    for &step in steps {
        match step {
            Step::Begin => scalar::begin_substep(&mut scalar_rows, &mut bodies, params),
            Step::Solve(push) => scalar::solve(&mut scalar_rows, &mut bodies, params, push),
            Step::Fresh => {
                scalar_rows.iter_mut().for_each(|c| c.push_impulse = 0.0);
                scalar::solve(&mut scalar_rows, &mut bodies, params, true);
            }
            Step::Relax => {
                move_on(&mut bodies, &moved_on);
                scalar::solve(&mut scalar_rows, &mut bodies, params, false);
            }
        }
    }
    let (vel, push) = BodyState::split(&state);
    let mut wide_state = BodyState::of(vel0);
    let mut bodies = SolverBodies {
        state: &mut wide_state,
        delta,
        deep,
    };
    for &step in steps {
        match step {
            Step::Begin => {
                colouring.run(&mut bodies, &Pass::Begin(*params, false));
                colouring.run(&mut bodies, &Pass::Measure);
            }
            Step::Solve(push) => colouring.run(&mut bodies, &Pass::solve(params, push)),
            Step::Fresh => colouring.run(&mut bodies, &Pass::fresh(params)),
            Step::Relax => {
                move_on(&mut bodies, &moved_on);
                colouring.run(&mut bodies, &Pass::relax(params));
            }
        }
    }
    let mut wide_rows = rows.to_vec();
    colouring.store(&mut wide_rows);
    let (wide_vel, wide_push) = BodyState::split(&wide_state);
    // Bit for bit (`==` would let -0 pass for +0).
    let bits = |v: &[Vec2]| {
        v.iter()
            .flat_map(|v| [v.x.to_bits(), v.y.to_bits()])
            .collect::<Vec<_>>()
    };
    assert_eq!(bits(&wide_vel), bits(&vel));
    assert_eq!(bits(&wide_push), bits(&push));
    for (w, s) in wide_rows.iter().zip(&scalar_rows) {
        let impulses = |c: &Constraint| {
            [
                c.normal_impulse,
                c.tangent_impulse,
                c.push_impulse,
                c.max_normal_impulse,
            ]
            .map(f32::to_bits)
        };
        assert_eq!(impulses(w), impulses(s));
    }
    (vel, push, scalar_rows)
}

#[test]
fn lanes_solve_as_the_scalar_solver_does() {
    // One box on the ground, one on top of it, a third beside: the
    // wide passes (a warm start that carries the push of the deep pile
    // of bodies 0 and 1, then the Gauss-Seidel passes) give the bits of
    // the scalar passes in the list's order.
    let rows = vec![
        Constraint {
            base_separation: -0.02,
            push_impulse: 0.3,
            ..row(0, None, 0.0)
        },
        Constraint {
            normal: Vec2::new(0.6, 0.8),
            base_separation: 0.01,
            push_impulse: 0.2,
            ..row(0, Some(1), 1.0)
        },
        // Body 2 is not in the deep pile: its push starts from nothing.
        Constraint {
            normal: Vec2::X,
            friction: 0.2,
            tangent_impulse: 0.1,
            push_impulse: 0.4,
            ..row(2, Some(1), 0.5)
        },
        // Body 3 is kinematic (held): read, never written.
        Constraint {
            normal: Vec2::new(0.0, -1.0),
            ..row(2, Some(3), 0.0)
        },
    ];
    let vel0 = [
        Vec2::new(0.3, -2.0),
        Vec2::new(-1.0, 0.5),
        Vec2::new(0.2, 0.1),
        Vec2::new(-0.0, 1.5),
    ];
    let delta = [
        Vec2::new(0.0, -0.01),
        Vec2::ZERO,
        Vec2::new(0.001, 0.0),
        Vec2::ZERO,
    ];
    let deep = [true, true, false, false];
    let params = SolverParams {
        carry_push: true,
        ..SolverParams::for_tests()
    };
    let mut colouring = Colouring {
        switches: TestSwitches {
            blocks_always: true,
            ..TestSwitches::default()
        },
        ..Colouring::default()
    };
    colouring.build(&rows, 0..rows.len(), 4, &deep);
    assert_eq!(colouring.colour_count(), 4, "a chain of four");
    let steps = [
        Step::Begin,
        Step::Solve(true),
        Step::Solve(true),
        Step::Solve(false),
    ];
    let (vel, push, _) = wide_and_scalar(&rows, (&vel0, &delta, &deep), &params, &steps);
    assert_eq!(
        vel[3].x.to_bits(),
        (-0.0f32).to_bits(),
        "held body untouched"
    );
    assert!(push[0] != Vec2::ZERO, "the carried push moved body 0");
    // On through the substep: the bodies move (the kinematic body 3 too),
    // and the relax pass measures from the displacements in the states.
    let moved_by = [
        Vec2::new(0.0, -0.01),
        Vec2::new(0.002, 0.003),
        Vec2::new(0.001, 0.0),
        Vec2::new(0.004, 0.0),
    ];
    let steps = [
        Step::Begin,
        Step::Solve(true),
        Step::Solve(true),
        Step::Relax,
        Step::Solve(false),
    ];
    wide_and_scalar(&rows, (&vel0, &moved_by, &deep), &params, &steps);
}

#[test]
fn blocks_at_rest_leave_the_push_out_with_the_scalar_solvers_bits() {
    // A pile with no contact deeper than the slop (5 mm): its push passes
    // change nothing, and the blocks leave the push out. Normals with
    // negative parts make the zeros of the push arithmetic signed both
    // ways; the push impulses the rows bring along are stale (a replayed
    // substep's first pass starts from zero).
    let mut rows: Vec<_> = [
        (0, None, Vec2::Y, -0.004),
        (0, Some(1), Vec2::new(-0.6, 0.8), -0.001),
        (1, Some(2), Vec2::new(0.0, -1.0), 0.0),
        (2, None, Vec2::new(0.8, -0.6), 0.002),
        (3, Some(2), Vec2::NEG_X, -0.005),
        (3, Some(4), Vec2::new(-0.6, -0.8), -0.003),
        (4, None, Vec2::Y, -0.0),
    ]
    .into_iter()
    .map(|(a, b, normal, base_separation)| Constraint {
        normal,
        base_separation,
        push_impulse: 0.4,
        ..row(a, b, if b.is_some() { 1.0 } else { 0.0 })
    })
    .collect();
    let vel0 = [
        Vec2::new(-0.0, -0.2),
        Vec2::new(0.0, -0.0),
        Vec2::new(0.1, -0.0),
        Vec2::new(-0.0, -0.0),
        Vec2::new(0.3, -0.1),
    ];
    let delta = [Vec2::ZERO; 5];
    let params = SolverParams::for_tests();
    let steps = [
        Step::Fresh,
        Step::Solve(true),
        Step::Begin,
        Step::Solve(true),
        Step::Solve(true),
        Step::Solve(false),
    ];
    let resting = || RESTING.with(|n| n.get());
    let mut colouring = Colouring {
        switches: TestSwitches {
            blocks_always: true,
            ..TestSwitches::default()
        },
        ..Colouring::default()
    };
    colouring.build(&rows, 0..rows.len(), vel0.len(), &[]);
    let blocks = colouring.blocks.len();
    let before = resting();
    let (_, push, scalar) = wide_and_scalar(&rows, (&vel0, &delta, &[]), &params, &steps);
    assert_eq!(
        resting() - before,
        4 * blocks,
        "every block, every pass with the push"
    );
    assert!(push.iter().all(|p| *p == Vec2::ZERO), "nothing pushed");
    assert!(scalar.iter().all(|c| c.push_impulse.to_bits() == 0));

    // One contact 2 cm deep: its push spreads to the bodies after it in
    // the list, and only the blocks it does not reach leave it out.
    rows[2].base_separation = -0.02;
    let before = resting();
    let (_, push, _) = wide_and_scalar(&rows, (&vel0, &delta, &[]), &params, &steps);
    let left_out = resting() - before;
    assert!(
        push[1] != Vec2::ZERO && push[2] != Vec2::ZERO,
        "bodies 1 and 2 pushed"
    );
    assert!(
        0 < left_out && left_out < 4 * blocks,
        "{left_out} of {}",
        4 * blocks
    );

    // A floor of sixteen bodies on the ground, neighbours pushing on each
    // other in pairs, one body 2 cm deep: blocks of several lanes, one of
    // them deep among lanes at rest (a check of one lane alone would leave
    // its push out). The blocks that hold neither that body nor its
    // neighbour, which its push reaches, leave the push out in every pass.
    let ground = (0..16).map(|i| Constraint {
        base_separation: if i == 13 { -0.02 } else { -0.002 },
        ..row(i, None, 0.0)
    });
    let sides = (0..8).map(|i| Constraint {
        normal: Vec2::new(0.6, 0.8),
        base_separation: -0.001,
        ..row(2 * i, Some(2 * i + 1), 1.0)
    });
    let floor: Vec<_> = ground.chain(sides).collect();
    let vel0 = [Vec2::new(0.0, -0.1); 16];
    let mut colouring = Colouring {
        switches: TestSwitches {
            blocks_always: true,
            ..TestSwitches::default()
        },
        ..Colouring::default()
    };
    colouring.build(&floor, 0..floor.len(), vel0.len(), &[]);
    let far_from_it = |k: &Block| !k.a.iter().chain(&k.b).any(|&i| i == 12 || i == 13);
    let apart = colouring.blocks.iter().filter(|k| far_from_it(k)).count();
    assert!(0 < apart && apart < colouring.blocks.len());
    let before = resting();
    let (_, push, _) = wide_and_scalar(&floor, (&vel0, &[Vec2::ZERO; 16], &[]), &params, &steps);
    assert_eq!(
        resting() - before,
        4 * apart,
        "the blocks apart, every pass"
    );
    assert!(
        push[12] != Vec2::ZERO && push[13] != Vec2::ZERO,
        "bodies 12 and 13 pushed"
    );
    assert!(push[..12].iter().all(|p| *p == Vec2::ZERO));
}

#[test]
fn blocks_are_chosen_while_at_most_half_their_lanes_are_padding() {
    // Three chains of `links` contacts (colours 0 to links - 1) and a body
    // touching 128 + `over` others (one contact in each colour, the rest
    // left over), judged at eight lanes: `links` 128 gives four contacts
    // a colour, half the lanes, blocks; a chain one link shorter leaves
    // one colour three, past half padding: one by one. The contacts left
    // over count for neither.
    let rows = |links: [u32; 3], over: u32| {
        let mut rows: Vec<_> = (0..COLOURS as u32 + over)
            .map(|i| row(0, Some(1 + i), 1.0))
            .collect();
        for (j, &n) in links.iter().enumerate() {
            let first = 1000 * (j as u32 + 1);
            rows.extend((0..n).map(|i| row(first + i, Some(first + i + 1), 1.0)));
        }
        rows
    };
    for over in [0, 2, 40] {
        let mut c = Colouring::default();
        let even = rows([128, 128, 128], over);
        c.build(&even, 0..even.len(), 4000, &[]);
        assert_eq!(c.overflow.len(), over as usize);
        assert_eq!(c.blocks.len(), COLOURS * 4usize.div_ceil(LANES), "blocks");
        let short = rows([128, 128, 127], over);
        c.build(&short, 0..short.len(), 4000, &[]);
        assert!(c.blocks.is_empty(), "one by one ({over} left over)");
        assert_eq!(c.overflow.len(), short.len());
    }
}

#[test]
fn rows_that_move_other_bodies_a_are_coloured_anew() {
    // The same bodies B in the same order, another body A: the second
    // row now shares body 1 with the first, so it takes the next colour.
    let mut c = Colouring {
        switches: TestSwitches {
            blocks_always: true,
            ..TestSwitches::default()
        },
        ..Colouring::default()
    };
    let apart = [row(0, Some(1), 1.0), row(2, Some(3), 1.0)];
    c.build(&apart, 0..2, 4, &[]);
    assert_eq!(c.colour_of, [0, 0]);
    let shared = [row(0, Some(1), 1.0), row(1, Some(3), 1.0)];
    c.build(&shared, 0..2, 4, &[]);
    assert_eq!(c.reused, 0);
    assert_eq!(c.colour_of, [0, 1]);
    assert_colours_share_no_moved_body(&c, 4);
}

#[test]
fn impulses_are_stored_into_rows_that_start_past_the_first() {
    // A colouring of rows 4 to 9 of a chain of ten, stored into those six
    // rows alone (as a region's rows are), from blocks or one by one: each
    // row gets its own impulse back.
    let mut rows: Vec<_> = (0..10).map(|i| row(i, Some(i + 1), 1.0)).collect();
    for blocks_always in [true, false] {
        let mut c = Colouring {
            switches: TestSwitches {
                blocks_always,
                ..TestSwitches::default()
            },
            ..Colouring::default()
        };
        c.build(&rows, 4..10, 11, &[]);
        assert_eq!(c.blocks.is_empty(), !blocks_always);
        for k in &mut c.blocks {
            for l in 0..LANES {
                k.normal_impulse[l] = k.row[l] as f32;
            }
        }
        for (o, &r) in c.overflow.iter_mut().zip(&c.overflow_rows) {
            o.normal_impulse = r as f32;
        }
        c.store_from(&mut rows[4..], 4);
        let stored: Vec<_> = rows.iter().map(|r| r.normal_impulse).collect();
        let expected: Vec<_> = (0..10)
            .map(|i| if i < 4 { 1.0 } else { i as f32 })
            .collect();
        assert_eq!(stored, expected, "blocks always: {blocks_always}");
    }
}

#[test]
fn a_block_of_bodies_of_many_masses_some_in_a_deep_pile_solves_as_the_scalar_solver() {
    // Eight bodies of other masses than 1 kg on the ground (a conveyor:
    // each contact has a belt speed), one colour: every lane of a block,
    // each with a push left from the last substep,
    // every other body in a deep pile. With the push carried, only the
    // deep bodies' lanes carry it; without, none does.
    let rows: Vec<_> = (0..8)
        .map(|i| {
            let inv_mass_a = 0.4 + 0.3 * i as f32;
            Constraint {
                normal: Vec2::new(0.1 * i as f32, 1.0).normalize(),
                base_separation: -0.01 * i as f32,
                inv_mass_a,
                mass: 1.0 / inv_mass_a,
                normal_impulse: 0.5 + 0.1 * i as f32,
                tangent_impulse: 0.05 * i as f32 - 0.2,
                push_impulse: 0.1 * (i + 1) as f32,
                tangent_speed: 0.3 * i as f32 - 1.0,
                ..row(i, None, 0.0)
            }
        })
        .collect();
    // Some bodies closing on the ground, some leaving it.
    let vel0: Vec<_> = (0..8)
        .map(|i| Vec2::new(0.1 * i as f32, 1.0 - 0.3 * i as f32))
        .collect();
    let delta: Vec<_> = (0..8).map(|i| Vec2::new(0.0, -0.001 * i as f32)).collect();
    let deep: Vec<_> = (0..8).map(|i| i % 2 == 0).collect();
    let steps = [
        Step::Begin,
        Step::Solve(true),
        Step::Relax,
        Step::Solve(false),
    ];
    for carry_push in [true, false] {
        let params = SolverParams {
            carry_push,
            ..SolverParams::for_tests()
        };
        let (_, push, rows) = wide_and_scalar(&rows, (&vel0, &delta, &deep), &params, &steps);
        assert!(push.iter().any(|p| *p != Vec2::ZERO));
        let held = rows.iter().filter(|c| c.normal_impulse > 0.0).count();
        assert!((2..8).contains(&held), "{held} contacts hold");
    }
}
