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


def blank(code):
    """The code with comments and the contents of literals removed."""
    code = re.sub(r'R"([^(\s]*)\((.*?)\)\1"', '""', code, flags=re.S)
    out, i, n = [], 0, len(code)
    while i < n:
        c = code[i]
        if code.startswith("//", i):
            j = code.find("\n", i)
            i = n if j < 0 else j
        elif code.startswith("/*", i):
            j = code.find("*/", i + 2)
            # keep the line count: a finding names its line
            out.append("\n" * code.count("\n", i, n if j < 0 else j))
            i = n if j < 0 else j + 2
        elif c == "'" and i > 0 and code[i - 1].isalnum():  # a digit separator: 1'000
            out.append(c)
            i += 1
        elif c in "\"'":
            j = i + 1
            while j < n and code[j] != c:
                j += 2 if code[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def main() -> int:
    root = pathlib.Path(sys.argv[1])
    files = sorted((root / ROOM).rglob("*.[ch]pp"))
    bad = []
    for p in files:
        for no, line in enumerate(blank(p.read_text(encoding="utf-8")).splitlines(), 1):
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
