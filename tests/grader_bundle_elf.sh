#!/usr/bin/env bash
# Every ELF file of the grader bundle (scripts/grader-bundle.sh) runs on glibc 2.35 and finds
# what it needs in the bundle: no symbol version above GLIBC_2.35 (nor GLIBC_PRIVATE, which
# ties a library to one glibc build) but an optional one whose every symbol the bundle's
# libpbrlab_glibc_2_36.so defines, every needed library carried in lib/ or glibc's own, no
# library with a search path of its own outside the bundle (it would hide pbrlab's RPATH from
# its dependencies), and bin/pbrlab with DT_RPATH $ORIGIN/../lib. Then the check itself on a
# copy of the bundle broken three ways (a library removed, a program needing GLIBC_2.36, a
# library with RUNPATH /usr/lib), each of which it must report.
# Usage: grader_bundle_elf.sh BUNDLE_DIR
set -euo pipefail
bundle=$(cd "$1" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
glibc='^(ld-linux-x86-64\.so\.2|libc\.so\.6|libm\.so\.6|libdl\.so\.2|libpthread\.so\.0|librt\.so\.1|libresolv\.so\.2|libutil\.so\.1|libanl\.so\.1|libmvec\.so\.1|libnsl\.so\.1|libBrokenLocale\.so\.1|libc_malloc_debug\.so\.0|libthread_db\.so\.1)$'
newest=2.35

# check DIR [FILE...]: prints one line per problem of DIR's ELF files (of those FILEs only, when
# given); counts them in $work/elf-count.
check() {
    local dir=$1 count=0
    shift
    while IFS= read -r -d '' f; do
        [ "$(head -c 4 "$f" | od -An -c | tr -d ' ')" = '177ELF' ] || continue
        count=$((count + 1))
        local name=${f#"$dir"/}
        # Versions needed from glibc (readelf's "Version needs" section: "Name: GLIBC_2.34
        # Flags: none"), with their flags.
        readelf -V --wide "$f" | awk '/Version needs section/ {needs = 1} /Version definition section/ {needs = 0}
            needs && match($0, /Name: GLIBC_[0-9A-Z_.]+/) {
                v = substr($0, RSTART + 6, RLENGTH - 6); flags = $0; sub(/.*Flags: /, "", flags)
                sub(/ .*/, "", flags); print v, flags}' | sort -u > "$work/versions"
        while read -r v flags; do
            if [ "$v" = GLIBC_PRIVATE ]; then
                echo "$name: needs GLIBC_PRIVATE"
            elif [ "$(printf '%s\n%s\n' "${v#GLIBC_}" "$newest" | sort -V | tail -1)" != "$newest" ]; then
                # Optional (WEAK) only where the compatibility library defines every symbol
                # taken from that version (scripts/glibc-optional-versions.py).
                if [ "$flags" != WEAK ]; then
                    echo "$name: needs $v (above GLIBC_$newest)"
                    continue
                fi
                readelf --dyn-syms --wide "$f" | awk -v v="@$v" '$7 == "UND" && index($8, v) {
                    sub(/@.*/, "", $8); print $8}' | sort -u > "$work/taken"
                while read -r symbol; do
                    grep -qx "$symbol@@$v" "$work/compat-symbols" ||
                        echo "$name: needs $symbol@$v, which neither glibc $newest nor $compat defines"
                done < "$work/taken"
            fi
        done < "$work/versions"
        readelf -d --wide "$f" > "$work/dynamic"
        while read -r needed; do
            [[ $needed =~ $glibc ]] && continue
            [ -f "$dir/lib/$needed" ] || echo "$name: needs $needed, which the bundle does not carry"
        done < <(sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' "$work/dynamic")
        local rpath runpath
        rpath=$(sed -n 's/.*(RPATH).*\[\(.*\)\]/\1/p' "$work/dynamic")
        runpath=$(sed -n 's/.*(RUNPATH).*\[\(.*\)\]/\1/p' "$work/dynamic")
        if [ "$name" = bin/pbrlab ]; then
            [ "$rpath" = '$ORIGIN/../lib' ] ||
                echo "$name: DT_RPATH is '$rpath', not \$ORIGIN/../lib"
            [ -z "$runpath" ] || echo "$name: has a RUNPATH ($runpath): not inherited by its libraries"
        else
            for p in $rpath $runpath; do
                [[ $p == '$ORIGIN'* ]] ||
                    echo "$name: searches $p, outside the bundle, for its dependencies"
            done
        fi
    done < <(if [ $# -gt 0 ]; then printf '%s\0' "$@"; else find "$dir" -type f -print0; fi)
    echo "$count" > "$work/elf-count"
}

compat=libpbrlab_glibc_2_36.so
readelf --dyn-syms --wide "$bundle/lib/$compat" | awk '$7 != "UND" && $8 ~ /@@GLIBC_/ {print $8}' \
    > "$work/compat-symbols"
echo "== the bundle: $bundle"
check "$bundle" > "$work/problems"
count=$(cat "$work/elf-count")
if [ -s "$work/problems" ]; then
    cat "$work/problems"
    exit 1
fi
# The bundle's own files, at least: pbrlab, a plugin per step, OSMesa and its LLVM.
for f in bin/pbrlab lib/libOSMesa.so.8 lib/libglapi.so.0 lib/libstdc++.so.6; do
    [ -f "$bundle/$f" ] || { echo "not in the bundle: $f"; exit 1; }
done
ls "$bundle"/lib/libLLVM-*.so.* > /dev/null
steps=$(find "$bundle/share/pbrlab/labs" -name step.json | wc -l)
plugins=$(find "$bundle/lib/pbrlab/modules" -name 'pbrlab-*.so' | wc -l)
[ "$steps" -gt 0 ] && [ "$steps" -eq "$plugins" ] ||
    { echo "$steps step folders but $plugins plugins"; exit 1; }
echo "$count ELF files: none needs more than GLIBC_$newest or a library the bundle lacks"

echo "== the check on a broken copy"
broken=$work/broken
cp -al "$bundle" "$broken"  # links: removing one leaves the bundle whole
rm "$broken/lib/libmd.so.0"  # libbsd's
cat > "$work/new.c" <<'C'
#include <stdlib.h>
int main(void) { return (int)(arc4random() & 1); }
C
cc -o "$broken/bin/needs-2.36" "$work/new.c"  # arc4random: GLIBC_2.36
echo 'int f(void) { return 1; }' > "$work/lib.c"
cc -shared -fPIC -o "$broken/lib/libelsewhere.so" "$work/lib.c" -Wl,--enable-new-dtags \
    -Wl,-rpath,/usr/lib
check "$broken" "$broken/lib/libbsd.so.0" "$broken/bin/needs-2.36" \
    "$broken/lib/libelsewhere.so" > "$work/broken-problems"
cat "$work/broken-problems"
for expected in "lib/libbsd.so.0: needs libmd.so.0, which the bundle does not carry" \
                "bin/needs-2.36: needs GLIBC_2.36 (above GLIBC_$newest)" \
                "lib/libelsewhere.so: searches /usr/lib, outside the bundle"; do
    grep -qF "$expected" "$work/broken-problems" || { echo "not reported: $expected"; exit 1; }
done
echo "the check reports each of the three breaks"
