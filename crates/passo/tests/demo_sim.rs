//! The demo's movements, driven without a window: walk, run, jump only
//! when standing, slide on ice, glide, wind.

use passo::demo::{Command, Entry, Input, Knobs, REWIND_BYTES, Sim, catalogue, load};
use passo_physics::glam::Vec2;
use std::time::Duration;

const FRAME: Duration = Duration::from_nanos(16_666_667);

fn playground() -> Sim {
    load(&Entry::File("playground".into())).unwrap()
}

fn run(sim: &mut Sim, frames: usize, input: Input) {
    for _ in 0..frames {
        sim.scene.set_input(input);
        sim.frame(FRAME);
    }
}

/// The playground with its player moved to `at`.
fn playground_with_player_at(at: Vec2) -> Sim {
    let mut sim = playground();
    let id = sim.scene.player.unwrap();
    sim.scene.lanes[0].world.set_position(id, at);
    sim
}

fn player(sim: &Sim) -> passo_physics::Body {
    sim.scene.lanes[0]
        .world
        .body(sim.scene.player.unwrap())
        .unwrap()
}

#[test]
fn walking_and_running_push_against_friction_and_stop_when_released() {
    let mut sim = playground();
    run(&mut sim, 30, Input::default()); // settle on the ground
    let start = player(&sim).position.x;
    run(
        &mut sim,
        90,
        Input {
            right: true,
            ..Default::default()
        },
    );
    let walk = player(&sim).velocity.x;
    assert!((3.0..=4.6).contains(&walk), "walking speed {walk}");
    assert!(player(&sim).position.x > start + 3.0);
    run(
        &mut sim,
        60,
        Input {
            right: true,
            run: true,
            ..Default::default()
        },
    );
    let running = player(&sim).velocity.x;
    assert!(running > walk + 2.0, "running {running} vs walking {walk}");
    // Released: kinetic friction (mu 0.8 with the ground's 0.6) stops the
    // player within v / (mu g) = about 1.3 s.
    run(&mut sim, 90, Input::default());
    assert_eq!(player(&sim).velocity.x, 0.0);
}

#[test]
fn jumping_works_only_when_standing() {
    let mut sim = playground();
    run(&mut sim, 30, Input::default());
    let ground_y = player(&sim).position.y;
    run(
        &mut sim,
        1,
        Input {
            jump: true,
            ..Default::default()
        },
    );
    assert!(
        player(&sim).velocity.y > 5.0,
        "the jump impulse gives 6.5 m/s"
    );
    run(&mut sim, 10, Input::default());
    let vy = player(&sim).velocity.y;
    // In the air, jump does nothing: vertical speed only changes by gravity.
    run(
        &mut sim,
        1,
        Input {
            jump: true,
            ..Default::default()
        },
    );
    let dv = player(&sim).velocity.y - vy;
    assert!(
        (dv + 9.81 / 60.0).abs() < 0.02,
        "a jump in the air changed vy by {dv}"
    );
    let mut top = 0.0f32;
    for _ in 0..60 {
        run(&mut sim, 1, Input::default());
        top = top.max(player(&sim).position.y - ground_y);
    }
    assert!(
        (1.8..=2.3).contains(&top),
        "jump height {top} (v^2 / 2g = 2.15 m)"
    );
}

#[test]
fn the_ice_patch_lets_the_player_slide_much_further() {
    let stop_distance = |x: f32| {
        let mut sim = playground_with_player_at(Vec2::new(x, 0.81));
        let id = sim.scene.player.unwrap();
        run(&mut sim, 10, Input::default());
        sim.scene.lanes[0]
            .world
            .set_velocity(id, Vec2::new(5.0, 0.0));
        let start = player(&sim).position.x;
        run(&mut sim, 120, Input::default());
        player(&sim).position.x - start
    };
    let on_ground = stop_distance(-6.0);
    let on_ice = stop_distance(5.5);
    // Ground: mu = sqrt(0.8 * 0.6) = 0.69, v^2 / (2 mu g) = 1.8 m.
    assert!((1.5..=2.1).contains(&on_ground), "ground {on_ground}");
    assert!(
        on_ice > 4.0 * on_ground,
        "ice {on_ice} vs ground {on_ground}"
    );
}

