#!/usr/bin/env bash
# The autograder zip graded as Gradescope grades it, on a system that has none of pbrlab's
# libraries: a minimal root file system (debootstrap --variant=minbase: Debian 12 "bookworm",
# or Ubuntu 22.04 "jammy", Gradescope's default base image), entered with chroot in a mount
# namespace of its own. The zip (`pbrlab autograder` with the grader bundle) is unpacked into
# its /autograder/source; setup.sh runs there (it installs nothing), then run_autograder on the
# reference solutions and on a wrong submission (a compile error, ndf's alpha = roughness,
# fresnel's pow6), and each results.json must be the one the native build writes for the same
# submission (pbrlab_gradescope_check --same-as: everything but the time taken). And every
# library pbrlab loads there, OSMesa's included, comes from the bundle or is glibc's own
# (LD_DEBUG=libs on a grade in the root).
# The root is made once and kept in ~/.cache/pbrlab/bare-roots/SUITE (PBRLAB_BARE_ROOTS
# instead), read-only to the test: what a run writes goes to mounts that vanish with it.
# Needs root (chroot, mounts; CI runs as root) and, the first time, the distribution's mirror:
# without either it says so and exits 77, which ctest reports as skipped, not passed.
# tests/fixtures/ubuntu-archive-keyring.gpg verifies Ubuntu's mirror: Ubuntu's archive signing
# keys (2012, and 2018: F6EC B376 2474 EDA9 D21B 7022 8719 20D1 991B C93C, which signs jammy), as
# the ubuntu-keyring package 2021.03.26 ships them; Debian 12 has no package of them, and the
# keys are under no copyright (that package's copyright file).
# Usage: grader_bare_system.sh SUITE BUNDLE_DIR BUILD_DIR RESULTS_CHECKER
set -euo pipefail
suite=$1
bundle=$(cd "$2" && pwd)
build=$(cd "$3" && pwd)
check=$4
here=$(cd "$(dirname "$0")" && pwd)
skip=77
case $suite in
    bookworm) mirror=http://deb.debian.org/debian keyring="" name="Debian 12" ;;
    jammy) mirror=http://archive.ubuntu.com/ubuntu name="Ubuntu 22.04"
           keyring=$here/fixtures/ubuntu-archive-keyring.gpg ;;
    *) echo "grader_bare_system: no suite $suite (bookworm, jammy)" >&2; exit 2 ;;
esac
roots=${PBRLAB_BARE_ROOTS:-${HOME:-/root}/.cache/pbrlab/bare-roots}
root=$roots/$suite
if [ "$(id -u)" -ne 0 ]; then
    echo "SKIPPED: the bare-system test needs root (chroot and mounts); the grader bundle was" \
         "NOT tested on a bare $name"
    exit $skip
fi

# The root, made once: in a folder of its own, renamed when complete, under a lock (two test
# runs at once make it once).
mkdir -p "$roots"
exec 9> "$roots/$suite.lock"
flock 9
if [ ! -f "$root/.pbrlab-complete" ]; then
    if ! wget -q -T 20 -t 2 -O /dev/null "$mirror/dists/$suite/InRelease"; then
        echo "SKIPPED: $mirror cannot be reached from here, and no $name root is cached in" \
             "$root: the grader bundle was NOT tested on a bare $name"
        exit $skip
    fi
    echo "== debootstrap --variant=minbase $suite (once: cached in $root)"
    rm -rf "$root.partial"
    start=$(date +%s)
    # Its own mount namespace: debootstrap mounts /proc and /sys in the root, and a failed run
    # would leave them mounted.
    if ! unshare --mount --propagation private \
            debootstrap --variant=minbase ${keyring:+--keyring="$keyring"} "$suite" \
            "$root.partial" "$mirror" > "$roots/$suite.log" 2>&1; then
        tail -20 "$roots/$suite.log"
        echo "debootstrap of $suite failed (log: $roots/$suite.log)"
        exit 1
    fi
    mkdir -p "$root.partial/autograder"
    rm -rf "$root"
    mv "$root.partial" "$root"
    touch "$root/.pbrlab-complete"
    echo "made in $(($(date +%s) - start)) s: $(du -sm "$root" | cut -f1) MB"
fi
flock -u 9
. "$root/etc/os-release"
echo "== in $PRETTY_NAME, glibc $(ls "$root"/usr/lib/x86_64-linux-gnu/libc.so.6 > /dev/null &&
    chroot "$root" /usr/bin/ldd --version | awk 'NR == 1 {print $NF}')"
# None of pbrlab's libraries (nor OSMesa's) is on that system.
for lib in libOSMesa.so.8 libLLVM-15.so.1 libpng16.so.16 libOpenEXRCore-3_1.so.30 libglfw.so.3; do
    if [ -n "$(find "$root/usr/lib" "$root/lib" -name "$lib" -print -quit 2>/dev/null)" ]; then
        echo "$lib is in the $name root: it is not bare"
        exit 1
    fi
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
now() { echo $(($(date +%s%N) / 1000000)); }  # ms
since() { local ms=$(($(now) - $1)); echo "$((ms / 1000)).$((ms % 1000 / 100)) s"; }
cat > "$work/assignment.json" <<'JSON'
{
  "name": "bare system test",
  "steps": ["ndotl", "ndf", "fresnel"],
  "points": {"ndf": 3},
  "checks": {"contract": 1, "probe": 2, "scenes": 2, "random": 2, "sphere_grid": 1,
             "invariants": 2},
  "time_limit_seconds": 120
}
JSON
echo "== pbrlab autograder"
"$bundle/bin/pbrlab" autograder --assignment "$work/assignment.json" --out "$work/zip" \
    --bundle "$bundle"
