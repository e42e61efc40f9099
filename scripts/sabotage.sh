#!/usr/bin/env bash
# The suite checked by sabotage (docs/grading.md, "The suite checked by sabotage"): in a scratch
# copy of this tree, each sabotage below breaks one thing the grader promises (a one-line
# change, found exactly once or it is an error, never a silent pass), the copy is rebuilt, and
# the tests named for that sabotage run; at least one of them must fail. The named tests must
# pass on the copy before any sabotage (a test that fails anyway proves nothing). Prints the
# table sabotage -> tests that caught it; exit 1 when a sabotage went unnoticed.
#
# Usage: scripts/sabotage.sh [--list | --check] [NAME ...]     (no NAME: every sabotage)
#   --check: only that each sabotage still applies to this tree (its text found exactly once),
#            nothing built; the default test run does this (Sabotage.EveryBreakStillApplies)
#   SABOTAGE_DIR        where the scratch copy (tree/) and its build (tree/build) go (default
#                       build/sabotage): kept between runs, at a fixed path, so that a second
#                       run rebuilds only what changed
#   SABOTAGE_JOBS       build jobs (default 1)
#   SABOTAGE_BUILD_TYPE CMAKE_BUILD_TYPE of the scratch build (default RelWithDebInfo)
# Run by `ctest -C sabotage -L sabotage` (tests/CMakeLists.txt; not in the default run).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
work=${SABOTAGE_DIR:-$here/build/sabotage}
jobs=${SABOTAGE_JOBS:-1}
build_type=${SABOTAGE_BUILD_TYPE:-RelWithDebInfo}
tree=$work/tree
# The build inside the copy, as build/ is inside this tree: the compiler sees the same relative
# paths (../../core/...), which ccache's base_dir rewriting needs to hit at all. The first
# run still compiles most files (their -DPBRLAB_SOURCE_DIR names the copy); later runs hit.
obj=$tree/build

# ---- the sabotages ------------------------------------------------------------------------
# sabotage NAME WHAT FILE TEXT REPLACEMENT TESTS: in FILE, TEXT (found exactly once) becomes
# REPLACEMENT; TESTS is a --gtest_filter whose tests must notice. Each catching test is chosen
# for what it asserts, and the cheapest that does (their time: docs/grading.md).
names=() whats=() files=() texts=() replacements=() filters=()
sabotage() {
    names+=("$1") whats+=("$2") files+=("$3") texts+=("$4") replacements+=("$5") filters+=("$6")
}

sabotage band-always-passes \
    "every value check passes: compareWithBand's excess forced to 0" \
    core/render/compare.cpp \
    'const double excess = band.excess(i, v, components);' \
    'const double excess = 0 * band.excess(i, v, components);' \
    'Labs/VariantTest.*/fresnel_mistake_pow6:Grade.InvariantsAreMeasuredOnTheStudentsFunctionAndDeduct'
sabotage band-enormous \
    "the pass band made enormous (bandAt's slack x 1e6)" \
    core/render/compare.cpp \
    '    band.slack[i] = slack;' \
    '    band.slack[i] = slack * 1e6;' \
    'Labs/VariantTest.*/fresnel_mistake_pow*'
sabotage estimator-band-always-passes \
    "an estimator's values checks against the converged integral always pass" \
    core/grading/estimator_band.cpp \
    '    run.report.category = CheckCategory::Estimator;' \
    '    run.report.category = CheckCategory::Estimator;
    run.report.passed = true;' \
    'EstimatorBand.*'
sabotage naming-off \
    "typical mistakes never named (typicalMistake returns \"\")" \
    core/grading/failure_message.cpp \
    'std::string StepGrader::typicalMistake(const ValuesRun& f, const Sample& sample) {' \
    'std::string StepGrader::typicalMistake(const ValuesRun& f, const Sample& sample) {
    return "";' \
    'Grade.EachProblemCostsOnlyItsOwnStep'
sabotage pattern-naming-off \
    "the mistake never named from the shape of the error (classifyError returns \"\")" \
    core/grading/error_patterns.cpp \
    '    exact = true;  // every pattern below explains every point, but the last ones' \
    '    exact = false;
    return "";' \
    'Feedback.*:Grade.InvariantsAreMeasuredOnTheStudentsFunctionAndDeduct'
sabotage invariants-never-deduct \
    "a failed invariant is reported and not deducted" \
    core/grading/checks.cpp \
    '        c.passed = inv.holds;' \
    '        c.passed = inv.holds;
        c.deducted = false;' \
    'Grade.InvariantsAreMeasuredOnTheStudentsFunctionAndDeduct'
sabotage screening-off \
    "the screening of a student's file refuses nothing (private helpers, host macros, ##, loops, comments)" \
    core/shader/preprocess.cpp \
    '            throw ShaderError(name + ":" + std::to_string(line) + ": error: " + why);' \
    '            (void)line, (void)why;' \
    'Preprocessor.AStudents*'
