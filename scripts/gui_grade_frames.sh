#!/usr/bin/env bash
# The GUI's frames while the settled grade runs (issue 23's measure): for each step below, the
# student's edit (`set`), 200 ms still, then the evaluation against the CPU reference on the
# evaluation thread; one row per run with what `gui --frame-times` prints for it ("evaluation
# 2") and, as the baseline of the same run, the frames while none ran. A benchmark, not a test
# (docs/speed-history.md).
#
#   scripts/gui_grade_frames.sh [PBRLAB] [RUNS]    (default build/pbrlab, 3)
#
# Each run has a fresh XDG_CONFIG_HOME (no remembered step or model) and the usual cache
# (PBRLAB_CACHE, else ~/.cache/pbrlab, kept: the IBL maps are precomputed once, as on a
# student's machine after the first launch).
set -euo pipefail
pbrlab=${1:-build/pbrlab}
runs=${2:-3}
config=$(mktemp -d)
trap 'rm -rf "$config"' EXIT

# step | scene option | the edit
edits=(
    "ndf|--scene sphere-grid|light_dir=0.3,1,0.2"
    "brdf||light_dir=0.3,1,0.2"
    "prefilter||samples=128"
    "mc_specular||samples=128"
    "brdf_lut||samples=1024"
)

# The first figure named $1 (sed quits there: no pipe for pipefail to see broken).
field() { sed -n "/$1 [0-9.]* ms/{s/.*$1 \([0-9.]*\) ms.*/\1/p;q;}"; }

echo "| step, edit | run | frames while it ran | median | longest | while none ran: longest |"
echo "|---|---|---|---|---|---|"
for row in "${edits[@]}"; do
    IFS='|' read -r id scene edit <<<"$row"
    for run in $(seq "$runs"); do
        rm -rf "${config:?}"/*
        # shellcheck disable=SC2086  # $scene is empty or two words
        out=$(XDG_CONFIG_HOME=$config timeout 300 xvfb-run -a -s '-screen 0 1280x800x24' \
            "$pbrlab" gui "$id" $scene --window 1280x720 --frames 20 --frame-times \
            --command wait --command 'wait --timeout 2 --file /nonexistent' \
            --command "set $edit" --command wait 2>&1) || true
        grade=$(grep '^evaluation 2 against' <<<"$out" || true)
        idle=$(grep '^while no evaluation ran' <<<"$out" || true)
        frames=$(sed -n 's/.*: \([0-9]*\) frames while it ran.*/\1/p' <<<"$grade")
        echo "| $id, $edit | $run | ${frames:-?} | $(field median <<<"$grade") ms |" \
            "$(field longest <<<"$grade") ms | $(field longest <<<"$idle") ms |"
    done
done
