//! The step gives the same bits on every platform: nothing in
//! `passo-physics` calls the standard library's transcendental functions
//! (`exp`, `sin`, `cos`, `powf`, ...), which call the platform's C library
//! and differ between glibc, macOS, MSVC and wasm in the last bits. They
//! come from the pure-Rust `libm` crate instead. Square roots, which IEEE
//! 754 rounds exactly everywhere, are allowed.
//!
//! The check reads the sources (outside comments, string literals and code
//! marked `#[cfg(test)]`: a test module, or a single test-only item, field,
//! statement or match arm) for a call of a forbidden method.

mod source_scan;

use source_scan::strip;
use std::fs;
use std::path::Path;

const FORBIDDEN: [&str; 22] = [
    "exp", "exp2", "exp_m1", "ln", "log", "log2", "log10", "ln_1p", "powf", "powi", "sin", "cos",
    "tan", "asin", "acos", "atan", "atan2", "sin_cos", "sinh", "cosh", "tanh", "hypot",
];

/// The forbidden calls in a file's code (comments, string literals and
/// code marked `#[cfg(test)]` left out).
fn forbidden_calls(text: &str) -> Vec<String> {
    let code = strip(text);
    let mut found = Vec::new();
    for (n, line) in code.lines().enumerate() {
        for name in FORBIDDEN {
            let calls = [
                format!(".{name}("),
                format!("f32::{name}("),
                format!("f64::{name}("),
            ];
            if calls.iter().any(|call| line.contains(call.as_str())) {
                found.push(format!("line {}: {}", n + 1, line.trim()));
            }
        }
        // glam's angle helpers call sin and cos.
        for helper in ["from_angle(", "to_angle(", "angle_to(", "rotate_towards("] {
            if line.contains(helper) {
                found.push(format!("line {}: {}", n + 1, line.trim()));
            }
        }
    }
    found
}

#[test]
fn no_platform_transcendental_function_is_called_in_the_physics() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut bad = Vec::new();
    let mut read = 0;
    let mut folders = vec![src];
    while let Some(folder) = folders.pop() {
        for entry in fs::read_dir(&folder).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") && !path.ends_with("tests.rs") {
                read += 1;
                for call in forbidden_calls(&fs::read_to_string(&path).unwrap()) {
                    bad.push(format!("{}: {call}", path.display()));
                }
            }
        }
    }
    assert!(read > 20, "read the sources");
    assert!(bad.is_empty(), "use libm instead:\n{}", bad.join("\n"));
}

#[test]
fn the_check_sees_a_call_and_skips_comments_and_tests() {
    assert_eq!(forbidden_calls("let a = x.exp();").len(), 1);
    assert_eq!(forbidden_calls("let a = f32::sin(x);").len(), 1);
    assert_eq!(forbidden_calls("let d = Vec2::from_angle(a);").len(), 1);
    assert_eq!(
        forbidden_calls("let a = (x * 2.0).cos() + y.sqrt();").len(),
        1
    );
    assert!(forbidden_calls("let a = libm::expf(x); // not x.exp()").is_empty());
    assert!(
        forbidden_calls("fn f() {}\n#[cfg(test)]\nmod tests { fn g() { 1f32.sin(); } }").is_empty()
    );
}

#[test]
fn the_check_sees_calls_after_single_test_only_items() {
    let code = r#"struct S {
    #[cfg(test)]
    seen: f32,
    kept: f32,
}
impl S {
    #[cfg(test)]
    fn for_tests() -> f32 { 1f32.sin() }
    fn run(&self, p: Pass) -> f32 {
        let a = match p {
            #[cfg(test)]
            Pass::Measure => {}
            #[cfg(test)]
            Pass::Other => 2f32.cos(),
            Pass::Solve => self.kept.exp(),
        };
        #[cfg(test)]
        let n = if a { a.ln() } else { a.log2() };
        let s = "x.tan() }";
        let c = '{';
        a.powf(2.0)
    }
}
#[cfg(test)]
mod tests;
fn after(x: f32) -> f32 { x.atan2(1.0) }
"#;
    let found = forbidden_calls(code);
    let lines: Vec<&str> = found.iter().map(|f| f.split(':').next().unwrap()).collect();
    assert_eq!(lines, ["line 15", "line 21", "line 26"], "{found:?}");
}
