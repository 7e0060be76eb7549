//! The netplay game in two tabs: a signalling server in this process, two
//! tabs of one headless Chromium that meet through it and play over
//! WebRTC, each following the scripted input, and their checksums tick by
//! tick against a straight native run of the same inputs, as
//! `tests/netplay.rs` checks two native peers over UDP.

use crate::cdp::{Browser, Page};
use anyhow::{Result, bail};
use passo_netplay::game::straight_checksums;
use serde_json::{Value, json};
use std::path::Path;
use std::time::{Duration, Instant};

/// Plays `frames` ticks in two tabs of the page at `base`; returns the
/// table's row (which says `**failed**` when a check fails).
/// With `save`, each tab's picture at the end goes there
/// (`netplay-tab0.png`, `netplay-tab1.png`).
pub fn check(base: &str, frames: u64, save: Option<&Path>) -> Result<String> {
    let signal = passo_netplay::signal::spawn("127.0.0.1:0")?;
    let browser = Browser::launch(&[])?;
    let room = format!("check-{}", std::process::id());
    let url =
        format!("{base}/netplay.html?room={room}&signal=ws://{signal}&script&frames={frames}");
    // Each in a window of its own: a tab hidden behind the other would get
    // no animation frames, and so play no ticks.
    let mut tabs = [
        Page::open_in_window(&browser)?,
        Page::open_in_window(&browser)?,
    ];
    for tab in &mut tabs {
        tab.call("Page.navigate", json!({ "url": url }))?;
    }
    let start = Instant::now();
    // Connecting takes a second or two; the ticks run at 60 a second.
    let limit = Duration::from_secs(60 + frames / 20);
    let states = loop {
        let states = tabs
            .iter_mut()
            .map(|tab| tab.eval("window.passoNetplay || null"))
            .collect::<Result<Vec<Value>>>()?;
        if let Some(e) = states.iter().find_map(|s| s["error"].as_str()) {
            bail!("a tab stopped: {e}");
        }
        if states.iter().all(|s| s["checksums"].is_array()) {
            break states;
        }
        if start.elapsed() > limit {
            let errors: Vec<String> = tabs.iter_mut().flat_map(Page::take_errors).collect();
            bail!(
                "timed out after {limit:?}; the tabs: {} and {}; console: {errors:?}",
                states[0],
                states[1]
            );
        }
        std::thread::sleep(Duration::from_millis(200));
    };
    let straight: Vec<String> = straight_checksums(frames)
        .iter()
        .map(|c| format!("{c:032x}"))
        .collect();
    let mut problems = Vec::new();
    let mut players = Vec::new();
    for (i, state) in states.iter().enumerate() {
        players.push(state["me"].as_u64());
        let sums: Vec<&str> = state["checksums"]
            .as_array()
            .map(|a| a.iter().filter_map(Value::as_str).collect())
            .unwrap_or_default();
        if let Some(t) = (0..straight.len()).find(|&t| sums.get(t) != Some(&straight[t].as_str())) {
            problems.push(format!(
                "tab {i} differs from the native run first after tick {}",
                t + 1
            ));
        }
        if state["desyncs"].as_u64() != Some(0) {
            problems.push(format!("tab {i} saw desyncs: {}", state["desyncs"]));
        }
    }
    if !matches!(players[..], [Some(0), Some(1)] | [Some(1), Some(0)]) {
        problems.push(format!("the tabs are not players 0 and 1: {players:?}"));
    }
    let rollbacks: Vec<u64> = states
        .iter()
        .map(|s| s["rollbacks"].as_u64().unwrap_or(0))
        .collect();
    if rollbacks.iter().all(|&r| r == 0) {
        problems.push("neither tab predicted and rolled back".into());
    }
    if let Some(dir) = save {
        std::fs::create_dir_all(dir)?;
        for (i, tab) in tabs.iter_mut().enumerate() {
            std::fs::write(
                dir.join(format!("netplay-tab{i}.png")),
                tab.screenshot_png()?,
            )?;
        }
    }
    for tab in &mut tabs {
        problems.extend(tab.take_errors());
    }
    let result = if problems.is_empty() {
        "ok".to_owned()
    } else {
        format!("**failed**: {}", problems.join("; "))
    };
    Ok(format!(
        "| two tabs over WebRTC, scripted input | {frames} | {} and {} | {result} |",
        rollbacks[0], rollbacks[1]
    ))
}
