//! A small client of Chromium's DevTools protocol: launch a headless
//! browser, open a page, call methods on it, and keep the events that come
//! between the answers (console messages, exceptions).

use anyhow::{Context, Result, anyhow, bail};
use serde_json::{Value, json};
use std::io::{BufRead, BufReader};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::Duration;
use tungstenite::stream::MaybeTlsStream;
use tungstenite::{Message, WebSocket};

/// A headless Chromium, killed when dropped.
pub struct Browser {
    child: Child,
    /// The browser's DevTools address (`ws://…`).
    pub ws_url: String,
    profile: std::path::PathBuf,
}

impl Browser {
    /// Starts `chromium` headless with `flags`, a fresh profile, and the
    /// DevTools protocol on a free port.
    pub fn launch(flags: &[&str]) -> Result<Self> {
        let profile = std::env::temp_dir().join(format!("passo-web-check-{}", std::process::id()));
        std::fs::create_dir_all(&profile)?;
        let mut child = Command::new("chromium")
            .args(["--headless", "--no-sandbox", "--remote-debugging-port=0"])
            .arg(format!("--user-data-dir={}", profile.display()))
            .args([
                "--no-first-run",
                "--no-default-browser-check",
                "--mute-audio",
            ])
            .args(flags)
            .arg("about:blank")
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .context("starting chromium (on Debian: apt-get install chromium)")?;
        let stderr = child.stderr.take().expect("piped");
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stderr).lines().map_while(Result::ok) {
                if let Some(i) = line.find("ws://") {
                    let _ = tx.send(line[i..].trim().to_owned());
                }
                // Chromium's own logs are read and dropped, so it never
                // blocks on a full pipe.
            }
        });
        let ws_url = rx
            .recv_timeout(Duration::from_secs(30))
            .map_err(|_| anyhow!("chromium did not open its DevTools port within 30 s"))?;
        Ok(Self {
            child,
            ws_url,
            profile,
        })
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
        let _ = std::fs::remove_dir_all(&self.profile);
    }
}

/// One page of the browser, driven over the browser's connection.
pub struct Page {
    ws: WebSocket<MaybeTlsStream<TcpStream>>,
    next_id: u64,
    session: String,
    /// Events not yet looked at, oldest first.
    pub events: Vec<Value>,
}

impl Page {
    /// Opens a blank page in `browser`, with its console, log and page
    /// events on.
    pub fn open(browser: &Browser) -> Result<Self> {
        Self::open_with(browser, false)
    }

    /// [`open`](Self::open), in a window of its own: pages that must run
    /// side by side, since a page hidden behind another gets no animation
    /// frames.
    pub fn open_in_window(browser: &Browser) -> Result<Self> {
        Self::open_with(browser, true)
    }

    fn open_with(browser: &Browser, new_window: bool) -> Result<Self> {
        let (mut ws, _) = tungstenite::connect(browser.ws_url.as_str())
            .context("connecting to chromium's DevTools")?;
        if let MaybeTlsStream::Plain(s) = ws.get_mut() {
            s.set_read_timeout(Some(Duration::from_secs(120)))?;
        }
        let mut page = Self {
            ws,
            next_id: 1,
            session: String::new(),
            events: Vec::new(),
        };
        let target = page.call(
            "Target.createTarget",
            json!({ "url": "about:blank", "newWindow": new_window }),
        )?;
        let target_id = target["targetId"].clone();
        let attached = page.call(
            "Target.attachToTarget",
            json!({ "targetId": target_id, "flatten": true }),
        )?;
        page.session = attached["sessionId"]
            .as_str()
            .ok_or_else(|| anyhow!("no session: {attached}"))?
            .to_owned();
        for domain in ["Runtime.enable", "Log.enable", "Page.enable"] {
            page.call(domain, json!({}))?;
        }
        Ok(page)
    }

    /// The page as it shows now, a PNG file's bytes.
    pub fn screenshot_png(&mut self) -> Result<Vec<u8>> {
        let shot = self.call("Page.captureScreenshot", json!({ "format": "png" }))?;
        Ok(base64::Engine::decode(
            &base64::engine::general_purpose::STANDARD,
            shot["data"].as_str().unwrap_or_default(),
        )?)
    }

    /// Calls `method` and returns its result; events read meanwhile are
    /// kept in [`events`](Self::events).
    pub fn call(&mut self, method: &str, params: Value) -> Result<Value> {
        let id = self.next_id;
        self.next_id += 1;
        let mut message = json!({ "id": id, "method": method, "params": params });
        if !self.session.is_empty() {
            message["sessionId"] = json!(self.session);
        }
        self.ws.send(Message::text(message.to_string()))?;
        loop {
            let text = match self.ws.read()? {
                Message::Text(t) => t.to_string(),
                Message::Close(_) => bail!("chromium closed the connection"),
                _ => continue,
            };
            let value: Value = serde_json::from_str(&text)?;
            if value["id"].as_u64() == Some(id) {
                if let Some(e) = value.get("error") {
                    bail!("{method}: {e}");
                }
                return Ok(value["result"].clone());
            }
            self.events.push(value);
        }
    }

    /// Evaluates `expression` in the page and returns its value.
    pub fn eval(&mut self, expression: &str) -> Result<Value> {
        let r = self.call(
            "Runtime.evaluate",
            json!({ "expression": expression, "returnByValue": true }),
        )?;
        if let Some(e) = r.get("exceptionDetails") {
            bail!("{expression}: {e}");
        }
        Ok(r["result"]["value"].clone())
    }

    /// The errors among the events so far (console errors, uncaught
    /// exceptions, errors the browser logged), as text; the events are
    /// cleared.
    pub fn take_errors(&mut self) -> Vec<String> {
        let mut errors = Vec::new();
        for e in self.events.drain(..) {
            let p = &e["params"];
            match e["method"].as_str() {
                Some("Runtime.consoleAPICalled")
                    if matches!(p["type"].as_str(), Some("error" | "assert")) =>
                {
                    let args: Vec<String> = p["args"]
                        .as_array()
                        .into_iter()
                        .flatten()
                        .map(|a| {
                            a["value"]
                                .as_str()
                                .map_or_else(|| a.to_string(), str::to_owned)
                        })
                        .collect();
                    errors.push(format!("console: {}", args.join(" ")));
                }
                Some("Runtime.exceptionThrown") => {
                    let d = &p["exceptionDetails"];
                    let text = d["exception"]["description"]
                        .as_str()
                        .or(d["text"].as_str())
                        .unwrap_or("?");
                    errors.push(format!("exception: {text}"));
                }
                Some("Log.entryAdded") if p["entry"]["level"].as_str() == Some("error") => {
                    errors.push(format!("log: {}", p["entry"]["text"]));
                }
                _ => {}
            }
        }
        errors
    }
}
