//! The files of `passo-physics` import one way only. The crate is a tree
//! of folders that are layers: at every level (the crate root, then each
//! folder's `mod.rs`), a module imports only the modules declared above it
//! at that level. So a folder imports only the root's modules and the
//! folders above it, and inside a folder each file imports only the files
//! above it. A folder's `mod.rs` may use its own files, and its files may
//! use what the `mod.rs` itself defines.
//!
//! The check reads the sources as text: every `crate::…` path outside
//! comments, string literals and code marked `#[cfg(test)]` (a test
//! module, or a single test-only item, field, statement or match arm) is an
//! import, and a name the crate root re-exports (`crate::World`) counts as
//! an import of the module that defines it. Run it with
//! `cargo test -p passo-physics --test module_graph -- --nocapture` to see
//! the graph.

mod source_scan;

use source_scan::{rust_files, strip};
use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};

/// A module path inside the crate: `[]` is the root, `["solver", "lanes"]`.
type Module = Vec<String>;

/// The modules a file declares (`mod x;`, `pub mod x;`, `pub(crate) mod
/// x;`), in order; test-only modules are left out by `strip`.
fn declared(code: &str) -> Vec<String> {
    code.lines()
        .filter_map(|line| {
            let line = line.trim();
            let rest = line
                .strip_prefix("pub(crate) mod ")
                .or_else(|| line.strip_prefix("pub mod "))
                .or_else(|| line.strip_prefix("mod "))?;
            rest.strip_suffix(';').map(str::to_string)
        })
        .collect()
}

/// The crate's module tree: each module with the file that holds it and
/// the modules it declares, in order.
struct Tree {
    files: BTreeMap<Module, PathBuf>,
    children: BTreeMap<Module, Vec<String>>,
}

impl Tree {
    fn read(src: &Path) -> Self {
        let mut tree = Tree {
            files: BTreeMap::new(),
            children: BTreeMap::new(),
        };
        tree.add(Vec::new(), src.join("lib.rs"));
        tree
    }

    fn add(&mut self, module: Module, file: PathBuf) {
        let code = strip(&fs::read_to_string(&file).unwrap());
        let kids = declared(&code);
        // `a.rs` declares its modules in `a/`, `a/mod.rs` and `lib.rs` beside them.
        let dir = if matches!(
            file.file_name().and_then(|n| n.to_str()),
            Some("mod.rs" | "lib.rs")
        ) {
            file.parent().unwrap().to_path_buf()
        } else {
            file.with_extension("")
        };
        for kid in &kids {
            let flat = dir.join(format!("{kid}.rs"));
            let folder = dir.join(kid).join("mod.rs");
            let path = if flat.exists() { flat } else { folder };
            assert!(path.exists(), "{} declares `{kid}`", file.display());
            let mut m = module.clone();
            m.push(kid.clone());
            self.add(m, path);
        }
        self.children.insert(module.clone(), kids);
        self.files.insert(module, file);
    }

    /// The longest prefix of `path` that is a module.
    fn module_of(&self, path: &[String]) -> Module {
        let mut m: Module = Vec::new();
        for segment in path {
            let mut next = m.clone();
            next.push(segment.clone());
            if !self.files.contains_key(&next) {
                break;
            }
            m = next;
        }
        m
    }
}

/// The names `lib.rs` re-exports, each with the path it comes from.
fn exports(lib: &str) -> BTreeMap<String, Vec<String>> {
    let mut out = BTreeMap::new();
    for statement in strip(lib).split(';') {
        // Attributes before the `pub use` (`#[doc(hidden)]`) are skipped.
        let mut statement = statement.trim();
        while let Some(rest) = statement.strip_prefix("#[") {
            statement = rest
                .split_once(']')
                .map_or("", |(_, after)| after.trim_start());
        }
        let Some(path) = statement.strip_prefix("pub use ") else {
            continue;
        };
        let mut paths = Vec::new();
        full_paths(path, &mut Vec::new(), &mut paths);
        for p in paths {
            if let Some(name) = p.last() {
                out.insert(name.clone(), p.clone());
            }
        }
    }
    out
}