sabotage student-macros-leak \
    "a student's macros are not #undef'd after its file" \
    core/shader/preprocess.cpp \
    '        for (const std::string& macro : studentMacros) out.text += "#undef " + macro + "\n";' \
    '        for (const std::string& macro : studentMacros) (void)macro;' \
    'Preprocessor.AStudentsMacrosEndWithItsFile'
sabotage gradescope-total-wrong \
    "Gradescope's total is the sum of the rows' maxima, not of their scores" \
    core/course/gradescope.cpp \
    'for (const json& t : tests) score = addPoints(score, t["score"].get<double>());' \
    'for (const json& t : tests) score = addPoints(score, t["max_score"].get<double>());' \
    'Assignment.PartialCreditIsTheWeightsShareOfTheChecksPassedOnceOneShowsWork'
sabotage visibility-ignored \
    "every Gradescope row visible, whatever the assignment says" \
    core/course/gradescope.cpp \
    '{"visibility", a.visibilityOf(g.id, category)},' \
    '{"visibility", "visible"},' \
    'Assignment.PartialCreditIsTheWeightsShareOfTheChecksPassedOnceOneShowsWork'
sabotage partial-credit-inverted \
    "partial credit inverted: passed checks earn before a values check shows work, not after" \
    core/course/assignment.cpp \
    '            s.earning += passed && workShown;' \
    '            s.earning += passed && !workShown;' \
    'Assignment.PartialCreditIsTheWeightsShareOfTheChecksPassedOnceOneShowsWork'
sabotage work-gate-off \
    "passed checks earn points before any values check shows work (the stub's checks score)" \
    core/course/assignment.cpp \
    '        workShown = workShown || (check.value("shows_work", false) && check.value("passed", false));' \
    '        workShown = workShown || !check.is_null();' \
    'Assignment.PartialCreditIsTheWeightsShareOfTheChecksPassedOnceOneShowsWork'
sabotage contract-failure-scores \
    "a failed contract check no longer zeroes the step's partial credit" \
    core/course/assignment.cpp \
    '            if (c == CheckCategory::Contract && !check.value("passed", false)) return {};' \
    '            if (c == CheckCategory::Contract && !check.value("passed", false)) continue;' \
    'Assignment.AFailedContractCheckScoresTheStepZero'
sabotage release-ignored \
    "the kit hands out every step whatever the release dates" \
    core/course/assignment.cpp \
    '        o.steps.erase(std::find(o.steps.begin(), o.steps.end(), through) + 1, o.steps.end());' \
    '        (void)through;' \
    'Assignment.TheReleaseScheduleDecidesWhatTheKitHandsOut'
sabotage robustness-deducted \
    "the extreme-input sweep deducts (it is reported, not deducted, unless weighted)" \
    core/grading/checks.cpp \
    '    c.deducted = false;' \
    '    c.deducted = true;' \
    'Labs/VariantTest.*/ndf_correct_correct_lesson'

