#!/usr/bin/env bash
# Gradescope autograder setup (runs once when the image is built, as root, Ubuntu/Debian).
# The autograder zip holds this file, run_autograder and a pbrlab source tree in ./pbrlab.
set -euo pipefail
cd /autograder/source/pbrlab
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPBRLAB_BUILD_TESTS=OFF
cmake --build build -j "$(nproc)"
