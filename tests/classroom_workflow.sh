#!/usr/bin/env bash
# `pbrlab classroom`: the workflow parses as YAML, has one command-grader step per step of the
# assignment with that step's points and a command that fails unless the step passed, and the
# reporter reads every step's result, whether pbrlab is built from source in a debian:bookworm
# container or installed from the grader bundle (the same grading steps); --pages writes the
# Pages workflow and the assignment it reads; the committed docs/autograder/classroom.yml is what
# the command writes; and --fail-unless-passed's exit status is what the command grader reads.
# GitHub's workflow schema and shellcheck: tests/workflow_schema.sh.
# Usage: classroom_workflow.sh PBRLAB SOURCE_DIR
set -euo pipefail
pbrlab=$1
source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
bundle_url=https://github.com/my-course/pbrlab/releases/download/v1.0/pbrlab-grader.tar.gz

echo "== an assignment: ndf 3 points, fresnel the default 2; from source, from the bundle"
cat > "$work/assignment.json" <<'JSON'
{"name": "test", "steps": ["ndf", "fresnel"], "points": {"default": 2, "ndf": 3}}
JSON
"$pbrlab" classroom --assignment "$work/assignment.json" --repository my-course/pbrlab \
    --out "$work/repo"
"$pbrlab" classroom --assignment "$work/assignment.json" --bundle-url "$bundle_url" \
    --out "$work/bundle"
python3 - "$work/repo/.github/workflows/classroom.yml" \
    "$work/bundle/.github/workflows/classroom.yml" "$bundle_url" <<'PY'
import sys, yaml
def grading(path):
    workflow = yaml.safe_load(open(path))
    assert workflow["on"] == {"push": None, "workflow_dispatch": None, "repository_dispatch": None}
    job = workflow["jobs"]["run-autograding-tests"]
    assert job["runs-on"] == "ubuntu-latest", job["runs-on"]
    assert job["if"] == "github.actor != 'github-classroom[bot]'", job["if"]
    steps = job["steps"]
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
    assert "student" in open(path).read()  # the warning that students control it
    # Before the first grader: the student's files checked out, pbrlab installed.
    first = steps.index(graders[0])
    assert any(s.get("uses", "").startswith("actions/checkout@") for s in steps[:first]), steps
    return job, steps[:first], steps[first:]

def caches(steps):
    """{path: restore step} of steps' caches, each checked to have its save step later (the same
    path and key, keyed by pbrlab's version): the package saved right after it is built (the job
    has not failed yet there), pbrlab's grading cache after the graders whatever they found (the
    reporter fails the job on a failed test, and a failed job would save nothing)."""
    saved_when = {"/opt/pbrlab/deb": "steps.{}.outputs.cache-hit != 'true'",
                  "~/.cache/pbrlab": "always() && steps.{}.outputs.cache-hit != 'true'"}
    restores = {s["with"]["path"]: s for s in steps
                if s.get("uses", "").startswith("actions/cache/restore@")}
    for path, r in restores.items():
        assert r["with"]["key"].endswith("-${{ steps.pbrlab.outputs.version }}"), r
        save = next(s for s in steps if s.get("uses", "").startswith("actions/cache/save@")
                    and s["with"] == r["with"])
        assert save["if"] == saved_when[path].format(r["id"]), save
        assert steps.index(save) > steps.index(r), steps
    return restores

job, install, graded = grading(sys.argv[1])
assert job["container"] == "debian:bookworm", job
fetch = next(s for s in install if s.get("id") == "pbrlab")
assert fetch["env"] == {"PBRLAB_SOURCE": "https://github.com/my-course/pbrlab.git",
                        "PBRLAB_REF": "HEAD"}, fetch
assert 'fetch -q --depth 1 "$PBRLAB_SOURCE" "$PBRLAB_REF"' in fetch["run"], fetch
assert 'echo "version=$(git -C' in fetch["run"], fetch
cached = caches(job["steps"])
assert sorted(cached) == ["/opt/pbrlab/deb", "~/.cache/pbrlab"], cached
build = next(s for s in install if s.get("name") == "Install pbrlab")
assert "scripts/install-deps.sh" in build["run"] and "cpack -G DEB" in build["run"], build
assert "/opt/pbrlab/deb/pbrlab_*.deb" in build["run"], build
assert graded[-2]["uses"].startswith("actions/cache/save@"), graded[-2]  # after the last grader

bundle_job, bundle_install, bundle_graded = grading(sys.argv[2])
assert "container" not in bundle_job, bundle_job  # the runner as it is
assert bundle_graded == graded  # the same grading, reporter included
download = next(s for s in bundle_install if s.get("name", "").startswith("Install pbrlab"))
assert download["env"] == {"PBRLAB_BUNDLE_URL": sys.argv[3]}, download
assert '"$RUNNER_TEMP/pbrlab/bin" >> "$GITHUB_PATH"' in download["run"], download
assert download["id"] == "pbrlab" and 'echo "version=$(sha256sum' in download["run"], download
assert list(caches(bundle_job["steps"])) == ["~/.cache/pbrlab"], bundle_job
print("ok:", len(graded) - 1, "graders, from source and from the bundle")
PY

