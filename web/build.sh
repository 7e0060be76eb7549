#!/usr/bin/env bash
# Builds the web demo into a static folder (default target/web-demo/) that any
# static file server can serve: index.html, passo-web.js and
# passo-web_bg.wasm, and the two-tab netplay game (netplay.html,
# passo-netplay.js and passo-netplay_bg.wasm, which also needs a signalling
# server: web/netplay.sh). Needs the wasm32 target, wasm-bindgen-cli at the
# version of the wasm-bindgen crate in Cargo.lock, and binaryen's wasm-opt
# (optional: without it the .wasm is larger):
#   rustup target add wasm32-unknown-unknown
#   cargo install wasm-bindgen-cli --version 0.2.130
#   sudo apt-get install binaryen
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-target/web-demo}"

# wasm-bindgen's command must be the version of its crate in Cargo.lock.
want=$(grep -A1 '^name = "wasm-bindgen"$' Cargo.lock | sed -n 's/^version = "\(.*\)"/\1/p')
if ! command -v wasm-bindgen > /dev/null; then
    echo "wasm-bindgen not found: cargo install wasm-bindgen-cli --version $want" >&2
    exit 1
elif ! wasm-bindgen --version | grep -qF "$want"; then
    echo "$(wasm-bindgen --version) found, $want needed: cargo install wasm-bindgen-cli --version $want" >&2
    exit 1
fi

# wasm's 128-bit vectors (simd128, in every browser since 2023) for the
# solver's lanes: the same bits as without (the cross_platform program
# checks both).
export CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUSTFLAGS="-C target-feature=+simd128"
cargo build --profile web --target wasm32-unknown-unknown -p passo --bin passo-web -p passo-netplay --bin passo-netplay
mkdir -p "$out"
# Each program: shrunk with wasm-opt, then its JavaScript glue made.
for name in passo-web passo-netplay; do
    wasm="target/wasm32-unknown-unknown/web/$name.wasm"
    if command -v wasm-opt > /dev/null; then
        # Size, not speed: the physics' float arithmetic is left as it is
        # (wasm-opt keeps IEEE semantics), so the bits stay those of native.
        # It runs before wasm-bindgen, whose table of JavaScript values an
        # older wasm-opt (Debian 12's) breaks. The features are those rustc's
        # wasm32 target turns on, and simd128.
        wasm-opt -Oz --enable-bulk-memory --enable-multivalue --enable-mutable-globals \
            --enable-nontrapping-float-to-int --enable-reference-types --enable-sign-ext --enable-simd \
            "$wasm" -o "$out/$name.opt.wasm"
        wasm="$out/$name.opt.wasm"
    else
        echo "warning: wasm-opt not found (apt-get install binaryen): $name.wasm is not shrunk" >&2
    fi
    wasm-bindgen --target web --no-typescript --remove-name-section --remove-producers-section \
        --out-dir "$out" --out-name "$name" "$wasm"
    rm -f "$out/$name.opt.wasm"
done
cp web/index.html "$out/index.html"
cp web/netplay.html "$out/netplay.html"
ls -l "$out"
