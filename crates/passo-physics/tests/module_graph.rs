//! The files of `passo-physics` import one way only: each module uses only
//! modules declared above it in `lib.rs`, which lists them in the order
//! data flows through them. So no two files import each other, directly or
//! in a circle.
//!
//! The check reads the sources as text: every `crate::…` path outside
//! comments, string literals and code marked `#[cfg(test)]` (a test
//! module, or a single test-only item, field, statement or match arm) is an
//! import, and a name the
//! crate root re-exports (`crate::World`) counts as an import of the module
//! that defines it. Run it with
//! `cargo test -p passo-physics --test module_graph -- --nocapture` to see
//! the graph.

mod source_scan;

use source_scan::strip;
use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

/// The modules of `lib.rs` in declaration order, and the module each
/// re-exported name comes from.
fn crate_root(src: &Path) -> (Vec<String>, BTreeMap<String, String>) {
    let lib = fs::read_to_string(src.join("lib.rs")).unwrap();
    let code = strip(&lib);
    let mut order = Vec::new();
    let mut exports = BTreeMap::new();
    for line in code.lines() {
        let line = line.trim();
        if let Some(rest) = line
            .strip_prefix("pub mod ")
            .or_else(|| line.strip_prefix("mod "))
        {
            order.push(rest.trim_end_matches(';').to_string());
        }
    }
    // `pub use module::{A, B};` and `pub use module::A;`, possibly over
    // several lines.
    for statement in code.split(';') {
        let statement = statement.trim();
        let Some(path) = statement.strip_prefix("pub use ") else {
            continue;
        };
        let Some((module, names)) = path.split_once("::") else {
            continue;
        };
        let names = names.trim_matches(|c| c == '{' || c == '}');
        for name in names.split(',') {
            let name = name.trim();
            if !name.is_empty() {
                exports.insert(name.to_string(), module.to_string());
            }
        }
    }
    (order, exports)
}

/// The first segment of each path in a `use` tree or path that follows
/// `crate::`.
fn first_segments(tree: &str, out: &mut Vec<String>) {
    let tree = tree.trim_start();
    if let Some(inner) = tree.strip_prefix('{') {
        // Split the group at its top-level commas.
        let mut depth = 0;
        let mut start = 0;
        for (i, c) in inner.char_indices() {
            match c {
                '{' => depth += 1,
                '}' if depth == 0 => {
                    first_segments_of_item(&inner[start..i], out);
                    return;
                }
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    first_segments_of_item(&inner[start..i], out);
                    start = i + 1;
                }
                _ => {}
            }
        }
    } else {
        first_segments_of_item(tree, out);
    }
}

fn first_segments_of_item(item: &str, out: &mut Vec<String>) {
    let ident: String = item
        .trim_start()
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect();
    if !ident.is_empty() {
        out.push(ident);
    }
}

/// The modules a file imports, resolved through the root's re-exports.
fn imports(code: &str, modules: &[String], exports: &BTreeMap<String, String>) -> Vec<String> {
    let mut names = Vec::new();
    for (i, _) in code.match_indices("crate::") {
        first_segments(&code[i + "crate::".len()..], &mut names);
    }
    let mut found: Vec<String> = names
        .into_iter()
        .filter_map(|name| {
            if modules.contains(&name) {
                Some(name)
            } else {
                exports.get(&name).cloned()
            }
        })
        .collect();
    found.sort();
    found.dedup();
    found
}

#[test]
fn every_module_imports_only_modules_declared_above_it() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let (order, exports) = crate_root(&src);
    assert!(order.len() > 10, "lib.rs lists the modules: {order:?}");
    let mut on_disk: Vec<String> = fs::read_dir(&src)
        .unwrap()
        .filter_map(|e| {
            let name = e.unwrap().file_name().into_string().unwrap();
            name.strip_suffix(".rs")
                .filter(|m| *m != "lib")
                .map(str::to_string)
        })
        .collect();
    on_disk.sort();
    let mut declared = order.clone();
    declared.sort();
    assert_eq!(declared, on_disk, "every file is a module of lib.rs");

    let mut wrong = Vec::new();
    for (rank, module) in order.iter().enumerate() {
        let text = fs::read_to_string(src.join(format!("{module}.rs"))).unwrap();
        let deps = imports(&strip(&text), &order, &exports);
        println!("{module} <- {}", deps.join(", "));
        for dep in deps {
            let dep_rank = order.iter().position(|m| *m == dep).unwrap();
            if dep_rank >= rank && dep != *module {
                wrong.push(format!("{module} imports {dep}, declared below it"));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "imports against the flow:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn the_checker_sees_imports_through_groups_and_re_exports() {
    let modules: Vec<String> = ["body", "world", "solver"].map(String::from).to_vec();
    let exports = BTreeMap::from([("World".to_string(), "world".to_string())]);
    let code =
        "use crate::{World, solver::{self, SolverBodies}};\nlet x = crate::body::Body::new();";
    assert_eq!(
        imports(&strip(code), &modules, &exports),
        ["body", "solver", "world"]
    );
    // Comments and test modules do not count.
    let code = "// crate::world\nfn f() {}\n#[cfg(test)]\nmod tests { use crate::World; }";
    assert!(imports(&strip(code), &modules, &exports).is_empty());
}

#[test]
fn the_checker_skips_only_the_code_marked_for_tests() {
    let modules: Vec<String> = ["body", "world", "solver", "step", "shape"]
        .map(String::from)
        .to_vec();
    let exports = BTreeMap::new();
    let code = r#"
struct S {
    #[cfg(test)]
    seen: crate::world::Seen,
    kept: crate::body::Body,
}
impl S {
    /// A helper for tests.
    #[cfg(test)]
    #[allow(dead_code)]
    pub(crate) fn for_tests() -> Self { crate::world::make() }
    fn run(&self, p: Pass) {
        match p {
            #[cfg(test)]
            Pass::Measure => {}
            #[cfg(test)]
            Pass::Other => crate::world::other(),
            Pass::Solve => crate::solver::solve(),
        }
        #[cfg(test)]
        let n = if a { crate::world::a() } else { crate::world::b() };
        #[cfg(test)]
        {
            crate::world::count();
        }
        let s = "crate::world }";
        let c = '{';
        crate::shape::f(s, c);
    }
}
#[cfg(test)]
mod tests;
fn after() { crate::step::run() }
"#;
    let stripped = strip(code);
    assert_eq!(
        imports(&stripped, &modules, &exports),
        ["body", "shape", "solver", "step"],
        "{stripped}"
    );
    assert_eq!(stripped.lines().count(), code.lines().count());
}
