//! The web demo's page (in a browser only): its address's options, where
//! errors show, downloads, and the state it shows tests (`window.passo`,
//! see `web`).

use wasm_bindgen::{JsCast, JsValue};

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

/// What the page shows its tests each frame (see `web`).
pub(super) struct Shown<'a> {
    pub(super) scene: &'a str,
    pub(super) tick: u64,
    pub(super) hash: u64,
    pub(super) player: Option<[f32; 2]>,
    pub(super) backend: String,
    pub(super) frames: u64,
    pub(super) size: (u32, u32),
    pub(super) panel: f32,
    /// Centre x, y and height, metres.
    pub(super) camera: [f32; 3],
}

/// Sets `window.passo` to `shown`.
pub(super) fn publish(shown: &Shown<'_>) {
    let Some(window) = web_sys::window() else {
        return;
    };
    let state = js_sys::Object::new();
    let set = |k: &str, v: JsValue| {
        let _ = js_sys::Reflect::set(&state, &k.into(), &v);
    };
    let array = |values: &[f32]| {
        let a = js_sys::Array::new();
        for v in values {
            a.push(&(*v).into());
        }
        JsValue::from(a)
    };
    set("scene", shown.scene.into());
    set("tick", (shown.tick as f64).into());
    set("hash", format!("{:016x}", shown.hash).into());
    set("player", shown.player.map_or(JsValue::NULL, |p| array(&p)));
    set("backend", shown.backend.as_str().into());
    set("frames", (shown.frames as f64).into());
    set("width", shown.size.0.into());
    set("height", shown.size.1.into());
    set("panel", shown.panel.into());
    set("camera", array(&shown.camera));
    let _ = js_sys::Reflect::set(&window, &"passo".into(), &state);
}

/// Offers `text` to the user as a file named `name`: the browser's own
/// download (a page has no disk of its own to write to).
pub(super) fn download(name: &str, text: &str) -> Result<(), String> {
    let fail = |e: JsValue| format!("{e:?}");
    let window = web_sys::window().ok_or("no window")?;
    let document = window.document().ok_or("no document")?;
    let parts = js_sys::Array::of1(&text.into());
    let blob = web_sys::Blob::new_with_str_sequence(&parts).map_err(fail)?;
    let url = web_sys::Url::create_object_url_with_blob(&blob).map_err(fail)?;
    let link: web_sys::HtmlAnchorElement = document
        .create_element("a")
        .map_err(fail)?
        .dyn_into()
        .map_err(|_| "not a link".to_owned())?;
    link.set_href(&url);
    link.set_download(name);
    link.click();
    web_sys::Url::revoke_object_url(&url).map_err(fail)
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
