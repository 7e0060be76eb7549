//! Replays: a run recorded with input by tick plays back to the same final
//! state, headless or in a window, whatever the frame rate of either.

use passo::demo::{Command, Entry, Input, Replay, Sim, load, run_replay};
use std::process::Command as Process;
use std::time::Duration;

/// Plays the scripted session on `sim` with frames of `frame` seconds.
fn script(sim: &mut Sim, frame: Duration) {
    let mut t = 0u32;
    // Frames of uneven length around `frame`.
    let mut next = || {
        t += 1;
        frame + Duration::from_micros(u64::from(t % 7) * 900)
    };
    let walk = Input {
        right: true,
        ..Default::default()
    };
    for _ in 0..40 {
        sim.scene.set_input(walk);
        sim.frame(next());
    }
    sim.scene.set_input(Input {
        right: true,
        jump: true,
        ..Default::default()
    });
    sim.frame(next());
    for _ in 0..30 {
        sim.scene.set_input(Input {
            glide: true,
            run: true,
            right: true,
            ..Default::default()
        });
        sim.frame(next());
    }
    let mut knobs = sim.session.knobs;
    knobs.wind = true;
    knobs.wind_speed = -12.0;
    sim.command(Command::Knobs {
        knobs,
        friction: false,
        restitution: false,
        drag: false,
    })
    .unwrap();
    sim.command(Command::Spawn {
        at: [2.0, 6.0],
        round: true,
    })
    .unwrap();
    for _ in 0..20 {
        sim.scene.set_input(Input::default());
        sim.frame(next());
    }
    let ball = sim.scene.lanes[0].world.bodies().last().unwrap().id;
    sim.command(Command::Fling {
        index: ball.index(),
        generation: ball.generation(),
        velocity: [-6.0, 8.0],
    })
    .unwrap();
    sim.command(Command::Rate(120.0)).unwrap();
    for _ in 0..30 {
        sim.scene.set_input(Input {
            left: true,
            ..Default::default()
        });
        sim.frame(next());
    }
}

fn record(frame: Duration) -> Replay {
    let mut sim = load(&Entry::File("playground".into())).unwrap();
    sim.start_recording().unwrap();
    script(&mut sim, frame);
    sim.stop_recording().unwrap()
}

#[test]
fn a_recorded_run_replays_to_the_same_final_state() {
    let replay = record(Duration::from_micros(6944)); // about 144 FPS
    assert!(replay.ticks > 60, "{} ticks", replay.ticks);
    // The session's integrator and sliders at tick 0 (the rate is the
    // scene's own), then the script's four commands.
    assert!(replay.inputs.len() >= 4 && replay.commands.len() == 2 + 4);
    assert!(replay.commands[..2].iter().all(|(tick, _)| *tick == 0));
    assert_eq!(
        run_replay(&replay).unwrap(),
        replay.final_hash,
        "headless, tick by tick"
    );

    // Played back in a live simulation driven at 30 FPS.
    let mut sim = load(&Entry::File("playground".into())).unwrap();
    sim.start_playback(replay.clone()).unwrap();
    for _ in 0..200 {
        sim.frame(Duration::from_micros(33_333));
        // Live input is ignored during playback.
        sim.scene.set_input(Input {
            left: true,
            jump: true,
            ..Default::default()
        });
    }
    let (played, total, result, recorded) = sim.session.playback_status().unwrap();
    assert_eq!(
        (played, total),
        (replay.ticks, replay.ticks),
        "stops at the last tick"
    );
    assert_eq!(result, Some(recorded));

    // The file form.
    let text = replay.to_ron();
    assert_eq!(Replay::from_ron(&text).unwrap(), replay);
}