#[test]
fn gliding_opens_a_large_drag_area_and_falls_slowly() {
    let fall_speed = |glide: bool| {
        let mut sim = playground_with_player_at(Vec2::new(-12.0, 12.0));
        run(
            &mut sim,
            90,
            Input {
                glide,
                ..Default::default()
            },
        );
        -player(&sim).velocity.y
    };
    let (falling, gliding) = (fall_speed(false), fall_speed(true));
    // Gliding: Cd A = 0.5 * 40 = 20 m², terminal speed sqrt(2 m g / (rho Cd A)) = 7.5 m/s.
    assert!(falling > 12.0, "falling at {falling}");
    assert!((6.5..=8.0).contains(&gliding), "gliding at {gliding}");
}

#[test]
fn wind_pushes_through_drag() {
    let mut sim = playground_with_player_at(Vec2::new(-12.0, 12.0));
    sim.session.knobs.wind = true;
    sim.session.knobs.wind_speed = 20.0;
    sim.apply_knobs();
    run(
        &mut sim,
        30,
        Input {
            glide: true,
            ..Default::default()
        },
    );
    assert!(player(&sim).velocity.x > 5.0, "{}", player(&sim).velocity.x);
}

#[test]
fn every_listed_scene_loads_and_the_integrators_differ_as_theory_says() {
    for (name, entry) in catalogue() {
        let mut sim = load(&entry).unwrap_or_else(|e| panic!("{name}: {e}"));
        run(&mut sim, 5, Input::default());
    }
    let mut sim = load(&Entry::Integrators).unwrap();
    let e0: Vec<f64> = sim
        .scene
        .lanes
        .iter()
        .map(|l| l.world.total_energy())
        .collect();
    run(&mut sim, 300, Input::default());
    let drift: Vec<f64> = sim
        .scene
        .lanes
        .iter()
        .zip(&e0)
        .map(|(l, e)| (l.world.total_energy() - e) / e)
        .collect();
    // explicit Euler, semi-implicit Euler, Verlet, RK4 after 5 s at 60 Hz.
    assert!(drift[0] > 10.0, "explicit Euler gains energy: {drift:?}");
    assert!(
        drift[1].abs() < 0.2,
        "semi-implicit Euler stays bounded: {drift:?}"
    );
    assert!(drift[2].abs() < 0.01 && drift[3].abs() < 0.001, "{drift:?}");
    assert_eq!(sim.scene.history.series.len(), 4);
    assert_eq!(sim.scene.history.time.len(), 300);
}

#[test]
fn spawning_and_flinging_bodies() {
    let mut sim = playground();
    let n = sim.scene.body_count();
    let id = sim.spawn(Vec2::new(0.0, 10.0), true).unwrap();
    assert_eq!(sim.scene.body_count(), n + 1);
    assert_eq!(sim.scene.pick(Vec2::new(0.1, 10.0)), Some(id));
    assert_eq!(sim.scene.pick(Vec2::new(0.0, 13.0)), None);
    sim.scene.fling(id, Vec2::new(3.0, 4.0));
    assert_eq!(
        sim.scene.lanes[0].world.body(id).unwrap().velocity,
        Vec2::new(3.0, 4.0)
    );
    // Scene bodies stay sorted by id for colour lookups.
    let ids: Vec<_> = sim.scene.lanes[0].bodies.iter().map(|b| b.id).collect();
    assert!(ids.windows(2).all(|w| w[0] < w[1]));
}

#[test]
fn dragging_a_body_pulls_it_to_the_pointer_and_letting_go_drops_it() {
    fn world(sim: &Sim) -> &passo_physics::World {
        &sim.scene.lanes[0].world
    }
    let mut sim = load(&Entry::File("joints".into())).unwrap();
    run(&mut sim, 30, Input::default());
    let crate_ = sim
        .scene
        .pick(Vec2::new(-8.0, 8.5))
        .expect("the chain's last crate");
    let start = world(&sim).body(crate_).unwrap().position;
    let grab = |id: passo_physics::BodyId, at: Vec2| Command::Grab {
        index: id.index(),
        generation: id.generation(),
        at: at.to_array(),
    };
    sim.command(grab(crate_, start)).unwrap();
    assert_eq!(world(&sim).joint_len(), 22, "a target joint more");
    // Pull it 3 m to the right: it swings out on its chain.
    let target = start + Vec2::new(3.0, 0.0);
    sim.command(Command::Drag {
        at: target.to_array(),
    })
    .unwrap();
    run(&mut sim, 120, Input::default());
    let pulled = world(&sim).body(crate_).unwrap().position;
    assert!(
        pulled.x > start.x + 1.5,
        "pulled toward the pointer: {pulled}"
    );
    sim.command(Command::Release).unwrap();
    assert_eq!(world(&sim).joint_len(), 21, "let go");
    // It swings on its chain, which holds it no farther from the beam
    // than it hung (straight while it swings).
    let hook = Vec2::new(-8.0, 12.8);
    let hung = (start - hook).length();
    for _ in 0..120 {
        run(&mut sim, 1, Input::default());
        let at = world(&sim).body(crate_).unwrap().position;
        assert!((at - hook).length() < hung + 0.02, "the chain holds: {at}");
    }
    // A grab of a body that is gone does nothing.
    sim.command(Command::Release).unwrap();
    sim.command(Command::Drag { at: [0.0, 0.0] }).unwrap();
}

