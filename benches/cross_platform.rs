//! Checks that every shipped scene hashes the same, tick by tick, on every
//! platform and lane width Passo compiles for. It builds `scene_hashes` for
//! each platform below, runs it (aarch64 under `qemu-aarch64`, wasm32 under
//! Node.js's WASI), and compares each table with the x86-64 build's (so it
//! runs on an x86-64 Linux machine).
//! A mismatch is reported scene by scene with the first tick that differs,
//! and the program exits with 1.
//!
//! `cargo run --release -p passo-benches --bin cross_platform [PLATFORM...]`
//!
//! Platforms: `x86-64` (SSE2; the reference),
//! `x86-64-avx2` (AVX2 and FMA, eight lanes; needs a CPU that has them),
//! `aarch64` (NEON), `wasm32` (scalar) and `wasm32-simd128`. With none named,
//! all of them. They need, on Debian: `apt-get install qemu-user
//! gcc-aarch64-linux-gnu libc6-dev-arm64-cross nodejs` and `rustup target add
//! aarch64-unknown-linux-gnu wasm32-wasip1`. Each platform builds in its own
//! folder under `target/cross-platform/`.

use passo_benches::hashes::{HashTable, differences, parse_table};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

/// One way to build and run `scene_hashes`.
struct Platform {
    name: &'static str,
    /// The instruction set the lanes compile to.
    lanes: &'static str,
    /// The Rust target (`None`: this machine's).
    target: Option<&'static str>,
    rustflags: &'static str,
    /// Why this machine cannot run it, if it cannot.
    unavailable: fn() -> Option<&'static str>,
}

const PLATFORMS: [Platform; 5] = [
    Platform {
        name: "x86-64",
        lanes: "SSE2",
        target: Some("x86_64-unknown-linux-gnu"),
        rustflags: "",
        unavailable: not_x86_64,
    },
    Platform {
        name: "x86-64-avx2",
        lanes: "AVX2 + FMA",
        target: Some("x86_64-unknown-linux-gnu"),
        rustflags: "-C target-feature=+avx2,+fma",
        unavailable: no_avx2,
    },
    Platform {
        name: "aarch64",
        lanes: "NEON",
        target: Some("aarch64-unknown-linux-gnu"),
        rustflags: "",
        unavailable: || None,
    },
    Platform {
        name: "wasm32",
        lanes: "scalar",
        target: Some("wasm32-wasip1"),
        rustflags: "",
        unavailable: || None,
    },
    Platform {
        name: "wasm32-simd128",
        lanes: "simd128",
        target: Some("wasm32-wasip1"),
        rustflags: "-C target-feature=+simd128",
        unavailable: || None,
    },
];

fn not_x86_64() -> Option<&'static str> {
    (!cfg!(target_arch = "x86_64")).then_some("this machine is not x86-64")
}

fn no_avx2() -> Option<&'static str> {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
        return None;
    }
    Some("this CPU has no AVX2 and FMA")
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Builds `scene_hashes` for `p` and returns the program's path.
fn build(p: &Platform) -> Result<PathBuf, String> {
    let target_dir = root().join("target/cross-platform").join(p.name);
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut cmd = Command::new(cargo);
    cmd.current_dir(root())
        .args(["build", "--quiet", "--release", "-p", "passo-benches"])
        .args(["--bin", "scene_hashes"])
        .env("CARGO_TARGET_DIR", &target_dir)
        .env("RUSTFLAGS", p.rustflags)
        .env(
            "CARGO_TARGET_AARCH64_UNKNOWN_LINUX_GNU_LINKER",
            "aarch64-linux-gnu-gcc",
        );
    let mut out = target_dir.clone();
    if let Some(target) = p.target {
        cmd.args(["--target", target]);
        out.push(target);
    }
    let exe = if p.name.starts_with("wasm32") {
        "scene_hashes.wasm"
    } else {
        "scene_hashes"
    };
    let status = cmd.status().map_err(|e| format!("cargo: {e}"))?;
    if !status.success() {
        return Err(format!(
            "the build failed (is the target installed? `rustup target add {}`)",
            p.target.unwrap_or("?")
        ));
    }
    Ok(out.join("release").join(exe))
}

