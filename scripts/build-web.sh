#!/usr/bin/env bash
# Builds the lab for the browser (docs/web.md) into BUILD_DIR/site (default build-web/site):
# index.html, index.js, index.wasm and index.data, served as static files.
#   bash scripts/build-web.sh [BUILD_DIR]
# Installs Debian's emscripten, dpkg-dev and chromium (web/debian-packages.txt) beside
# debian-packages.txt's, and a deb-src entry for bookworm so that CMake can fetch Dear ImGui's
# source package (nothing is vendored).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=${1:-build-web}
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
emcmake cmake -S web -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$(nproc)"
echo "build-web: the site is in $build/site (serve it: python3 -m http.server -d $build/site)"