/// Every full path of a `use` tree or path (`a::{b::C, d}` gives `a::b::C`
/// and `a::d`), the segments read as identifiers.
fn full_paths(tree: &str, prefix: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    let tree = tree.trim_start();
    if let Some(inner) = tree.strip_prefix('{') {
        let mut depth = 0;
        let mut start = 0;
        for (i, c) in inner.char_indices() {
            match c {
                '{' => depth += 1,
                '}' if depth == 0 => {
                    full_paths(&inner[start..i], prefix, out);
                    return;
                }
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    full_paths(&inner[start..i], prefix, out);
                    start = i + 1;
                }
                _ => {}
            }
        }
        return;
    }
    let ident: String = tree
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect();
    if ident.is_empty() || ident == "self" {
        if !prefix.is_empty() {
            out.push(prefix.clone());
        }
        return;
    }
    prefix.push(ident.clone());
    let rest = tree[ident.len()..].trim_start();
    if let Some(rest) = rest.strip_prefix("::") {
        full_paths(rest, prefix, out);
    } else {
        out.push(prefix.clone());
    }
    prefix.pop();
}

/// The modules a file's code imports, resolved through the root's
/// re-exports.
fn imports(code: &str, tree: &Tree, exports: &BTreeMap<String, Vec<String>>) -> Vec<Module> {
    let mut paths = Vec::new();
    for (i, _) in code.match_indices("crate::") {
        full_paths(&code[i + "crate::".len()..], &mut Vec::new(), &mut paths);
    }
    let mut found: Vec<Module> = paths
        .into_iter()
        .map(|p| match exports.get(&p[0]) {
            Some(full) if !tree.files.contains_key(&p[..1]) => full.clone(),
            _ => p,
        })
        .map(|p| tree.module_of(&p))
        .filter(|m| !m.is_empty())
        .collect();
    found.sort();
    found.dedup();
    found
}

/// Why `from` may not import `to`, if it may not: the two modules that are
/// siblings under their common parent, and `to`'s is declared below.
fn against_the_flow(tree: &Tree, from: &Module, to: &Module) -> Option<String> {
    let common = from.iter().zip(to).take_while(|(a, b)| a == b).count();
    if common == from.len() || common == to.len() {
        // A folder's `mod.rs` using its own files, or a file using what
        // its folder's `mod.rs` defines.
        return None;
    }
    let siblings = &tree.children[&from[..common].to_vec()];
    let rank = |name: &String| siblings.iter().position(|s| s == name).unwrap();
    let (a, b) = (&from[common], &to[common]);
    (rank(b) > rank(a)).then(|| {
        format!(
            "{} imports {}: `{b}` is declared below `{a}`",
            from.join("::"),
            to.join("::")
        )
    })
}

#[test]
fn every_module_imports_only_modules_declared_above_it() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let tree = Tree::read(&src);
    assert!(tree.files.len() > 40, "lib.rs lists the modules");
    // Every file but the test modules' is a module of the tree.
    let mut on_disk = Vec::new();
    rust_files(&src, &mut on_disk);
    let mut stray: Vec<_> = on_disk
        .iter()
        .filter(|p| p.file_name().unwrap() != "tests.rs")
        .filter(|p| !tree.files.values().any(|f| f == *p))
        .collect();
    stray.sort();
    assert!(stray.is_empty(), "files no module declares: {stray:?}");

    let exports = exports(&fs::read_to_string(src.join("lib.rs")).unwrap());
    let mut wrong = Vec::new();
    for (module, file) in &tree.files {
        let deps = imports(&strip(&fs::read_to_string(file).unwrap()), &tree, &exports);
        let names: Vec<String> = deps.iter().map(|d| d.join("::")).collect();
        println!("{} <- {}", module.join("::"), names.join(", "));
        wrong.extend(
            deps.iter()
                .filter_map(|d| against_the_flow(&tree, module, d)),
        );
    }
    assert!(
        wrong.is_empty(),
        "imports against the flow:\n{}",
        wrong.join("\n")
    );
}

