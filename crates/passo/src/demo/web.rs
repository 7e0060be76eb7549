//! The demo in a browser (`wasm32-unknown-unknown`): the page's options,
//! the files built into the program, logs and panics on the console, and
//! the state the page shows its tests.
//!
//! The page's address takes these options:
//! - `?scene=NAME`: the scene to open (default `playground`);
//! - `&backend=webgl`: WebGL2 even where WebGPU is there;
//! - `&ticks=N`: run exactly N ticks as fast as frames come, then pause;
//! - `?bench`: no demo: time the physics on the page's thread and set
//!   `window.passoBench` (see `bench::BROWSER_CASES`).
//!
//! Each frame the page's `window.passo` holds `{ scene, tick, hash,
//! player, backend, frames, width, height, panel, camera }`: `hash` as 16
//! hex digits, `player` as `[x, y]` or `null`, the canvas's size and the
//! panel's width in pixels, `camera` as `[x, y, height]`. An error that
//! stopped the demo is in `window.passoError`.

use super::app::{App, DemoArgs, GpuReady};
use super::catalogue::Entry;
use super::page::{ConsoleLog, query, report_error};
use super::sim::load;
use wasm_bindgen::JsValue;
use winit::event_loop::EventLoop;
use winit::platform::web::EventLoopExtWebSys;

/// Starts the demo on the page: a canvas appended to its body.
pub fn start() {
    console_error_panic_hook::set_once();
    let _ = log::set_logger(&ConsoleLog).map(|()| log::set_max_level(log::LevelFilter::Info));
    passo_scene::embed_files(crate::scenes::LEVEL_FILES);
    if query("bench").is_some() {
        return bench();
    }
    if let Err(e) = try_start() {
        report_error(&e);
    }
}

fn try_start() -> anyhow::Result<()> {
    let first = Entry::named(&query("scene").unwrap_or_else(|| "playground".into()));
    let sim = load(&first)?;
    let event_loop = EventLoop::<GpuReady>::with_user_event().build()?;
    let (w, h) = page_size();
    let args = DemoArgs {
        size: (w, h),
        ..DemoArgs::default()
    };
    let mut app = App::new(args, sim, first, event_loop.create_proxy());
    app.stop_at_tick = query("ticks").and_then(|t| t.parse().ok());
    app.webgl_only = query("backend").as_deref() == Some("webgl");
    event_loop.spawn_app(app);
    Ok(())
}

/// The page's `?bench`: times the physics cases of
/// [`BROWSER_CASES`](crate::bench::BROWSER_CASES) (no demo, no GPU) and
/// sets `window.passoBench` to `[{ name, ms, hash }]`.
fn bench() {
    let results = js_sys::Array::new();
    for case in &crate::bench::BROWSER_CASES {
        let (ms, hash) = crate::bench::time_case(case);
        log::info!("{}: {ms:.3} ms a tick", case.name);
        let row = js_sys::Object::new();
        let _ = js_sys::Reflect::set(&row, &"name".into(), &case.name.into());
        let _ = js_sys::Reflect::set(&row, &"ms".into(), &ms.into());
        let _ = js_sys::Reflect::set(&row, &"hash".into(), &format!("{hash:016x}").into());
        results.push(&row);
    }
    if let Some(window) = web_sys::window() {
        let _ = js_sys::Reflect::set(&window, &"passoBench".into(), &results);
    }
}

/// The page's inner size, CSS pixels (the canvas fills it).
fn page_size() -> (u32, u32) {
    let window = web_sys::window();
    let px = |v: Option<JsValue>| v.and_then(|v| v.as_f64()).unwrap_or(800.0).max(1.0) as u32;
    let w = px(window.as_ref().and_then(|w| w.inner_width().ok()));
    let h = px(window.as_ref().and_then(|w| w.inner_height().ok()));
    (w, h)
}