# ---- helpers ------------------------------------------------------------------------------
list() {
    for k in "${!names[@]}"; do printf '%-30s %s\n' "${names[$k]}" "${whats[$k]}"; done
}
if [ "${1:-}" = --list ]; then list; exit 0; fi
check=false
if [ "${1:-}" = --check ]; then check=true; shift; fi
chosen=("$@")
if [ ${#chosen[@]} -eq 0 ]; then chosen=("${names[@]}"); fi
index() {
    for k in "${!names[@]}"; do if [ "${names[$k]}" = "$1" ]; then echo "$k"; return; fi; done
    echo "no sabotage named $1 (--list)" >&2
    exit 2
}
for n in "${chosen[@]}"; do index "$n" > /dev/null; done

# The scratch copy follows this tree (tracked and untracked files, as git sees them): only the
# files that differ are copied, with a new time, so make rebuilds what changed (and undoes the
# previous sabotage).
sync_tree() {
    mkdir -p "$tree"
    local f inside=${work#"$here"/}
    while IFS= read -r -d '' f; do
        # (The scratch copy itself, where its folder is inside this tree and not ignored.)
        if [ "$inside" != "$work" ] && [ "${f#"$inside"/}" != "$f" ]; then continue; fi
        if [ -f "$here/$f" ] && ! cmp -s "$here/$f" "$tree/$f"; then
            mkdir -p "$(dirname "$tree/$f")"
            cp "$here/$f" "$tree/$f"
        fi
    done < <(git -C "$here" ls-files -z -co --exclude-standard)
    # ../shared (reference data some tests read), where this tree has one.
    if [ -d "$here/../shared" ] && [ ! -e "$work/shared" ]; then
        ln -s "$here/../shared" "$work/shared"
    fi
}
# replace PATH TEXT [REPLACEMENT]: TEXT, found exactly once in PATH (else an error saying how
# often), becomes REPLACEMENT; without one, PATH is left as it is.
replace() {
    python3 - "$@" <<'PY'
import sys
path, text = sys.argv[1:3]
source = open(path).read()
count = source.count(text)
if count != 1:
    sys.exit(f"sabotage does not apply: found {count} times (not once) in {path}:\n  {text}")
if len(sys.argv) > 3:
    open(path, "w").write(source.replace(text, sys.argv[3]))
PY
}
apply() {  # FILE TEXT REPLACEMENT
    replace "$tree/$1" "$2" "$3" || exit 2
}
if $check; then
    stale=0
    for n in "${chosen[@]}"; do
        k=$(index "$n")
        replace "$here/${files[$k]}" "${texts[$k]}" || { echo "  (sabotage $n)" >&2; stale=1; }
    done
    [ $stale -eq 0 ] && echo "${#chosen[@]} sabotages apply to this tree"
    exit $stale
fi
build() {
    local launcher=()
    if command -v ccache > /dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
    if [ ! -f "$obj/CMakeCache.txt" ]; then
        cmake -S "$tree" -B "$obj" -DCMAKE_BUILD_TYPE="$build_type" -DPBRLAB_BUILD_BENCHMARKS=OFF \
            "${launcher[@]}" > /dev/null
    fi
    cmake --build "$obj" -j"$jobs" "$@" > "$work/build.log" 2>&1 ||
        { tail -30 "$work/build.log"; echo "sabotage: the build failed" >&2; exit 2; }
}
tests_of() {  # FILTER: the tests it selects, one full name per line
    "$obj/tests/pbrlab_tests" --gtest_list_tests --gtest_filter="$1" |
        awk '/^[^ ]/ { suite = $1 } /^  / { print suite $1 }'
}
run_tests() {  # FILTER LOG: 0 when every test passed; the failed ones in LOG.failed
    # Each test in a process of its own, as ctest runs them: a test that holds a GL context
    # would otherwise be inherited by the grader's forks of the tests after it, and hang them.
    local name code
    : > "$2"
    : > "$2.failed"
    while IFS= read -r name; do
        code=0
        (cd "$obj/tests" &&
            timeout 900 ./pbrlab_tests --gtest_filter="$name" < /dev/null >> "$2" 2>&1) ||
            code=$?
        case $code in
            0) ;;
            1) echo "$name" >> "$2.failed" ;;
            124) echo "$name (timed out)" >> "$2.failed" ;;
            *) echo "$name (exit $code)" >> "$2.failed" ;;
        esac
    done < <(tests_of "$1")
    [ ! -s "$2.failed" ]
}
failed_tests() {  # LOG: the tests that failed, one per line, without the suite's prefix
    sed 's#^Labs/VariantTest\.[^/]*/#VariantTest/#' "$1.failed"
}

# ---- baseline: the copy as it is, every catching test passes ------------------------------
export PBRLAB_CACHE=$work/caches/pbrlab MESA_SHADER_CACHE_DIR=$work/caches/mesa \
    XDG_CACHE_HOME=$work/caches/xdg-cache
start=$(date +%s)
echo "== scratch copy: $tree"
sync_tree
build
union=""
for n in "${chosen[@]}"; do
    k=$(index "$n")
    # Each pattern names at least one test (a typo would make the sabotage look caught by none,
    # or, worse, leave it unrun).
    IFS=: read -r -a patterns <<< "${filters[$k]}"
    for p in "${patterns[@]}"; do
        if [ -z "$(tests_of "$p")" ]; then
            echo "sabotage $n: no test matches $p" >&2
            exit 2
        fi
    done
    union+="${union:+:}${filters[$k]}"
done
echo "== baseline: the catching tests on the unsabotaged copy"
if ! run_tests "$union" "$work/baseline.log"; then
    failed_tests "$work/baseline.log" | sed 's/^/  failed: /'
    echo "sabotage: the catching tests fail before any sabotage ($work/baseline.log)" >&2
    exit 2
fi
echo "   passed ($(($(date +%s) - start)) s so far)"

# ---- each sabotage ------------------------------------------------------------------------
table="| sabotage | file | tests that caught it | seconds |\n|---|---|---|---|\n"
missed=()
for n in "${chosen[@]}"; do
    k=$(index "$n")
    t0=$(date +%s)
    echo "== $n: ${whats[$k]}"
    sync_tree  # undoes the previous one
    apply "${files[$k]}" "${texts[$k]}" "${replacements[$k]}"
    build --target pbrlab_tests
    caught=""
    if ! run_tests "${filters[$k]}" "$work/$n.log"; then
        caught=$(failed_tests "$work/$n.log" | paste -sd, - | sed 's/,/, /g')
        [ -n "$caught" ] || caught="(the test program failed: $work/$n.log)"
    fi
    seconds=$(($(date +%s) - t0))
    if [ -n "$caught" ]; then
        echo "   caught by: $caught"
    else
        echo "   NOT CAUGHT by ${filters[$k]}"
        missed+=("$n")
        caught="**none** (${filters[$k]})"
    fi
    table+="| $n | ${files[$k]#core/} | $caught | $seconds |\n"
done
sync_tree  # the copy as this tree is again (its build catches up on the next run)

echo
printf '%b' "$table"
echo
echo "$((${#chosen[@]} - ${#missed[@]})) of ${#chosen[@]} sabotages caught in $(($(date +%s) - start)) s"
if [ ${#missed[@]} -gt 0 ]; then
    echo "not caught: ${missed[*]}" >&2
    exit 1
fi
