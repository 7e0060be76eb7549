//! The command line, run as a user runs it.

use passo::snapshot::GameSnapshot;
use std::process::{Command, Output};

fn passo(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_passo"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .output()
        .expect("the passo binary runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn help_documents_every_subcommand() {
    let out = passo(&["--help"]);
    assert!(out.status.success());
    let text = stdout(&out);
    for command in ["simulate", "scenes"] {
        assert!(text.contains(command), "--help lacks {command}:\n{text}");
    }
    let out = passo(&["simulate", "--help"]);
    for flag in ["--ticks", "--csv", "--every", "--hash"] {
        assert!(stdout(&out).contains(flag), "simulate --help lacks {flag}");
    }
}

#[test]
fn simulate_prints_the_same_hash_for_the_same_run() {
    let a = passo(&["simulate", "pyramid", "--ticks", "120", "--hash"]);
    let b = passo(&[
        "simulate",
        "assets/scenes/pyramid.ron",
        "--ticks",
        "120",
        "--hash",
    ]);
    assert!(a.status.success(), "{}", stderr(&a));
    let hash = stdout(&a);
    assert_eq!(hash.trim().len(), 16, "{hash}");
    assert_eq!(hash, stdout(&b));
    // A resting pyramid is exactly at rest: one more tick changes no bit.
    let c = passo(&["simulate", "pyramid", "--ticks", "121", "--hash"]);
    assert_eq!(hash, stdout(&c));
    // Falling rain is not.
    let d = passo(&["simulate", "rain", "--ticks", "20", "--hash"]);
    let e = passo(&["simulate", "rain", "--ticks", "21", "--hash"]);
    assert_ne!(stdout(&d), stdout(&e));
}

#[test]
fn simulate_drives_the_path_platforms_as_the_demo_does() {
    // The demo, headless, with no input: 123 ticks of the playground.
    let mut sim = passo::demo::load(&passo::demo::Entry::File("playground".into())).unwrap();
    for _ in 0..123 {
        sim.session.timestep.advance_ticks(1);
        sim.tick();
    }
    let demo = format!("{:016x}", sim.scene.lanes[0].world.state_hash());
    let out = passo(&["simulate", "playground", "--ticks", "123", "--hash"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(stdout(&out).trim(), demo, "the same bits as the demo");
    assert!(
        stderr(&out).contains("bodies, 60 Hz,"),
        "the rate for people: {}",
        stderr(&out)
    );

    // The playground's moving platform (a kinematic box 4 m wide, 0.3 m
    // high) is somewhere else after a second.
    let dir = std::env::temp_dir().join(format!("passo-cli-platform-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("playground.csv");
    let path = csv.to_str().unwrap();
    let out = passo(&[
        "simulate",
        "playground",
        "--ticks",
        "60",
        "--every",
        "60",
        "--csv",
        path,
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = std::fs::read_to_string(&csv).unwrap();
    let file = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/scenes/playground.ron"
    );
    let scene = passo_scene::Scene::load(file.as_ref()).unwrap();
    let built = scene.build().unwrap();
    assert!(!built.platforms.is_empty(), "the playground has platforms");
    let dt = f64::from(
        passo_loop::FixedTimestep::from_hz(scene.file.rate_hz)
            .unwrap()
            .dt(),
    );
    for platform in &built.platforms {
        let row = |tick: &str| -> Vec<f32> {
            let line = text
                .lines()
                .find(|l| l.starts_with(&format!("{tick},{},", platform.id.index())))
                .unwrap();
            line.split(',')
                .skip(2)
                .map(|v| v.parse().unwrap())
                .collect()
        };
        let (first, last) = (row("0"), row("60"));
        let expected = platform.at(60.0 * dt);
        assert_eq!(&first[..2], &[platform.start.x, platform.start.y]);
        assert!(
            (last[0] - expected.x).abs() < 1e-4 && (last[1] - expected.y).abs() < 1e-4,
            "platform {} at {last:?}, not {expected}",
            platform.id.index()
        );
        assert!(expected != platform.start, "it moved");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn simulate_writes_csv_rows_at_the_chosen_interval() {
    let dir = std::env::temp_dir().join(format!("passo-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("projectile.csv");
    let out = passo(&[
        "simulate",
        "projectile",
        "--ticks",
        "60",
        "--every",
        "25",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = std::fs::read_to_string(&csv).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "tick,body,x,y,vx,vy");
    // Two bodies at ticks 0, 25, 50 and 60.
    let ticks: Vec<&str> = lines[1..]
        .iter()
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(ticks, ["0", "0", "25", "25", "50", "50", "60", "60"]);
    // The ball (body 1) after 25 ticks of 1/60 s in free flight: x = 10.6066 t.
    let row: Vec<f32> = lines[4].split(',').map(|v| v.parse().unwrap()).collect();
    assert_eq!(row[1], 1.0);
    assert!((row[2] - 10.6066 * 25.0 / 60.0).abs() < 1e-3, "{row:?}");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn bad_input_gives_a_clear_error_and_a_non_zero_exit() {
    let out = passo(&["simulate", "no_such_scene"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("no scene named `no_such_scene`"));

    let dir = std::env::temp_dir().join(format!("passo-cli-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("bad.ron");
    std::fs::write(&file, "(name: \"bad\", bodies: [(mas: 1)])").unwrap();
    let out = passo(&["simulate", file.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(err.contains("bad.ron:1:"), "{err}");
    assert!(err.contains("did you mean `mass`?"), "{err}");
    std::fs::remove_dir_all(dir).unwrap();

    // The demo's integrator comparison is listed, and the headless
    // commands say where to run it.
    let out = passo(&["scenes"]);
    assert!(stdout(&out).contains("integrators "), "{}", stdout(&out));
    let out = passo(&["simulate", "integrators"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("run it with `passo demo --scene integrators`"),
        "{}",
        stderr(&out)
    );

    let out = passo(&["simulate", "rain", "--every", "0"]);
    assert_eq!(out.status.code(), Some(2), "clap rejects a zero interval");
}

#[test]
fn a_saved_snapshot_resumes_to_the_same_hash_as_an_uninterrupted_run() {
    let dir = std::env::temp_dir().join(format!("passo-cli-snap-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let whole = passo(&["simulate", "rain", "--ticks", "50", "--hash"]);
    for name in ["rain.bin", "rain.ron"] {
        let file = dir.join(name);
        let first = passo(&[
            "simulate",
            "rain",
            "--ticks",
            "30",
            "--save",
            file.to_str().unwrap(),
        ]);
        assert!(first.status.success(), "{}", stderr(&first));
        let rest = passo(&[
            "simulate",
            "rain",
            "--ticks",
            "20",
            "--resume",
            file.to_str().unwrap(),
            "--hash",
        ]);
        assert!(rest.status.success(), "{}", stderr(&rest));
        assert_eq!(stdout(&rest), stdout(&whole), "{name}");
        // Another scene does not resume from it: its platforms would not be
        // driven and its bodies not named (a stack resumed from a
        // playground's snapshot flew its lift off, exit 0).
        let other = passo(&[
            "simulate",
            "stack",
            "--ticks",
            "1",
            "--resume",
            file.to_str().unwrap(),
        ]);
        assert_eq!(other.status.code(), Some(1), "{name}: {}", stderr(&other));
        let err = stderr(&other);
        assert!(
            err.contains(name) && err.contains("snapshot of the scene `Rain`, not `Stack`"),
            "{err}"
        );
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn snapshots_and_replays_no_run_could_make_are_refused_and_a_resume_says_so() {
    let dir = std::env::temp_dir().join(format!("passo-cli-bad-snap-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // A loop whose step is longer than a world steps (two hours, which
    // the loop itself refuses, written into a file): the resumed run
    // panicked in `World::step`.
    let world = passo_physics::World::default();
    let slowest = passo_loop::FixedTimestep::from_hz(1.0 / 3600.0).unwrap();
    let text = GameSnapshot::capture(&world, &slowest).to_ron();
    let hour = "secs: 3600,";
    assert_eq!(text.matches(hour).count(), 1, "{text}");
    let text = text.replace(hour, "secs: 7200,");
    let err = GameSnapshot::from_ron(&text).and_then(|s| s.restore());
    let err = format!("{:#}", err.unwrap_err());
    assert!(
        err.contains("snapshot loop") && err.contains("at most 3600 s (MAX_STEP), got 7200 s"),
        "{err}"
    );
    let file = dir.join("slow.ron");
    std::fs::write(&file, text).unwrap();
    let out = passo(&[
        "simulate",
        "projectile",
        "--ticks",
        "1",
        "--resume",
        file.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    // Files that never end are refused at the limit, not read into all
    // the memory there is.
    for (args, want) in [
        (
            vec!["simulate", "projectile", "--resume", "/dev/zero"],
            "larger than a snapshot file may be (1024 MiB)",
        ),
        (
            vec!["replay", "/dev/zero"],
            "larger than a replay file may be (64 MiB)",
        ),
    ] {
        let out = passo(&args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        assert!(stderr(&out).contains(want), "{args:?}: {}", stderr(&out));
    }
    // A resumed run names its snapshot and runs at its rate (100 Hz), not
    // the scene's (60 Hz).
    let world = passo_physics::World::default();
    let fast = passo_loop::FixedTimestep::from_hz(100.0).unwrap();
    let file = dir.join("fast.ron");
    GameSnapshot::capture(&world, &fast).save(&file).unwrap();
    let out = passo(&[
        "simulate",
        "projectile",
        "--ticks",
        "100",
        "--resume",
        file.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains(&format!(
            "(resumed from {}): 0 bodies, 100 Hz",
            file.display()
        )),
        "{err}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn render_refuses_an_output_that_is_not_png_before_simulating() {
    // The rain for 10^8 ticks would take hours; the name was checked only
    // after them.
    let out = passo(&[
        "render",
        "rain",
        "--ticks",
        "100000000",
        "--out",
        "rain.jpg",
    ]);
    assert_eq!(out.status.code(), Some(2), "an argument error");
    assert!(
        stderr(&out).contains("--out <OUT>': must name a .png file, got rain.jpg"),
        "{}",
        stderr(&out)
    );
    // The demo's screenshot too: it wrote PNG data under any name.
    let out = passo(&["demo", "--frames", "1", "--screenshot", "shot.jpg"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("--screenshot <SCREENSHOT>': must name a .png file, got shot.jpg"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn outputs_in_a_directory_that_does_not_exist_are_refused_before_the_work() {
    // Each was written only at the end: a render of 10^8 ticks, a long
    // simulation, or a whole recorded session, lost to a mistyped
    // directory.
    let missing = "/nonexistent-passo-dir/out";
    for (args, flag) in [
        (
            vec!["render", "rain", "--ticks", "100000000", "--out"],
            "--out <OUT>",
        ),
        (
            vec!["simulate", "rain", "--ticks", "100000000", "--save"],
            "--save <SAVE>",
        ),
        (vec!["demo", "--record"], "--record <RECORD>"),
        (
            vec!["demo", "--frames", "1", "--screenshot"],
            "--screenshot <SCREENSHOT>",
        ),
    ] {
        let file = if flag.contains("SAVE") || flag.contains("RECORD") {
            format!("{missing}/x.ron")
        } else {
            format!("{missing}/x.png")
        };
        let mut args = args;
        args.push(&file);
        let out = passo(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: an argument error");
        let err = stderr(&out);
        assert!(
            err.contains(flag) && err.contains("the directory /nonexistent-passo-dir/out of"),
            "{err}"
        );
    }
    // A file in the working directory (no directory named) is fine.
    assert_eq!(passo::render_cmd::output_path("x.png"), Ok("x.png".into()));
}

#[test]
fn report_refuses_an_output_directory_it_cannot_make_before_measuring() {
    // An existing file where the directory should go: before, the error
    // came after minutes of measuring.
    let file = std::env::temp_dir().join(format!("passo-report-file-{}", std::process::id()));
    std::fs::write(&file, "not a directory").unwrap();
    let out = passo(&["report", "--out", file.to_str().unwrap()]);
    std::fs::remove_file(&file).unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("creating"), "{}", stderr(&out));
}

/// The cells of the table rows (lines starting with `| ` and not a header).
fn table_rows(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| scene") && !l.starts_with("|-"))
        .map(|l| {
            l.trim_matches('|')
                .split('|')
                .map(|c| c.trim().to_owned())
                .collect()
        })
        .collect()
}

#[test]
fn bench_sleep_reports_a_settled_pyramid_asleep_and_cheaper() {
    let out = passo(&[
        "bench",
        "sleep",
        "--rain",
        "200",
        "--pyramid",
        "6",
        "--settle",
        "3",
        "--ticks",
        "10",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let rows = table_rows(&stdout(&out));
    assert_eq!(rows.len(), 2, "{}", stdout(&out));
    let pyramid = &rows[1];
    assert_eq!(pyramid[0], "pyramid 6");
    assert_eq!(pyramid[1], "21");
    assert_eq!(pyramid[2], "21", "every box of the pyramid sleeps");
    let on: f64 = pyramid[3].parse().unwrap();
    let off: f64 = pyramid[4].parse().unwrap();
    assert!(on >= 0.0 && off > 0.0);
}

#[test]
fn bench_physics_reports_every_scene_with_its_penetration() {
    let out = passo(&[
        "bench",
        "physics",
        "--rain",
        "200",
        "--pyramid",
        "5",
        "--ticks",
        "30",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let rows = table_rows(&stdout(&out));
    let names: Vec<&str> = rows.iter().map(|r| r[0].as_str()).collect();
    assert_eq!(names, ["rain 200", "pyramid 5"]);
    for row in &rows {
        let end: f64 = row[4].parse().unwrap();
        let worst: f64 = row[5].parse().unwrap();
        assert!((0.0..50.0).contains(&end) && worst >= end, "{row:?}");
    }
}

#[test]
fn bench_platforms_runs_platforms_of_the_length_asked_for() {
    let out = passo(&[
        "bench",
        "platforms",
        "--bodies",
        "300",
        "--platforms",
        "4",
        "--length",
        "30",
        "--above",
        "--ticks",
        "10",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let rows = table_rows(&stdout(&out));
    assert_eq!(rows.len(), 2, "a header and one row: {rows:?}");
    assert_eq!(rows[1][..4], ["300", "4", "30", "10"]);
    let penetration: f64 = rows[1][6].parse().unwrap();
    assert!((0.0..50.0).contains(&penetration), "{rows:?}");
}

#[test]
fn numeric_arguments_out_of_range_are_refused_before_any_work() {
    // `report --cost-bodies 0` used to grow memory until the machine
    // killed it.
    for args in [
        &["report", "--cost-bodies", "0"][..],
        &["report", "--cost-steps", "0"],
        &["report", "--long-steps", "1000000000000"],
        &["simulate", "rain", "--ticks", "99999999999999"],
        &["bench", "physics", "--rain", "0"],
        &["bench", "platforms", "--ticks", "0"],
        &["bench", "platforms", "--length", "nan"],
        &["bench", "platforms", "--length", "0"],
    ] {
        let out = passo(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(
            stderr(&out).contains("is not in"),
            "{args:?}: {}",
            stderr(&out)
        );
    }
}

#[test]
fn simulate_says_so_when_a_step_was_dropped_for_a_non_finite_velocity() {
    let dir = std::env::temp_dir().join(format!("passo-cli-nan-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // A force field enormous against a tiny mass overflows the velocity.
    let scene = dir.join("overflow.ron");
    std::fs::write(
        &scene,
        "(name: \"overflow\", forces: (force_field: (3e38, 0)), max_speed: inf, bodies: [(mass: 1e-30)])",
    )
    .unwrap();
    let out = passo(&["simulate", scene.to_str().unwrap(), "--ticks", "3"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("non-finite velocity"),
        "{}",
        stderr(&out)
    );
}
