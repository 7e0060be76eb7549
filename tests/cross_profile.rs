//! The same scene gives the same bits however Passo is compiled: every
//! shipped scene is stepped 300 ticks, hashed at every tick, by a small program
//! (`benches/scene_hashes.rs`) built four ways — the test profile (physics
//! at opt-level 3), physics at opt-level 1, release, and release with
//! `-C target-cpu=native` (FMA and wide vectors where the machine has them)
//! — and the hashes must agree. Each build has its own target folder under
//! `target/cross-profile/`, so the first run compiles the small crates four
//! times (about two minutes on two cores) and later runs reuse them.

use std::path::PathBuf;
use std::process::Command;

use passo_benches::hashes::{HashTable, differences, parse_table};

fn hashes(name: &str, release: bool, env: &[(&str, &str)]) -> HashTable {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let target = root.join("target/cross-profile").join(name);
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut cmd = Command::new(cargo);
    cmd.current_dir(&root)
        .args([
            "run",
            "--quiet",
            "-p",
            "passo-benches",
            "--bin",
            "scene_hashes",
        ])
        .env("CARGO_TARGET_DIR", &target)
        .env_remove("RUSTFLAGS");
    if release {
        cmd.arg("--release");
    }
    for (k, v) in env {
        cmd.env(k, v);
    }
    let out = cmd.output().expect("cargo runs");
    assert!(
        out.status.success(),
        "{name}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    parse_table(&String::from_utf8(out.stdout).unwrap()).unwrap()
}

#[test]
fn every_shipped_scene_hashes_the_same_in_every_build() {
    let reference = hashes("dev", false, &[]);
    assert!(reference.len() >= 10, "every scene ran: {reference:?}");
    for (name, release, env) in [
        (
            "dev-physics-opt1",
            false,
            &[("CARGO_PROFILE_DEV_PACKAGE_PASSO_PHYSICS_OPT_LEVEL", "1")][..],
        ),
        ("release", true, &[][..]),
        (
            "release-native",
            true,
            &[("RUSTFLAGS", "-C target-cpu=native")][..],
        ),
    ] {
        let report = differences(&reference, &hashes(name, release, env));
        assert!(report.is_empty(), "{name}:\n{}", report.join("\n"));
    }
}
