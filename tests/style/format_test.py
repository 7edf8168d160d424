#!/usr/bin/env python3
"""Formatting check (CTest `format`): every C++ file under src/, include/ and tests/ is as the
repository's .clang-format lays it out, by clang-format 14 (Debian 12's; other versions lay some
constructs out differently, so they are not used). A file that differs fails the test, named with
the command that mends it. First the check itself is checked: a planted misformatted file must be
found. Without clang-format 14 the test skips (exit 77) with a message.

usage: format_test.py SOURCE_DIR
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

SKIP = 77
FOLDERS = ("src", "include", "tests")
SUFFIXES = (".cpp", ".hpp", ".h", ".cc")


def clang_format_14():
    for name in ("clang-format-14", "clang-format"):
        path = shutil.which(name)
        if path is None:
            continue
        version = subprocess.run([path, "--version"], capture_output=True, text=True).stdout
        if re.search(r"version 14\.", version):
            return path
    return None


def differing(tool, style_file, files):
    """The files clang-format would change (--dry-run --Werror reports each as an error)."""
    found = set()
    for start in range(0, len(files), 200):
        batch = files[start:start + 200]
        r = subprocess.run([tool, f"--style=file:{style_file}", "--dry-run", "--Werror", *batch],
                           capture_output=True, text=True)
        for line in r.stderr.splitlines():
            m = re.match(r"(.+?):\d+:\d+: (?:error|warning):", line)
            if m:
                found.add(m.group(1))
        if r.returncode != 0 and not found.intersection(batch):
            sys.exit(f"format: clang-format failed: {r.stderr.strip()[:300]}")
    return sorted(found)


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
    tool = clang_format_14()
    if tool is None:
        print("format: SKIP: clang-format 14 not found (Debian 12: apt-get install clang-format)")
        return SKIP
    style_file = os.path.join(root, ".clang-format")
    # the check must be able to fail: a planted misformatted file is found
    with tempfile.TemporaryDirectory() as d:
        planted = os.path.join(d, "planted.cpp")
        with open(planted, "w") as f:
            f.write("int  f( int x ){return x;}\n")
        if differing(tool, style_file, [planted]) != [planted]:
            print("format: the check missed a planted misformatted file")
            return 1
    files = []
    for folder in FOLDERS:
        for dirpath, _, names in os.walk(os.path.join(root, folder)):
            files += [os.path.join(dirpath, n) for n in sorted(names) if n.endswith(SUFFIXES)]
    files.sort()
    bad = differing(tool, style_file, files)
    for path in bad:
        print(f"{os.path.relpath(path, root)}: differs from .clang-format "
              f"(mend: {os.path.basename(tool)} -i {os.path.relpath(path, root)})")
    print(f"format: {len(files)} C++ files checked, {len(bad)} differ")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
