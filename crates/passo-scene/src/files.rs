//! Where the loaders read files: the disk, or files built into the program.
//! A browser has no disk, so the web demo hands its levels and their images
//! to [`embed_files`] once, and every later read (scenes, Tiled maps,
//! tilesets, images) finds them there, by path.

use std::path::{Component, Path, PathBuf};
use std::sync::OnceLock;

/// The files built into the program, by path made absolute and plain (see
/// [`plain`]), sorted; `None` until [`embed_files`] is called.
static EMBEDDED: OnceLock<Vec<(PathBuf, &'static [u8])>> = OnceLock::new();

/// Reads every file from `files` instead of the disk from now on, for the
/// whole program: for a platform without files (a browser). Paths are
/// compared once made plain (`a/../b` is `b`), so a map's relative
/// `../levels/first.tmx` finds the file embedded as
/// `/assets/levels/first.tmx`. A relative path is taken from `/`. Returns
/// `false`, and changes nothing, if files were embedded before.
///
/// ```
/// use passo_scene::{embed_files, read_at_most};
/// use std::path::Path;
///
/// static LEVEL: &[u8] = b"--------";
/// assert!(embed_files(&[("/game/levels/one.txt", LEVEL)]));
/// let read = read_at_most(Path::new("/game/scenes/../levels/one.txt"), 100);
/// assert_eq!(read.unwrap(), LEVEL);
/// assert!(read_at_most(Path::new("/etc/passwd"), 100).is_err(), "only what was embedded");
/// ```
pub fn embed_files(files: &[(&str, &'static [u8])]) -> bool {
    let mut list: Vec<(PathBuf, &'static [u8])> = files
        .iter()
        .map(|(path, bytes)| (plain(Path::new(path)), *bytes))
        .collect();
    list.sort_by(|a, b| a.0.cmp(&b.0));
    EMBEDDED.set(list).is_ok()
}

/// `path` absolute (from `/`) with its `.` and `..` taken out, by its
/// words alone (links are not followed: embedded files have none).
fn plain(path: &Path) -> PathBuf {
    let mut out = PathBuf::from("/");
    for part in path.components() {
        match part {
            Component::ParentDir => {
                out.pop();
            }
            Component::Normal(name) => out.push(name),
            Component::Prefix(_) | Component::RootDir | Component::CurDir => {}
        }
    }
    out
}

fn not_found(path: &Path) -> std::io::Error {
    std::io::Error::new(
        std::io::ErrorKind::NotFound,
        format!("{} is not among the program's files", path.display()),
    )
}

/// Whether `path` is a regular file (not a folder, a device or a pipe).
pub(crate) fn is_file(path: &Path) -> std::io::Result<bool> {
    match EMBEDDED.get() {
        Some(files) => {
            let path = plain(path);
            Ok(files.binary_search_by(|f| f.0.cmp(&path)).is_ok())
        }
        None => Ok(std::fs::metadata(path)?.is_file()),
    }
}

/// `path` absolute, with its links resolved; an error if nothing is there.
pub(crate) fn real_path(path: &Path) -> std::io::Result<PathBuf> {
    match EMBEDDED.get() {
        Some(files) => {
            let path = plain(path);
            // A file, or a folder holding one.
            if files.iter().any(|f| f.0.starts_with(&path)) {
                Ok(path)
            } else {
                Err(not_found(&path))
            }
        }
        None => path.canonicalize(),
    }
}

/// A reader of the file at `path`.
pub(crate) fn open(path: &Path) -> std::io::Result<Box<dyn std::io::Read>> {
    match EMBEDDED.get() {
        Some(files) => {
            let path = plain(path);
            let i = files
                .binary_search_by(|f| f.0.cmp(&path))
                .map_err(|_| not_found(&path))?;
            Ok(Box::new(files[i].1))
        }
        None => Ok(Box::new(std::fs::File::open(path)?)),
    }
}

#[cfg(test)]
mod tests {
    use super::plain;
    use std::path::Path;

    #[test]
    fn a_path_is_made_plain_by_its_words() {
        for (path, want) in [
            ("/a/b/../c", "/a/c"),
            ("a/./b", "/a/b"),
            ("/a/scenes/../levels/x.tmx", "/a/levels/x.tmx"),
            ("/../..", "/"),
            ("/a/b/", "/a/b"),
        ] {
            assert_eq!(plain(Path::new(path)), Path::new(want), "{path}");
        }
    }
}
