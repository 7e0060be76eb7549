//! Checks the web demo in a real browser: serves the built folder on
//! 127.0.0.1, opens it in headless Chromium through the DevTools protocol,
//! and for WebGPU and for WebGL2 checks that
//! - every page loads with no console error or uncaught exception;
//! - every shipped scene, run exactly N ticks, has the state hash of the
//!   native build (the demo's own `Sim`, stepped here);
//! - every scene draws: the browser's frame at that tick matches the
//!   native off-screen render of the same frame (same camera, same size):
//!   at most [`MAX_DIFFERENT`] of the drawn pixels differ;
//! - a key press moves the player in the Playground;
//! - the netplay game, in two tabs that play each other over WebRTC,
//!   agrees tick by tick with a straight native run (`netplay.rs`).
//!
//! `bash web/build.sh && cargo run --release -p passo-web-check -- [--ticks N] [--scenes a,b] [--backends webgpu,webgl] [--netplay-frames N] [--dir DIR] [--save DIR]`
//! (`--netplay-frames 0` leaves the netplay check out; default 600 ticks)
//!
//! It prints a table and exits with 1 when a check fails.
//!
//! `--bench` instead times the physics on one thread natively and in the
//! browser, in one run (`passo::bench::BROWSER_CASES`), and prints the
//! ratio; `--bench --write` puts that table in BENCHMARKS.md.

mod cdp;
mod netplay;
mod serve;

use anyhow::{Context, Result, anyhow, bail};
use cdp::{Browser, Page};
use passo::demo::{Entry, Sim, load, render_scene_offscreen};
use passo_render::{AdapterChoice, Camera2D, RgbaImage};
use serde_json::{Value, json};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// How far a pixel's channel may differ between the browser's frame and
/// the native one before the pixel counts as different: the two software
/// rasterisers (SwiftShader, lavapipe) round edges differently.
const CHANNEL_TOLERANCE: u8 = 48;
/// The share of the scene's drawn pixels (not the background) that may
/// differ.
const MAX_DIFFERENT: f64 = 0.03;
/// The browser's page size, CSS pixels (one device pixel each).
const PAGE: (u32, u32) = (1280, 720);

/// Chromium's flags for each backend. SwiftShader gives WebGL2; Vulkan on
/// SwiftShader gives a WebGPU adapter whose frames reach the page.
const WEBGPU_FLAGS: &[&str] = &[
    "--enable-unsafe-webgpu",
    "--enable-features=Vulkan",
    "--use-vulkan=swiftshader",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
];

struct Args {
    dir: PathBuf,
    ticks: u64,
    scenes: Vec<String>,
    backends: Vec<String>,
    save: Option<PathBuf>,
    bench: bool,
    write: bool,
    netplay_frames: u64,
}

fn parse_args() -> Result<Args> {
    let mut args = Args {
        dir: PathBuf::from("target/web-demo"),
        ticks: 120,
        scenes: passo::scenes::names()
            .into_iter()
            .map(str::to_owned)
            .collect(),
        backends: vec!["webgpu".into(), "webgl".into()],
        save: None,
        bench: false,
        write: false,
        netplay_frames: 600,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or_else(|| anyhow!("{flag} needs a value"));
        match flag.as_str() {
            "--dir" => args.dir = PathBuf::from(value()?),
            "--ticks" => args.ticks = value()?.parse().context("--ticks")?,
            "--scenes" => args.scenes = value()?.split(',').map(str::to_owned).collect(),
            "--backends" => args.backends = value()?.split(',').map(str::to_owned).collect(),
            "--save" => args.save = Some(PathBuf::from(value()?)),
            "--bench" => args.bench = true,
            "--write" => args.write = true,
            "--netplay-frames" => {
                args.netplay_frames = value()?.parse().context("--netplay-frames")?;
            }
            _ => bail!("unknown option {flag}; see the file's comment for the options"),
        }
    }
    if !args.dir.join("index.html").is_file() {
        bail!(
            "{} holds no built web demo: run `bash web/build.sh` first",
            args.dir.display()
        );
    }
    if args.netplay_frames > 0 && !args.dir.join("netplay.html").is_file() {
        bail!(
            "{} holds no netplay page: run `bash web/build.sh` again",
            args.dir.display()
        );
    }
    for b in &args.backends {
        if b != "webgpu" && b != "webgl" {
            bail!("unknown backend {b}: webgpu or webgl");
        }
    }
    Ok(args)
}

