#!/usr/bin/env python3
"""Every #include between rooms is one HACKING.md's folder table allows.

HACKING.md's "Folders" table has a row per room: its folder in backticks,
its job, and what it "may include": the rooms it names in backticks (a
folder of the table), "everything", or no room ("-", or only outside
libraries). A room's own files and the shared helpers of
`protocol/internal/top/detail/` that come with `protocol/` are always
allowed. Every C++ file git tracks belongs to the room with the longest
folder that holds it; a file in no room, a row that names a folder the
table does not have, and an include of a room its row does not name are
errors, so the map cannot drift from the code (issue 48).

An include "a/b.hpp" is the tracked file at that path beside the
including file, or else the one whose path ends with it (the including
room's first when there are several).

usage: include_map.py SOURCE_DIR
"""
import pathlib
import re
import subprocess
import sys

INTERNAL = "protocol/internal/top/detail/"


def table(text):
    """{room: set of allowed rooms or None for everything}, in table order."""
    rows = {}
    part = text.split("## Folders", 1)[-1].split("\n## ", 1)[0]
    for line in part.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 3 or not cells[0].startswith("`"):
            continue
        room = cells[0].strip("`")
        may = cells[2]
        rows[room] = None if may.startswith("everything") else set(re.findall(r"`([^`]+/)`", may))
    return rows


def room_of(path, rooms):
    best = None
    for r in rooms:
        if path.startswith(r) and (best is None or len(r) > len(best)):
            best = r
    return best


def resolve(src, inc, files, by_suffix, rooms):
    beside = (pathlib.PurePosixPath(src).parent / inc).as_posix()
    if beside in files:
        return beside
    cands = by_suffix.get(inc, [])
    if not cands:
        return None  # a system or third-party header
    mine = [c for c in cands if room_of(c, rooms) == room_of(src, rooms)]
    return (mine or cands)[0]


def main() -> int:
    root = pathlib.Path(sys.argv[1])
    rows = table((root / "HACKING.md").read_text(encoding="utf-8"))
    errors = []
    if len(rows) < 10:
        errors.append("HACKING.md: no folder table found")
    for room, may in rows.items():
        for r in may or ():
            if r not in rows:
                errors.append(f"HACKING.md: `{room}` may include `{r}`, which is no folder of the table")
    ls = subprocess.run(["git", "-C", str(root), "ls-files", "*.cpp", "*.hpp", "*.h"],
                        capture_output=True, text=True, check=False)
    if ls.returncode == 0:
        files = set(ls.stdout.split())
    else:  # not a git checkout (a tarball): every file but the build trees
        files = {p.relative_to(root).as_posix() for p in root.rglob("*")
                 if p.suffix in (".cpp", ".hpp", ".h")
                 and not p.relative_to(root).parts[0].startswith("build")}
    by_suffix = {}
    for f in sorted(files):
        parts = f.split("/")
        for i in range(len(parts)):
            by_suffix.setdefault("/".join(parts[i:]), []).append(f)
    edges = 0
    for f in sorted(files):
        src = room_of(f, rows)
        if src is None:
            errors.append(f"{f}: in no folder of HACKING.md's table")
            continue
        may = rows[src]
        text = (root / f).read_text(encoding="utf-8", errors="replace")
        for n, line in enumerate(text.splitlines(), 1):
            m = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
            if not m:
                continue
            to = resolve(f, m.group(1), files, by_suffix, rows)
            dst = room_of(to, rows) if to else None
            if dst is None or dst == src:
                continue
            edges += 1
            ok = may is None or dst in may or (dst == INTERNAL and "protocol/" in may)
            if not ok:
                errors.append(f"{f}:{n}: includes {to} (`{dst}`), which HACKING.md's "
                              f"row for `{src}` does not allow")
    for e in errors:
        print(e)
    print(f"include map: {len(files)} files, {len(rows)} rooms, {edges} includes between "
          f"rooms, {len(errors)} errors")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
