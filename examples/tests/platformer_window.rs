//! The platformer example in a real window: under Xvfb (a virtual X
//! display) its scripted player reaches the goal of the Tiled level, and
//! the last frame shows the player.

use passo_render::RgbaImage;
use std::path::PathBuf;
use std::process::Command;

/// An example's binary, which `cargo test` builds beside the tests.
fn example(name: &str) -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let profile_dir = exe.parent().unwrap().parent().unwrap();
    profile_dir.join("examples").join(name)
}

/// Pixels of the player's orange in `image`.
fn orange_pixels(image: &RgbaImage) -> usize {
    (0..image.height)
        .flat_map(|y| (0..image.width).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            image
                .get(x, y)
                .is_some_and(|p| p[0] > 200 && (90..130).contains(&p[1]) && p[2] < 90)
        })
        .count()
}

/// Runs example `name` with `args` on lavapipe under Xvfb, saving its last
/// frame; returns what it printed and the frame.
fn run_under_xvfb(name: &str, args: &[&str]) -> (String, RgbaImage) {
    if Command::new("xvfb-run").arg("--help").output().is_err() {
        panic!("xvfb-run is missing: install `xvfb xauth` (see the README) to run the window test");
    }
    let dir = std::env::temp_dir().join(format!("passo-{name}-{}", std::process::id()));
    let runtime = dir.join("runtime");
    std::fs::create_dir_all(&runtime).unwrap();
    let shot = dir.join(format!("{name}.png"));
    let out = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24"])
        .arg(example(name))
        .args(args)
        .args(["--software", "--screenshot"])
        .arg(&shot)
        .env("XDG_RUNTIME_DIR", &runtime)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{name} failed:\n{stdout}\n{stderr}");
    (stdout, RgbaImage::load_png(&shot).unwrap())
}

#[test]
fn the_scripted_player_reaches_the_goal_in_a_window() {
    let (stdout, shot) = run_under_xvfb(
        "platformer",
        &["--autopilot", "--until-goal", "--frames", "20000"],
    );
    assert!(stdout.contains("goal reached at tick"), "{stdout}");
    // The last frame shows the player (its orange) somewhere.
    let image = shot;
    let orange = orange_pixels(&image);
    assert!(orange > 100, "{orange} orange pixels");
    // The HUD: the coin's gold at the top left, and the coins taken of
    // the three as gold digits beside it (lit pixels between x 50 and 110).
    let gold = |p: Option<[u8; 4]>| p.is_some_and(|p| p[0] > 200 && p[1] > 150 && p[2] < 100);
    assert!(
        gold(image.get(28, 28)),
        "the HUD's coin: {:?}",
        image.get(28, 28)
    );
    let digits = (50..110)
        .flat_map(|x| (14..42).map(move |y| (x, y)))
        .filter(|&(x, y)| gold(image.get(x, y)))
        .count();
    assert!(digits > 60, "{digits} gold pixels of the HUD's digits");
}

#[test]
fn the_slopes_example_runs_its_capsule_over_the_slopes_in_a_window() {
    let (stdout, shot) = run_under_xvfb("slopes", &["--autopilot", "--frames", "240"]);
    // It ran right from its spawn point at 14.75 m (how far depends on
    // how many ticks the frames took; the run over the slopes is tested
    // without a window): the line ends "player at (x, y)".
    let x: f32 = stdout
        .rsplit("player at (")
        .next()
        .and_then(|rest| rest.split(',').next())
        .and_then(|x| x.trim().parse().ok())
        .unwrap_or_else(|| panic!("no position in {stdout}"));
    assert!(x > 15.0, "{stdout}");
    // The capsule in the last frame.
    assert!(orange_pixels(&shot) > 100, "{stdout}");
}