echo "== --ref: the branch or tag fetched"
"$pbrlab" classroom --steps ndf --repository my-course/pbrlab --ref release/2026 --out "$work/ref"
grep -q 'PBRLAB_REF: "release/2026"' "$work/ref/.github/workflows/classroom.yml"

echo "== --pages: pages.yml, which builds the site for a copy of the assignment"
"$pbrlab" classroom --assignment "$work/assignment.json" --bundle-url "$bundle_url" \
    --repository my-course/pbrlab --pages --out "$work/pages"
cmp "$work/assignment.json" "$work/pages/.github/pbrlab/assignment.json"
python3 - "$work/pages/.github/workflows/pages.yml" <<'PY'
import re, sys, yaml
workflow = yaml.safe_load(open(sys.argv[1]))
build, deploy = workflow["jobs"]["build"], workflow["jobs"]["deploy"]
assert "github.event.repository.is_template" in build["if"], build["if"]  # not in students' copies
assert build["container"] == "debian:bookworm", build
steps = build["steps"]
fetch = next(s for s in steps if s.get("id") == "pbrlab")  # the source, even with a bundle
assert fetch["env"]["PBRLAB_SOURCE"] == "https://github.com/my-course/pbrlab.git", fetch
site = next(s for s in steps if s.get("name") == "Build the site")
m = re.search(r'build-web\.sh (\S+) \\\s+--assignment "\$GITHUB_WORKSPACE/\.github/pbrlab/assignment\.json"',
              site["run"])
assert m, site["run"]
upload = steps[-1]
assert upload["uses"].startswith("actions/upload-pages-artifact@"), upload
assert upload["with"]["path"] == m.group(1) + "/assignment-site", upload  # what build-web.sh writes
assert workflow["permissions"] == {"contents": "read"}, workflow["permissions"]
assert deploy["needs"] == "build", deploy
assert deploy["permissions"] == {"pages": "write", "id-token": "write"}, deploy
assert deploy["environment"]["name"] == "github-pages", deploy
assert deploy["steps"][-1]["uses"].startswith("actions/deploy-pages@"), deploy
print("ok: pages")
PY
grep -q 'assignment-site' "$source/scripts/build-web.sh"

echo "== refused, nothing written: --pages without an assignment or the source; a bad URL or ref"
refused() {  # EXPECTED_MESSAGE ARGS...
    local expected=$1
    shift
    rm -rf "$work/refused"
    if "$pbrlab" classroom "$@" --out "$work/refused" 2> "$work/err.txt"; then
        echo "classroom accepted $*"; exit 1
    fi
    grep -qF -- "$expected" "$work/err.txt" || { cat "$work/err.txt"; exit 1; }
    test ! -e "$work/refused"
}
refused "--pages: pass --assignment" --repository my-course/pbrlab --pages
refused "--pages builds the site from pbrlab's source" --assignment "$work/assignment.json" \
    --bundle-url "$bundle_url" --pages
refused "expected the https URL" --bundle-url "http://example.org/pbrlab.tar.gz"
# shellcheck disable=SC2016  # an Actions expression, as pasted
refused "expected the https URL" --bundle-url 'https://example.org/${{github.token}}.tar.gz'
refused "expected the https URL" --bundle-url 'https://example.org/a b.tar.gz'
refused "expected a branch or tag" --repository my-course/pbrlab --ref '-u'
refused "expected a branch or tag" --repository my-course/pbrlab --ref 'v1;rm -rf /'
refused "expected a branch or tag" --repository my-course/pbrlab --ref 'a..b'

echo "== bad points are an error naming the field"
echo '{"steps": ["ndf"], "points": {"ndf": 1.5}}' > "$work/bad.json"
if "$pbrlab" classroom --assignment "$work/bad.json" --repository my-course/pbrlab \
    --out "$work/bad" 2> "$work/err.txt"; then
    echo "fractional points accepted"; exit 1
fi
grep -q "bad.json: points.ndf" "$work/err.txt"

echo "== no --repository nor --bundle-url (or not OWNER/NAME): an error saying what to pass"
for repository in "" "--repository my-course" "--repository a/b;rm"; do
    # shellcheck disable=SC2086  # the option and its value are two words, or none
    if "$pbrlab" classroom $repository --out "$work/norepo" 2> "$work/err.txt"; then
        echo "classroom wrote a workflow with ${repository:-no --repository}"; exit 1
    fi
    grep -q -- "--repository" "$work/err.txt"
    grep -q "OWNER/NAME" "$work/err.txt"
    [ -n "$repository" ] || grep -q -- "--bundle-url" "$work/err.txt"
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
