//! The platformer's game, without a window: the scripted player reaches
//! the goal of the level made in Tiled, and the game-feel helpers do what
//! they say.

use passo_examples::platformer::{
    COYOTE_TIME, GRAVITY, JUMP_CUT, JUMP_SPEED, Keys, Platformer, WALK_SPEED, follow_camera,
};
use passo_physics::glam::Vec2;
use std::path::PathBuf;

const DT: f32 = 1.0 / 60.0;

fn level() -> Platformer {
    let scene = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/platformer.ron");
    Platformer::load(&scene).unwrap()
}

#[test]
fn the_scripted_player_reaches_the_goal() {
    let mut game = level();
    for _ in 0..60 * 20 {
        let keys = game.autopilot();
        game.update(keys, DT);
        if game.reached.is_some() {
            break;
        }
    }
    let at = game.player_position();
    assert!(
        game.reached.is_some(),
        "stuck at {at} after {} ticks",
        game.tick
    );
    // The goal is at the end of the bottom corridor, x in [13.5, 14] m.
    assert!(at.x > 13.0, "at {at}");
}

#[test]
fn a_held_jump_reaches_v2_over_2g_and_a_tapped_one_less() {
    let apex = |hold: usize| {
        let mut game = level();
        for _ in 0..30 {
            game.update(Keys::default(), DT);
        }
        let start = game.player_position().y;
        let mut top = start;
        for tick in 0..90 {
            let keys = Keys {
                jump: tick < hold,
                ..Keys::default()
            };
            game.update(keys, DT);
            top = top.max(game.player_position().y);
        }
        top - start
    };
    let full = JUMP_SPEED * JUMP_SPEED / (2.0 * GRAVITY);
    let held = apex(90);
    assert!((held - full).abs() < 0.1, "held: {held} m, v²/2g = {full}");
    // Let go after 3 ticks: the upward speed is cut to JUMP_CUT of itself.
    let tapped = apex(3);
    assert!(tapped < 0.5 * held, "tapped: {tapped} m");
    const { assert!(JUMP_CUT < 1.0) };
}

#[test]
fn coyote_time_lets_a_jump_start_just_after_walking_off_an_edge() {
    // Walk off the block at x = 2.5..4 m (top at 1.5 m) and press jump a
    // few ticks after leaving it: the jump still happens.
    let mut game = level();
    // Up onto the block first.
    for _ in 0..600 {
        let keys = game.autopilot();
        game.update(keys, DT);
        if game.player_position().y > 1.8 && game.player_position().x > 3.0 {
            break;
        }
    }
    let mut left_edge = None;
    for tick in 0..120 {
        let past = game.player_position().x > 4.0 + 0.2 + 0.05;
        if past && left_edge.is_none() {
            left_edge = Some(tick);
        }
        let late = left_edge.is_some_and(|t| tick - t == 3);
        let keys = Keys {
            right: true,
            jump: late,
            ..Keys::default()
        };
        let before = game.player_position().y;
        game.update(keys, DT);
        if late {
            const { assert!(3.0 * DT < COYOTE_TIME) };
            assert!(game.player_position().y > before, "the late jump rose");
            return;
        }
    }
    panic!("never walked off the block");
}

/// How far the player moves in 15 ticks holding `keys`, after settling.
fn moved_holding(keys: Keys) -> passo_physics::glam::Vec2 {
    let mut game = level();
    for _ in 0..30 {
        game.update(Keys::default(), DT);
    }
    let start = game.player_position();
    for _ in 0..15 {
        game.update(keys, DT);
    }
    game.player_position() - start
}

#[test]
fn walking_moves_at_walking_speed() {
    let moved = moved_holding(Keys {
        right: true,
        ..Keys::default()
    });
    assert!(
        (moved.x - WALK_SPEED * 15.0 * DT).abs() < 0.02,
        "moved {moved}"
    );
}

#[test]
fn the_wind_carries_the_player_standing_still() {
    let moved = moved_holding(Keys {
        wind: true,
        ..Keys::default()
    });
    // On the ground the wind carries it at half of WIND_SPEED.
    let expected = 0.5 * passo_examples::platformer::WIND_SPEED * 15.0 * DT;
    assert!(
        (moved.x - expected).abs() < 0.01,
        "moved {moved}, expected {expected}"
    );
}

