#!/usr/bin/env python3
"""topconf drive (issue 50) end to end: the harness itself, with small
drivers that show its grading can fail.

  drive_check.py --topconf BIN --out DIR [--chromium]

Runs, side by side (each case is 2-4 s of real time):
- good: drive_fake_driver.py (a SkyDroid driver over UDP) on cases 2.1,
  2.4, 7.1 as agent "good": every case passes, its beliefs are read (the
  non-JSON line counted, no environment error), JSON, JUnit and HTML
  agree; then bad (--wrong-sign --no-stop) as agent "bad": 2.1 and 2.4
  fail, exit 1; the agents' table has both columns, each cell the run's
  grade; its page is offline and, with --chromium, renders in headless
  Chromium with the pass and fail colours;
- silent: `sleep 30` on a SIP pty: 1.4 fails (the stream never asked
  again), 2.1 is unimplemented (no motion command), the driver is stopped
  by SIGTERM after the case (not 30 s), its stderr kept;
- missing: an --exec that does not exist: a case error naming it, exit 2,
  at once;
- persistent: the good driver following its intents file, --persistent:
  both cases pass, the file holds a case line per case;
- bad usage: an unknown case, --json /dev/full: exit 2.
Exit 77 (skip) when --chromium is given and Chromium is absent.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "analyzer"))
import report_check  # noqa: E402

FAKE = os.path.join(HERE, "drive_fake_driver.py")


def drive(topconf, out, args, wait=True):
    cmd = [topconf, "drive", "--no-color"] + args
    p = subprocess.Popen(cmd, cwd=out, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    p.started = time.monotonic()
    return p.communicate() + (p.returncode, time.monotonic() - p.started) if wait else p


def finish(p):
    o, e = p.communicate(timeout=120)
    return o, e, p.returncode, time.monotonic() - p.started


def grades(path):
    j = json.load(open(path))
    return j, {c["id"]: c for c in j["cases"]}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--topconf", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--chromium", action="store_true",
                    help="the agents' table only, rendered in headless Chromium")
    a = ap.parse_args()
    a.topconf = os.path.abspath(a.topconf)
    chromium = shutil.which("chromium") or "/usr/bin/chromium"
    if a.chromium and not os.path.exists(chromium):
        print("chromium not installed: skipped")
        return 77
    shutil.rmtree(a.out, ignore_errors=True)
    os.makedirs(a.out)
    errors = []
    fake = "%s %s {host}:{port}" % (sys.executable, FAKE)
    three = ["--model", "c12", "--case", "2.1", "--case", "2.4", "--case", "7.1"]
    runs = {"good": ["--exec", fake, "--agent", "good", "--out", "t", "--json", "good.json",
                     "--junit", "good.xml", "--html", "good.html"] + three}
    if not a.chromium:
        runs["silent"] = ["--model", "sip", "--link", "pty", "--case", "1.4", "--case", "2.1",
                          "--exec", "sleep 30", "--out", "silent", "--json", "silent.json"]
        runs["missing"] = ["--model", "c12", "--case", "2.1", "--exec", "/no/such/driver {port}",
                           "--out", "missing", "--json", "missing.json"]
        runs["persistent"] = ["--model", "c12", "--case", "2.1", "--case", "2.4", "--persistent",
                              "--exec", fake + " --follow", "--out", "persistent", "--json",
                              "persistent.json"]
    runs = {k: drive(a.topconf, a.out, v, wait=False) for k, v in runs.items()}
    # The second agent after the first (the others still running): the
    # table holds both.
    done = {"good": finish(runs.pop("good"))}
    bad = drive(a.topconf, a.out, three + ["--exec", fake + " --wrong-sign --no-stop", "--agent",
                                           "bad", "--out", "t", "--json", "bad.json", "--junit",
                                           "bad.xml"], wait=False)
    done.update({k: finish(p) for k, p in runs.items()})
    done["bad"] = finish(bad)
    for name, want in (("good", 0), ("bad", 1), ("silent", 1), ("missing", 2), ("persistent", 0)):
        if name not in done:
            continue
        o, e, rc, secs = done[name]
        if rc != want:
            errors.append("%s: exit %d, not %d:\n%s%s" % (name, rc, want, o, e))
    path = lambda f: os.path.join(a.out, f)  # noqa: E731

    j, g = grades(path("good.json"))
    for cid in ("2.1", "2.4", "7.1"):
        c = g.get(cid, {})
        if c.get("grade") != "pass":
            errors.append("good %s: %s (%s)" % (cid, c.get("grade"), c.get("reason")))
        if c.get("non_json_lines") != 1 or c.get("errors") or c.get("beliefs", 0) < 5:
            errors.append("good %s: beliefs %s, non-JSON %s, errors %s" %
                          (cid, c.get("beliefs"), c.get("non_json_lines"), c.get("errors")))
        if not os.path.exists(os.path.join(a.out, "t", "agents", "good", c.get("capture", "-"))):
            errors.append("good %s: no capture %s" % (cid, c.get("capture")))
    if j.get("summary", {}).get("pass") != 3 or j.get("agent") != "good":
        errors.append("good: summary %s, agent %s" % (j.get("summary"), j.get("agent")))
    xml = ET.parse(path("good.xml")).getroot().find("testsuite")
    if xml is None or xml.get("tests") != "3" or xml.get("failures") != "0":
        errors.append("good.xml: %s" % (xml.attrib if xml is not None else "no testsuite"))
    html = open(path("good.html"), encoding="utf-8").read()
    errors += report_check.check_offline("good.html", html)
    if 'href="t/agents/good/cases/2.1/wire.pcap"' not in html:
        errors.append("good.html: no link to case 2.1's capture from where the page is")

    j, g = grades(path("bad.json"))
    want = {"2.1": "fail", "2.4": "fail", "7.1": "pass"}
    got = {k: g.get(k, {}).get("grade") for k in want}
    if got != want:
        errors.append("bad: %s, not %s: %s" % (got, want, {k: g[k]["reason"] for k in g}))
    # JUnit: a failed case is a <failure> with its reason, a passed one none
    xml = ET.parse(path("bad.xml")).getroot().find("testsuite")
    cases = {c.get("name", "").split(" ")[0]: c for c in
             (xml.findall("testcase") if xml is not None else [])}
    if xml is None or xml.get("tests") != "3" or xml.get("failures") != "2":
        errors.append("bad.xml: %s" % (xml.attrib if xml is not None else "no testsuite"))
    for cid, grade in want.items():
        failure = cases[cid].find("failure") if cid in cases else None
        if (failure is not None) != (grade == "fail") or \
                (failure is not None and not failure.get("message")):
            errors.append("bad.xml %s: failure element %s for a %s" % (cid, failure, grade))
    if "-" not in g.get("2.1", {}).get("reason", "") or "pitch" not in g.get("2.1", {}).get(
            "reason", ""):
        errors.append("bad 2.1 does not say the pitch went down: %s" % g.get("2.1"))
    # topdump read each case's capture (a note says why when it could not);
    # what it names depends on timing (the axis left turning of bad 2.4 is
    # usually axis-left-moving), so only that it ran, and that it names no
    # such thing on the good driver.
    named = lambda c: [d["name"] for d in c.get("diagnoses", [])]  # noqa: E731
    for name in ("good", "bad"):
        for cid, c in grades(path(name + ".json"))[1].items():
            if c.get("diagnoses_note"):
                errors.append("%s %s: no diagnoses: %s" % (name, cid, c["diagnoses_note"]))
    if "axis-left-moving" in named(grades(path("good.json"))[1].get("2.4", {})):
        errors.append("good 2.4: topdump names axis-left-moving")

    if a.chromium:
        return table(a, chromium, errors)
    j, g = grades(path("silent.json"))
    o, e, rc, secs = done["silent"]
    if g.get("1.4", {}).get("grade") != "fail" or g.get("2.1", {}).get("grade") != \
            "unimplemented":
        errors.append("silent: %s" % {k: (c["grade"], c["reason"]) for k, c in g.items()})
    if "signal 15" not in g.get("2.1", {}).get("driver_exit", "") or secs > 15:
        errors.append("silent: driver_exit %r after %.1f s" % (g.get("2.1", {}).get(
            "driver_exit"), secs))
    if not os.path.exists(os.path.join(a.out, "silent", "cases", "2.1", "stderr.txt")):
        errors.append("silent: no stderr.txt in the case's folder")

    j, g = grades(path("missing.json"))
    o, e, rc, secs = done["missing"]
    c = g.get("2.1", {})
    if c.get("grade") != "error" or "exited at once" not in c.get("reason", "") or \
            "/no/such/driver" not in c.get("reason", "") or secs > 5:
        errors.append("missing: %s after %.1f s" % (c, secs))

    j, g = grades(path("persistent.json"))
    if not j.get("persistent") or [g.get(k, {}).get("grade") for k in ("2.1", "2.4")] != \
            ["pass", "pass"]:
        errors.append("persistent: %s" % {k: (c["grade"], c["reason"]) for k, c in g.items()})
    lines = [json.loads(x) for x in open(path("persistent/persistent/intents.jsonl"))]
    if [x["id"] for x in lines if x["do"] == "case"] != ["2.1", "2.4"]:
        errors.append("persistent intents: %s" % lines)

    o, e, rc, _ = drive(a.topconf, a.out, ["--model", "c12", "--case", "10.1", "--exec", "true"])
    if rc != 2 or "10.1" not in e:
        errors.append("unknown case: exit %d, %r" % (rc, e))
    o, e, rc, _ = drive(a.topconf, a.out, ["--model", "c12", "--case", "6.4", "--exec", "true",
                                           "--out", "full", "--json", "/dev/full"])
    if rc != 2 or "/dev/full" not in e:
        errors.append("--json /dev/full: exit %d, %r" % (rc, e))

    return table(a, chromium, errors)


def table(a, chromium, errors):
    """The agents' table (good and bad) against their runs."""
    path = lambda f: os.path.join(a.out, f)  # noqa: E731
    t = json.load(open(path("t/table.json")))
    cols = [c["agent"] for c in t.get("columns", [])]
    if cols != ["bad", "good"]:
        errors.append("table columns %s" % cols)
    cells = {(r["id"], c["column"]): c["grade"] for r in t.get("rows", []) for c in r["cells"]}
    for (cid, col), want in {("2.1", 0): "fail", ("2.1", 1): "pass", ("2.4", 0): "fail",
                             ("7.1", 1): "pass"}.items():
        if cells.get((cid, col)) != want:
            errors.append("table %s column %d: %s, not %s" % (cid, col, cells.get((cid, col)),
                                                             want))
    if [r["id"] for r in t.get("rows", [])][:2] != ["1.1", "1.2"]:
        errors.append("table rows not in case order")
    page = path("t/table.html")
    text = open(page, encoding="utf-8").read()
    errors += report_check.check_offline("table.html", text)
    if 'href="agents/good/cases/2.1"' not in text:
        errors.append("table.html: no link to the good agent's case 2.1")
    if a.chromium:
        colours = [bytes.fromhex(c) for c in ("e6f6e6", "fbe3e3")]
        errors += report_check.render_check(chromium, page, path("t"), "drive-table",
                                            os.path.getsize(page), colours)
    for e in errors:
        print("FAIL " + e)
    print("drive: %d problems" % len(errors))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
