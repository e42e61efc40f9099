#!/usr/bin/env bash
# The grader bundle (docs/assignment.md, "The grader bundle"): a folder that grades on any
# x86-64 Linux with glibc >= 2.35 and /bin/sh, whatever else it has or lacks:
#   bin/pbrlab                 the headless pbrlab (no GUI, no GLFW or X11), RPATH $ORIGIN/../lib
#   lib/                       every shared library it loads or opens (OSMesa and its llvmpipe
#                              included), copied from this machine's Debian packages, but
#                              glibc's own (libc, libm, libdl, libpthread, librt, ld-linux, ...);
#                              and libpbrlab_glibc_2_36.so, for glibc 2.35 (below)
#   lib/pbrlab/modules/        the step plugins
#   share/pbrlab/              shaders, assets and the step folders (solutions included: it
#                              grades)
#   share/doc/PACKAGE/copyright  the licence of each Debian package a library came from
#   pbrlab-grader-bundle.txt   what it is, and where each library came from
# `pbrlab autograder` zips it for Gradescope; `OUT/bin/pbrlab` runs from wherever OUT is put.
#   bash scripts/grader-bundle.sh [--out DIR] [--tarball]
#                                 [--assignment FILE --zip-out DIR [--gradescope-timeout S]]
#                                 [BUILD_DIR]
# BUILD_DIR (default build) is a native build of pbrlab (it has grader/pbrlab, the headless
# executable); OUT defaults to BUILD_DIR/grader-bundle, where `BUILD_DIR/pbrlab autograder`
# looks for it. --tarball also writes OUT's parent/pbrlab-grader_VERSION_ARCH.tar.gz.
# --assignment with --zip-out also writes ZIP_OUT/autograder.zip, with the bundle's own pbrlab
# (`pbrlab autograder`; --gradescope-timeout: the assignment's timeout on Gradescope, if raised).
set -euo pipefail
cd "$(dirname "$0")/.."
source_dir=$(pwd)
build=build out="" tarball=false assignment="" zip_out="" timeout=600
while [ $# -gt 0 ]; do
    case $1 in
        --out) out=$(realpath -m "$2"); shift 2 ;;
        --tarball) tarball=true; shift ;;
        --assignment) assignment=$(realpath "$2"); shift 2 ;;
        --zip-out) zip_out=$(realpath -m "$2"); shift 2 ;;
        --gradescope-timeout) timeout=$2; shift 2 ;;
        -*) echo "grader-bundle: unknown option $1" >&2; exit 2 ;;
        *) build=$1; shift ;;
    esac
done
build=$(realpath "$build")
if [ ! -x "$build/grader/pbrlab" ]; then
    echo "grader-bundle: $build/grader/pbrlab: not built (cmake --build $build)" >&2
    exit 2
fi
if [ -n "$assignment" ] && [ -z "$zip_out" ]; then
    echo "grader-bundle: --assignment goes with --zip-out DIR" >&2
    exit 2
fi
[ -n "$out" ] || out=$build/grader-bundle
rm -rf "$out"
mkdir -p "$out/bin" "$out/lib/pbrlab" "$out/share/doc"
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT

# The step plugins and the data as `cmake --install` lays them out (the same step folders as
# the Debian package: cmake/install_steps.cmake), stripped.
cmake --install "$build" --prefix "$stage" --strip > "$stage.log" 2>&1 ||
    { cat "$stage.log" >&2; rm -f "$stage.log"; exit 1; }
rm -f "$stage.log"
cp -r "$stage/lib/pbrlab/modules" "$out/lib/pbrlab/"
cp -r "$stage/share/pbrlab" "$out/share/"
strip --strip-unneeded -o "$out/bin/pbrlab" "$build/grader/pbrlab"
chmod 755 "$out/bin/pbrlab"
# arc4random for glibc 2.35 (core/native/bundle/glibc_2_36.cpp), which pbrlab loads first.
compat=libpbrlab_glibc_2_36.so
strip --strip-unneeded -o "$out/lib/$compat" "$build/lib/$compat"

