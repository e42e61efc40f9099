#!/usr/bin/env bash
# The site in a real browser: builds it into NATIVE_BUILD/web with README's commands as written
# there (the build folder added), then headless Chromium renders every step against
# NATIVE_BUILD/pbrlab's pictures, types into the editor, reloads (web/test/site_test.mjs;
# NATIVE_BUILD/web-test), uses the page as a student does: hangs, views, fresh badges, laptop
# sizes (web/test/page_test.mjs; NATIVE_BUILD/web-page); and checks the assignment's site for
# answers (web/test/assignment_test.mjs, NATIVE_BUILD/web-assignment).
#   bash scripts/test-web.sh NATIVE_BUILD [--steps ndf,brdf]
set -euo pipefail
cd "$(dirname "$0")/.."
native=$(cd "${1:?usage: test-web.sh NATIVE_BUILD [--steps ids]}" && pwd)
shift
# README's site commands ("In a browser"), each with the build folder; the assignment's with
# this build's pbrlab when it is not the one README's default finds (build/pbrlab).
mapfile -t commands < <(sed -n '/^## In a browser/,/^## /p' README.md |
    sed -n 's/^    \(bash scripts\/build-web\.sh[^#]*\).*/\1/p')
if [ ${#commands[@]} -ne 2 ]; then
    echo "test-web: README's site commands not found (${#commands[@]} of 2)" >&2
    exit 1
fi
for command in "${commands[@]}"; do
    extra=()
    if [[ $command == *--assignment* ]] && [ "$native" != "$(pwd)/build" ]; then
        extra=(--pbrlab "$native/pbrlab")
    fi
    echo "test-web: README's command: $command"
    # shellcheck disable=SC2086 # README's words, as a shell splits them
    $command "$native/web" "${extra[@]}"
done
# Each part's output goes to the terminal and to a log; the end repeats every failed check, so
# that the tail of a long run (all a CI page may show) says what failed. A browser part that
# fails runs once more: its checks wait on a real page's timers and workers, and a machine busy
# elsewhere can miss a wait once. It passes only if the second run passes every check, and the
# first run's failures are printed either way.
logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT
failed=()
retried=()
run_part() {
    local name=$1
    shift
    if node --experimental-websocket "$@" 2>&1 | tee "$logs/$name.log"; then
        return
    fi
    echo "test-web: $name failed once; running it again"
    mv "$logs/$name.log" "$logs/$name.first.log"
    retried+=("$name")
    if ! node --experimental-websocket "$@" 2>&1 | tee "$logs/$name.log"; then
        failed+=("$name")
    fi
}
run_part site web/test/site_test.mjs --site "$native/web/site" \
    --pbrlab "$native/pbrlab" --out "$native/web-test" "$@"
run_part page web/test/page_test.mjs --site "$native/web/site" \
    --pbrlab "$native/pbrlab" --out "$native/web-page"
run_part assignment web/test/assignment_test.mjs --site "$native/web/assignment-site" \
    --full-site "$native/web/site" --steps-dir "$native/web/assignment-steps" \
    --pbrlab "$native/pbrlab" --out "$native/web-assignment"
for name in "${retried[@]}"; do
    echo "test-web: $name's first run failed these checks:"
    grep -E '^FAIL' "$logs/$name.first.log" || tail -n 5 "$logs/$name.first.log"
done
if [ ${#failed[@]} -eq 0 ]; then
    echo "test-web: every part passed${retried[*]:+ (run twice: ${retried[*]})}"
    exit 0
fi
for name in "${failed[@]}"; do
    echo "test-web: $name failed twice; its failed checks and last lines:"
    grep -E '^FAIL' "$logs/$name.log" || true
    tail -n 5 "$logs/$name.log"
done
exit 1