/// Runs the program built for `p` with `args` and returns what it printed.
fn run(p: &Platform, program: &Path, args: &[&str]) -> Result<String, String> {
    let assets = root().join("assets");
    let (mut cmd, tool, package) = match p.target {
        Some("aarch64-unknown-linux-gnu") => {
            let mut cmd = Command::new("qemu-aarch64");
            cmd.args(["-L", "/usr/aarch64-linux-gnu"]).arg(program);
            cmd.args(
                args.iter()
                    .map(|a| a.replace("{scenes}", &scenes_dir(&assets))),
            );
            (cmd, "qemu-aarch64", "qemu-user gcc-aarch64-linux-gnu")
        }
        Some("wasm32-wasip1") => {
            let mut cmd = Command::new("node");
            cmd.arg("--no-warnings")
                .arg(root().join("benches/wasi_run.mjs"))
                .arg(program)
                .arg(&assets)
                .arg("/assets");
            cmd.args(args.iter().map(|a| a.replace("{scenes}", "/assets/scenes")));
            (cmd, "node", "nodejs")
        }
        _ => {
            let mut cmd = Command::new(program);
            cmd.args(
                args.iter()
                    .map(|a| a.replace("{scenes}", &scenes_dir(&assets))),
            );
            (cmd, "the program", "")
        }
    };
    let out = cmd
        .output()
        .map_err(|e| format!("cannot start {tool} ({e}); on Debian: apt-get install {package}"))?;
    if !out.status.success() {
        return Err(format!(
            "{tool} failed: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        ));
    }
    String::from_utf8(out.stdout).map_err(|e| e.to_string())
}

fn scenes_dir(assets: &Path) -> String {
    assets.join("scenes").display().to_string()
}

/// Builds and runs `p`: its lane count and its table.
fn table_of(p: &Platform) -> Result<(String, HashTable), String> {
    let program = build(p)?;
    let lanes = run(p, &program, &["--lanes"])?.trim().to_owned();
    let table = parse_table(&run(p, &program, &["{scenes}"])?)?;
    Ok((lanes, table))
}

fn main() -> ExitCode {
    let wanted: Vec<String> = std::env::args().skip(1).collect();
    if let Some(bad) = wanted
        .iter()
        .find(|w| !PLATFORMS.iter().any(|p| p.name == w.as_str()))
    {
        let names: Vec<_> = PLATFORMS.iter().map(|p| p.name).collect();
        eprintln!(
            "unknown platform `{bad}`; the platforms: {}",
            names.join(", ")
        );
        return ExitCode::from(2);
    }
    let reference_platform = &PLATFORMS[0];
    if let Some(why) = (reference_platform.unavailable)() {
        eprintln!(
            "the reference ({}) cannot run: {why}",
            reference_platform.name
        );
        return ExitCode::FAILURE;
    }
    let reference = match table_of(reference_platform) {
        Ok((_, t)) => t,
        Err(e) => {
            eprintln!("{}: {e}", reference_platform.name);
            return ExitCode::FAILURE;
        }
    };
    let ticks = reference.values().map(Vec::len).max().unwrap_or(0);
    println!(
        "Every shipped scene ({}), hashed after each of {ticks} ticks, against {}:\n",
        reference.len(),
        reference_platform.name
    );
    println!("| platform | lanes | solver lanes | result |");
    println!("|---|---|---:|---|");
    let mut failed = false;
    let mut details = Vec::new();
    for p in &PLATFORMS {
        if !wanted.is_empty() && !wanted.iter().any(|w| w == p.name) {
            continue;
        }
        let (width, result) = if let Some(why) = (p.unavailable)() {
            ("–".to_owned(), format!("not run: {why}"))
        } else {
            match table_of(p) {
                Err(e) => {
                    failed = true;
                    ("–".to_owned(), format!("error: {e}"))
                }
                Ok((width, table)) => {
                    let report = differences(&reference, &table);
                    if report.is_empty() {
                        (width, "same bits".to_owned())
                    } else {
                        failed = true;
                        let result = format!("**differs** in {} scenes (below)", report.len());
                        details.extend(report.into_iter().map(|r| format!("{}: {r}", p.name)));
                        (width, result)
                    }
                }
            }
        };
        println!("| {} | {} | {width} | {result} |", p.name, p.lanes);
    }
    if !details.is_empty() {
        println!("\nWhere the bits differ, scene by scene:");
        for line in details {
            println!("- {line}");
        }
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
