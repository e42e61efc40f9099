#!/usr/bin/env bash
# The workflows `pbrlab classroom` writes (classroom.yml from source and from the grader bundle,
# pages.yml, and the committed docs/autograder/classroom.yml) pass GitHub's workflow parser
# (tests/workflow_schema/validate.mjs, @actions/workflow-parser pinned by its package-lock.json,
# installed here with npm ci), and their shell scripts pass shellcheck; broken workflows and a
# broken script are rejected, naming what is wrong. Then the bundle path's install script runs
# as the workflow runs it, on a bundle of this build: the bundle's pbrlab on PATH grades
# a step.
# Usage: workflow_schema.sh PBRLAB SOURCE_DIR BINARY_DIR GRADER_BUNDLE_DIR
# shellcheck disable=SC2016  # the ${{ }} and $VAR in single quotes are workflow text, not shell
set -euo pipefail
pbrlab=$(realpath "$1")
source=$(realpath "$2")
tools=$(realpath "$3")/workflow-schema
bundle=$(realpath "$4")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

echo "== GitHub's workflow parser, as the lock file pins it"
command -v npm > /dev/null ||
    bash "$source/scripts/install-deps.sh" "$source/tests/workflow_schema/debian-packages.txt"
mkdir -p "$tools"
cp "$source/tests/workflow_schema/validate.mjs" "$tools/"
if ! cmp -s "$source/tests/workflow_schema/package-lock.json" "$tools/package-lock.json" ||
    [ ! -d "$tools/node_modules/@actions/workflow-parser" ]; then
    cp "$source/tests/workflow_schema/package.json" "$source/tests/workflow_schema/package-lock.json" \
        "$tools/"
    (cd "$tools" && npm ci --no-audit --no-fund --loglevel=error)
fi
validate() { node "$tools/validate.mjs" "$@"; }

echo "== the generated workflows"
cat > "$work/assignment.json" <<'JSON'
{"name": "test", "steps": ["ndf", "fresnel"], "points": {"default": 2, "ndf": 3}}
JSON
"$pbrlab" classroom --assignment "$work/assignment.json" --repository my-course/pbrlab \
    --ref v1.0 --pages --out "$work/source"
"$pbrlab" classroom --assignment "$work/assignment.json" \
    --bundle-url https://github.com/my-course/pbrlab/releases/download/v1.0/pbrlab-grader.tar.gz \
    --out "$work/bundle"
good=("$work/source/.github/workflows/classroom.yml" "$work/source/.github/workflows/pages.yml"
      "$work/bundle/.github/workflows/classroom.yml" "$source/docs/autograder/classroom.yml")
validate "${good[@]}"

echo "== broken workflows are rejected, naming the mistake"
classroom=$work/source/.github/workflows/classroom.yml
pages=$work/source/.github/workflows/pages.yml
broken() {  # NAME FILE SED_EXPRESSION EXPECTED_MESSAGE
    sed "$3" "$2" > "$work/$1.yml"
    cmp -s "$2" "$work/$1.yml" && fail "$1: the edit changed nothing"
    if validate "$work/$1.yml" > "$work/$1.txt"; then
        cat "$work/$1.txt"; fail "$1: accepted"
    fi
    grep -qF -- "$4" "$work/$1.txt" || { cat "$work/$1.txt"; fail "$1: not '$4'"; }
    echo "rejected $1: $(head -1 "$work/$1.txt")"
}
broken runs-on "$classroom" 's/^    runs-on:/    runs_on:/' "Required property is missing: runs-on"
broken permission "$classroom" 's/^  checks: write/  checks: always/' "Unexpected value 'always'"
broken event "$classroom" 's/^  workflow_dispatch:/  workflow-dispatch:/' \
    "Unexpected value 'workflow-dispatch'"
broken expression "$classroom" 's/\(NDF_RESULTS: "${{steps.ndf.outputs.result\)}}/\1}/' \
    "The expression is not closed"
broken step "$classroom" 's/^        uses: actions\/checkout@v4/        use: actions\/checkout@v4/' \
    "Unexpected value 'use'"
broken needs "$pages" 's/^    needs: build/    needs: bulid/' "bulid"
broken context "$pages" 's/url: ${{ steps.deployment/url: ${{ step.deployment/' \
    "Unrecognized named-value: 'step'"

echo "== every run script passes shellcheck (a broken one does not)"
python3 - "$work/scripts" "${good[@]}" <<'PY'
import os, re, sys, yaml
out = sys.argv[1]
os.makedirs(out)
for n, path in enumerate(sys.argv[2:]):
    for job_id, job in yaml.safe_load(open(path))["jobs"].items():
        for k, step in enumerate(job["steps"]):
            if "run" in step:
                # An expression is replaced by the text it stands for, a plain word.
                script = re.sub(r"\$\{\{.*?\}\}", "expression", step["run"])
                with open(f"{out}/{n}-{job_id}-{k}.sh", "w") as f:
                    f.write("#!/usr/bin/env bash\nset -eo pipefail\n" + script)
PY
ls "$work/scripts"/*.sh > /dev/null
shellcheck "$work/scripts"/*.sh
printf '#!/usr/bin/env bash\nmkdir -p $RUNNER_TEMP/pbrlab\n' > "$work/unquoted.sh"
if shellcheck "$work/unquoted.sh" > /dev/null; then fail "shellcheck passed an unquoted path"; fi

echo "== the bundle path's install step, run as the workflow runs it"
# The real bundle of this build (scripts/grader-bundle.sh), packed as its --tarball packs it.
tar -czf "$work/bundle.tar.gz" -C "$(dirname "$bundle")" "$(basename "$bundle")"
python3 - "$work/bundle/.github/workflows/classroom.yml" "$work/install.sh" <<'PY'
import sys, yaml
steps = yaml.safe_load(open(sys.argv[1]))["jobs"]["run-autograding-tests"]["steps"]
install = next(s for s in steps if s.get("name", "").startswith("Install pbrlab"))
open(sys.argv[2], "w").write(install["run"])
PY
mkdir -p "$work/runner"
: > "$work/github_path"
: > "$work/github_output"
RUNNER_TEMP=$work/runner GITHUB_PATH=$work/github_path GITHUB_OUTPUT=$work/github_output \
    PBRLAB_BUNDLE_URL=file://$work/bundle.tar.gz bash -eo pipefail "$work/install.sh"
test "$(cat "$work/github_path")" = "$work/runner/pbrlab/bin" ||
    fail "GITHUB_PATH: $(cat "$work/github_path")"
# The grading cache's key: the bundle's checksum.
test "$(cat "$work/github_output")" = "version=$(sha256sum "$work/bundle.tar.gz" | cut -c1-16)" ||
    fail "GITHUB_OUTPUT: $(cat "$work/github_output")"
"$pbrlab" kit --with-solutions --out "$work/kit" > /dev/null
# In the student's folder, with the environment the command grader gives (PATH and HOME).
(cd "$work/kit" && env -i PATH="$(cat "$work/github_path"):/usr/bin:/bin" HOME="$HOME" \
    pbrlab grade . --steps ndf --fail-unless-passed > /dev/null)
echo "workflow schema: ok"