#[test]
fn the_rain_count_slider_rebuilds_the_scene() {
    let mut sim = load(&Entry::File("rain".into())).unwrap();
    assert_eq!(sim.scene.rain_count(), Some(2000));
    sim.set_rain_count(300).unwrap();
    assert_eq!(sim.scene.rain_count(), Some(300));
    assert_eq!(sim.scene.lanes[0].world.dynamic_len(), 300);
}

#[test]
fn a_settled_scene_sleeps_in_the_demo_and_a_slider_wakes_it() {
    let mut sim = load(&Entry::File("stack".into())).unwrap();
    run(&mut sim, 180, Input::default());
    let (sleeping, solved, contacts) = sim.scene.sleep_counts();
    let bodies = sim.scene.lanes[0].world.dynamic_len();
    assert_eq!(sleeping, bodies, "every box of the stack sleeps");
    assert_eq!(solved, 0);
    assert!(contacts >= bodies);
    // A slider (new settings) wakes them all.
    move_slider(&mut sim, |k| k.gravity = -5.0, false);
    run(&mut sim, 1, Input::default());
    assert_eq!(sim.scene.sleep_counts().0, 0);
}

#[test]
fn a_reset_rebuilds_the_scene_and_keeps_the_session() {
    for entry in [Entry::File("playground".into()), Entry::Integrators] {
        let fresh = load(&entry).unwrap();
        let mut sim = load(&entry).unwrap();
        move_slider(&mut sim, |k| k.gravity = -5.0, false);
        let knobs = sim.session.knobs;
        sim.command(Command::Spawn {
            at: [1.0, 4.0],
            round: true,
        })
        .unwrap();
        sim.scene.set_interpolation(false);
        run(&mut sim, 30, Input::default());
        let tick = sim.session.timestep.tick();
        sim.command(Command::Reset).unwrap();
        assert_eq!(
            (sim.scene.body_count(), sim.scene.state_hash()),
            (fresh.scene.body_count(), fresh.scene.state_hash()),
            "{entry:?}: bodies back at the start"
        );
        assert!(
            sim.scene.history.time.is_empty(),
            "{entry:?}: plot restarted"
        );
        assert_eq!(sim.session.timestep.tick(), tick, "{entry:?}: loop kept");
        assert_eq!(sim.session.knobs, knobs, "{entry:?}: sliders kept");
        for lane in &sim.scene.lanes {
            let gravity = lane.world.settings().forces.gravity;
            assert_eq!(
                gravity,
                Some(Vec2::new(0.0, -5.0)),
                "{entry:?}: sliders applied"
            );
        }
        assert!(!sim.scene.interpolation(), "{entry:?}: switch kept");
    }
}

/// Moves a slider of the panel (`drag`: the drag-area one).
fn move_slider(sim: &mut Sim, change: impl FnOnce(&mut Knobs), drag: bool) {
    let mut knobs = sim.session.knobs;
    change(&mut knobs);
    sim.command(Command::Knobs {
        knobs,
        friction: false,
        restitution: false,
        drag,
    })
    .unwrap();
}

fn walk() -> Input {
    Input {
        right: true,
        ..Input::default()
    }
}

/// Walks right for `frames` frames, calling `before` ahead of each, and
/// returns the state hash before each frame.
fn walk_keeping_hashes(
    sim: &mut Sim,
    frames: usize,
    mut before: impl FnMut(&mut Sim, usize),
) -> Vec<u64> {
    (0..frames)
        .map(|frame| {
            let hash = sim.scene.state_hash();
            before(sim, frame);
            run(sim, 1, walk());
            hash
        })
        .collect()
}

