#!/usr/bin/env python3
"""topconf table (issue 49 part 4) end to end.

  table_check.py --topconf BIN --out DIR [--chromium]

Three real `topconf run --driver ... --json` runs against the in-process
topsim (ardupilot-skydroid on a C13 with a capture, on a C12 with
placeholder identity, ardupilot-topotek on a SIP whose GIA stream never
comes), merged by `topconf table`: the JSON's columns, verdicts, grade
groups and cells are checked against the runs' own reports, the cells of a
run with a capture link it, and an unreadable input is exit 2 naming the
file. The page is checked offline (no external URL) and,
with --chromium, loaded by headless Chromium (report_check.render_check:
no console message, a screenshot that shows the pass, non-strict and fail
colours). Exit 77 (skip) when --chromium is given and Chromium is absent.
"""
import argparse
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "analyzer"))
import report_check  # noqa: E402

RUNS = [  # stem, driver, model, extra arguments, expected verdict
    ("c13", "ardupilot-skydroid", "c13", ["--firmware", "C13@V1.0.78", "--pcap", "c13.pcap"],
     "compatible"),
    ("c12-placeholder", "ardupilot-skydroid", "c12",
     ["--sim-fault", "placeholder-identity", "--firmware", "C12@0.0.0"], "compatible without"),
    ("sip-no-gia", "ardupilot-topotek", "sip", ["--sim-fault", "no-stream=GIA"], "incompatible"),
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--topconf", required=True)
    a, chromium = report_check.page_check_args(ap)
    errors, reports = [], []
    for stem, driver, model, extra, verdict in RUNS:
        out = stem + ".json"
        r = subprocess.run([a.topconf, "run", "--driver", driver, "--model", model, "-q",
                            "--json", out] + extra, cwd=a.out, capture_output=True, text=True)
        want_rc = 1 if verdict == "incompatible" else 0
        if r.returncode != want_rc:
            errors.append("%s: topconf run exit %d, not %d: %s" %
                          (stem, r.returncode, want_rc, r.stdout + r.stderr))
        reports.append(json.load(open(os.path.join(a.out, out))))
    files = [s + ".json" for s, *_ in RUNS]
    r = subprocess.run([a.topconf, "table"] + files + ["--json", "table.json", "--html",
                                                       "table.html"], cwd=a.out,
                       capture_output=True, text=True)
    if r.returncode != 0:
        errors.append("topconf table exit %d: %s" % (r.returncode, r.stderr))
        return report(errors)
    errors += check_json(json.load(open(os.path.join(a.out, "table.json"))), reports)
    r = subprocess.run([a.topconf, "table", files[0], "no-such.json"], cwd=a.out,
                       capture_output=True, text=True)
    if r.returncode != 2 or "no-such.json" not in r.stderr:
        errors.append("an unreadable input: exit %d, %r" % (r.returncode, r.stderr))
    page = os.path.join(a.out, "table.html")
    text = open(page, encoding="utf-8").read()
    errors += report_check.check_offline("table.html", text)
    if 'href="c13.pcap"' not in text:
        errors.append("table.html: no link to c13.pcap")
    if a.chromium:
        colours = [bytes.fromhex(c) for c in ("e6f6e6", "fff5d6", "fbe3e3")]
        errors += report_check.render_check(chromium, page, a.out, "table",
                                            os.path.getsize(page), colours)
    return report(errors)


def check_json(t, reports):
    """The table's problems against the runs' own reports."""
    errors = []
    cols = t.get("columns", [])
    got = [(c["firmware"], c["driver"], c["verdict"]) for c in cols]
    want = [(x[3][x[3].index("--firmware") + 1] if "--firmware" in x[3] else x[2], x[1], x[4])
            for x in RUNS]
    if got != want:
        errors.append("columns %s, not %s" % (got, want))
    if cols and cols[0].get("capture") != "c13.pcap":
        errors.append("the C13 column names no capture: %s" % cols[0])
    grades = [g["grade"] for g in t.get("groups", [])]
    if grades != ["must", "should", "info"]:
        errors.append("groups %s" % grades)
    cells = {}
    for g in t.get("groups", []):
        for row in g["rows"]:
            if row["grade"] != g["grade"]:
                errors.append("%s graded %s in group %s" % (row["case"], row["grade"], g["grade"]))
            for c in row["cells"]:
                cells[(row["case"], c["column"])] = c
    for i, rep in enumerate(reports):
        for n in rep["compatibility"]["needs"]:
            c = cells.get((n["case"], i))
            if c is None or c["result"] != n["result"] or c["served"] != n["served"]:
                errors.append("column %d, %s: cell %s, the run says %s" %
                              (i, n["case"], c, n["result"]))
            elif (c.get("capture") is not None) != (i == 0):
                errors.append("column %d, %s: capture %s" % (i, n["case"], c.get("capture")))
    lost = cells.get(("driver/ardupilot-skydroid/version", 1), {})
    if lost.get("served", True):
        errors.append("the placeholder version is served in the table: %s" % lost)
    return errors


def report(errors):
    return report_check.verdict(errors, "table: %d problems" % len(errors))


if __name__ == "__main__":
    sys.exit(main())
