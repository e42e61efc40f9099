#!/usr/bin/env bash
# The main job: install, build, then open the GUI when a display exists, or render a headless
# gallery of every step into ./gallery (OSMesa: no GPU and no display needed).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
if [ -n "${DISPLAY:-}" ] && ./build/pbrlab gui --help >/dev/null 2>&1; then
    exec ./build/pbrlab gui "$@"
fi
./build/pbrlab gallery --out gallery "$@"
echo "no display: open gallery/index.html to see every step"
