#!/usr/bin/env bash
# The speed gate's own test (scripts/bench.sh): a pbrlab slowed down by a fixed delay per
# process must fail the gate on the figures it slows, saying which, and the same figures with
# the real pbrlab, measured in the same call, must pass (else the failure proves nothing).
#   bench_gate.sh BUILD_DIR
set -euo pipefail
build=$(cd "${1:?usage: bench_gate.sh BUILD_DIR}" && pwd)
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# 0.5 s more per process: start (--help, about 20 ms) and render (about 0.2 s) grow several
# times over; a real regression of that size is what the gate is for.
cat >"$work/slower-pbrlab" <<EOF
#!/bin/sh
sleep 0.5
exec "$build/pbrlab" "\$@"
EOF
chmod +x "$work/slower-pbrlab"

status=0
if bash "$root/scripts/bench.sh" "$build" --only start,render --runs 3 >"$work/real.log" 2>&1; then
    echo "ok   the real pbrlab passes the gate on start and render"
else
    echo "FAIL the real pbrlab fails the gate on start and render:"
    status=1
fi
cat "$work/real.log"
if bash "$root/scripts/bench.sh" "$build" --only start,render --runs 3 \
    --pbrlab "$work/slower-pbrlab" >"$work/slower.log" 2>&1; then
    echo "FAIL a pbrlab 0.5 s slower per process passes the gate:"
    status=1
elif [ "$(grep -c 'SLOWER' "$work/slower.log")" -eq 2 ]; then
    echo "ok   a pbrlab 0.5 s slower per process fails the gate on both figures"
else
    echo "FAIL a pbrlab 0.5 s slower per process fails the gate, but not on both figures:"
    status=1
fi
cat "$work/slower.log"
exit "$status"
