//! The `passo` app as a library: what the demo and the command-line tools
//! share, and what the cross-crate tests check (drawing a world, finding
//! scenes, headless rendering).

#![warn(unreachable_pub)]

pub mod bench;
pub mod demo;
pub mod draw;
pub mod progress;
pub mod render_cmd;
// The accuracy report draws its plots with fonts from the system, which a
// browser does not have.
#[cfg(not(target_arch = "wasm32"))]
pub mod report;
pub mod scenes;
pub mod simulate;
pub mod snapshot;

/// A monotonic clock's reading: `std`'s, or in a browser (where `std`'s
/// panics) `performance.now()`'s.
#[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
pub(crate) use std::time::Instant;
#[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
pub(crate) use web_time::Instant;

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

/// Reads a level's PNG image (a tileset's): from the disk, or from the
/// files built into the program ([`passo_scene::embed_files`]: the web demo).
pub(crate) fn load_image(path: &std::path::Path) -> Result<passo_render::RgbaImage, String> {
    let bytes = passo_scene::read_at_most(path, passo_scene::MAX_FILE_BYTES)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    passo_render::RgbaImage::decode_png(&bytes, &path.display().to_string())
        .map_err(|e| e.to_string())
}
