//! The tables of BENCHMARKS.md that the code decides to the bit: what the
//! solver does on the hard cases, the deepest overlaps of the collision
//! scenes, and the state of every shipped scene. None of them holds a
//! timing, so they do not vary from run to run or machine to machine.
//!
//! `cargo run --release -p passo-benches --bin tables` prints them, and
//! `-- --write` puts them into BENCHMARKS.md, between the markers
//! `<!-- table: NAME -->` and `<!-- /table -->`. A test of this crate
//! fails when a committed table no longer matches what the code gives.

use crate::stability::{Passo, cases, run};
use crate::{exact_max_overlap, pyramid_world, rain_world};
use passo_physics::World;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The command that rewrites the tables, as the documents and errors give
/// it.
pub const WRITE_COMMAND: &str = "cargo run --release -p passo-benches --bin tables -- --write";

/// One generated table: its marker name and its Markdown.
pub struct Table {
    /// The name in its markers, `<!-- table: NAME -->`.
    pub name: &'static str,
    /// The table, one line per row, with a trailing newline.
    pub markdown: String,
}

/// Every generated table, in the order BENCHMARKS.md shows them.
pub fn all() -> Vec<Table> {
    vec![
        Table {
            name: "stability",
            markdown: stability(),
        },
        Table {
            name: "collision_scenes",
            markdown: collision_scenes(),
        },
        Table {
            name: "shipped_scenes",
            markdown: shipped_scenes(),
        },
    ]
}

/// Passo on every hard case of [`crate::stability`], with the default
/// settings and sleeping off: the columns of the comparison with Box2D
/// but the timing.
pub fn stability() -> String {
    let mut out = String::from(
        "| case | rest (s) | rest overlap (mm) | peak overlap (mm) | energy gain (%) | returned (%) | escaped |\n\
         |---|---:|---:|---:|---:|---:|---:|\n",
    );
    for case in cases() {
        let o = run(&case, &mut Passo(case.world.clone()));
        let rest = o
            .rest
            .map_or(format!("> {:.0}", case.seconds), |t| format!("{t:.2}"));
        let returned = o
            .returned
            .map_or(String::new(), |r| format!("{:.1}", r * 100.0));
        writeln!(
            out,
            "| `{}` | {rest} | {:.1} | {:.1} | {:.2} | {returned} | {} |",
            case.name,
            o.rest_overlap * 1000.0,
            o.peak_overlap * 1000.0,
            o.energy_gain * 100.0,
            o.escaped,
        )
        .expect("writing to a string");
    }
    out
}

/// Ticks the collision scenes run, and how often their overlap is sampled.
const SCENE_TICKS: u32 = 300;
const SAMPLE_EVERY: u32 = 30;

/// The rains and pyramids of `passo bench physics`, as a game runs them
/// (sleeping on), 300 ticks at 60 Hz: the deepest overlap from exact
/// geometry at the end and at its worst of the samples every 30 ticks,
/// the bodies asleep at the end, and the state hash.
pub fn collision_scenes() -> String {
    let mut out = String::from(
        "| scene | bodies | overlap at the end (mm) | worst sampled (mm) | asleep at the end | state hash |\n\
         |---|---:|---:|---:|---:|---|\n",
    );
    let scenes: [(&str, World); 4] = [
        ("rain of 1 000", rain_world(1_000)),
        ("rain of 10 000", rain_world(10_000)),
        ("pyramid of base 20", pyramid_world(20)),
        ("pyramid of base 50", pyramid_world(50)),
    ];
    for (name, mut world) in scenes {
        let mut worst = 0.0f32;
        for tick in 1..=SCENE_TICKS {
            world.step(1.0 / 60.0);
            if tick % SAMPLE_EVERY == 0 {
                worst = worst.max(exact_max_overlap(&world));
            }
        }
        let dynamic = world
            .bodies()
            .filter(|b| b.kind == passo_physics::BodyKind::Dynamic)
            .count();
        writeln!(
            out,
            "| {name} | {dynamic} | {:.2} | {:.2} | {} | `{:016x}` |",
            exact_max_overlap(&world) * 1000.0,
            worst * 1000.0,
            world.sleeping_len(),
            world.state_hash(),
        )
        .expect("writing to a string");
    }
    out
}

