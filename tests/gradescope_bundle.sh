#!/usr/bin/env bash
# The Gradescope autograder as Gradescope runs it (docs/assignment.md): a Debian package of this
# build (cpack -G DEB), `pbrlab autograder` bundling it with an assignment of three steps,
# the zip unpacked into a fake /autograder tree, setup.sh (the .deb unpacked with dpkg-deb -x:
# no root) and run_autograder on two submissions: the reference solutions (full points) and
# two planted mistakes: ndf's alpha = roughness (no values check passes: nothing) and fresnel's
# pow6 (the weights' share of what passed). Each results.json is validated against Gradescope's
# documented format.
# Usage: gradescope_bundle.sh BUILD_DIR RESULTS_CHECKER
set -euo pipefail
build=$(cd "$1" && pwd)
check=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "== cpack -G DEB"
(cd "$work" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/package" > cpack.log)
deb=$(ls "$work"/package/pbrlab_*_*.deb)
dpkg-deb -I "$deb" | grep -E '^ (Package|Version|Architecture|Depends):'
dpkg-deb -c "$deb" > "$work/contents.txt"
for f in ./usr/bin/pbrlab ./usr/lib/pbrlab/modules/pbrlab-ndf.so ./usr/share/pbrlab/shaders/ \
         ./usr/include/pbrlab/module.h ./usr/lib/cmake/pbrlab/pbrlabConfig.cmake; do
    grep -q " $f" "$work/contents.txt" || { echo "not in the package: $f"; exit 1; }
done

echo "== pbrlab autograder"
cat > "$work/assignment.json" <<'JSON'
{
  "name": "bundle test",
  "steps": ["ndotl", "ndf", "fresnel"],
  "points": {"ndf": 3},
  "checks": {"contract": 1, "probe": 2, "scenes": 2, "random": 2, "sphere_grid": 1,
             "invariants": 2},
  "visibility": {"default": "visible", "fresnel": "after_due_date"},
  "time_limit_seconds": 120
}
JSON
"$build/pbrlab" autograder --assignment "$work/assignment.json" --out "$work/out" --deb "$deb"
mkdir -p "$work/autograder/source"
unzip -q "$work/out/autograder.zip" -d "$work/autograder/source"
test -x "$work/autograder/source/setup.sh"
test -x "$work/autograder/source/run_autograder"
cmp "$work/assignment.json" "$work/autograder/source/assignment.json"
# Gradescope copies run_autograder to /autograder, and runs setup.sh from the source folder.
cp "$work/autograder/source/run_autograder" "$work/autograder/run_autograder"

export PBRLAB_AUTOGRADER_ROOT="$work/autograder" PBRLAB_PREFIX="$work/root"
echo "== setup.sh"
(cd "$work/autograder/source" && bash ./setup.sh)
ls "$work/autograder/source/pbrlab-cache" > /dev/null
# The installed program (not the build's) grades from now on.
test -x "$work/root/usr/bin/pbrlab"

grade() {  # SUBMISSION_DIR EXPECTED_SCORE
    rm -rf "$work/autograder/submission" "$work/autograder/results"
    cp -r "$1" "$work/autograder/submission"
    (cd "$work/autograder" && ./run_autograder > "$work/stdout.txt")
    "$check" "$work/autograder/results/results.json" "$2"
}

echo "== run_autograder: the reference solutions"
"$work/root/usr/bin/pbrlab" kit --assignment "$work/assignment.json" --with-solutions \
    --out "$work/solutions" > /dev/null
grade "$work/solutions" 5
echo "== run_autograder: planted mistakes in ndf and fresnel"
cp -r "$work/solutions" "$work/mistake"
labs=$work/root/usr/share/pbrlab/labs
cp "$labs/ndf/mistakes/alpha_is_roughness.glsl" "$work/mistake/ndf.glsl"
cp "$labs/fresnel/mistakes/pow6.glsl" "$work/mistake/fresnel.glsl"
# ndotl 1 + ndf 0 (its contract and invariants hold, and a stub's would too) + fresnel
# 1 x (contract 1 + scenes 2 x 1/4 + invariants 2) / 10.
grade "$work/mistake" 1.35
grep -q '"visibility": "after_due_date"' "$work/autograder/results/results.json"
echo "autograder bundle: installed from the .deb, results.json valid, scores as the weights say"
