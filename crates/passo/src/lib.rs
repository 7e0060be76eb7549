//! The `passo` app as a library: what the demo and the command-line tools
//! share, and what the cross-crate tests check (drawing a world, finding
//! scenes, headless rendering).

#![warn(unreachable_pub)]

pub mod bench;
pub mod demo;
pub mod draw;
pub mod progress;
pub mod render_cmd;
pub mod report;
pub mod scenes;
pub mod simulate;
pub mod snapshot;

/// A command-line count in `[min, max]`: clap refuses anything else with a
/// message naming the range, so no argument can ask for an empty run or
/// for more memory than the machine has.
pub(crate) fn count_in(min: u64, max: u64) -> impl clap::builder::TypedValueParser<Value = usize> {
    use clap::builder::TypedValueParser;
    clap::builder::RangedU64ValueParser::<u64>::new()
        .range(min..=max)
        .map(|n| usize::try_from(n).unwrap_or(usize::MAX))
}

/// Reads `path` whole if it is at most `limit` bytes long (a `what` file:
/// "replay", "snapshot"), reading no more than that: a device or a pipe
/// that never ends is an error, not all the memory there is.
pub(crate) fn read_file_at_most(
    path: &std::path::Path,
    limit: u64,
    what: &str,
) -> anyhow::Result<Vec<u8>> {
    passo_scene::read_at_most(path, limit).map_err(|e| {
        if e.kind() == std::io::ErrorKind::InvalidData {
            anyhow::anyhow!(
                "{} is larger than a {what} file may be ({} MiB)",
                path.display(),
                limit >> 20
            )
        } else {
            anyhow::Error::new(e).context(format!("reading {}", path.display()))
        }
    })
}
