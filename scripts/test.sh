#!/usr/bin/env bash
# Install, build and run the whole test suite (headless: OSMesa, and Xvfb for the GUI test).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
cd build
ctest --output-on-failure -j "$(nproc)" --timeout 900
