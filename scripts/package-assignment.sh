#!/usr/bin/env bash
# The students' Debian package for an assignment (docs/assignment.md): pbrlab as `cpack -G DEB`
# packages it, with the step folders of `pbrlab kit --assignment A --date D --site-steps`
# instead of labs/: no solution the assignment has not released on that date (a withheld
# step has its starter, and views that call it run the student's file), no step after the
# last one released. The same folders as the assignment's site (scripts/build-web.sh
# --assignment). Writes OUT/pbrlab-assignment_DATE_ARCH.deb (default OUT:
# BUILD_DIR/assignment-package) and the step folders it packaged in OUT/steps.
#   bash scripts/package-assignment.sh --assignment FILE [--date YYYY-MM-DD] [--out OUT] [BUILD_DIR]
# BUILD_DIR (default build) is a native build of pbrlab; DATE defaults to today.
set -euo pipefail
cd "$(dirname "$0")/.."
build=build
assignment="" date=$(date -u +%F) out=""
while [ $# -gt 0 ]; do
    case $1 in
        --assignment) assignment=$(realpath "$2"); shift 2 ;;
        --date) date=$2; shift 2 ;;
        --out) out=$(realpath -m "$2"); shift 2 ;;
        -*) echo "package-assignment: unknown option $1" >&2; exit 2 ;;
        *) build=$1; shift ;;
    esac
done
[ -n "$assignment" ] || { echo "package-assignment: --assignment FILE is required" >&2; exit 2; }
build=$(realpath "$build")
[ -x "$build/pbrlab" ] || { echo "package-assignment: $build/pbrlab: not built" >&2; exit 2; }
[ -n "$out" ] || out=$build/assignment-package
rm -rf "$out"
mkdir -p "$out"
"$build/pbrlab" kit --assignment "$assignment" --date "$date" --site-steps --out "$out/steps"
(cd "$out" && PBRLAB_INSTALL_STEPS="$out/steps" \
    cpack -G DEB --config "$build/CPackConfig.cmake" -B "$out/cpack" > cpack.log)
deb=$(ls "$out"/cpack/pbrlab_*.deb)
arch=${deb##*_}
mv "$deb" "$out/pbrlab-assignment_${date}_${arch}"
rm -rf "$out/cpack"
echo "wrote $out/pbrlab-assignment_${date}_${arch}"