#[test]
fn a_recording_that_ends_with_a_command_replays_to_its_final_state() {
    // Paused after the last tick, a ball spawned, the recording stopped:
    // the recorded hash counts the ball, and playback applies commands
    // recorded after the last tick before it ends (it skipped them, so the
    // file failed `passo replay`). Also a replay of no tick at all.
    for ticks in [30, 0] {
        let mut sim = load(&Entry::File("playground".into())).unwrap();
        sim.start_recording().unwrap();
        for _ in 0..ticks {
            sim.session.timestep.advance_ticks(1);
            sim.tick();
        }
        sim.command(Command::Spawn {
            at: [2.0, 6.0],
            round: true,
        })
        .unwrap();
        let replay = sim.stop_recording().unwrap();
        assert_eq!(replay.ticks, ticks);
        // The session's integrator and sliders at tick 0, then the spawn.
        assert_eq!(replay.commands.len(), 2 + 1);
        assert_eq!(
            replay.commands[2],
            (
                ticks,
                Command::Spawn {
                    at: [2.0, 6.0],
                    round: true
                }
            )
        );
        assert_eq!(
            run_replay(&replay).unwrap(),
            replay.final_hash,
            "{ticks} ticks"
        );
    }
}

#[test]
fn a_different_input_gives_a_different_state() {
    let mut replay = record(Duration::from_micros(16_667));
    let (_, input) = replay.inputs.iter_mut().find(|(_, i)| i.right).unwrap();
    input.right = false;
    assert_ne!(run_replay(&replay).unwrap(), replay.final_hash);
}

