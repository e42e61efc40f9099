#!/usr/bin/env python3
"""Marks optional (VER_FLG_WEAK) a shared library's needs of glibc versions above a given one,
where every symbol it takes from such a version is one a compatibility library defines with
that version: then the library loads on the older glibc, and the dynamic linker binds those
symbols to the compatibility library (scripts/grader-bundle.sh, core/native/bundle/).

Usage: glibc-optional-versions.py NEWEST COMPAT_LIBRARY FILE...
  NEWEST  the newest glibc version the files may need (2.35)
Prints what it marked; exits 1, changing nothing in that file, when a file needs a version
above NEWEST for a symbol the compatibility library does not define."""
import struct
import sys

SHT_DYNSYM, SHT_VERDEF, SHT_VERNEED, SHT_VERSYM = 11, 0x6FFFFFFD, 0x6FFFFFFE, 0x6FFFFFFF
VER_FLG_WEAK = 0x2


def sections(data):
    if data[:4] != b"\x7fELF" or data[4] != 2 or data[5] != 1:
        raise ValueError("not a little-endian ELF64 file")
    shoff, = struct.unpack_from("<Q", data, 0x28)
    shentsize, shnum = struct.unpack_from("<HH", data, 0x3A)
    out = []
    for i in range(shnum):
        name, kind, _, _, offset, size, link, info, _, entsize = struct.unpack_from(
            "<IIQQQQIIQQ", data, shoff + i * shentsize)
        out.append({"type": kind, "offset": offset, "size": size, "link": link,
                    "info": info, "entsize": entsize})
    return out


def string(data, table, at):
    start = table["offset"] + at
    return data[start:data.index(b"\0", start)].decode()


def verneed(data, secs):
    """(offset of vna_flags, file, version name, version index) of every need."""
    out = []
    for sec in secs:
        if sec["type"] != SHT_VERNEED:
            continue
        strtab, at = secs[sec["link"]], sec["offset"]
        for _ in range(sec["info"]):
            _, count, file_, aux, next_ = struct.unpack_from("<HHIII", data, at)
            a = at + aux
            for _ in range(count):
                _, flags, other, name, anext = struct.unpack_from("<IHHII", data, a)
                out.append((a + 4, string(data, strtab, file_), string(data, strtab, name), other))
                a += anext
            at += next_
    return out


def symbols(data, secs):
    """(name, version index, defined) of every dynamic symbol."""
    dynsym = next((s for s in secs if s["type"] == SHT_DYNSYM), None)
    versym = next((s for s in secs if s["type"] == SHT_VERSYM), None)
    if dynsym is None:
        return []
    strtab, out = secs[dynsym["link"]], []
    for i in range(dynsym["size"] // 24):
        name, _, _, shndx, _, _ = struct.unpack_from("<IBBHQQ", data, dynsym["offset"] + i * 24)
        version = struct.unpack_from("<H", data, versym["offset"] + 2 * i)[0] & 0x7FFF \
            if versym else 0
        out.append((string(data, strtab, name), version, shndx != 0))
    return out


def defined_versions(data, secs):
    """{version index: name} of the file's own version definitions."""
    out = {}
    for sec in secs:
        if sec["type"] != SHT_VERDEF:
            continue
        strtab, at = secs[sec["link"]], sec["offset"]
        for _ in range(sec["info"]):
            _, _, index, count, _, aux, next_ = struct.unpack_from("<HHHHIII", data, at)
            name, _ = struct.unpack_from("<II", data, at + aux)
            out[index] = string(data, strtab, name)
            at += next_
    return out


def newer(version, newest):
    parts = lambda v: [int(x) for x in v.split(".")]
    return parts(version) > parts(newest)


def main():
    newest, compat, files = sys.argv[1], sys.argv[2], sys.argv[3:]
    with open(compat, "rb") as f:
        data = f.read()
    secs = sections(data)
    names = defined_versions(data, secs)
    provided = {(s, names.get(v)) for s, v, defined in symbols(data, secs) if defined}
    status = 0
    for path in files:
        with open(path, "rb") as f:
            data = bytearray(f.read())
        secs = sections(data)
        needs = [n for n in verneed(data, secs)
                 if n[1] == "libc.so.6" and n[2].startswith("GLIBC_2.")
                 and newer(n[2][len("GLIBC_"):], newest)]
        if not needs:
            continue
        syms = symbols(data, secs)
        missing = [(s, v) for _, _, v, index in needs for s, i, defined in syms
                   if i == index and not defined and (s, v) not in provided]
        if missing:
            print(f"{path}: needs {', '.join(f'{s}@{v}' for s, v in missing)}, which "
                  f"{compat} does not define: it cannot load on glibc {newest}")
            status = 1
            continue
        for flags_at, _, version, index in needs:
            flags, = struct.unpack_from("<H", data, flags_at)
            struct.pack_into("<H", data, flags_at, flags | VER_FLG_WEAK)
            taken = sorted(s for s, i, defined in syms if i == index and not defined)
            print(f"{path}: its need of {version} ({', '.join(taken)}) made optional")
        with open(path, "wb") as f:
            f.write(data)
    return status


if __name__ == "__main__":
    sys.exit(main())
