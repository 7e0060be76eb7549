//! A progress bar for long runs, drawn on standard error when it is a
//! terminal (and never otherwise, so logs and pipes stay clean).

use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

/// Draws `label [#####-----] 45% (450/1000)` at most ten times a second.
pub struct Progress {
    label: String,
    total: u64,
    enabled: bool,
    last: Option<Instant>,
}

impl Progress {
    /// A bar for `total` units of work; silent unless stderr is a terminal.
    pub fn new(label: &str, total: u64) -> Self {
        Self {
            label: label.to_owned(),
            total,
            enabled: std::io::stderr().is_terminal() && total > 0,
            last: None,
        }
    }

    /// Reports that `done` units are finished.
    pub fn set(&mut self, done: u64) {
        if !self.enabled {
            return;
        }
        let now = Instant::now();
        if self
            .last
            .is_some_and(|t| now - t < Duration::from_millis(100))
            && done < self.total
        {
            return;
        }
        self.last = Some(now);
        let fraction = done as f64 / self.total as f64;
        let filled = (fraction * 30.0) as usize;
        let bar: String = "#".repeat(filled) + &"-".repeat(30 - filled);
        let mut err = std::io::stderr();
        let _ = write!(
            err,
            "\r{} [{bar}] {:3.0}% ({done}/{})",
            self.label,
            fraction * 100.0,
            self.total
        );
        let _ = err.flush();
    }

    /// Clears the bar.
    pub fn finish(&mut self) {
        if self.enabled && self.last.is_some() {
            let _ = write!(
                std::io::stderr(),
                "\r{}\r",
                " ".repeat(self.label.len() + 60)
            );
        }
    }
}