#[test]
fn passo_replay_checks_the_final_state() {
    let dir = std::env::temp_dir().join(format!("passo-replay-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let replay = record(Duration::from_micros(16_667));
    let good = dir.join("good.ron");
    replay.save(&good).unwrap();
    let out = Process::new(env!("CARGO_BIN_EXE_passo"))
        .arg("replay")
        .arg(&good)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        String::from_utf8_lossy(&out.stdout).trim(),
        format!("{:016x}", replay.final_hash)
    );

    let bad = dir.join("bad.ron");
    Replay {
        final_hash: replay.final_hash ^ 1,
        ..replay.clone()
    }
    .save(&bad)
    .unwrap();
    let out = Process::new(env!("CARGO_BIN_EXE_passo"))
        .arg("replay")
        .arg(&bad)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("not the recorded"));

    // In a real window (Xvfb), the demo plays it, reports the match and
    // saves a picture of its final state: the replay ends long before frame
    // 2 000 (the run failed with "no frame was captured").
    if Process::new("xvfb-run").arg("--help").output().is_err() {
        panic!("xvfb-run is missing: install `xvfb xauth` (see the README)");
    }
    let runtime = dir.join("runtime");
    std::fs::create_dir_all(&runtime).unwrap();
    let shot = dir.join("end.png");
    let out = Process::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24"])
        .arg(env!("CARGO_BIN_EXE_passo"))
        .args([
            "demo",
            "--frames",
            "2000",
            "--size",
            "640x480",
            "--screenshot",
        ])
        .arg(&shot)
        .arg("--replay")
        .arg(&good)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .env("XDG_RUNTIME_DIR", &runtime)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("replay matched"), "{stdout}");
    assert!(
        stdout.contains(&format!("hash {:016x}", replay.final_hash)),
        "{stdout}"
    );
    let image = passo_render::RgbaImage::load_png(&shot).unwrap();
    assert_eq!((image.width, image.height), (640, 480));
    let background = image.get(0, 0).unwrap();
    let drawn = (0..480)
        .flat_map(|y| (0..640).map(move |x| (x, y)))
        .filter(|&(x, y)| image.get(x, y) != Some(background))
        .count();
    assert!(
        drawn > 10_000,
        "the panel and the scene are drawn: {drawn} pixels"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_level_scene_records_and_replays() {
    // The platformer's level map is found beside its scene file when the
    // recording restarts the scene, and again when the replay loads it
    // (both looked for it beside the scene's name in the working
    // directory, and failed).
    let mut sim = load(&Entry::File("platformer".into())).unwrap();
    sim.start_recording().unwrap();
    for frame in 0..90 {
        sim.scene.set_input(Input {
            right: frame < 60,
            jump: frame == 30,
            ..Default::default()
        });
        sim.frame(Duration::from_micros(16_667));
    }
    let replay = sim.stop_recording().unwrap();
    assert!(replay.ticks > 60, "{} ticks", replay.ticks);
    assert_eq!(run_replay(&replay).unwrap(), replay.final_hash);
    let mut other = replay.clone();
    other.inputs.retain(|(_, input)| !input.jump);
    assert_ne!(
        run_replay(&other).unwrap(),
        replay.final_hash,
        "the jump counts"
    );
}

#[test]
fn the_final_hash_is_written_as_the_commands_print_it_and_read_in_either_form() {
    let replay = Replay {
        scene: "stack".into(),
        ticks: 3,
        inputs: Vec::new(),
        commands: Vec::new(),
        final_hash: 0x05fb_82a0_c6e2_4792,
    };
    let text = replay.to_ron();
    let written = r#""05fb82a0c6e24792""#;
    assert!(text.contains(&format!("final_hash: {written}")), "{text}");
    assert_eq!(Replay::from_ron(&text).unwrap(), replay);
    // Files written before hold the hash as a decimal integer.
    let decimal = text.replace(written, &replay.final_hash.to_string());
    assert_eq!(Replay::from_ron(&decimal).unwrap(), replay);
    for bad in [
        r#""""#,
        r#""12345678901234567""#,
        r#""+12""#,
        r#""xyz""#,
        "-5",
    ] {
        let err = Replay::from_ron(&text.replace(written, bad)).unwrap_err();
        assert!(err.to_string().contains("state hash"), "{bad}: {err}");
    }
}

#[test]
fn replays_out_of_order_past_the_end_absurd_or_endless_are_refused() {
    let replay = record(Duration::from_micros(16_667));
    let mut late = replay.clone();
    late.commands.push((u64::MAX, Command::Reset));
    let mut backwards = replay.clone();
    backwards.inputs.reverse();
    let (first, _) = backwards.inputs[0];
    let (second, _) = backwards.inputs[1];
    let mut slow = replay.clone();
    slow.commands.push((replay.ticks, Command::Rate(1e-300)));
    let mut huge_rain = replay.clone();
    huge_rain
        .commands
        .push((replay.ticks, Command::RainCount(1_000_000)));
    let mut rebuilds = replay.clone();
    rebuilds
        .commands
        .extend((0..=Replay::MAX_REBUILDS).map(|i| match i % 2 {
            0 => (replay.ticks, Command::Reset),
            _ => (replay.ticks, Command::RainCount(100)),
        }));
    let endless = Replay {
        ticks: u64::MAX,
        ..replay.clone()
    };
    let spawn = (
        replay.ticks,
        Command::Spawn {
            at: [0.0, 5.0],
            round: true,
        },
    );
    let recorded_spawns = (replay.commands.iter())
        .filter(|(_, c)| matches!(c, Command::Spawn { .. }))
        .count();
    let room = Replay::MAX_SPAWNS - recorded_spawns;
    let mut spawns = replay.clone();
    spawns.commands.extend(vec![spawn.clone(); room + 1]);
    let mut nan_knobs = replay.clone();
    let mut knobs = load(&Entry::File("playground".into()))
        .unwrap()
        .session
        .knobs;
    knobs.gravity = f32::NAN;
    nan_knobs.commands.push((
        replay.ticks,
        Command::Knobs {
            knobs,
            friction: false,
            restitution: false,
            drag: false,
        },
    ));
    let cases = [
        (
            "nan_knobs",
            nan_knobs,
            // (`passo replay` panicked on it in the walk's force clamp.)
            format!(
                "the slider values set at tick {} must be finite, got {knobs:?}",
                replay.ticks
            ),
        ),
        (
            "late",
            late,
            format!(
                "a command at tick {} is past the last tick, {}",
                u64::MAX,
                replay.ticks
            ),
        ),
        (
            "backwards",
            backwards,
            format!("an input at tick {second} comes after one at tick {first}: out of order"),
        ),
        (
            "slow",
            slow,
            format!(
                "the rate set at tick {} must be in [1, 10000] Hz, got 1e-300",
                replay.ticks
            ),
        ),
        (
            "huge_rain",
            huge_rain,
            format!(
                "the rain count set at tick {} must be at most 20000, got 1000000",
                replay.ticks
            ),
        ),
        (
            "rebuilds",
            rebuilds,
            format!(
                "the replay rebuilds the scene {} times (resets and rain counts), more than the \
                 most a replay may, 4096",
                Replay::MAX_REBUILDS + 1
            ),
        ),
        (
            "spawns",
            spawns,
            "the replay spawns 20001 bodies, more than the most a replay may, 20000".to_string(),
        ),
        (
            "endless",
            endless.clone(),
            format!(
                "the replay has {} ticks, more than the most a replay may have, 4294967296",
                u64::MAX
            ),
        ),
    ];
    for (what, bad, want) in cases {
        let Err(err) = Replay::from_ron(&bad.to_ron()) else {
            panic!("the {what} replay was accepted");
        };
        assert_eq!(err.to_string(), want, "{what}");
    }
    assert!(Replay::from_ron(&replay.to_ron()).is_ok());

    // The limits themselves are allowed.
    let longest = Replay {
        ticks: Replay::MAX_TICKS,
        commands: vec![(0, Command::RainCount(Replay::MAX_RAIN_COUNT))],
        ..replay.clone()
    };
    longest.validate().unwrap();
    let mut most_spawns = replay.clone();
    most_spawns.commands.extend(vec![spawn; room]);
    most_spawns.validate().unwrap();
    // A list of commands longer than the cap is refused (after the file is
    // parsed; the file's size bounds what parsing reads).
    let mut many = replay.clone();
    many.commands = vec![(0, Command::Rate(60.0)); Replay::MAX_COMMANDS];
    many.validate().unwrap();
    many.commands.push((0, Command::Rate(60.0)));
    assert_eq!(
        many.validate().unwrap_err().to_string(),
        format!(
            "the replay has {} commands, more than the most a replay may have, {}",
            Replay::MAX_COMMANDS + 1,
            Replay::MAX_COMMANDS
        )
    );

    // `passo replay` refuses an endless file at once instead of playing it.
    let file = std::env::temp_dir().join(format!("passo-endless-{}.ron", std::process::id()));
    endless.save(&file).unwrap();
    let out = Process::new(env!("CARGO_BIN_EXE_passo"))
        .arg("replay")
        .arg(&file)
        .output()
        .unwrap();
    std::fs::remove_file(&file).unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("more than the most a replay may have"),
        "{stderr}"
    );

    // A file larger than a replay file may be is refused before it is
    // read.
    let big = std::env::temp_dir().join(format!("passo-big-{}.ron", std::process::id()));
    let file = std::fs::File::create(&big).unwrap();
    file.set_len(passo_scene::MAX_FILE_BYTES + 1).unwrap();
    let err = Replay::load(&big).unwrap_err().to_string();
    std::fs::remove_file(&big).unwrap();
    assert!(
        err.contains("larger than a replay file may be (64 MiB)"),
        "{err}"
    );
}