#[test]
fn holding_rewind_runs_the_scene_back_to_the_exact_states_it_passed() {
    let mut sim = playground();
    let walk = walk();
    // 60 frames of walking, a spawn and a slider change on the way.
    let hashes = walk_keeping_hashes(&mut sim, 60, |sim, frame| {
        if frame == 20 {
            sim.spawn(Vec2::new(0.0, 8.0), true).unwrap();
        }
        if frame == 40 {
            move_slider(sim, |k| k.gravity = -3.0, false);
        }
    });
    let bodies_at_end = sim.scene.body_count();
    assert_eq!(sim.scene.rewindable(), 60);
    // Rewind 30 frames (one tick each at 60 Hz): back before the slider.
    sim.rewinding = true;
    run(&mut sim, 30, walk);
    assert_eq!(sim.scene.state_hash(), hashes[30]);
    assert_eq!(sim.session.knobs.gravity, -9.81, "the slider is undone");
    // Further, past the spawn: the spawned body is gone, from the world
    // and from the drawing list.
    run(&mut sim, 15, walk);
    assert_eq!(sim.scene.state_hash(), hashes[15]);
    assert_eq!(sim.scene.body_count(), bodies_at_end - 1);
    assert_eq!(
        sim.scene.lanes[0].bodies.len(),
        sim.scene.lanes[0].world.len()
    );
    // Past the first kept state it holds still.
    run(&mut sim, 40, walk);
    assert_eq!(sim.scene.state_hash(), hashes[0]);
    assert_eq!(sim.scene.rewindable(), 0);
    // Released, the scene runs forward again from there, as it first did.
    sim.rewinding = false;
    run(&mut sim, 10, walk);
    let mut fresh = playground();
    run(&mut fresh, 10, walk);
    assert_eq!(sim.scene.state_hash(), fresh.scene.state_hash());
}

#[test]
fn rewind_is_off_while_recording() {
    let mut sim = playground();
    sim.start_recording().unwrap();
    run(&mut sim, 20, Input::default());
    let hash = sim.scene.state_hash();
    let kept = sim.scene.rewindable();
    sim.rewinding = true;
    run(&mut sim, 1, Input::default());
    assert_ne!(sim.scene.state_hash(), hash, "the scene stepped forward");
    assert_eq!(sim.scene.rewindable(), kept + 1, "and kept one more state");
    sim.scrub_to(0);
    assert_eq!(sim.scene.scrubbing(), None, "the timeline is off too");
}

#[test]
fn the_timeline_shows_any_kept_state_and_resuming_discards_the_later_ones() {
    let mut sim = playground();
    let walk = walk();
    let hashes = walk_keeping_hashes(&mut sim, 40, |_, _| {});
    let present = sim.scene.state_hash();
    assert!(sim.scene.rewind_bytes() > 0);
    // Drag back to tick 10, forward to 25, and to the present: nothing is
    // lost while scrubbing, and the loop holds still.
    sim.scrub_to(10);
    assert_eq!(sim.scene.state_hash(), hashes[10]);
    run(&mut sim, 5, walk);
    assert_eq!(sim.scene.state_hash(), hashes[10], "held on the timeline");
    sim.scrub_to(25);
    assert_eq!(sim.scene.state_hash(), hashes[25]);
    sim.scrub_to(40);
    assert_eq!(sim.scene.state_hash(), present);
    // Resume from tick 20: the run goes on from there as it first did,
    // and the states after it are gone.
    sim.scrub_to(20);
    sim.resume_from_timeline();
    assert_eq!(sim.scene.rewindable(), 20);
    run(&mut sim, 20, walk);
    assert_eq!(sim.scene.state_hash(), present);
}

