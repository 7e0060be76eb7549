#!/usr/bin/env bash
# Runs every fuzz target for SECONDS seconds (default 60) with a 1 GiB
# memory limit, after seeding its corpus from the shipped files. Needs a
# nightly toolchain and cargo-fuzz (`cargo install cargo-fuzz`).
# Usage: bash fuzz/run.sh [SECONDS] [TARGET ...]
set -euo pipefail
cd "$(dirname "$0")"
seconds="${1:-60}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    targets=(scene snapshot_postcard snapshot_ron replay tmx tmj tsx ascii)
fi
cargo run --quiet --release --bin seed
for target in "${targets[@]}"; do
    echo "== $target, ${seconds} s"
    # Built first, so that a target that does not build fails the run
    # (set -e and pipefail); the run's own output is filtered below.
    cargo +nightly fuzz build "$target" 2>&1 | tail -n 1
    cargo +nightly fuzz run "$target" "corpus/$target" -- \
        -max_total_time="$seconds" -rss_limit_mb=1024 -timeout=10 -print_final_stats=1 2>&1 \
        | grep -E '^(stat::number_of_executed_units|stat::peak_rss_mb|==|SUMMARY|Done|.*ERROR)' || true
    # A crash leaves an artifact: fail on any.
    if compgen -G "artifacts/$target/*" > /dev/null; then
        echo "fuzz target $target found a crash: fuzz/artifacts/$target" >&2
        exit 1
    fi
done
