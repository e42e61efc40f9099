#!/usr/bin/env bash
# The Gradescope autograder as Gradescope runs it (docs/assignment.md): `pbrlab autograder`
# zipping the grader bundle (scripts/grader-bundle.sh) with an assignment of three steps, the
# zip unpacked into a fake /autograder tree, setup.sh (nothing installed: the bundle's pbrlab
# runs where it is) and run_autograder on two submissions: the reference solutions (full
# points) and two planted mistakes: ndf's alpha = roughness (no values check passes: nothing)
# and fresnel's pow6 (the weights' share of what passed). Each results.json is validated
# against Gradescope's documented format, and its visibility compared row by row with what the
# assignment's rules give (step.category, step, category, default). The schedule: the bundle's
# kit, by date, hands out what the assignment's release and solutions entries say and writes the
# due date. And pbrlab killed: run_autograder still writes a results.json saying so.
# (grader_bare_system.sh runs the same zip on a system without pbrlab's libraries.)
# Usage: gradescope_bundle.sh BUNDLE_DIR RESULTS_CHECKER
set -euo pipefail
bundle=$(cd "$1" && pwd)
check=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pbrlab=$bundle/bin/pbrlab

echo "== pbrlab autograder"
cat > "$work/assignment.json" <<'JSON'
{
  "name": "bundle test",
  "steps": ["ndotl", "ndf", "fresnel"],
  "points": {"ndf": 3},
  "checks": {"contract": 1, "probe": 2, "scenes": 2, "random": 2, "sphere_grid": 1,
             "invariants": 2},
  "visibility": {"default": "visible", "fresnel": "after_due_date", "invariants": "hidden",
                 "fresnel.invariants": "after_published", "ndotl.probe": "after_published"},
  "release": [{"date": "2026-09-07", "through": "ndf"},
              {"date": "2026-09-21", "through": "fresnel"}],
  "solutions": [{"date": "2026-10-02", "through": "ndf"}],
  "due": "2026-10-01T23:59:00Z",
  "time_limit_seconds": 120
}
JSON
# The bundle's own pbrlab finds the bundle it runs from.
"$pbrlab" autograder --assignment "$work/assignment.json" --out "$work/out"
mkdir -p "$work/autograder/source"
unzip -q "$work/out/autograder.zip" -d "$work/autograder/source"
test -x "$work/autograder/source/setup.sh"
test -x "$work/autograder/source/run_autograder"
test -x "$work/autograder/source/pbrlab/bin/pbrlab"
cmp "$work/assignment.json" "$work/autograder/source/assignment.json"
cmp "$bundle/lib/libOSMesa.so.8" "$work/autograder/source/pbrlab/lib/libOSMesa.so.8"
# Gradescope's default timeout, 600 s, less the margin (gradingBudgetSeconds).
grep -q -- "--time-budget 540" "$work/autograder/source/run_autograder"
# Gradescope copies run_autograder to /autograder, and runs setup.sh from the source folder.
cp "$work/autograder/source/run_autograder" "$work/autograder/run_autograder"

export PBRLAB_AUTOGRADER_ROOT="$work/autograder"
echo "== setup.sh"
(cd "$work/autograder/source" && ./setup.sh)
ls "$work/autograder/source/pbrlab-cache" > /dev/null

grade() {  # SUBMISSION_DIR EXPECTED_SCORE
    rm -rf "$work/autograder/submission" "$work/autograder/results"
    cp -r "$1" "$work/autograder/submission"
    (cd "$work/autograder" && ./run_autograder > "$work/stdout.txt")
    "$check" "$work/autograder/results/results.json" "$2"
}

echo "== run_autograder: the reference solutions"
"$pbrlab" kit --assignment "$work/assignment.json" --with-solutions --out "$work/solutions" \
    > /dev/null