#[test]
fn a_recorded_session_rewound_to_a_tick_shows_the_state_recorded_at_that_tick() {
    // Record a session with a spawn and a slider change.
    let mut sim = playground();
    sim.start_recording().unwrap();
    let mut at_tick = Vec::new();
    for frame in 0..90 {
        if frame == 30 {
            sim.command(Command::Spawn {
                at: [2.0, 6.0],
                round: true,
            })
            .unwrap();
        }
        at_tick.push(sim.scene.state_hash());
        run(
            &mut sim,
            1,
            Input {
                right: frame < 50,
                ..Input::default()
            },
        );
    }
    let replay = sim.stop_recording().unwrap();
    // Play it back, then rewind the played session to tick 45.
    let mut played = playground();
    played.start_playback(replay).unwrap();
    run(&mut played, 95, Input::default());
    assert_eq!(played.scene.state_hash(), sim.scene.state_hash());
    // A finished replay can be rewound.
    played.scrub_to(45);
    assert_eq!(played.scene.state_hash(), at_tick[45]);
    played.scrub_to(29);
    assert_eq!(played.scene.state_hash(), at_tick[29], "before the spawn");
    // Forward again past the spawn: the spawned ball keeps its colour.
    played.scrub_to(45);
    let lane = &played.scene.lanes[0];
    assert_eq!(lane.bodies.len(), lane.world.len());
    // Resumed, the replay is over and the scene runs live from tick 45.
    played.resume_from_timeline();
    run(&mut played, 10, Input::default());
    assert_eq!(played.scene.rewindable(), 45 + 10);
    assert!(!played.session.is_playing());
}

#[test]
fn holding_rewind_after_a_replay_runs_it_back() {
    let mut sim = playground();
    sim.start_recording().unwrap();
    let hashes = walk_keeping_hashes(&mut sim, 60, |_, _| {});
    let replay = sim.stop_recording().unwrap();
    let mut played = playground();
    played.start_playback(replay).unwrap();
    run(&mut played, 65, Input::default());
    assert!(played.session.playback_finished());
    played.rewinding = true;
    // The first frame ends the replay and resumes the loop; every frame
    // runs back a tick.
    run(&mut played, 20, Input::default());
    assert_eq!(played.scene.state_hash(), hashes[40]);
    assert!(!played.session.is_playing());
}

#[test]
fn rewinding_past_a_drag_slider_change_puts_the_slider_back() {
    let mut sim = load(&Entry::File("drag_race".into())).unwrap();
    let before = sim.session.knobs.drag_scale;
    run(&mut sim, 10, Input::default());
    move_slider(&mut sim, |k| k.drag_scale = 3.0, true);
    run(&mut sim, 10, Input::default());
    assert_eq!(sim.session.knobs.drag_scale, 3.0);
    sim.rewinding = true;
    run(&mut sim, 15, Input::default());
    assert!((sim.session.knobs.drag_scale - before).abs() < 1e-6);
}

#[test]
fn the_platformer_level_is_played_with_the_character_mover() {
    let mut sim = load(&Entry::File("platformer".into())).unwrap();
    // A kinematic character at the level's `player` spawn point, (1, 1);
    // it falls to stand a skin above the floor (top at 0.5 m).
    let start = player(&sim);
    assert_eq!(start.kind, passo_physics::BodyKind::Kinematic);
    assert!((start.position.x - 1.0).abs() < 1e-6);
    run(&mut sim, 30, Input::default());
    let rest = player(&sim).position;
    assert!(
        (rest.y - (0.5 + 0.35 + 0.01)).abs() < 1e-3,
        "standing at {rest}"
    );
    // Walking right for a quarter of a second at 4.5 m/s, on the ground
    // (short of the block at x = 2.5 m, whose underside at 1 m is lower
    // than the character's head).
    run(
        &mut sim,
        15,
        Input {
            right: true,
            ..Input::default()
        },
    );
    let walked = player(&sim).position - rest;
    assert!((walked.x - 4.5 * 0.25).abs() < 0.02, "walked {walked}");
    assert!(walked.y.abs() < 1e-3);
    // A jump: up at 6.5 m/s under 9.81 m/s², apex v² / 2g = 2.15 m higher.
    let before = player(&sim).position.y;
    let mut highest = before;
    run(
        &mut sim,
        1,
        Input {
            jump: true,
            ..Input::default()
        },
    );
    // In the air 2 × 6.5 / 9.81 = 1.33 s: 80 ticks.
    for _ in 0..100 {
        run(&mut sim, 1, Input::default());
        highest = highest.max(player(&sim).position.y);
    }
    let apex = highest - before;
    assert!(
        (apex - 6.5f32.powi(2) / (2.0 * 9.81)).abs() < 0.12,
        "apex {apex} m"
    );
    assert!(
        (player(&sim).position.y - before).abs() < 1e-3,
        "landed again"
    );
}

