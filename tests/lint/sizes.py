#!/usr/bin/env python3
"""No C++ source file over 500 lines, the catalog tables excepted (issue 27).

A file that long mixes ideas: split it by idea. The catalog tables
(protocol/src/catalog_*.cpp) are one row per command and stay whole.

usage: sizes.py SOURCE_DIR
"""
import pathlib
import subprocess
import sys

LIMIT = 500
EXEMPT = ("protocol/src/catalog_",)


def main() -> int:
    root = pathlib.Path(sys.argv[1])
    files = subprocess.run(["git", "-C", str(root), "ls-files", "*.cpp", "*.hpp"],
                           capture_output=True, text=True, check=False)
    if files.returncode != 0:  # not a git checkout (a tarball): every file
        paths = [p.relative_to(root).as_posix() for p in root.rglob("*.[ch]pp")
                 if "build" not in p.relative_to(root).parts]
    else:
        paths = files.stdout.split()
    bad = []
    for rel in paths:
        if rel.startswith(EXEMPT):
            continue
        p = root / rel
        if not p.is_file():
            continue
        n = sum(1 for _ in p.open(encoding="utf-8", errors="replace"))
        if n > LIMIT:
            bad.append(f"{rel}: {n} lines (limit {LIMIT}; split it by idea)")
    for b in bad:
        print(b)
    print(f"sizes: {len(paths)} files, {len(bad)} over {LIMIT} lines")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
