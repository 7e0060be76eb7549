//! No two files of a crate import each other, directly or in a circle: for
//! every crate of the workspace the graph of `crate::` and `super::` imports
//! between its files has no cycle. (`passo-physics` is held to more: at
//! every level of its folders a module imports only modules declared
//! above it, see its `tests/module_graph.rs`.)
//!
//! The check reads the sources as text: paths outside comments and outside
//! `#[cfg(test)]` modules count, and a name a crate root re-exports counts
//! as an import of the module that defines it. See the graph with
//! `cargo test -p passo-tests --test module_cycles -- --nocapture`.

// The walk over a crate's files, shared with passo-physics' own checks.
#[allow(dead_code)]
#[path = "../crates/passo-physics/tests/source_scan/mod.rs"]
mod source_scan;

use source_scan::rust_files;
use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// A module path inside a crate: `[]` is the root, `["demo", "sim"]`.
type Module = Vec<String>;

fn module_of(src: &Path, file: &Path) -> Module {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Module = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib")) {
        parts.pop();
    }
    parts
}

/// The code of a file without comments and without its test module.
fn strip(text: &str) -> String {
    let text = match text.find("#[cfg(test)]") {
        Some(i) => &text[..i],
        None => text,
    };
    text.lines()
        .map(|line| line.find("//").map_or(line, |i| &line[..i]))
        .collect::<Vec<_>>()
        .join("\n")
}

#[derive(Debug, PartialEq)]
enum Token {
    Ident(String),
    Colons,
    Open,
    Close,
    Comma,
}

/// The tokens of the `use` tree or path that starts `text`, up to the
/// first token that cannot be part of one.
fn tokens(text: &str) -> Vec<Token> {
    let mut out = Vec::new();
    let mut chars = text.char_indices().peekable();
    let mut depth = 0i32;
    while let Some(&(i, c)) = chars.peek() {
        match c {
            c if c.is_whitespace() => {
                chars.next();
            }
            ':' if text[i..].starts_with("::") => {
                chars.next();
                chars.next();
                out.push(Token::Colons);
            }
            '{' => {
                chars.next();
                depth += 1;
                out.push(Token::Open);
            }
            '}' if depth > 0 => {
                chars.next();
                depth -= 1;
                out.push(Token::Close);
            }
            ',' if depth > 0 => {
                chars.next();
                out.push(Token::Comma);
            }
            c if c.is_alphanumeric() || c == '_' => {
                let mut ident = String::new();
                while let Some(&(_, c)) = chars.peek() {
                    if c.is_alphanumeric() || c == '_' {
                        ident.push(c);
                        chars.next();
                    } else {
                        break;
                    }
                }
                // An identifier not after `::` or `{`/`,` ends a path.
                let joins = matches!(
                    out.last(),
                    None | Some(Token::Colons | Token::Open | Token::Comma)
                );
                if !joins {
                    break;
                }
                out.push(Token::Ident(ident));
                if depth == 0 && !text[i + out_len(&out)..].trim_start().starts_with("::") {
                    break;
                }
            }
            _ => break,
        }
        if depth == 0 && matches!(out.last(), Some(Token::Close)) {
            break;
        }
    }
    out
}

fn out_len(out: &[Token]) -> usize {
    match out.last() {
        Some(Token::Ident(s)) => s.len(),
        _ => 0,
    }
}

/// Every full path of a `use` tree, from its tokens.
fn paths(tokens: &[Token], prefix: &[String], out: &mut Vec<Module>) -> usize {
    let mut path = prefix.to_vec();
    let mut i = 0;
    while i < tokens.len() {
        match &tokens[i] {
            Token::Ident(s) => {
                path.push(s.clone());
                i += 1;
            }
            Token::Colons => i += 1,
            Token::Open => {
                i += 1;
                loop {
                    i += paths(&tokens[i..], &path, out);
                    match tokens.get(i) {
                        Some(Token::Comma) => i += 1,
                        Some(Token::Close) => return i + 1,
                        _ => return i,
                    }
                }
            }
            Token::Comma | Token::Close => break,
        }
    }
    out.push(path);
    i
}

/// The modules a file's code imports.
fn imports(
    code: &str,
    me: &Module,
    modules: &BTreeSet<Module>,
    exports: &BTreeMap<String, Module>,
) -> BTreeSet<Module> {
    let mut found = BTreeSet::new();
    for (anchor, base) in [("crate::", Vec::new()), ("super::", parent(me))] {
        for (i, _) in code.match_indices(anchor) {
            // `crate::` inside `$crate::` or a longer word is not ours.
            if code[..i].ends_with(|c: char| c.is_alphanumeric() || c == '_' || c == '$') {
                continue;
            }
            let mut all = Vec::new();
            paths(&tokens(&code[i + anchor.len()..]), &base, &mut all);
            for path in all {
                if let Some(m) = resolve(&path, modules, exports)
                    && m != *me
                {
                    found.insert(m);
                }
            }
        }
    }
    found
}

/// The module `super` names in a file of module `me`.
fn parent(me: &Module) -> Module {
    me[..me.len().saturating_sub(1)].to_vec()
}

/// The longest module prefix of a path, or the module a re-exported name
/// comes from.
fn resolve(
    path: &[String],
    modules: &BTreeSet<Module>,
    exports: &BTreeMap<String, Module>,
) -> Option<Module> {
    for n in (1..=path.len()).rev() {
        if modules.contains(&path[..n].to_vec()) {
            return Some(path[..n].to_vec());
        }
    }
    if path.len() == 1 {
        return exports.get(&path[0]).cloned();
    }
    match path.first() {
        Some(name) => exports.get(name).cloned(),
        None => None,
    }
}

