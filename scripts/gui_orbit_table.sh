#!/usr/bin/env bash
# Frame times of the GUI while orbiting, for every step's default scene at the default window
# size: one row per step with the median and 95th percentile that `gui ID --frames N --orbit`
# prints (after its 3 warm-up frames) and the live picture's median side, each the median of
# RUNS runs. A benchmark, not a test (docs/speed-history.md).
#
#   scripts/gui_orbit_table.sh [PBRLAB] [FRAMES] [RUNS]    (default build/pbrlab, 60, 3)
#
# Each run has a fresh HOME (no remembered model or scene: the step's default scene) and the
# usual cache (PBRLAB_CACHE, else ~/.cache/pbrlab, kept: the IBL maps are precomputed once,
# as on a student's machine after the first launch).
set -euo pipefail
pbrlab=${1:-build/pbrlab}
frames=${2:-60}
runs=${3:-3}
cache=${PBRLAB_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/pbrlab}
home=$(mktemp -d)
trap 'rm -rf "$home"' EXIT

median() { sort -g | awk 'NF {v[++n] = $1} END {print (n ? v[int((n + 1) / 2)] : "?")}'; }

echo "| step | frame median | 95th percentile | picture side (median) |"
echo "|---|---|---|---|"
for id in $("$pbrlab" list | cut -f1); do
    medians="" p95s="" sides=""
    for _ in $(seq "$runs"); do
        rm -rf "${home:?}"/.config
        out=$(HOME=$home PBRLAB_CACHE=$cache xvfb-run -a -s '-screen 0 1920x1080x24' \
            "$pbrlab" gui "$id" --frames "$frames" --orbit 2>&1) || continue
        frame=$(grep -m1 '^frame: .* frames at' <<<"$out" || true)
        medians+="$(sed -n 's/.*median \([0-9.]*\) ms.*/\1/p' <<<"$frame")"$'\n'
        p95s+="$(sed -n 's/.*95th percentile \([0-9.]*\) ms.*/\1/p' <<<"$frame")"$'\n'
        sides+="$(grep 'of which the picture (median side): [0-9]* frames at' <<<"$out" |
            sed -n 's/.*frames at \([0-9]*\)x.*/\1/p')"$'\n'
    done
    echo "| $id | $(median <<<"$medians") ms | $(median <<<"$p95s") ms | $(median <<<"$sides") |"
done
