"""C++ source as the lints read it: comments out, literals kept or blanked.

code(text, literals) returns `text` with every comment removed but its
newlines, so that a finding still names its line, and every string or
character literal (raw strings too) kept as written (literals="keep") or
reduced to its two quotes and its newlines (literals="blank"). A ' inside a
number is a digit separator (1'000, 0x1'F), not a character literal; an
ordinary literal ends at the end of its line at the latest.
"""
import re

RAW = re.compile(r'R"([^(\s]*)\(')
# What may stand before R" of a raw string, or before ' of a character
# literal: nothing of a name, or an encoding prefix.
PREFIXES = {"", "u8", "u", "U", "L"}


def _word_before(text, i):
    """The name or number that ends just before text[i] ('' if none)."""
    j = i
    while j > 0 and (text[j - 1].isalnum() or text[j - 1] in "_'."):
        j -= 1
    return text[j:i]


def _literal(text, i, literals):
    """(what stands for the literal starting at text[i], where it ends)."""
    n, c = len(text), text[i]
    if c == "R":
        m = RAW.match(text, i)
        close = ")" + m.group(1) + '"'
        end = text.find(close, m.end())
        end = n if end < 0 else end + len(close)
    else:
        j = i + 1
        while j < n and text[j] != c and text[j] != "\n":
            j += 2 if text[j] == "\\" else 1
        end = min(j + 1, n)
    lit = text[i:end]
    if literals == "keep":
        return lit, end
    quote = '"' if c == "R" else c
    return quote + quote + "\n" * lit.count("\n"), end


def code(text, literals):
    """`text` with comments out and literals kept or blanked (see above)."""
    assert literals in ("keep", "blank")
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif c == "'" and _word_before(text, i)[:1].isdigit():  # 1'000
            out.append(c)
            i += 1
        elif c == '"' or c == "'" or (
            c == "R" and RAW.match(text, i) and _word_before(text, i) in PREFIXES
        ):
            lit, i = _literal(text, i, literals)
            out.append(lit)
        else:
            out.append(c)
            i += 1
    return "".join(out)