/// Names the crate root re-exports, by the module they come from.
fn root_exports(root: &str, modules: &BTreeSet<Module>) -> BTreeMap<String, Module> {
    let code = strip(root);
    let mut exports = BTreeMap::new();
    for (i, _) in code.match_indices("pub use ") {
        let mut all = Vec::new();
        paths(&tokens(&code[i + "pub use ".len()..]), &[], &mut all);
        for path in all {
            if let (Some(name), Some(m)) = (path.last(), resolve(&path, modules, &BTreeMap::new()))
            {
                exports.insert(name.clone(), m);
            }
        }
    }
    exports
}

/// A cycle in the graph, if there is one.
fn find_cycle(graph: &BTreeMap<Module, BTreeSet<Module>>) -> Option<Vec<Module>> {
    fn visit(
        m: &Module,
        graph: &BTreeMap<Module, BTreeSet<Module>>,
        state: &mut BTreeMap<Module, u8>,
        stack: &mut Vec<Module>,
    ) -> Option<Vec<Module>> {
        match state.get(m) {
            Some(2) => return None,
            Some(1) => {
                let start = stack.iter().position(|s| s == m).unwrap();
                let mut cycle = stack[start..].to_vec();
                cycle.push(m.clone());
                return Some(cycle);
            }
            _ => {}
        }
        state.insert(m.clone(), 1);
        stack.push(m.clone());
        for next in graph.get(m).into_iter().flatten() {
            if let Some(c) = visit(next, graph, state, stack) {
                return Some(c);
            }
        }
        stack.pop();
        state.insert(m.clone(), 2);
        None
    }
    let mut state = BTreeMap::new();
    graph
        .keys()
        .find_map(|m| visit(m, graph, &mut state, &mut Vec::new()))
}

fn name(m: &Module) -> String {
    if m.is_empty() {
        "(root)".into()
    } else {
        m.join("::")
    }
}

/// The import graph of a crate's library (binaries' `main.rs` excluded:
/// nothing imports them).
fn crate_graph(src: &Path) -> BTreeMap<Module, BTreeSet<Module>> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    files.retain(|f| f.file_name().is_none_or(|n| n != "main.rs"));
    let modules: BTreeSet<Module> = files.iter().map(|f| module_of(src, f)).collect();
    let root = fs::read_to_string(src.join("lib.rs")).unwrap_or_default();
    let exports = root_exports(&root, &modules);
    let mut graph = BTreeMap::new();
    for file in &files {
        let me = module_of(src, file);
        let code = strip(&fs::read_to_string(file).unwrap());
        let mut deps = imports(&code, &me, &modules, &exports);
        // The root declares every module and re-exports from them; that is
        // the index of the crate, not an import.
        if me.is_empty() {
            deps.clear();
        }
        graph.insert(me, deps);
    }
    graph
}

#[test]
fn no_crate_has_files_that_import_each_other() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../crates");
    let mut crates: Vec<PathBuf> = fs::read_dir(&root)
        .unwrap()
        .map(|e| e.unwrap().path().join("src"))
        .filter(|p| p.is_dir())
        .collect();
    crates.sort();
    assert!(crates.len() >= 5, "found the crates: {crates:?}");
    let mut cycles = Vec::new();
    for src in &crates {
        let graph = crate_graph(src);
        println!(
            "{}",
            src.parent().unwrap().file_name().unwrap().to_string_lossy()
        );
        for (m, deps) in &graph {
            let deps: Vec<String> = deps.iter().map(name).collect();
            println!("  {} <- {}", name(m), deps.join(", "));
        }
        if let Some(cycle) = find_cycle(&graph) {
            let names: Vec<String> = cycle.iter().map(name).collect();
            cycles.push(format!("{}: {}", src.display(), names.join(" -> ")));
        }
    }
    assert!(cycles.is_empty(), "import cycles:\n{}", cycles.join("\n"));
}

#[test]
fn the_checker_finds_a_cycle_through_groups_super_and_re_exports() {
    let m = |s: &str| -> Module {
        if s.is_empty() {
            Vec::new()
        } else {
            s.split("::").map(String::from).collect()
        }
    };
    let modules: BTreeSet<Module> = ["", "world", "demo", "demo::sim", "demo::replay"]
        .map(m)
        .into();
    let exports = BTreeMap::from([("World".to_string(), m("world"))]);
    let sim = "use super::replay::{Command, Replay};\nuse crate::{World, demo::{self}};";
    let found = imports(&strip(sim), &m("demo::sim"), &modules, &exports);
    assert_eq!(found, [m("demo"), m("demo::replay"), m("world")].into());
    let replay = "fn f() { let s = super::sim::Sim::new(); } // crate::world";
    let found = imports(&strip(replay), &m("demo::replay"), &modules, &exports);
    assert_eq!(found, [m("demo::sim")].into());
    let graph = BTreeMap::from([
        (m("demo::sim"), [m("demo::replay")].into()),
        (m("demo::replay"), [m("demo::sim")].into()),
    ]);
    assert!(find_cycle(&graph).is_some());
    let graph = BTreeMap::from([(m("demo::sim"), [m("demo::replay")].into())]);
    assert!(find_cycle(&graph).is_none());
}
