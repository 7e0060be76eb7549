//! The state hash of every shipped scene at every tick, as `scene_hashes`
//! prints it, and the comparison of two such tables that names, scene by
//! scene, the first tick that differs. `tests/cross_profile.rs` compares
//! builds of one machine with it, and the `cross_platform` program compares
//! x86-64 with aarch64 and wasm32.

use passo_scene::Scene;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

/// How many ticks every scene is stepped.
pub const TICKS: u32 = 300;

/// Every scene's hash after each tick, in tick order, by scene name.
pub type HashTable = BTreeMap<String, Vec<u64>>;

/// Steps every scene file of `dir` [`TICKS`] ticks at its own rate and
/// writes one line per tick: `scene tick hash` (the tick counts from 1,
/// the hash is 16 hex digits).
pub fn write_table(dir: &Path, out: &mut impl std::io::Write) -> std::io::Result<()> {
    for path in crate::scene_files(dir) {
        let scene = Scene::load(&path).map_err(std::io::Error::other)?;
        let mut built = scene.build().map_err(std::io::Error::other)?;
        let dt = (1.0 / scene.file.rate_hz) as f32;
        let name = path
            .file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
        for tick in 1..=TICKS {
            built.step(dt);
            writeln!(out, "{name} {tick} {:016x}", built.world.state_hash())?;
        }
    }
    Ok(())
}

/// Reads what [`write_table`] wrote. A line that does not parse, or a tick
/// out of order, is an error naming the line.
pub fn parse_table(text: &str) -> Result<HashTable, String> {
    let mut table = HashTable::new();
    for (i, line) in text.lines().enumerate() {
        let bad = || format!("line {}: `{line}` is not `scene tick hash`", i + 1);
        let mut words = line.split_whitespace();
        let (Some(scene), Some(tick), Some(hash), None) =
            (words.next(), words.next(), words.next(), words.next())
        else {
            return Err(bad());
        };
        let tick: usize = tick.parse().map_err(|_| bad())?;
        let hash = u64::from_str_radix(hash, 16).map_err(|_| bad())?;
        let hashes = table.entry(scene.to_owned()).or_default();
        if tick != hashes.len() + 1 {
            return Err(format!(
                "line {}: {scene} tick {tick} follows tick {}",
                i + 1,
                hashes.len()
            ));
        }
        hashes.push(hash);
    }
    Ok(table)
}

/// How `other` differs from `reference`, one line per scene: a scene
/// missing from either, the first tick whose hash differs, or a run that
/// stops early. Empty when the tables agree.
pub fn differences(reference: &HashTable, other: &HashTable) -> Vec<String> {
    let mut out = Vec::new();
    for (scene, want) in reference {
        let Some(got) = other.get(scene) else {
            out.push(format!("{scene}: missing"));
            continue;
        };
        if let Some(i) = want.iter().zip(got).position(|(a, b)| a != b) {
            out.push(format!(
                "{scene}: first differs at tick {} ({:016x} here, {:016x} in the reference)",
                i + 1,
                got[i],
                want[i]
            ));
        } else if got.len() != want.len() {
            out.push(format!(
                "{scene}: {} ticks here, {} in the reference",
                got.len(),
                want.len()
            ));
        }
    }
    for scene in other.keys().filter(|s| !reference.contains_key(*s)) {
        out.push(format!("{scene}: not in the reference"));
    }
    out
}

/// The last hash of every scene, one `scene hash` line each: a table short
/// enough to read.
pub fn summary(table: &HashTable) -> String {
    let mut out = String::new();
    for (scene, hashes) in table {
        let last = hashes.last().copied().unwrap_or_default();
        let _ = writeln!(out, "{scene} {last:016x}");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(rows: &[(&str, &[u64])]) -> HashTable {
        rows.iter()
            .map(|(s, h)| ((*s).to_owned(), h.to_vec()))
            .collect()
    }

    #[test]
    fn a_table_reads_back_what_was_written() {
        let text = "a 1 00000000000000ff\na 2 0000000000000100\nb 1 0000000000000001\n";
        let t = parse_table(text).unwrap();
        assert_eq!(t, table(&[("a", &[255, 256]), ("b", &[1])]));
    }

    #[test]
    fn a_bad_line_or_a_skipped_tick_is_an_error_naming_the_line() {
        for (text, want) in [
            ("a 1\n", "line 1"),
            ("a 1 zz\n", "line 1"),
            ("a 1 01\na 1 02 x\n", "line 2"),
            ("a 1 01\na 3 02\n", "line 2: a tick 3 follows tick 1"),
        ] {
            let e = parse_table(text).unwrap_err();
            assert!(e.contains(want), "{text:?}: {e}");
        }
    }

    #[test]
    fn each_scene_reports_its_first_differing_tick() {
        let reference = table(&[("a", &[1, 2, 3, 4]), ("b", &[5, 6]), ("c", &[7])]);
        assert!(differences(&reference, &reference).is_empty());
        // Sweep where `a` first differs: the report names that tick.
        for first in 0..4 {
            let mut a = vec![1, 2, 3, 4];
            for h in &mut a[first..] {
                *h += 100;
            }
            let other = table(&[("a", &a), ("b", &[5, 6]), ("c", &[7])]);
            let d = differences(&reference, &other);
            assert_eq!(d.len(), 1, "{d:?}");
            assert!(
                d[0].starts_with(&format!("a: first differs at tick {}", first + 1)),
                "{d:?}"
            );
        }
        let other = table(&[("a", &[1, 2]), ("b", &[5, 9]), ("d", &[0])]);
        assert_eq!(
            differences(&reference, &other),
            [
                "a: 2 ticks here, 4 in the reference",
                "b: first differs at tick 2 (0000000000000009 here, 0000000000000006 in the reference)",
                "c: missing",
                "d: not in the reference",
            ]
        );
    }

    #[test]
    fn every_shipped_scene_is_in_the_table_at_every_tick() {
        // Two scenes for speed: the table's shape, not the physics.
        let dir = std::env::temp_dir().join(format!("passo-hashes-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for name in ["spring", "orbit"] {
            let from = Path::new(crate::SCENES_DIR).join(format!("{name}.ron"));
            std::fs::copy(from, dir.join(format!("{name}.ron"))).unwrap();
        }
        let mut out = Vec::new();
        write_table(&dir, &mut out).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        let t = parse_table(&String::from_utf8(out).unwrap()).unwrap();
        assert_eq!(t.keys().collect::<Vec<_>>(), ["orbit", "spring"]);
        for hashes in t.values() {
            assert_eq!(hashes.len(), TICKS as usize);
            // A moving scene changes its state every tick.
            assert!(hashes.windows(2).all(|w| w[0] != w[1]));
        }
    }
}
