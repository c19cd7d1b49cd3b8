#!/usr/bin/env python3
"""Device rules live in protocol/: a lint for their literals elsewhere.

A catalog identifier written as a string literal ("ERE", "GAC"), an address
letter as a char literal ('P', 'U') or a timing rule as a number (0.25 of a
rate, 20 ms of quiet, a speed hold) outside protocol/ re-derives a rule the
library owns (top/device.hpp, top/motion.hpp, top/catalog.hpp). Each file
may keep the literals that tests/lint/device_rules.allow grants it, with
the reason written there; a file with more fails, and so does a file with
fewer than its grant (lower the grant: the ratchet only tightens).

usage: device_rules.py SOURCE_DIR [--write]   (--write regenerates the
allowance counts, keeping the reasons; review the diff)
"""
import pathlib
import re
import sys

import cpp_text

SCAN = ["analyzer", "conformance", "fuzz", "tools", "bench"]
SUFFIXES = {".cpp", ".hpp", ".h", ".in"}
# An independent reference parser (differential fuzzing) and data makers
# whose literals are the frames they make.
SKIP = {"fuzz/reference.hpp", "captures/make_captures.cpp"}

KINDS = {
    "address": re.compile(r"'[UMDEPG]'"),
    "timing": re.compile(r"\b0\.25\b|milliseconds\(\s*20\s*\)|speed_hold_ms\s*=\s*[1-9]"),
}
IDENT = re.compile(r'"([A-Z][A-Z0-9]{2})"')


def identifiers(root):
    text = (root / "docs" / "CATALOG.md").read_text(encoding="utf-8")
    return set(re.findall(r"^### ([A-Z0-9]{3}):", text, re.M))


def scan(root):
    idents = identifiers(root)
    found = {}  # (path, kind) -> [line numbers]
    for top in SCAN:
        for p in sorted((root / top).rglob("*")):
            rel = p.relative_to(root).as_posix()
            if p.suffix not in SUFFIXES or rel in SKIP or not p.is_file():
                continue
            code = cpp_text.code(p.read_text(encoding="utf-8", errors="replace"), "keep")
            for no, line in enumerate(code.split("\n"), 1):
                for kind, rx in KINDS.items():
                    for _ in rx.finditer(line):
                        found.setdefault((rel, kind), []).append(no)
                for m in IDENT.finditer(line):
                    if m.group(1) in idents:
                        found.setdefault((rel, "ident"), []).append(no)
    return found


def read_allow(path):
    allow = {}
    for raw in path.read_text(encoding="utf-8").splitlines():
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        head, _, why = line.partition("#")
        f, kind, count = head.split()
        allow[(f, kind)] = (int(count), why.strip())
    return allow


def main():
    root = pathlib.Path(sys.argv[1])
    allow_path = root / "tests" / "lint" / "device_rules.allow"
    found = scan(root)
    allow = read_allow(allow_path)
    if "--write" in sys.argv:
        lines = [l for l in allow_path.read_text(encoding="utf-8").splitlines() if l.startswith("#")]
        for key in sorted(found):
            why = allow.get(key, (0, "TODO: say why this file keeps them"))[1]
            lines.append(f"{key[0]} {key[1]} {len(found[key])}  # {why}")
        allow_path.write_text("\n".join(lines) + "\n", encoding="utf-8")
        return 0
    bad = 0
    for key, lines in sorted(found.items()):
        granted = allow.get(key, (0, ""))[0]
        if len(lines) > granted:
            bad += 1
            print(f"{key[0]}: {len(lines)} {key[1]} literal(s), {granted} allowed, at lines "
                  f"{', '.join(map(str, lines))}: ask protocol/ (top/device.hpp, top/motion.hpp)")
    for key, (granted, _) in sorted(allow.items()):
        have = len(found.get(key, []))
        if have < granted:
            bad += 1
            print(f"{key[0]}: {key[1]} allowance {granted} but {have} found: lower it in "
                  f"tests/lint/device_rules.allow")
    if any("TODO" in why for _, why in allow.values()):
        bad += 1
        print("tests/lint/device_rules.allow: an allowance without its reason (TODO)")
    print(f"device_rules: {sum(len(v) for v in found.values())} literals in "
          f"{len({k[0] for k in found})} files, {bad} problem(s)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