/// A small tree: `body`, then `solver` with `scalar` and `lanes`, then `world`.
fn small_tree() -> Tree {
    let module = |p: &str| -> Module {
        p.split("::")
            .filter(|s| !s.is_empty())
            .map(String::from)
            .collect()
    };
    let mut tree = Tree {
        files: BTreeMap::new(),
        children: BTreeMap::new(),
    };
    for m in [
        "",
        "body",
        "solver",
        "solver::scalar",
        "solver::lanes",
        "world",
    ] {
        tree.files.insert(module(m), PathBuf::new());
    }
    tree.children
        .insert(module(""), module("body::solver::world"));
    tree.children
        .insert(module("solver"), module("scalar::lanes"));
    tree
}

#[test]
fn the_checker_sees_imports_through_groups_and_re_exports() {
    let tree = small_tree();
    let exports = BTreeMap::from([("World".to_string(), vec!["world".into(), "World".into()])]);
    let code =
        "use crate::{World, solver::{self, lanes::Wide}};\nlet x = crate::body::Body::new();";
    let found: Vec<String> = imports(&strip(code), &tree, &exports)
        .iter()
        .map(|m| m.join("::"))
        .collect();
    assert_eq!(found, ["body", "solver", "solver::lanes", "world"]);
    // Comments and test modules do not count.
    let code = "// crate::world\nfn f() {}\n#[cfg(test)]\nmod tests { use crate::World; }";
    assert!(imports(&strip(code), &tree, &exports).is_empty());
}

#[test]
fn the_checker_applies_the_rule_at_every_level() {
    let tree = small_tree();
    let m = |p: &str| -> Module { p.split("::").map(String::from).collect() };
    // Down the root's list, and down a folder's list: allowed.
    assert_eq!(
        against_the_flow(&tree, &m("world"), &m("solver::lanes")),
        None
    );
    assert_eq!(
        against_the_flow(&tree, &m("solver::lanes"), &m("solver::scalar")),
        None
    );
    assert_eq!(
        against_the_flow(&tree, &m("solver::lanes"), &m("body")),
        None
    );
    // A folder and its own files: allowed both ways.
    assert_eq!(
        against_the_flow(&tree, &m("solver"), &m("solver::lanes")),
        None
    );
    assert_eq!(
        against_the_flow(&tree, &m("solver::lanes"), &m("solver")),
        None
    );
    // Up a list, at either level: refused.
    assert!(against_the_flow(&tree, &m("body"), &m("solver::scalar")).is_some());
    assert!(against_the_flow(&tree, &m("solver::scalar"), &m("solver::lanes")).is_some());
    assert!(against_the_flow(&tree, &m("solver::scalar"), &m("world")).is_some());
}

#[test]
fn the_checker_skips_only_the_code_marked_for_tests() {
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
            Pass::Solve => crate::solver::scalar::solve(),
        }
        #[cfg(test)]
        let n = if a { crate::world::a() } else { crate::world::b() };
        #[cfg(test)]
        {
            crate::world::count();
        }
        let s = "crate::world }";
        let c = '{';
        crate::solver::lanes::f(s, c);
    }
}
#[cfg(test)]
mod tests;
fn after() { crate::body::run() }
"#;
    let stripped = strip(code);
    let found: Vec<String> = imports(&stripped, &small_tree(), &BTreeMap::new())
        .iter()
        .map(|m| m.join("::"))
        .collect();
    assert_eq!(
        found,
        ["body", "solver::lanes", "solver::scalar"],
        "{stripped}"
    );
    assert_eq!(stripped.lines().count(), code.lines().count());
}
