#!/usr/bin/env bash
# The two-tab netplay game: builds the web folder (web/build.sh), then
# serves it on http://127.0.0.1:8000 with a signalling server on port 3536
# (where the page looks for it). Open http://127.0.0.1:8000/netplay.html in
# two tabs. Ctrl-C stops both servers.
set -euo pipefail
cd "$(dirname "$0")/.."
port="${1:-8000}"
bash web/build.sh target/web-demo
cargo build --release -p passo-netplay --bin passo-signal
target/release/passo-signal 127.0.0.1:3536 &
signal=$!
trap 'kill $signal 2> /dev/null' EXIT
echo "Netplay: open http://127.0.0.1:$port/netplay.html in two tabs  (Ctrl-C stops the servers)"
python3 -m http.server --bind 127.0.0.1 "$port" --directory target/web-demo
