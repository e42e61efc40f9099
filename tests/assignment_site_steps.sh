#!/usr/bin/env bash
# `pbrlab kit --assignment A --site-steps` (docs/web.md, "A site for an assignment"): the step
# folders of a site that carries no solution the assignment has not released, and the renderer
# over them (PBRLAB_DATA pointing at a data root with those folders as labs/): a withheld step's
# function comes from the student's file where one is given, else from its starter.
# Usage: assignment_site_steps.sh PBRLAB SOURCE_DIR
set -euo pipefail
pbrlab=$1
source=$2
assignment=$source/docs/autograder/assignment.json
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

echo "== before the solutions are out (2026-09-22): steps through specular, five withheld"
"$pbrlab" kit --assignment "$assignment" --date 2026-09-22 --site-steps --out "$work/data/labs" |
    tee "$work/out.txt"
grep -q "solutions withheld: ndotl, ndf, smith, fresnel, specular$" "$work/out.txt" ||
    fail "the withheld steps"
for id in ndotl ndf smith fresnel specular; do
    test -f "$work/data/labs/$id/starter.glsl" || fail "$id has no starter.glsl"
    for gone in solution.glsl mistakes variants module.cpp; do
        test ! -e "$work/data/labs/$id/$gone" || fail "$id still has $gone"
    done
    grep -q "BEGIN SOLUTION" "$work/data/labs/$id/starter.glsl" || fail "$id: not the kit's starter"
done
# A step the assignment does not give keeps its solution; none after the last released one.
test -f "$work/data/labs/g1/solution.glsl" || fail "g1 (not assigned) lost its solution"
test ! -e "$work/data/labs/f0/starter.glsl" || fail "f0 (not assigned) is withheld"
test ! -e "$work/data/labs/brdf" || fail "brdf (after specular) is in the site"

echo "== the renderer over those folders"
ln -s "$source/shaders" "$work/data/shaders"
ln -s "$source/assets" "$work/data/assets"
"$pbrlab" kit --with-solutions --out "$work/solutions" > /dev/null
"$pbrlab" render specular --submission "$work/solutions" --out "$work/full.png" 2> /dev/null
# With correct student files for the withheld steps it calls, the same picture to the byte.
PBRLAB_DATA=$work/data "$pbrlab" render specular --submission "$work/solutions" \
    --out "$work/withheld.png" 2> /dev/null
cmp -s "$work/full.png" "$work/withheld.png" ||
    fail "specular over the student's withheld steps differs from the reference render"
# Without them, the starters (every function 0): a different picture.
PBRLAB_DATA=$work/data "$pbrlab" render specular --out "$work/starters.png" 2> /dev/null
! cmp -s "$work/full.png" "$work/starters.png" || fail "specular over the starters is the reference"

echo "== IBL steps withheld: split_sum reads the prefiltered map and the LUT"
# The maps are the host's (precomputed by bins and by quadrature, no step's code), so split_sum
# over withheld prefilter and brdf_lut is the reference render, with or without their files.
cat > "$work/ibl.json" <<'JSON'
{"steps": ["brdf_lut", "prefilter", "split_sum"]}
JSON
"$pbrlab" kit --assignment "$work/ibl.json" --site-steps --out "$work/ibl/labs" > /dev/null
ln -s "$source/shaders" "$work/ibl/shaders"
ln -s "$source/assets" "$work/ibl/assets"
"$pbrlab" render split_sum --submission "$work/solutions" --size 128x128 --out "$work/ibl-full.png" \
    2> /dev/null
PBRLAB_DATA=$work/ibl "$pbrlab" render split_sum --submission "$work/solutions" --size 128x128 \
    --out "$work/ibl-withheld.png" 2> /dev/null
cmp -s "$work/ibl-full.png" "$work/ibl-withheld.png" ||
    fail "split_sum over withheld steps, with their files, differs from the reference render"
mkdir "$work/only-split-sum"
cp "$work/solutions/split_sum.glsl" "$work/only-split-sum/"
PBRLAB_DATA=$work/ibl "$pbrlab" render split_sum --submission "$work/only-split-sum" \
    --size 128x128 --out "$work/ibl-starters.png" 2> /dev/null
cmp -s "$work/ibl-full.png" "$work/ibl-starters.png" ||
    fail "split_sum over withheld steps, without their files, differs from the reference render"

echo "== once the solutions are out (2026-10-02), nothing is withheld; before any release, an error"
"$pbrlab" kit --assignment "$assignment" --date 2026-10-02 --site-steps --out "$work/later" |
    grep -q "solutions withheld: none$" || fail "solutions out: something withheld"
if "$pbrlab" kit --assignment "$assignment" --date 2026-09-01 --site-steps --out "$work/early" \
    2> "$work/early.txt"; then
    fail "a site before the first release"
fi
grep -q "nothing is out by 2026-09-01" "$work/early.txt" || fail "the reason: $(cat "$work/early.txt")"
echo "ok"
