//! Replays in RON: parsed and checked as `passo replay` does, then, when
//! short enough to play within the time-out, played headless.
#![no_main]

use libfuzzer_sys::fuzz_target;
use passo::demo::{Command, Replay, run_replay};

/// Ticks played at most: longer replays are only parsed and checked, so a
/// run stays well inside the fuzzer's time-out.
const MAX_TICKS_PLAYED: u64 = 120;
/// Rain counts played at most, for the same reason.
const MAX_RAIN_PLAYED: u32 = 2_000;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    // `from_ron` checks the replay as `passo replay` does.
    let Ok(replay) = Replay::from_ron(text) else {
        return;
    };
    // Scenes by name only: a path would let the fuzzer read any file.
    let by_name = replay
        .scene
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || c == '_');
    let short = replay.ticks <= MAX_TICKS_PLAYED
        && replay.commands.len() <= 256
        && replay.commands.iter().all(|(_, command)| match command {
            Command::RainCount(n) => *n <= MAX_RAIN_PLAYED,
            _ => true,
        });
    if by_name && short {
        let _ = run_replay(&replay);
    }
});
