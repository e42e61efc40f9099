#!/usr/bin/env bash
# The site in a real browser (web/test/site_test.mjs): builds it into NATIVE_BUILD/web, then
# headless Chromium renders every step against NATIVE_BUILD/pbrlab's pictures, types into the
# editor, reloads; screenshots and figures.json go to NATIVE_BUILD/web-test. Then an
# assignment's site (docs/autograder/assignment.json before its solutions are out) is built
# beside it and checked for answers (web/test/assignment_test.mjs, NATIVE_BUILD/web-assignment).
#   bash scripts/test-web.sh NATIVE_BUILD [--steps ndf,brdf]
set -euo pipefail
cd "$(dirname "$0")/.."
native=$(cd "${1:?usage: test-web.sh NATIVE_BUILD [--steps ids]}" && pwd)
shift
bash scripts/build-web.sh "$native/web"
bash scripts/build-web.sh "$native/web" --assignment docs/autograder/assignment.json \
    --date 2026-09-22 --pbrlab "$native/pbrlab"
failed=0
node --experimental-websocket web/test/site_test.mjs --site "$native/web/site" \
    --pbrlab "$native/pbrlab" --out "$native/web-test" "$@" || failed=1
node --experimental-websocket web/test/assignment_test.mjs --site "$native/web/assignment-site" \
    --full-site "$native/web/site" --steps-dir "$native/web/assignment-steps" \
    --pbrlab "$native/pbrlab" --out "$native/web-assignment" || failed=1
exit $failed
