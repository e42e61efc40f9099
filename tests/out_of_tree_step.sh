#!/usr/bin/env bash
# A step from outside the source tree, as an instructor adds one (docs/authoring-a-module.md):
# pbrlab installed with cmake --install, a step folder made by `pbrlab new-step` and built
# against the installed package (find_package(pbrlab)), then loaded with --modules (and
# $PBRLAB_MODULES): it must be listed at its declared position, rendered, checked, in the kit,
# graded and in the gallery like the built-in steps, and the steps after it move down one
# without any change to their folders.
# Usage: out_of_tree_step.sh BUILD_DIR
set -euo pipefail
build=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export PBRLAB_CACHE="$work/cache"

echo "== cmake --install"
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
pbrlab="$work/prefix/bin/pbrlab"

echo "== new-step, inserted between ndotl (order 40) and ndf (order 50)"
"$pbrlab" new-step half_lambert --out "$work/step" --order 45
cmake -S "$work/step" -B "$work/step/build" -DCMAKE_PREFIX_PATH="$work/prefix" \
    -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/step/build" > "$work/build.log"
modules="$work/step/build/modules"
test -f "$modules/pbrlab-half_lambert.so"

echo "== list"
"$pbrlab" --modules "$modules" list | tee "$work/list.txt"
grep -qP '^ndotl\t4\tdirect\t' "$work/list.txt"
grep -qP '^half_lambert\t5\tdirect\t' "$work/list.txt"
grep -qP '^ndf\t6\tdirect\t' "$work/list.txt"
grep -qP '^split_sum\t22\tibl\t' "$work/list.txt"
PBRLAB_MODULES="$modules" "$pbrlab" list | grep -qP '^half_lambert\t5\t'
# Without the folder the built-in steps are as they were.
"$pbrlab" list | grep -qP '^ndf\t5\tdirect\t'

echo "== render, check"
"$pbrlab" --modules "$modules" render half_lambert --size 64x64 --out "$work/half_lambert.png"
test -s "$work/half_lambert.png"
"$pbrlab" --modules "$modules" check half_lambert
"$pbrlab" --modules "$modules" check ndf

echo "== kit and grade"
"$pbrlab" --modules "$modules" kit --out "$work/kit" > /dev/null
test -f "$work/kit/half_lambert.glsl"
grep -q 'float halfLambert(vec3 N, vec3 L)' "$work/kit/half_lambert.glsl"
"$pbrlab" --modules "$modules" kit --with-solutions --out "$work/solutions" > /dev/null
"$pbrlab" --modules "$modules" grade "$work/solutions" --steps half_lambert,ndf \
    --json "$work/solutions.json" | tee "$work/grade.txt"
grep -qE '^half_lambert +passed +1 / 1 ' "$work/grade.txt"
grep -qE '^ndf +passed' "$work/grade.txt"
"$pbrlab" --modules "$modules" grade "$work/kit" --steps half_lambert | tee "$work/stub.txt"
grep -qE '^half_lambert +failed +0 / 1 ' "$work/stub.txt"

echo "== feedback names the step's own terms (its namedTerms)"
mkdir "$work/unsquared"
sed 's/return wrapped \* wrapped;/return wrapped;/' "$work/solutions/half_lambert.glsl" \
    > "$work/unsquared/half_lambert.glsl"
if cmp -s "$work/solutions/half_lambert.glsl" "$work/unsquared/half_lambert.glsl"; then
    echo "the template's solution changed: no square to remove"; exit 1
fi
"$pbrlab" --modules "$modules" grade "$work/unsquared" --steps half_lambert \
    --json "$work/unsquared.json" > "$work/unsquared.txt" || true
grep -qE '^half_lambert +failed' "$work/unsquared.txt"
grep -qF '(0.5 N.L + 0.5)^1 where the reference has (0.5 N.L + 0.5)^2' "$work/unsquared.json"

echo "== gallery"
"$pbrlab" --modules "$modules" gallery --out "$work/gallery" --size 48x48 > /dev/null
test -s "$work/gallery/05-half_lambert.png"
test -s "$work/gallery/06-ndf.png"
echo "== gui: the step's term view is in the view chooser"
if command -v xvfb-run > /dev/null; then
    gui() {
        (cd "$work" && HOME="$work" xvfb-run -a -s '-screen 0 1280x800x24' "$pbrlab" \
            --modules "$modules" gui ndotl --window 640x400 --frames 2 "$@")
    }
    gui --view half_lambert --screenshot "$work/term.png" > "$work/gui.log" 2>&1
    test -s "$work/term.png"
    # An unknown view is refused with the known ones listed: the step's among them.
    if gui --view nonsense --screenshot "$work/none.png" > "$work/gui-bad.log" 2>&1; then
        echo "gui --view nonsense did not fail"; exit 1
    fi
    grep -q 'N.L, half_lambert, D' "$work/gui-bad.log"
else
    echo "(xvfb-run not installed: the GUI part is left out)"
fi
echo "out-of-tree step: listed, rendered, checked, in the kit, graded with its named terms, in the gallery and the GUI"
