#!/usr/bin/env bash
# Builds the web demo (web/build.sh) and serves it on http://127.0.0.1:8000
# (another port: `web/serve.sh 8080`). Any static file server would do;
# this one is Python's, which Debian has.
set -euo pipefail
cd "$(dirname "$0")/.."
port="${1:-8000}"
bash web/build.sh target/web-demo
echo "Passo in the browser: http://127.0.0.1:$port/  (Ctrl-C stops the server)"
exec python3 -m http.server --bind 127.0.0.1 "$port" --directory target/web-demo
