#!/usr/bin/env bash
# The site in a real browser (web/test/site_test.mjs): builds it into NATIVE_BUILD/web, then
# headless Chromium renders every step against NATIVE_BUILD/pbrlab's pictures, types into the
# editor, reloads; screenshots and figures.json go to NATIVE_BUILD/web-test.
#   bash scripts/test-web.sh NATIVE_BUILD [--steps ndf,brdf]
set -euo pipefail
cd "$(dirname "$0")/.."
native=$(cd "${1:?usage: test-web.sh NATIVE_BUILD [--steps ids]}" && pwd)
shift
bash scripts/build-web.sh "$native/web"
node --experimental-websocket web/test/site_test.mjs --site "$native/web/site" \
    --pbrlab "$native/pbrlab" --out "$native/web-test" "$@"
