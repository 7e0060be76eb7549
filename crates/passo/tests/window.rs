//! The demo in a real window: under Xvfb (a virtual X display) the demo
//! runs a fixed number of frames through a resize, a minimise, a restore and
//! a 400 ms frame, presents every frame it can, exits cleanly, and its
//! screenshot shows the scene's bodies where the camera puts them. Without
//! any display it exits with a clear message.

use passo_physics::glam::Vec2;
use passo_render::{Camera2D, RgbaImage};
use passo_scene::Scene;
use std::process::Command;

fn passo() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_passo"));
    c.current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    c
}

/// Parses `... window 864x632; camera centre (x, y) height h`.
fn parse_summary(line: &str) -> ((u32, u32), Camera2D, u64, u64, f64) {
    let field = |name: &str| -> &str {
        let start = line
            .find(name)
            .unwrap_or_else(|| panic!("no `{name}` in {line:?}"))
            + name.len();
        line[start..].split(';').next().unwrap().trim()
    };
    let (w, h) = field("window ").split_once('x').unwrap();
    let centre = field("camera centre ");
    let (x, rest) = centre.trim_start_matches('(').split_once(',').unwrap();
    let (y, height) = rest.split_once(')').unwrap();
    let height = height.trim().trim_start_matches("height").trim();
    let presented = field("presented ")
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let skipped = field("skipped ").parse().unwrap();
    let dropped = field("dropped ").trim_end_matches(" s").parse().unwrap();
    (
        (w.parse().unwrap(), h.parse().unwrap()),
        Camera2D {
            centre: Vec2::new(x.trim().parse().unwrap(), y.trim().parse().unwrap()),
            height: height.parse().unwrap(),
        },
        presented,
        skipped,
        dropped,
    )
}

#[test]
fn the_demo_runs_in_a_real_window_and_shows_the_scene() {
    if Command::new("xvfb-run").arg("--help").output().is_err() {
        panic!("xvfb-run is missing: install `xvfb xauth` (see the README) to run the window test");
    }
    let dir = std::env::temp_dir().join(format!("passo-window-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let shot = dir.join("pyramid.png");
    let runtime = dir.join("runtime");
    std::fs::create_dir_all(&runtime).unwrap();
    let out = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24"])
        .arg(env!("CARGO_BIN_EXE_passo"))
        .args([
            "demo",
            "--scene",
            "pyramid",
            "--frames",
            "40",
            "--size",
            "800x600",
            "--stress",
            "--screenshot",
        ])
        .arg(&shot)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .env("XDG_RUNTIME_DIR", &runtime)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "exit {:?}\nstdout: {stdout}\nstderr: {stderr}",
        out.status.code()
    );
    let (size, camera, presented, skipped, dropped) = parse_summary(stdout.lines().last().unwrap());
    assert_eq!(presented, 40, "every requested frame was presented");
    assert!(
        skipped >= 1,
        "frames while minimised were skipped, not drawn: {stdout}"
    );
    assert!(
        (dropped - 0.15).abs() < 1e-6,
        "the 400 ms frame was cut to 250 ms: {stdout}"
    );
    assert_eq!(size, (864, 632), "the window followed the resize");

    let image = RgbaImage::load_png(&shot).unwrap();
    assert_eq!((image.width, image.height), size);
    let scene = Scene::load(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/scenes/pyramid.ron"
    )))
    .unwrap();
    let built = scene.build().unwrap();
    let mut checked = 0;
    for body in &built.bodies {
        let b = built.world.body(body.id).unwrap();
        if b.mass.is_infinite() {
            continue;
        }
        let px = camera.world_to_pixel(b.position, size);
        let got = image.get(px.x as u32, px.y as u32).unwrap();
        let want = body.colour.0;
        assert!(
            got.iter().zip(want).all(|(a, b)| a.abs_diff(b) <= 3),
            "box at {} (pixel {px}) shows {got:?}, its colour is {want:?}",
            b.position
        );
        checked += 1;
    }
    assert_eq!(checked, 210);
    // Above the pyramid, beside the panel: the background.
    let sky = camera.world_to_pixel(Vec2::new(8.0, 18.0), size);
    let got = image.get(sky.x as u32, sky.y as u32).unwrap();
    assert!(
        got.iter()
            .zip(passo::draw::BACKGROUND)
            .all(|(a, b)| a.abs_diff(b) <= 2),
        "{got:?}"
    );
    // The panel has no fill of its own: its margin shows the scene's
    // background, which the bodies, clipped beside the panel, never cover.
    for y in [100, size.1 / 2, size.1 - 20] {
        let got = image.get(3, y).unwrap();
        assert!(
            got.iter()
                .zip(passo::draw::BACKGROUND)
                .all(|(a, b)| a.abs_diff(b) <= 2),
            "panel margin at y = {y}: {got:?}"
        );
    }
    // The panel's plot (130 px on a grey-20 ground) is whole in the window:
    // it comes right after the scene, so no window cuts it off. (The most
    // ground rows in a few columns: a curve crosses each column somewhere.)
    let plot_rows = (140..=200)
        .step_by(10)
        .map(|x| {
            (0..image.height)
                .filter(|&y| image.get(x, y) == Some([20, 20, 20, 255]))
                .count()
        })
        .max()
        .unwrap();
    assert!(
        plot_rows >= 120,
        "{plot_rows} rows of the plot in the window"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn without_a_display_the_demo_explains_and_fails() {
    let out = passo()
        .args(["demo", "--scene", "stack"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("no display"), "{stderr}");
    assert!(
        stderr.contains("passo simulate") && stderr.contains("xvfb-run"),
        "{stderr}"
    );
}

#[test]
fn a_bad_scene_name_fails_before_opening_a_window() {
    let out = passo().args(["demo", "--scene", "nope"]).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no scene named `nope`"));
}