#[test]
fn a_big_scene_keeps_fewer_ticks_within_the_rewind_budget() {
    // 2 000 circles piling up: their snapshots grow as contacts appear,
    // past the 512 bytes a body first assumed (which kept 131 ticks, 190
    // MB). The budget follows the states as they are measured.
    let mut sim = load(&Entry::File("rain".into())).unwrap();
    let mut most = 0;
    // 10 s: the pile settles at about 700 bytes a body.
    for _ in 0..600 {
        sim.frame(FRAME);
        most = most.max(sim.scene.rewind_bytes());
    }
    let kept = sim.scene.rewindable();
    let per_state = sim.scene.rewind_bytes() / (kept + 1);
    assert!(
        (10..600).contains(&kept),
        "{kept} ticks kept at {per_state} bytes each"
    );
    // The budget, give or take the state being saved and one spare.
    assert!(
        most <= REWIND_BYTES + 2 * per_state,
        "{most} bytes held, {kept} ticks of {per_state}"
    );
    assert!(
        sim.scene.rewind_bytes() >= REWIND_BYTES - 3 * per_state,
        "the budget is used: {} bytes",
        sim.scene.rewind_bytes()
    );
}

#[test]
fn changing_the_rate_moves_platforms_and_the_plot_on_from_where_they_were() {
    // The platforms' clock and the plot's time were ticks × the current
    // step: at 60 Hz → 120 Hz after 6 s, the lift jumped 2.4 m in a tick
    // (290 m/s) and the plot's time went back to 3 s.
    let mut sim = playground();
    let lifts: Vec<_> = sim.scene.lanes[0]
        .world
        .bodies()
        .filter(|b| b.kind == passo_physics::BodyKind::Kinematic)
        .map(|b| b.id)
        .collect();
    assert!(!lifts.is_empty(), "the playground has moving platforms");
    let place = |sim: &Sim| -> Vec<Vec2> {
        let world = &sim.scene.lanes[0].world;
        lifts
            .iter()
            .map(|&id| world.body(id).unwrap().position)
            .collect()
    };
    let tick = |sim: &mut Sim| {
        sim.session.timestep.advance_ticks(1);
        sim.tick();
    };
    for _ in 0..360 {
        tick(&mut sim);
    }
    let t_before = *sim.scene.history.time.back().unwrap();
    let before = place(&sim);
    sim.command(Command::Rate(120.0)).unwrap();
    for _ in 0..3 {
        tick(&mut sim);
    }
    for (a, b) in before.iter().zip(place(&sim)) {
        // Three ticks of 1/120 s at the paths' few m/s: centimetres.
        assert!((b - *a).length() < 0.1, "a platform jumped from {a} to {b}");
    }
    let t_after = *sim.scene.history.time.back().unwrap();
    assert!(
        (t_after - (t_before + 3.0 / 120.0)).abs() < 1e-4,
        "plot time {t_before} -> {t_after}"
    );
    for id in &lifts {
        let v = sim.scene.lanes[0].world.body(*id).unwrap().velocity;
        assert!(v.length() < 10.0, "a platform moves at {v}");
    }
}

#[test]
fn slider_values_that_are_not_finite_are_refused() {
    // A NaN gravity reached the walk's force clamp and panicked.
    let mut sim = playground();
    let before = sim.session.knobs;
    let mut knobs = before;
    knobs.gravity = f32::NAN;
    let command = Command::Knobs {
        knobs,
        friction: false,
        restitution: false,
        drag: false,
    };
    assert!(sim.command(command).is_err());
    assert_eq!(sim.session.knobs, before, "the sliders are as they were");
    run(
        &mut sim,
        30,
        Input {
            right: true,
            ..Default::default()
        },
    );
}

#[test]
fn a_frame_of_ticks_runs_exactly_that_many_whatever_the_pause() {
    // The web demo's `?ticks=N` runs paused frames of a counted number of
    // ticks; they must give the state of N ordinary ticks.
    for n in [1u32, 7, 60, 61, 150] {
        let mut counted = playground();
        counted.session.timestep.pause();
        let mut left = n;
        while left > 0 {
            let k = left.min(60);
            counted.frame_of_ticks(k);
            left -= k;
        }
        let mut framed = playground();
        run(&mut framed, n as usize, Input::default());
        assert_eq!(counted.session.timestep.tick(), u64::from(n));
        assert_eq!(
            framed.session.timestep.tick(),
            u64::from(n),
            "one tick a frame"
        );
        assert_eq!(
            counted.scene.state_hash(),
            framed.scene.state_hash(),
            "{n} ticks"
        );
        // Paused, an ordinary frame runs none.
        counted.frame(FRAME * 5);
        assert_eq!(counted.session.timestep.tick(), u64::from(n));
    }
}
