#!/usr/bin/env bash
# Builds the lab for the browser (docs/web.md) into BUILD_DIR/site (default build-web/site):
# index.html, index.js, index.wasm, the grader (grader.js, grader.wasm, grader_worker.js) and the
# data both read (lab.data, lab-data.js), served as static files.
#   bash scripts/build-web.sh [BUILD_DIR]
# For an assignment (docs/assignment.md), a site without the solutions it has not released
# (its step folders written by the desktop's pbrlab: --pbrlab, else build/pbrlab, else the one on
# PATH, else build/pbrlab built first), in BUILD_DIR/assignment-site:
#   bash scripts/build-web.sh [BUILD_DIR] --assignment FILE [--date YYYY-MM-DD] [--pbrlab PATH]
# Installs Debian's emscripten, dpkg-dev and chromium (web/debian-packages.txt) beside
# debian-packages.txt's, and a deb-src entry for bookworm so that CMake can fetch Dear ImGui's
# source package (nothing is vendored).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=build-web
assignment="" date="" pbrlab=""
while [ $# -gt 0 ]; do
    case $1 in
        --assignment) assignment=$(realpath "$2"); shift 2 ;;
        --date) date=$2; shift 2 ;;
        --pbrlab) pbrlab=$(realpath "$2"); shift 2 ;;
        -*) echo "build-web: unknown option $1" >&2; exit 2 ;;
        *) build=$1; shift ;;
    esac
done
if [ -z "$assignment" ] && { [ -n "$date" ] || [ -n "$pbrlab" ]; }; then
    echo "build-web: --date and --pbrlab go with --assignment" >&2
    exit 2
fi
bash scripts/install-deps.sh debian-packages.txt web/debian-packages.txt
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
if ! grep -rqs '^\s*\(Types: deb-src\|deb-src \)' /etc/apt/sources.list /etc/apt/sources.list.d/; then
    echo "build-web: adding a deb-src entry for bookworm (apt-get source imgui)"
    printf 'Types: deb-src\nURIs: http://deb.debian.org/debian\nSuites: bookworm\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' |
        $sudo tee /etc/apt/sources.list.d/pbrlab-deb-src.sources >/dev/null
    $sudo apt-get update -qq
fi
# Debian's emcc runs on node: its modules are Debian's, wherever this machine's node comes from;
# its cache is the package's own (frozen), so EM_CACHE must not point elsewhere.
export NODE_PATH=/usr/share/nodejs
unset EM_CACHE
# With ccache (the desktop's build uses it too, when installed) a rebuild compiles only what
# changed: em++ is a compiler to ccache like any other.
launcher=()
if command -v ccache >/dev/null; then
    launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
if [ -z "$assignment" ]; then
    emcmake cmake -S web -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
        -DPBRLAB_ASSIGNMENT_STEPS= >/dev/null
    cmake --build "$build" -j "$(nproc)"
    echo "build-web: the site is in $build/site (serve it: python3 -m http.server -d $build/site)"
    exit 0
fi
# The desktop's pbrlab writes the step folders: the one given, this checkout's, the one
# installed, else this checkout's built now (scripts/build.sh, as README's set-up does).
if [ -z "$pbrlab" ] && [ -x build/pbrlab ]; then pbrlab=$root/build/pbrlab; fi
[ -n "$pbrlab" ] || pbrlab=$(command -v pbrlab || true)
if [ -z "$pbrlab" ]; then
    echo "build-web: no desktop pbrlab (--pbrlab PATH, build/pbrlab or on PATH): building it"
    bash scripts/build.sh
    pbrlab=$root/build/pbrlab
fi
mkdir -p "$build"
steps=$(realpath "$build")/assignment-steps
rm -rf "$steps"
"$pbrlab" kit --assignment "$assignment" ${date:+--date "$date"} --site-steps --out "$steps"
emcmake cmake -S web -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
    -DPBRLAB_ASSIGNMENT_STEPS="$steps" >/dev/null
cmake --build "$build" -j "$(nproc)" --target assignment_site_version
echo "build-web: the assignment's site is in $build/assignment-site"
