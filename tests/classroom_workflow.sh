#!/usr/bin/env bash
# `pbrlab classroom`: the workflow parses as YAML, has one command-grader step per step of the
# assignment with that step's points and a command that fails unless the step passed, and the
# reporter reads every step's result; the committed docs/autograder/classroom.yml is what the
# command writes; and --fail-unless-passed's exit status is what the command grader reads.
# Usage: classroom_workflow.sh PBRLAB SOURCE_DIR
set -euo pipefail
pbrlab=$1
source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "== an assignment: ndf 3 points, fresnel the default 2"
cat > "$work/assignment.json" <<'JSON'
{"name": "test", "steps": ["ndf", "fresnel"], "points": {"default": 2, "ndf": 3}}
JSON
"$pbrlab" classroom --assignment "$work/assignment.json" --repository my-course/pbrlab \
    --out "$work/repo"
python3 - "$work/repo/.github/workflows/classroom.yml" <<'PY'
import sys, yaml
workflow = yaml.safe_load(open(sys.argv[1]))
steps = workflow["jobs"]["run-autograding-tests"]["steps"]
graders = [s for s in steps if s.get("uses", "").startswith("classroom-resources/autograding-command-grader@")]
assert [(s["id"], s["with"]["max-score"]) for s in graders] == [("ndf", 3), ("fresnel", 2)], graders
for s in graders:
    assert s["with"]["command"] == f"pbrlab grade . --steps {s['id']} --fail-unless-passed", s
    assert s["with"]["test-name"].startswith(s["id"] + ": "), s
reporter = steps[-1]
assert reporter["uses"].startswith("classroom-resources/autograding-grading-reporter@"), reporter
assert reporter["with"]["runners"] == "ndf,fresnel", reporter
assert reporter["env"] == {"NDF_RESULTS": "${{steps.ndf.outputs.result}}",
                           "FRESNEL_RESULTS": "${{steps.fresnel.outputs.result}}"}, reporter["env"]
assert "student" in open(sys.argv[1]).read()  # the warning that students control it
install = next(s for s in steps if s.get("name") == "Install pbrlab")
assert "git clone --depth 1 https://github.com/my-course/pbrlab.git " in install["run"], install
print("ok:", len(graders), "graders")
PY

echo "== bad points are an error naming the field"
echo '{"steps": ["ndf"], "points": {"ndf": 1.5}}' > "$work/bad.json"
if "$pbrlab" classroom --assignment "$work/bad.json" --repository my-course/pbrlab \
    --out "$work/bad" 2> "$work/err.txt"; then
    echo "fractional points accepted"; exit 1
fi
grep -q "bad.json: points.ndf" "$work/err.txt"

echo "== no --repository (or not OWNER/NAME): an error saying what to pass, nothing written"
for repository in "" "--repository my-course" "--repository a/b;rm"; do
    # shellcheck disable=SC2086  # the option and its value are two words, or none
    if "$pbrlab" classroom $repository --out "$work/norepo" 2> "$work/err.txt"; then
        echo "classroom wrote a workflow with ${repository:-no --repository}"; exit 1
    fi
    grep -q -- "--repository" "$work/err.txt"
    grep -q "OWNER/NAME" "$work/err.txt"
    test ! -e "$work/norepo/.github/workflows/classroom.yml"
done

echo "== the committed workflow is the generated one (its placeholder repository given)"
"$pbrlab" classroom --repository YOUR-ORG/pbrlab --out "$work/all"
diff -u "$source/docs/autograder/classroom.yml" "$work/all/.github/workflows/classroom.yml"
python3 -c 'import sys, yaml; yaml.safe_load(open(sys.argv[1]))' "$source/docs/autograder/classroom.yml"

echo "== --fail-unless-passed: 0 for a passing step, 1 for a failing one"
"$pbrlab" kit --with-solutions --out "$work/kit" > /dev/null
"$pbrlab" grade "$work/kit" --steps ndf --fail-unless-passed
cp "$source/labs/ndf/mistakes/alpha_is_roughness.glsl" "$work/kit/ndf.glsl"
set +e
"$pbrlab" grade "$work/kit" --steps ndf --fail-unless-passed
status=$?
set -e
test "$status" -eq 1
echo "classroom workflow: ok"