/// Every scene of `assets/scenes/` after 300 ticks at its own rate, as
/// `passo simulate SCENE --ticks 300 --hash` runs it: its bodies, the
/// deepest overlap and the state hash.
pub fn shipped_scenes() -> String {
    let mut out = String::from(
        "| scene | bodies | deepest overlap (mm) | state hash |\n|---|---:|---:|---|\n",
    );
    for path in crate::scene_files(Path::new(crate::SCENES_DIR)) {
        let scene = passo_scene::Scene::load(&path).expect("a shipped scene loads");
        let mut built = scene.build().expect("a shipped scene builds");
        let dt = (1.0 / scene.file.rate_hz) as f32;
        for _ in 0..300 {
            built.step(dt);
        }
        let name = path.file_stem().expect("a file name").to_string_lossy();
        writeln!(
            out,
            "| `{name}` | {} | {:.2} | `{:016x}` |",
            built.world.len(),
            exact_max_overlap(&built.world) * 1000.0,
            built.world.state_hash(),
        )
        .expect("writing to a string");
    }
    out
}

/// The markers around a generated table.
fn markers(name: &str) -> (String, &'static str) {
    (format!("<!-- table: {name} -->\n"), "<!-- /table -->")
}

/// The table `name` as `doc` holds it, between its markers.
pub fn committed<'a>(doc: &'a str, name: &str) -> Result<&'a str, String> {
    let (open, close) = markers(name);
    let start = doc
        .find(&open)
        .ok_or_else(|| format!("no `{}` marker", open.trim_end()))?
        + open.len();
    let len = doc[start..]
        .find(close)
        .ok_or_else(|| format!("the table `{name}` has no closing `{close}`"))?;
    Ok(&doc[start..start + len])
}

/// `doc` with the table `name` replaced by `markdown`.
pub fn replace(doc: &str, name: &str, markdown: &str) -> Result<String, String> {
    let old = committed(doc, name)?;
    let start = old.as_ptr() as usize - doc.as_ptr() as usize;
    Ok(format!(
        "{}{markdown}{}",
        &doc[..start],
        &doc[start + old.len()..]
    ))
}

/// Whether the command line asks to write the tables (`--write`, the
/// only argument such a command takes); exits with a message otherwise.
pub fn write_flag() -> bool {
    match std::env::args().nth(1).as_deref() {
        None => false,
        Some("--write") => true,
        Some(other) => {
            eprintln!("unknown argument `{other}`; the only one is --write");
            std::process::exit(2);
        }
    }
}

/// The path of BENCHMARKS.md.
pub fn benchmarks_md() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../BENCHMARKS.md")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replace_swaps_only_the_named_table() {
        let doc = "a\n<!-- table: x -->\n| old |\n<!-- /table -->\nb\n<!-- table: y -->\n| y |\n<!-- /table -->\n";
        let new = replace(doc, "x", "| new |\n").unwrap();
        assert_eq!(
            new,
            "a\n<!-- table: x -->\n| new |\n<!-- /table -->\nb\n<!-- table: y -->\n| y |\n<!-- /table -->\n"
        );
        assert_eq!(committed(&new, "y").unwrap(), "| y |\n");
        assert!(replace(doc, "z", "").is_err());
        assert!(committed("<!-- table: x -->\nno end", "x").is_err());
    }

    /// The committed tables are what the code gives: a change that moves
    /// a figure must rewrite them ([`WRITE_COMMAND`]) in the same commit.
    #[test]
    fn the_generated_tables_in_benchmarks_md_match_the_code() {
        let doc = std::fs::read_to_string(benchmarks_md()).expect("BENCHMARKS.md");
        let mut stale = Vec::new();
        for table in all() {
            let committed = committed(&doc, table.name).unwrap_or_else(|e| panic!("{e}"));
            if committed != table.markdown {
                stale.push(format!(
                    "table `{}` in BENCHMARKS.md is\n{committed}\nbut the code gives\n{}",
                    table.name, table.markdown
                ));
            }
        }
        assert!(
            stale.is_empty(),
            "{}\nrun `{WRITE_COMMAND}` and commit the result",
            stale.join("\n")
        );
    }
}