#[test]
fn settings_changed_before_recording_are_part_of_the_replay() {
    // The wind, the gravity, the rate, the integrator and the rain's size
    // set before "record" stay in force through the restart that begins a
    // recording, but the replay did not say so: played from the scene's
    // first state it ended elsewhere (`passo replay` reported the wrong
    // hash).
    for scene in ["playground", "rain"] {
        let mut sim = load(&Entry::File(scene.into())).unwrap();
        let mut knobs = sim.session.knobs;
        knobs.wind = true;
        knobs.wind_speed = 9.0;
        knobs.gravity = -4.0;
        let knobs = Command::Knobs {
            knobs,
            friction: false,
            restitution: false,
            drag: false,
        };
        sim.command(knobs).unwrap();
        sim.command(Command::Rate(90.0)).unwrap();
        sim.command(Command::Integrator(
            passo_physics::Integrator::VelocityVerlet,
        ))
        .unwrap();
        if sim.scene.rain_count().is_some() {
            sim.command(Command::RainCount(300)).unwrap();
        }
        sim.start_recording().unwrap();
        for _ in 0..60 {
            sim.scene.set_input(Input {
                right: true,
                ..Default::default()
            });
            sim.frame(Duration::from_micros(16_667));
        }
        let replay = sim.stop_recording().unwrap();
        assert!(replay.ticks > 60, "{scene}: {} ticks", replay.ticks);
        assert_eq!(run_replay(&replay).unwrap(), replay.final_hash, "{scene}");
    }
}
