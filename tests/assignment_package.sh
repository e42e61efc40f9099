#!/usr/bin/env bash
# The students' Debian package for an assignment (scripts/package-assignment.sh, docs/web.md
# "No answers in what students get"): built by date as the assignment's site is, unpacked, and
# searched for the withheld steps' answers; its pbrlab runs. The default install (labs/) keeps
# every step and its solutions.
# Usage: assignment_package.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
source=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

echo "== the package before the solutions are out (2026-09-22)"
bash "$source/scripts/package-assignment.sh" --assignment "$source/docs/autograder/assignment.json" \
    --date 2026-09-22 --out "$work/package" "$build"
deb=$work/package/pbrlab-assignment_2026-09-22_amd64.deb
test -f "$deb" || fail "no $deb"
dpkg-deb -x "$deb" "$work/root"
labs=$work/root/usr/share/pbrlab/labs
modules=$work/root/usr/lib/pbrlab/modules
for id in ndotl ndf smith fresnel specular; do
    test -f "$labs/$id/starter.glsl" || fail "$id has no starter.glsl"
    for gone in solution.glsl mistakes module.cpp; do
        test ! -e "$labs/$id/$gone" || fail "$id still has $gone in the package"
    done
    test -f "$modules/pbrlab-$id.so" || fail "$id's plugin is not in the package"
done
test ! -e "$labs/brdf" || fail "brdf (after the last step released) is in the package"
test ! -e "$modules/pbrlab-brdf.so" || fail "brdf's plugin is in the package"

# Every code line of 16 characters or more of a withheld step's solution and planted mistakes
# that is not also in its starter, its handout or shaders/: in no file of the package.
searched=0
for id in ndotl ndf smith fresnel specular; do
    while IFS= read -r line; do
        grep -qF -- "$line" "$labs/$id/starter.glsl" "$labs/$id/README.md" && continue
        grep -rqF -- "$line" "$source/shaders" && continue
        searched=$((searched + 1))
        if grep -rlaF -- "$line" "$work/root" > "$work/found.txt"; then
            fail "$id's answer line \"$line\" is in $(head -1 "$work/found.txt")"
        fi
    done < <(cat "$source/labs/$id/solution.glsl" "$source/labs/$id"/mistakes/*.glsl |
             sed -e 's|//.*||' -e 's/^[[:space:]]*//' -e 's/[[:space:]]*$//' |
             awk 'length >= 16' | sort -u)
done
echo "searched the package for $searched answer lines: none found"
[ "$searched" -ge 25 ] || fail "only $searched lines searched: the test would miss an answer"

echo "== its pbrlab: the steps through specular, drawn over the starters"
"$work/root/usr/bin/pbrlab" list > "$work/list.txt" 2> "$work/list.err"
[ "$(wc -l < "$work/list.txt")" -eq 10 ] || fail "pbrlab list: $(cat "$work/list.txt")"
! grep -q warning "$work/list.err" || fail "pbrlab list warns: $(cat "$work/list.err")"
"$work/root/usr/bin/pbrlab" render specular --out "$work/specular.png" 2> /dev/null
test -s "$work/specular.png" || fail "the package's pbrlab did not render specular"

echo "== the default install keeps every step and its solution"
cmake --install "$build" --prefix "$work/full" > /dev/null
test -f "$work/full/share/pbrlab/labs/ndf/solution.glsl" || fail "ndf's solution not installed"
test -f "$work/full/share/pbrlab/labs/split_sum/step.json" || fail "split_sum not installed"
test -f "$work/full/lib/pbrlab/modules/pbrlab-brdf.so" || fail "brdf's plugin not installed"
echo "ok"
