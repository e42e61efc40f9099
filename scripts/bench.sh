#!/usr/bin/env bash
# pbrlab's speed figures (docs/speed.md), each as a ratio to a yardstick timed in the same call,
# compared with the ratios recorded in tests/bench_ratios.json.
#   bash scripts/bench.sh [BUILD_DIR] [--runs N] [--only a,b] [--record] [--pbrlab PATH]
#                         [--env HDR] [--json FILE] [--cpus LIST]
# --cpus runs everything, figures and yardsticks, on those CPUs only (`taskset -c LIST`: 0 is
# one core, as Gradescope grades by default; docs/grading-at-scale.md).
# A ratio, not a time: the yardsticks are programs that do not change when pbrlab does
# (tests/yardstick_draw.cpp, a trivial OSMesa draw; tests/yardstick_ibl.cpp, LearnOpenGL's IBL
# pipeline; /bin/true, a process), so a slower or busier machine moves both sides. Each figure
# and its yardstick run in turn, N times (default 5), and the ratio is that of their medians.
# Exit 1 when a ratio is above its recorded value times the margin recorded with it (the
# measured noise and why: docs/speed.md); --record writes the ratios measured there instead,
# keeping each figure's margin.
# --pbrlab runs another program in pbrlab's place (tests/bench_gate.sh: a slowed-down one must
# fail). Figures:
#   start            pbrlab --help                                  / /bin/true
#   render           pbrlab render ndotl --size 256x256 --out x.png / trivial OSMesa draw
#   precompute       pbrlab precompute --env HDR, empty caches      / LearnOpenGL's pipeline
#   grade-correct    pbrlab grade, the 21 solutions, warm caches    / LearnOpenGL's pipeline
#   grade-wrong      pbrlab grade, one planted mistake a step, warm / LearnOpenGL's pipeline
#   grade-cold       pbrlab grade, the 21 solutions, empty caches   / LearnOpenGL's pipeline
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=build
runs=5
only=""
record=0
pbrlab=""
env=""
json=""
cpus=""
while [ $# -gt 0 ]; do
    case "$1" in
        --runs) runs=$2; shift 2 ;;
        --only) only=$2; shift 2 ;;
        --record) record=1; shift ;;
        --pbrlab) pbrlab=$2; shift 2 ;;
        --env) env=$2; shift 2 ;;
        --json) json=$2; shift 2 ;;
        --cpus) cpus=$2; shift 2 ;;
        -*) echo "bench: unknown option $1" >&2; exit 2 ;;
        *) build=$1; shift ;;
    esac
done
build=$(cd "$build" && pwd)
[ -n "$pbrlab" ] || pbrlab=$build/pbrlab
draw=$build/tests/pbrlab_yardstick_draw
ibl=$build/tests/pbrlab_yardstick_ibl
for program in "$pbrlab" "$draw" "$ibl"; do
    [ -x "$program" ] || { echo "bench: $program is missing (build first)" >&2; exit 2; }
done
recorded=$root/tests/bench_ratios.json
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export LC_ALL=C

# The inputs: an environment (the project's sky unless --env), the solutions, and the first
# planted mistake (by name) of every step.
if [ -z "$env" ]; then
    env=$work/sky.hdr
    "$pbrlab" environment --out "$env" --width 1024 >/dev/null
fi
"$pbrlab" kit --with-solutions --out "$work/correct" >/dev/null
mkdir -p "$work/wrong"
for mistakes in labs/*/mistakes; do
    files=("$mistakes"/*.glsl)
    [ -e "${files[0]}" ] || continue
    cp "${files[0]}" "$work/wrong/$(basename "$(dirname "$mistakes")").glsl"
done
# The warm figures share one cache, filled by an uncounted run of each.
warm=$work/cache-warm
mkdir -p "$warm/pbrlab" "$warm/mesa"

pinned=()
[ -z "$cpus" ] || pinned=(taskset -c "$cpus")
# Wall time of a command in seconds (its output discarded); exit 1 when it fails.
seconds() {
    local start end
    start=$(date +%s%N)
    if ! "$@" >/dev/null 2>&1; then
        echo "bench: failed: $*" >&2
        return 1
    fi
    end=$(date +%s%N)
    echo "$(( (end - start) / 1000 ))" | awk '{printf "%.6f\n", $1 / 1e6}'
}
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
# On the CPUs of --cpus (else any).
pin() { "${pinned[@]}" "$@"; }
# A fresh, empty cache for each cold run (pbrlab's and Mesa's shader cache).
cold() {
    local dir
    dir=$(mktemp -d -p "$work")
    pin env PBRLAB_CACHE="$dir/pbrlab" MESA_SHADER_CACHE_DIR="$dir/mesa" "$@"
}
warmed() { pin env PBRLAB_CACHE="$warm/pbrlab" MESA_SHADER_CACHE_DIR="$warm/mesa" "$@"; }

declare -A commands yardsticks
commands[start]="pin $pbrlab --help"
yardsticks[start]="pin /bin/true"
commands[render]="warmed $pbrlab render ndotl --size 256x256 --out $work/x.png"
yardsticks[render]="warmed $draw"
commands[precompute]="cold $pbrlab precompute --env $env --out $work/maps"
yardsticks[precompute]="cold $ibl $env"
commands[grade-correct]="warmed $pbrlab grade $work/correct --json $work/correct.json"
yardsticks[grade-correct]="warmed $ibl $env"
commands[grade-wrong]="warmed $pbrlab grade $work/wrong --json $work/wrong.json"
yardsticks[grade-wrong]="warmed $ibl $env"
commands[grade-cold]="cold $pbrlab grade $work/correct --json $work/cold.json"
yardsticks[grade-cold]="warmed $ibl $env"
allFigures=(start render precompute grade-correct grade-wrong grade-cold)
figures=("${allFigures[@]}")
if [ -n "$only" ]; then IFS=, read -r -a figures <<<"$only"; fi

# The recorded ratio and margin of a figure ("" when none is recorded).
recordedField() {
    [ -f "$recorded" ] || return 0
    sed -n "s/.*\"$1\": *{[^}]*\"$2\": *\([0-9.eE+-]*\).*/\1/p" "$recorded"
}