grade "$work/solutions" 5
echo "== run_autograder: planted mistakes in ndf and fresnel"
cp -r "$work/solutions" "$work/mistake"
labs=$bundle/share/pbrlab/labs
cp "$labs/ndf/mistakes/alpha_is_roughness.glsl" "$work/mistake/ndf.glsl"
cp "$labs/fresnel/mistakes/pow6.glsl" "$work/mistake/fresnel.glsl"
# ndotl 1 + ndf 0 (its contract and invariants hold, and a stub's would too) + fresnel
# 1 x (contract 1 + scenes 2 x 1/4 + invariants 2) / 10.
grade "$work/mistake" 1.35
echo "== visibility, row by row"
# What the rules give: the most specific key wins (step.category, step, category, default).
# ndotl: probe by "ndotl.probe", invariants by the category; ndf: invariants by the category;
# fresnel: invariants by "fresnel.invariants", its other rows by the step; the rest default.
cat > "$work/visibility.expected" <<'ROWS'
(result): visible
ndotl: contract: visible
ndotl: probe: after_published
ndotl: scenes: visible
ndotl: random: visible
ndotl: sphere_grid: visible
ndotl: invariants: hidden
ndf: contract: visible
ndf: probe: visible
ndf: scenes: visible
ndf: random: visible
ndf: sphere_grid: visible
ndf: invariants: hidden
fresnel: contract: after_due_date
fresnel: probe: after_due_date
fresnel: scenes: after_due_date
fresnel: random: after_due_date
fresnel: sphere_grid: after_due_date
fresnel: invariants: after_published
ROWS
"$check" "$work/autograder/results/results.json" 1.35 --visibility | tail -n +2 \
    > "$work/visibility.txt"
diff "$work/visibility.expected" "$work/visibility.txt"
# The summary shown with the whole result lists the steps whose rows are visible now only.
# (Only the summary's table has "| step |" cells: the rows' outputs are lists.)
results=$work/autograder/results/results.json
grep -qF '| ndf |' "$results" || { echo "ndf missing from the summary"; exit 1; }
if grep -qF '| fresnel |' "$results"; then echo "fresnel (after_due_date) in the summary"; exit 1; fi

echo "== pbrlab killed: run_autograder still writes a results.json, which says so"
real=$work/autograder/source/pbrlab/bin/pbrlab
mv "$real" "$real.real"
printf '#!/bin/sh\nkill -KILL $$\n' > "$real"
chmod 755 "$real"
rm -rf "$work/autograder/results"
(cd "$work/autograder" && ./run_autograder > /dev/null 2>&1)
mv "$real.real" "$real"
"$check" "$work/autograder/results/results.json" 0
grep -q 'Not graded.*exit status 137' "$work/autograder/results/results.json" ||
    { cat "$work/autograder/results/results.json"; exit 1; }

echo "== the kit by date: release, solutions, due"
kit() {  # DATE OUT
    "$pbrlab" kit --assignment "$work/assignment.json" --date "$1" --out "$2"
}
if kit 2026-09-06 "$work/kit-early" > "$work/kit-early.txt" 2>&1; then
    echo "a kit before the first release"; exit 1
fi
grep -q "the first release is on 2026-09-07" "$work/kit-early.txt"
kit 2026-09-07 "$work/kit-first" > /dev/null
test -f "$work/kit-first/ndotl.glsl" && test -f "$work/kit-first/ndf.glsl"
test ! -e "$work/kit-first/fresnel.glsl" || { echo "fresnel handed out before 2026-09-21"; exit 1; }
if cmp -s "$work/kit-first/ndf.glsl" "$labs/ndf/solution.glsl"; then
    echo "ndf's solution handed out before 2026-10-02"; exit 1
fi
grep -qx "Due: 2026-10-01T23:59:00Z" "$work/kit-first/README.md"
kit 2026-10-02 "$work/kit-solutions" > /dev/null
cmp "$work/kit-solutions/ndotl.glsl" "$labs/ndotl/solution.glsl"
cmp "$work/kit-solutions/ndf.glsl" "$labs/ndf/solution.glsl"
if cmp -s "$work/kit-solutions/fresnel.glsl" "$labs/fresnel/solution.glsl"; then
    echo "fresnel's solution handed out: solutions go through ndf only"; exit 1
fi
echo "autograder zip: set up with nothing installed, results.json valid, scores as the" \
     "weights say, visibility row by row, the kit by date"
