#!/usr/bin/env bash
# Compares the step costs of two commits in the same conditions: builds the
# probe `benches/steps.rs` (of the working tree) against each commit's
# passo-physics and passo-benches, then runs the two binaries interleaved,
# ROUNDS times each. Across runs this machine varies by 20-30 %, so compare
# within one run of this script only.
#
#   bash benches/compare.sh OLD_COMMIT [NEW_COMMIT (default: the working tree)] [ROUNDS]
#
# WHAT picks the probes (default: integration rain pyramid sleep settle rays).
# The probe uses `passo_benches::busy_world`: OLD_COMMIT must have it
# (2026-12-02 on); for an older one, build an older `benches/steps.rs`.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
old="${1:?usage: compare.sh OLD_COMMIT [NEW_COMMIT] [ROUNDS]}"
new="${2:-}"
rounds="${3:-3}"
work="$(mktemp -d)"
trap 'git -C "$root" worktree remove --force "$work/old-tree" 2>/dev/null || true;
      git -C "$root" worktree remove --force "$work/new-tree" 2>/dev/null || true; rm -rf "$work"' EXIT

git -C "$root" worktree add -q --detach "$work/old-tree" "$old"
if [ -n "$new" ]; then
    git -C "$root" worktree add -q --detach "$work/new-tree" "$new"
    new_root="$work/new-tree"
else
    new_root="$root"
fi

for side in old new; do
    tree="$([ "$side" = old ] && echo "$work/old-tree" || echo "$new_root")"
    mkdir -p "$work/$side/src"
    cp "$root/benches/steps.rs" "$work/$side/src/main.rs"
    cat > "$work/$side/Cargo.toml" <<TOML
[package]
name = "steps-$side"
version = "0.0.0"
edition = "2024"
publish = false
[dependencies]
passo-physics = { path = "$tree/crates/passo-physics", features = ["parallel"] }
passo-benches = { path = "$tree/benches" }
# The probe asks cfg!(feature = "parallel"): passo-physics has it here.
[features]
default = ["parallel"]
parallel = []
[profile.release]
debug = "line-tables-only"
[workspace]
TOML
    CARGO_TARGET_DIR="$work/target-$side" cargo build --release --quiet --manifest-path "$work/$side/Cargo.toml"
done

for round in $(seq "$rounds"); do
    for side in old new; do
        for what in ${WHAT:-integration rain pyramid sleep settle rays}; do
            "$work/target-$side/release/steps-$side" "$what" | sed "s/^/$side round $round: /"
        done
    done
done