mkdir -p "$work/autograder/source"
unzip -q "$work/zip/autograder.zip" -d "$work/autograder/source"

# in_root COMMAND: runs COMMAND with /bin/sh in the root, as root with nothing of this
# environment, /autograder the test's folder; /proc, /tmp and /root are fresh mounts.
in_root() {
    unshare --mount --propagation private --pid --fork sh -c '
        set -e
        root=$1 autograder=$2
        mount --bind "$autograder" "$root/autograder"
        mount -t proc proc "$root/proc"
        mount -t tmpfs tmpfs "$root/tmp"
        mount -t tmpfs tmpfs "$root/root"
        exec chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root \
            /bin/sh -c "$3"' in_root "$root" "$work/autograder" "$1"
}

# Gradescope copies run_autograder to /autograder and runs setup.sh from the source folder.
cp "$work/autograder/source/run_autograder" "$work/autograder/run_autograder"
echo "== setup.sh"
start=$(now)
in_root "cd /autograder/source && ./setup.sh" > "$work/setup.log" 2>&1 ||
    { cat "$work/setup.log"; echo "setup.sh failed in the $name root"; exit 1; }
tail -1 "$work/setup.log"
echo "setup.sh: $(since "$start")"

echo "== the submissions"
"$bundle/bin/pbrlab" kit --assignment "$work/assignment.json" --with-solutions \
    --out "$work/solutions" > /dev/null
cp -r "$work/solutions" "$work/wrong"
labs=$bundle/share/pbrlab/labs
printf 'vec3 ndotl(vec3 n, vec3 l) { return not glsl; }\n' > "$work/wrong/ndotl.glsl"
cp "$labs/ndf/mistakes/alpha_is_roughness.glsl" "$work/wrong/ndf.glsl"
cp "$labs/fresnel/mistakes/pow6.glsl" "$work/wrong/fresnel.glsl"

# The native build's results for the same files (its own caches: nothing shared with the root).
native_cache=$work/native-cache
for sub in solutions wrong; do
    PBRLAB_CACHE=$native_cache "$build/pbrlab" grade "$work/$sub" \
        --assignment "$work/assignment.json" --gradescope "$work/$sub.native.json" > /dev/null
done

grade_in_root() {  # NAME EXPECTED_SCORE
    rm -rf "$work/autograder/submission" "$work/autograder/results"
    cp -r "$work/$1" "$work/autograder/submission"
    start=$(now)
    in_root "cd /autograder && ./run_autograder" > "$work/$1.log" 2>&1 ||
        { cat "$work/$1.log"; echo "run_autograder failed in the $name root"; exit 1; }
    echo "run_autograder ($1): $(since "$start")"
    # The submission's folder is named in some messages: the same name on both sides.
    sed "s#/autograder/submission#SUBMISSION#g" "$work/autograder/results/results.json" \
        > "$work/$1.root.json"
    sed "s#$work/$1#SUBMISSION#g" "$work/$1.native.json" > "$work/$1.native-named.json"
    "$check" "$work/$1.root.json" "$2" --same-as "$work/$1.native-named.json"
}
# The solutions: every point. Wrong: ndotl 0 (compile error), ndf 0 (no values check passes),
# fresnel 1 x (contract 1 + scenes 2 x 1/4 + invariants 2) / 10 = 0.35.
grade_in_root solutions 5
grade_in_root wrong 0.35
grep -q '"compile_error"' "$work/autograder/results/results.json" ||
    { echo "the wrong submission's ndotl is no compile error"; exit 1; }

echo "== where the libraries come from"
# Every library a grade loads (the parent and its grading child: OSMesa, LLVM, ...), by the
# dynamic linker's own account.
in_root "cd /autograder && LD_DEBUG=libs LD_DEBUG_OUTPUT=/autograder/ld-debug \
    PBRLAB_CACHE=/autograder/source/pbrlab-cache \
    /autograder/source/pbrlab/bin/pbrlab grade /autograder/submission --steps ndf" \
    > "$work/ld.log" 2>&1 || { cat "$work/ld.log"; exit 1; }
cat "$work"/autograder/ld-debug.* | sed -n 's/.*calling init: //p' | sort -u > "$work/loaded.txt"
grep -q '/libOSMesa.so.8$' "$work/loaded.txt" || { echo "no OSMesa among:"; cat "$work/loaded.txt"; exit 1; }
outside=$(grep -v '^/autograder/source/pbrlab/' "$work/loaded.txt" |
    grep -Ev '/(ld-linux-x86-64\.so\.2|libc\.so\.6|libm\.so\.6|libdl\.so\.2|libpthread\.so\.0|librt\.so\.1)$' || true)
if [ -n "$outside" ]; then
    echo "loaded from the $name system, not the bundle:"
    echo "$outside"
    exit 1
fi
echo "$(wc -l < "$work/loaded.txt") libraries loaded: glibc's from $name, every other one" \
     "from the bundle"
echo "grader bundle on a bare $PRETTY_NAME: setup.sh, then results.json as the native build's"
