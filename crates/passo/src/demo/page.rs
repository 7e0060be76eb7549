//! The web demo's page (in a browser only): its address's options, where
//! errors show, and the state it shows tests (`window.passo`, see `web`).

use super::running::Running;
use wasm_bindgen::JsValue;

/// The value of `name` in the page's query string.
pub(super) fn query(name: &str) -> Option<String> {
    let search = web_sys::window()?.location().search().ok()?;
    web_sys::UrlSearchParams::new_with_str(&search)
        .ok()?
        .get(name)
}

/// Shows an error that stopped the demo: on the console, in the page, and
/// in `window.passoError`.
pub(super) fn report_error(e: &anyhow::Error) {
    let text = format!("{e:#}");
    web_sys::console::error_1(&text.clone().into());
    if let Some(window) = web_sys::window() {
        let _ = js_sys::Reflect::set(&window, &"passoError".into(), &text.clone().into());
        if let Some(body) = window.document().and_then(|d| d.body()) {
            let _ = body.insert_adjacent_text("afterbegin", &format!("Passo stopped: {text}"));
        }
    }
}

/// Sets `window.passo` to the running scene's state.
pub(super) fn publish(r: &Running, frames: u64) {
    let Some(window) = web_sys::window() else {
        return;
    };
    let scene = &r.sim.scene;
    let state = js_sys::Object::new();
    let set = |k: &str, v: JsValue| {
        let _ = js_sys::Reflect::set(&state, &k.into(), &v);
    };
    set("scene", r.sim.session.entry_name.as_str().into());
    set("tick", (r.sim.session.timestep.tick() as f64).into());
    set("hash", format!("{:016x}", scene.state_hash()).into());
    let player = scene
        .player
        .and_then(|id| scene.lanes[0].world.body(id))
        .map(|b| {
            let xy = js_sys::Array::new();
            xy.push(&b.position.x.into());
            xy.push(&b.position.y.into());
            JsValue::from(xy)
        });
    set("player", player.unwrap_or(JsValue::NULL));
    set(
        "backend",
        format!("{:?}", r.gpu.adapter.get_info().backend).into(),
    );
    set("frames", (frames as f64).into());
    let _ = js_sys::Reflect::set(&window, &"passo".into(), &state);
}

/// `log` on the browser's console.
pub(super) struct ConsoleLog;

impl log::Log for ConsoleLog {
    fn enabled(&self, metadata: &log::Metadata<'_>) -> bool {
        metadata.level() <= log::Level::Info
    }

    fn log(&self, record: &log::Record<'_>) {
        if !self.enabled(record.metadata()) {
            return;
        }
        let text = JsValue::from(format!("{}: {}", record.target(), record.args()));
        match record.level() {
            log::Level::Error => web_sys::console::error_1(&text),
            log::Level::Warn => web_sys::console::warn_1(&text),
            _ => web_sys::console::log_1(&text),
        }
    }

    fn flush(&self) {}
}