#[test]
fn a_crushed_player_starts_again_at_the_spawn_point() {
    // The player walks 1.5 m from where it landed, and a block comes down
    // onto it there: the game puts it back at the spawn point.
    use passo_physics::glam::Vec2;
    use passo_physics::{BodyDef, Shape};
    let mut game = level();
    for _ in 0..30 {
        game.update(Keys::default(), DT);
    }
    let start = game.player_position();
    let right = Keys {
        right: true,
        ..Keys::default()
    };
    for _ in 0..20 {
        game.update(right, DT);
    }
    let walked = game.player_position();
    assert!(walked.x > start.x + 1.0, "it walked: {start} -> {walked}");
    let block = BodyDef::new_kinematic(
        walked + Vec2::new(0.0, 1.0),
        Shape::rect(0.6, 0.4),
        Vec2::ZERO,
    );
    let block = game.world.add_body(block).unwrap();
    for tick in 1..=60 {
        let y = (walked.y + 1.0 - 3.0 * tick as f32 * DT).max(walked.y);
        game.world
            .set_kinematic_target(block, Vec2::new(walked.x, y), DT);
        game.update(Keys::default(), DT);
        if game.crushed > 0 {
            break;
        }
    }
    assert_eq!(game.crushed, 1, "crushed once");
    // Put back at the spawn point, it lands where it first stood.
    for _ in 0..30 {
        game.update(Keys::default(), DT);
    }
    assert_eq!(game.crushed, 1, "crushed once");
    let at = game.player_position();
    assert!(
        (at - start).length() < 0.02,
        "back at the start {start}: {at}"
    );
}

/// The camera follows the player through the level, and its view never
/// shows past the level's edges: the shipped level is 24 m wide and 7.5 m
/// tall, and the view 8 m tall, so the level fills it from top to bottom
/// wherever the player is.
#[test]
fn the_camera_follows_the_player_and_stays_inside_the_level() {
    let mut game = level();
    let bounds = game.bounds;
    assert_eq!(game.coins_total, 5, "the level's coins");
    assert!(
        (bounds.size() - Vec2::new(24.0, 7.5)).length() < 1e-4,
        "{bounds:?}"
    );
    for aspect in [4.0 / 3.0, 16.0 / 10.0, 0.5] {
        let view = Vec2::new(8.0 * aspect, 8.0);
        let mut centre = game.player_position();
        let mut game = level();
        let mut seen = (f32::INFINITY, f32::NEG_INFINITY);
        for _ in 0..60 * 20 {
            let keys = game.autopilot();
            game.update(keys, DT);
            centre = follow_camera(centre, game.player_position(), view, bounds);
            // Taller than the level: centred on it.
            assert_eq!(centre.y, bounds.centre().y);
            if view.x < bounds.size().x {
                assert!(centre.x - view.x / 2.0 >= bounds.min.x - 1e-4, "{centre}");
                assert!(centre.x + view.x / 2.0 <= bounds.max.x + 1e-4, "{centre}");
            } else {
                assert_eq!(centre.x, bounds.centre().x);
            }
            seen = (seen.0.min(centre.x), seen.1.max(centre.x));
            if game.reached.is_some() {
                break;
            }
        }
        assert!(game.reached.is_some());
        if view.x < bounds.size().x {
            // It scrolled from the level's left end to the goal (13.75 m).
            assert!(seen.0 <= bounds.min.x + view.x / 2.0 + 1e-3, "{seen:?}");
            assert!(
                seen.1 >= (13.75 - view.x / 2.0).min(bounds.max.x - view.x / 2.0) - 0.5,
                "{seen:?}"
            );
        }
    }
    game.update(Keys::default(), DT);
    assert!((game.seconds(DT) - DT).abs() < 1e-6);
}

/// Past the goal the level slopes: a hill, a 2:1 ramp up to a ledge and a
/// wall too steep to walk, all drawn in Tiled as polygons. The scripted
/// player runs over the hill and up the ramp on the ground, takes both
/// coins there, and jumps the steep wall it cannot walk up.
#[test]
fn the_scripted_player_runs_over_the_slopes_past_the_goal() {
    let mut game = level();
    for _ in 0..60 * 40 {
        let keys = game.autopilot();
        game.update(keys, DT);
        if game.player_position().x > 23.0 && game.coins == 4 {
            break;
        }
    }
    let at = game.player_position();
    assert!(at.x > 23.0, "past the steep wall: {at}");
    // The coins on the hill and past the steep wall were taken.
    for name in ["coin 4", "coin 5"] {
        let coin = game
            .bodies
            .iter()
            .find(|b| b.name.as_deref() == Some(name))
            .unwrap();
        assert!(!game.world.contains(coin.id), "{name} is still there");
    }
}