failed=0
results=()
printf '%-14s %10s %10s %8s %9s %7s  %s\n' figure "median s" "yardstick" ratio recorded margin verdict
for figure in "${figures[@]}"; do
    command=${commands[$figure]:-}
    [ -n "$command" ] || { echo "bench: unknown figure $figure" >&2; exit 2; }
    # shellcheck disable=SC2086 # the commands are words
    # One uncounted run of each (a cold figure's command excepted: each of its runs starts
    # empty anyway): the warm figures' caches filled, the programs read from disk once.
    # shellcheck disable=SC2086
    ${yardsticks[$figure]} >/dev/null 2>&1 || true
    # shellcheck disable=SC2086
    [[ $command == cold\ * ]] || $command >/dev/null 2>&1 || true
    : >"$work/a" && : >"$work/b"
    for ((run = 0; run < runs; ++run)); do
        # shellcheck disable=SC2086
        seconds ${yardsticks[$figure]} >>"$work/b"
        # shellcheck disable=SC2086
        seconds $command >>"$work/a"
    done
    a=$(median <"$work/a")
    b=$(median <"$work/b")
    ratio=$(awk -v a="$a" -v b="$b" 'BEGIN {printf "%.4g", a / b}')
    want=$(recordedField "$figure" ratio)
    margin=$(recordedField "$figure" margin)
    verdict="(not recorded)"
    if [ -n "$want" ] && [ -n "$margin" ]; then
        if awk -v r="$ratio" -v w="$want" -v m="$margin" 'BEGIN {exit !(r > w * m)}'; then
            verdict="SLOWER: over ${want} x ${margin}"
            failed=1
        else
            verdict=ok
        fi
    fi
    printf '%-14s %10.4f %10.4f %8s %9s %7s  %s\n' "$figure" "$a" "$b" "$ratio" "${want:--}" \
        "${margin:--}" "$verdict"
    results+=("\"$figure\": {\"seconds\": $a, \"yardstick\": $b, \"ratio\": $ratio}")
done

if [ -n "$json" ]; then
    { echo "{"; (IFS=$'\n'; echo "${results[*]}" | sed '$!s/$/,/; s/^/  /'); echo "}"; } >"$json"
fi
if [ "$record" = 1 ]; then
    # Every figure: the ratio measured now, else the one recorded; each keeps its recorded
    # margin (a new figure's default: 1.5).
    declare -A measured
    for line in "${results[@]}"; do
        figure=${line%%\": *}
        figure=${figure#\"}
        measured[$figure]=$(sed -n 's/.*"ratio": \([^}]*\)}.*/\1/p' <<<"$line")
    done
    lines=()
    for figure in "${allFigures[@]}"; do
        ratio=${measured[$figure]:-$(recordedField "$figure" ratio)}
        [ -n "$ratio" ] || continue
        margin=$(recordedField "$figure" margin)
        lines+=("  \"$figure\": {\"ratio\": $ratio, \"margin\": ${margin:-1.5}}")
    done
    { echo "{"; (IFS=$'\n'; echo "${lines[*]}" | sed '$!s/$/,/'); echo "}"; } >"$recorded.new"
    mv "$recorded.new" "$recorded"
    echo "bench: wrote $recorded"
    exit 0
fi
if [ "$failed" = 1 ]; then
    echo "bench: slower than recorded beyond the margin (docs/speed.md says how the margins were measured)" >&2
    exit 1
fi
