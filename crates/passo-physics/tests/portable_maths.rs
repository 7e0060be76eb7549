//! The step gives the same bits on every platform: nothing in
//! `passo-physics` calls the standard library's transcendental functions
//! (`exp`, `sin`, `cos`, `powf`, ...), which call the platform's C library
//! and differ between glibc, macOS, MSVC and wasm in the last bits. They
//! come from the pure-Rust `libm` crate instead. Square roots, which IEEE
//! 754 rounds exactly everywhere, are allowed.
//!
//! The check reads the sources (outside comments and test modules) for a
//! call of a forbidden method.

use std::fs;
use std::path::Path;

const FORBIDDEN: [&str; 22] = [
    "exp", "exp2", "exp_m1", "ln", "log", "log2", "log10", "ln_1p", "powf", "powi", "sin", "cos",
    "tan", "asin", "acos", "atan", "atan2", "sin_cos", "sinh", "cosh", "tanh", "hypot",
];

/// The forbidden calls in a file's code (comments and tests left out).
fn forbidden_calls(text: &str) -> Vec<String> {
    let code = match text.find("#[cfg(test)]") {
        Some(i) => &text[..i],
        None => text,
    };
    let mut found = Vec::new();
    for (n, line) in code.lines().enumerate() {
        let line = line.split("//").next().unwrap_or("");
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
    for entry in fs::read_dir(&src).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "rs") {
            read += 1;
            for call in forbidden_calls(&fs::read_to_string(&path).unwrap()) {
                bad.push(format!("{}: {call}", path.display()));
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