# glibc's own libraries stay the system's: they must match its dynamic linker.
glibc='^(ld-linux-x86-64\.so\.2|linux-vdso\.so\.1|libc\.so\.6|libm\.so\.6|libdl\.so\.2|libpthread\.so\.0|librt\.so\.1|libresolv\.so\.2|libutil\.so\.1|libanl\.so\.1|libmvec\.so\.1|libnsl\.so\.1|libBrokenLocale\.so\.1|libc_malloc_debug\.so\.0|libthread_db\.so\.1)$'
# OSMesa is opened with dlopen (core/native/context_osmesa.cpp), so no ldd of pbrlab names it.
# (awk reads to the end: a reader that quits early would end ldconfig with SIGPIPE, a failure
# under pipefail.)
osmesa=$(ldconfig -p | awk '$1 == "libOSMesa.so.8" && /x86-64/ && !found {print $NF; found = 1}')
[ -n "$osmesa" ] || { echo "grader-bundle: no libOSMesa.so.8 (libosmesa6)" >&2; exit 1; }
ldd "$out/bin/pbrlab" "$out"/lib/pbrlab/modules/*.so "$osmesa" > "$stage/ldd.txt"
if grep -q "not found" "$stage/ldd.txt"; then
    grep "not found" "$stage/ldd.txt" >&2
    exit 1
fi
{ awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}' "$stage/ldd.txt"; echo "libOSMesa.so.8 $osmesa"; } |
    sort -u > "$stage/libraries.txt"

# Each library under its soname (what the dynamic linker looks for), a copy (unzip tools differ
# on links), unchanged: its search path comes from pbrlab's RPATH (CMakeLists.txt says why).
# Where it came from: the Debian package that installed it, whose copyright file goes along.
manifest=$stage/manifest.txt
: > "$manifest"
while read -r soname path; do
    [[ $soname =~ $glibc ]] && continue
    [ "$soname" = "$compat" ] && continue
    cp -L "$path" "$out/lib/$soname"
    chmod 644 "$out/lib/$soname"
    real=$(realpath "$path")
    package=""
    for candidate in "$real" "${real#/usr}" "$path"; do
        package=$(dpkg -S "$candidate" 2>/dev/null | sed -n "1s/:.*//p") && [ -n "$package" ] &&
            break
    done
    version=unknown
    if [ -n "$package" ]; then
        version=$(dpkg-query -W -f='${Version}' "$package")
        mkdir -p "$out/share/doc/$package"
        cp "/usr/share/doc/$package/copyright" "$out/share/doc/$package/copyright"
    fi
    printf '%-28s %-28s %s\n' "$soname" "${package:-?}" "$version" >> "$manifest"
done < "$stage/libraries.txt"

# Debian 12's libraries were built against glibc 2.36. Of its symbols above 2.35 they use only
# arc4random (libstdc++, libLLVM): those needs are marked optional, the function coming from
# $compat; any other symbol of a newer glibc stops the bundle here.
python3 "$source_dir/scripts/glibc-optional-versions.py" 2.35 "$out/lib/$compat" \
    $(find "$out/lib" -maxdepth 1 -name '*.so*' ! -name "$compat" | sort) > "$stage/optional.txt"
sed "s#$out/##" "$stage/optional.txt"

version=$(awk -F= '/^CMAKE_PROJECT_VERSION:/ {print $2}' "$build/CMakeCache.txt")
commit=$(git -C "$source_dir" describe --always --dirty 2>/dev/null || echo unknown)
{
    echo "pbrlab's grader bundle: pbrlab $version ($commit), headless, for x86-64 Linux with"
    echo "glibc >= 2.35 (Ubuntu 22.04 and later, Debian 12 and later, Fedora 36 and later)."
    echo "Run bin/pbrlab from anywhere; it needs nothing of the system but glibc and /bin/sh."
    echo "Made by scripts/grader-bundle.sh; docs/assignment.md says how it is used and tested."
    echo
    echo "The libraries in lib/, and the Debian package each is a copy of (its licence in"
    echo "share/doc/PACKAGE/copyright):"
    echo
    cat "$manifest"
    echo
    echo "Changed from Debian's files, so that they load on glibc 2.35 (lib/$compat, pbrlab's"
    echo "own, defines arc4random@GLIBC_2.36 from getrandom; glibc 2.35's dynamic linker notes"
    echo "\"weak version \`GLIBC_2.36' not found\" on stderr once per run, which is that):"
    echo
    sed "s#$out/##" "$stage/optional.txt"
} > "$out/pbrlab-grader-bundle.txt"

# It starts with nothing of the environment (the bare-system test runs it with nothing else).
env -i "$out/bin/pbrlab" list > /dev/null
size=$(du -sm "$out" | cut -f1)
echo "wrote $out ($size MB, $(wc -l < "$manifest") libraries)"

if $tarball; then
    arch=$(uname -m)
    tar_file=$(dirname "$out")/pbrlab-grader_${version}_${arch}.tar.gz
    tar -C "$(dirname "$out")" -czf "$tar_file" "$(basename "$out")"
    echo "wrote $tar_file ($(du -m "$tar_file" | cut -f1) MB)"
fi
if [ -n "$assignment" ]; then
    "$out/bin/pbrlab" autograder --assignment "$assignment" --out "$zip_out" \
        --gradescope-timeout "$timeout"
fi