/// The demo's scene `name` stepped exactly `ticks` ticks, as the page's
/// `?ticks=` steps it.
fn native_sim(name: &str, ticks: u64) -> Result<Sim> {
    let mut sim = load(&Entry::named(name))?;
    sim.session.timestep.pause();
    let mut left = ticks;
    while left > 0 {
        let n = left.min(60);
        sim.frame_of_ticks(n as u32);
        left -= n;
    }
    Ok(sim)
}

/// Polls the page's `window.passo` until `done` says so, for at most
/// `limit`; an error the demo reported stops the wait.
fn wait_for(page: &mut Page, limit: Duration, done: impl Fn(&Value) -> bool) -> Result<Value> {
    let start = Instant::now();
    loop {
        let v = page.eval("({ state: window.passo || null, error: window.passoError || null })")?;
        if let Some(e) = v["error"].as_str() {
            bail!("the demo stopped: {e}");
        }
        if !v["state"].is_null() && done(&v["state"]) {
            return Ok(v["state"].clone());
        }
        if start.elapsed() > limit {
            bail!(
                "timed out after {limit:?}; the page's state: {}",
                v["state"]
            );
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

fn num(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or(f64::NAN)
}

/// Of the scene's drawn pixels (right of the panel, and not the
/// background in either picture), the share whose largest channel
/// difference passes [`CHANNEL_TOLERANCE`]. An error if the sizes differ
/// or nothing is drawn.
fn different_share(web: &RgbaImage, native: &RgbaImage, panel: f32) -> Result<f64> {
    if (web.width, web.height) != (native.width, native.height) {
        bail!(
            "the browser's frame is {}x{}, the native one {}x{}",
            web.width,
            web.height,
            native.width,
            native.height
        );
    }
    // A pixel's width of slack where the panel's edge is drawn.
    let left = (panel.ceil() as u32 + 2).min(web.width);
    let pixel = |image: &RgbaImage, x: u32, y: u32| {
        let i = 4 * (y * image.width + x) as usize;
        [image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]]
    };
    let far = |a: [u8; 3], b: [u8; 3]| (0..3).any(|c| a[c].abs_diff(b[c]) > CHANNEL_TOLERANCE);
    // The background: each picture's most common colour.
    let background = |image: &RgbaImage| {
        let mut counts = std::collections::BTreeMap::new();
        for y in 0..image.height {
            for x in left..image.width {
                *counts.entry(pixel(image, x, y)).or_insert(0u64) += 1;
            }
        }
        counts.into_iter().max_by_key(|&(_, n)| n).map(|(c, _)| c)
    };
    let (Some(web_bg), Some(native_bg)) = (background(web), background(native)) else {
        bail!("no scene area beside the panel");
    };
    let (mut drawn, mut different) = (0u64, 0u64);
    for y in 0..web.height {
        for x in left..web.width {
            let (a, b) = (pixel(web, x, y), pixel(native, x, y));
            if far(a, web_bg) || far(b, native_bg) {
                drawn += 1;
                different += u64::from(far(a, b));
            }
        }
    }
    if drawn == 0 {
        bail!("nothing is drawn in either picture");
    }
    Ok(different as f64 / drawn as f64)
}

/// One scene on one backend: its hash and its picture against native.
fn check_scene(
    page: &mut Page,
    base: &str,
    backend: &str,
    scene: &str,
    args: &Args,
) -> Result<String> {
    let url = format!(
        "{base}/?scene={scene}&ticks={}&backend={backend}",
        args.ticks
    );
    page.call("Page.navigate", json!({ "url": url }))?;
    let ticks = args.ticks as f64;
    let reached = wait_for(page, Duration::from_secs(120), |s| {
        s["scene"].as_str() == Some(scene) && num(s, "tick") == ticks
    })?;
    // Two more frames at that tick, so the picture is of it.
    let frames = num(&reached, "frames");
    let state = wait_for(page, Duration::from_secs(30), |s| {
        num(s, "frames") >= frames + 2.0
    })?;
    let png = page.screenshot_png()?;
    let browser_frame = RgbaImage::decode_png(&png, "the screenshot")?;

    let sim = native_sim(scene, args.ticks)?;
    let native_hash = format!("{:016x}", sim.scene.state_hash());
    let web_hash = state["hash"].as_str().unwrap_or("?").to_owned();
    let size = (num(&state, "width") as u32, num(&state, "height") as u32);
    let panel = num(&state, "panel") as f32;
    let c = &state["camera"];
    let camera = Camera2D {
        centre: passo_render::glam::Vec2::new(
            c[0].as_f64().unwrap_or(0.0) as f32,
            c[1].as_f64().unwrap_or(0.0) as f32,
        ),
        height: c[2].as_f64().unwrap_or(1.0) as f32,
    };
    let native_frame = render_scene_offscreen(&sim, camera, size, panel, AdapterChoice::Software)?;
    if let Some(dir) = &args.save {
        std::fs::create_dir_all(dir)?;
        browser_frame.save_png(dir.join(format!("{scene}-{backend}.png")))?;
        native_frame.save_png(dir.join(format!("{scene}-native.png")))?;
    }
    let share = different_share(&browser_frame, &native_frame, panel)?;
    let errors = page.take_errors();
    let mut problems = Vec::new();
    if web_hash != native_hash {
        problems.push(format!("hash {web_hash} here, {native_hash} native"));
    }
    if share > MAX_DIFFERENT {
        problems.push(format!("{:.2} % of the pixels differ", share * 100.0));
    }
    problems.extend(errors);
    let result = if problems.is_empty() {
        "ok".to_owned()
    } else {
        format!("**failed**: {}", problems.join("; "))
    };
    Ok(format!(
        "| {backend} | {scene} | {} | {web_hash} | {} | {:.3} % | {result} |",
        args.ticks,
        if web_hash == native_hash {
            "same"
        } else {
            "differs"
        },
        share * 100.0
    ))
}

/// The Playground's player walks right while the right arrow is held.
fn check_keyboard(page: &mut Page, base: &str, backend: &str) -> Result<String> {
    page.call(
        "Page.navigate",
        json!({ "url": format!("{base}/?scene=playground&backend={backend}") }),
    )?;
    let before = wait_for(page, Duration::from_secs(60), |s| {
        s["scene"].as_str() == Some("playground") && num(s, "tick") >= 30.0
    })?;
    let x0 = before["player"][0]
        .as_f64()
        .ok_or_else(|| anyhow!("no player"))?;
    page.eval("document.querySelector('canvas').focus()")?;
    let key = |kind: &str| json!({ "type": kind, "key": "ArrowRight", "code": "ArrowRight", "windowsVirtualKeyCode": 39 });
    page.call("Input.dispatchKeyEvent", key("keyDown"))?;
    let t0 = num(&before, "tick");
    wait_for(page, Duration::from_secs(60), |s| {
        num(s, "tick") >= t0 + 60.0
    })?;
    page.call("Input.dispatchKeyEvent", key("keyUp"))?;
    let after = wait_for(page, Duration::from_secs(10), |_| true)?;
    let x1 = after["player"][0].as_f64().unwrap_or(x0);
    let errors = page.take_errors();
    let moved = x1 - x0;
    let result = if moved > 0.5 && errors.is_empty() {
        "ok".to_owned()
    } else {
        format!("**failed**: moved {moved:.3} m; {}", errors.join("; "))
    };
    Ok(format!(
        "| {backend} | playground, right arrow held 1 s | | | | | player moved {moved:.2} m right: {result} |"
    ))
}

fn main() -> std::process::ExitCode {
    match run() {
        Ok(true) => std::process::ExitCode::SUCCESS,
        Ok(false) => std::process::ExitCode::FAILURE,
        Err(e) => {
            eprintln!("web_check: {e:#}");
            std::process::ExitCode::FAILURE
        }
    }
}

/// The physics' speed natively and in the browser, in one run.
fn bench(base: &str, write: bool) -> Result<bool> {
    let browser = Browser::launch(&[])?;
    let mut page = Page::open(&browser)?;
    page.call("Page.navigate", json!({ "url": format!("{base}/?bench") }))?;
    let start = Instant::now();
    let web = loop {
        let v = page.eval("window.passoBench || null")?;
        if v.is_array() {
            break v;
        }
        if start.elapsed() > Duration::from_secs(300) {
            bail!("the page's benchmark did not finish in 5 minutes");
        }
        std::thread::sleep(Duration::from_millis(200));
    };
    let mut table = String::from(
        "| world | native, ms a tick | Chromium (wasm32), ms a tick | wasm ÷ native | same bits |\n\
         |---|---:|---:|---:|---|\n",
    );
    let mut same = true;
    for (i, case) in passo::bench::BROWSER_CASES.iter().enumerate() {
        let (native_ms, hash) = passo::bench::time_case(case);
        let row = &web[i];
        let web_ms = row["ms"].as_f64().unwrap_or(f64::NAN);
        let equal = row["hash"].as_str() == Some(format!("{hash:016x}").as_str());
        same &= equal;
        table.push_str(&format!(
            "| {} | {native_ms:.3} | {web_ms:.3} | {:.2} | {} |\n",
            case.name,
            web_ms / native_ms,
            if equal { "yes" } else { "**no**" }
        ));
    }
    print!("{table}");
    if write {
        let path = passo_benches::tables::benchmarks_md();
        let doc = std::fs::read_to_string(&path)?;
        let doc =
            passo_benches::tables::replace(&doc, "web_speed", &table).map_err(|e| anyhow!(e))?;
        std::fs::write(&path, doc)?;
        println!("written to {}", path.display());
    }
    Ok(same)
}

fn run() -> Result<bool> {
    let args = parse_args()?;
    let base = serve::serve(&args.dir)?;
    if args.bench {
        return bench(&base, args.write);
    }
    println!(
        "The web demo in headless Chromium against the native build: state hash after {} ticks, \
         and the share of the scene's drawn pixels (not background) differing by more than \
         {CHANNEL_TOLERANCE} in a channel (at most {} % allowed).\n",
        args.ticks,
        MAX_DIFFERENT * 100.0
    );
    println!(
        "| backend | scene | ticks | hash in the browser | against native | drawn pixels differing | result |"
    );
    println!("|---|---|---:|---|---|---:|---|");
    let mut ok = true;
    for backend in &args.backends {
        let flags: &[&str] = if backend == "webgpu" {
            WEBGPU_FLAGS
        } else {
            &["--use-angle=swiftshader", "--enable-unsafe-swiftshader"]
        };
        let browser = Browser::launch(flags)?;
        let mut page = Page::open(&browser)?;
        // The check of console errors must see one: make one and look.
        page.eval("console.error('web_check: a console error, to see it is seen')")?;
        page.eval("1")?;
        if !page
            .take_errors()
            .iter()
            .any(|e| e.contains("to see it is seen"))
        {
            bail!("console errors do not reach the check: it could not fail on one");
        }
        page.call(
            "Emulation.setDeviceMetricsOverride",
            json!({ "width": PAGE.0, "height": PAGE.1, "deviceScaleFactor": 1, "mobile": false }),
        )?;
        let mut rows: Vec<Result<String>> = args
            .scenes
            .iter()
            .map(|scene| check_scene(&mut page, &base, backend, scene, &args))
            .collect();
        if args.scenes.iter().any(|s| s == "playground") {
            rows.push(check_keyboard(&mut page, &base, backend));
        }
        for (i, row) in rows.into_iter().enumerate() {
            let row = row.unwrap_or_else(|e| {
                let scene = args.scenes.get(i).map_or("keyboard", String::as_str);
                format!("| {backend} | {scene} | | | | | **failed**: {e:#} |")
            });
            ok &= !row.contains("**failed**");
            println!("{row}");
        }
    }
    if args.netplay_frames > 0 {
        println!(
            "\nThe netplay game in two tabs, each tick's checksum against a straight native run \
             of the same inputs.\n"
        );
        println!("| game | ticks | rollbacks (each tab) | result |");
        println!("|---|---:|---|---|");
        let row = netplay::check(&base, args.netplay_frames, args.save.as_deref())
            .unwrap_or_else(|e| format!("| two tabs over WebRTC | | | **failed**: {e:#} |"));
        ok &= !row.contains("**failed**");
        println!("{row}");
    }
    Ok(ok)
}
