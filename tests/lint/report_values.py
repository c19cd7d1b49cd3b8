#!/usr/bin/env python3
"""The report reads values, never text (issue 48, "Values between rooms").

analyzer/report/ groups, ranks and decides by enums, codes and struct
fields. It may write text for people but never reads it back: no
substring, search or comparison of a message or display string, no name
parsed back into its value (*_from_string), and describe() only appended
to the text being written (`t += describe(cause)`), never kept, compared or
searched. The check runs over the code with comments and the contents of
string and character literals blanked.

usage: report_values.py SOURCE_DIR
"""
import pathlib
import re
import sys

import cpp_text

ROOM = "analyzer/report"

# (pattern, what it reads)
RULES = [
    (r"\.substr\s*\(", "a substring of text"),
    (r"\b(starts|ends)_with\s*\(", "a prefix or suffix of text"),
    (r"\.compare\s*\(", "text compared"),
    (r"\.(r?find|find_(first|last)_(not_)?of)\s*\(\s*\"", "text searched for a literal"),
    (r"\.(rfind|find_(first|last)_(not_)?of)\s*\(", "text searched"),
    (r"\b(message|text|msg|what|title)\w*\s*\.\s*find\s*\(", "a message searched"),
    (r"\bnpos\b", "a search's result"),
    (r"\b(strcmp|strncmp|strstr|strcasecmp|sscanf)\s*\(", "C text compared or parsed"),
    (r"\bstd::regex\b", "text matched"),
    (r"_from_string\s*\(", "a name parsed back into its value"),
    (r"[!=]=\s*\"|\"\s*[!=]=", "text compared with a literal"),
    (r"(?<!\+=)(?<!\+= )\bdescribe\s*\(", "describe() kept, compared or searched"),
]


def main() -> int:
    root = pathlib.Path(sys.argv[1])
    files = sorted((root / ROOM).rglob("*.[ch]pp"))
    bad = []
    for p in files:
        for no, line in enumerate(cpp_text.code(p.read_text(encoding="utf-8"), "blank").splitlines(), 1):
            for pat, what in RULES:
                if re.search(pat, line):
                    rel = p.relative_to(root).as_posix()
                    bad.append(f"{rel}:{no}: {what}: {line.strip()}")
    for b in bad:
        print(b)
    print(f"report_values: {len(files)} files of {ROOM}, {len(bad)} reads of text")
    return 1 if bad or not files else 0


if __name__ == "__main__":
    sys.exit(main())
