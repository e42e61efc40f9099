#!/usr/bin/env python3
"""The product's functions stay short enough to read in one sitting: none over --most lines
(docs/architecture.md). Lists each one longer, with its file and line, and exits 1; with no
file named, checks every .cpp and .h that git tracks in core/ and labs/.

Function bounds come from Universal Ctags (Debian's universal-ctags): a function's lines run
from its signature to its closing brace, comments inside included.

Usage: function_lengths.py [--most N] [--root DIR] [FILE ...]
       function_lengths.py --self-test    (a function one line over the limit is named, one at
                                           the limit is not)
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile


def product_files(root):
    listed = subprocess.run(["git", "-C", root, "ls-files", "core", "labs"], check=True,
                            capture_output=True, text=True).stdout.split()
    return [f for f in listed if f.endswith((".cpp", ".h"))]


def long_functions(root, files, most):
    tags = subprocess.run(["ctags", "--output-format=json", "--fields=+ne", "--kinds-c++=f",
                           "--language-force=c++", "-f", "-"] + files,
                          cwd=root, check=True, capture_output=True, text=True).stdout
    found = []
    for line in tags.splitlines():
        tag = json.loads(line)
        if tag.get("_type") != "tag" or "end" not in tag:
            continue
        lines = tag["end"] - tag["line"] + 1
        if lines > most:
            name = (tag["scope"] + "::" if "scope" in tag else "") + tag["name"]
            found.append((tag["path"], tag["line"], name, lines))
    return sorted(found)


def function_of(name, lines):
    """A C++ function `name` of exactly `lines` lines, signature to closing brace."""
    body = [f"    x += {i};" for i in range(lines - 3)]
    return "\n".join([f"int {name}(int x) {{"] + body + ["    return x;", "}", ""])


def self_test(most):
    with tempfile.TemporaryDirectory() as root:
        with open(os.path.join(root, "lengths.cpp"), "w") as out:
            out.write(function_of("oneOver", most + 1) + "\n" + function_of("atTheLimit", most))
        found = [name for _, _, name, _ in long_functions(root, ["lengths.cpp"], most)]
    if found != ["oneOver"]:
        print(f"self-test: expected only oneOver ({most + 1} lines) to be named, got {found}")
        return 1
    print(f"self-test: a function of {most + 1} lines is named, one of {most} is not")
    return 0


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--most", type=int, default=80)
    parser.add_argument("--root", default=".")
    parser.add_argument("--self-test", action="store_true")
    parser.add_argument("files", nargs="*")
    args = parser.parse_args()
    if args.self_test:
        return self_test(args.most)
    files = args.files or product_files(args.root)
    found = long_functions(args.root, files, args.most)
    for path, line, name, lines in found:
        print(f"{path}:{line}: {name} is {lines} lines (at most {args.most}: split it into "
              "pieces named for what they do)")
    print(f"{len(files)} files, {len(found)} functions over {args.most} lines")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
