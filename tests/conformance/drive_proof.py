#!/usr/bin/env python3
"""topconf drive proved on known bugs (issue 50 item 5): one run of
`topconf drive` against the built topkit_drive_client, clean or with one
--bug, and its JSON report checked: the clean client fails no case (and
acts on every intent its driver has a call for: no case `unimplemented`),
each bug fails exactly the cases EXPECT gives it, and no case is an
`error`. One ctest per run (tests/conformance/CMakeLists.txt), so ctest
spreads them; every case of a run at once (--jobs), the short durations.

usage: drive_proof.py --topconf BIN --client BIN --model M --link L
                      [--bug NAME] [--case ID ...] --out DIR
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

# The cases each bug fails, by driver, over the links it is run on below
# (docs/DRIVE.md "Known driver bugs"; docs/drive-adapter.md). Where this is
# more than the case that names the bug, the comment says why.
EXPECT = {
    "pitch-rate-sign": {"2.1"},
    "uart-address-on-network": {"6.4"},  # run on UDP with --case 6.4; on a pty it fails nothing
    "strict-version": {"3.2"},
    # 1.1 as well: its device (no-stream=GIA) still echoes the switch GIA 01,
    # which the bug reads as an attitude, and then the driver sends rates.
    "echo-as-attitude": {"1.1", "6.5"},
    "range-fixed-offsets": {"8.3"},
    "month-zero-based": {"9.1"},
    "no-stop-after-last-rate": {"2.4"},
    # 1.3 as well: a stream that stops for good is asked again only by a
    # driver that re-enables it.
    "no-reenable-after-reboot": {"1.3", "1.4"},
    "rates-on-stale-attitude": {"2.5"},
}

DRIVERS = {"sip": "ardupilot-topotek", "c12": "ardupilot-skydroid", "c13": "ardupilot-skydroid"}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--topconf", required=True)
    ap.add_argument("--client", required=True)
    ap.add_argument("--model", required=True, choices=sorted(DRIVERS))
    ap.add_argument("--link", required=True, choices=["pty", "udp"])
    ap.add_argument("--bug")
    ap.add_argument("--case", action="append", default=[])
    ap.add_argument("--expect-none", action="store_true",
                    help="the bug fails nothing here (uart-address-on-network on a pty)")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()

    shutil.rmtree(a.out, ignore_errors=True)
    os.makedirs(a.out)
    out = os.path.abspath(a.out)
    where = "--pty {pty}" if a.link == "pty" else "--udp {host}:{port}"
    exec_ = f"'{a.client}' --driver {DRIVERS[a.model]} {where}" + (f" --bug {a.bug}" if a.bug else "")
    report = os.path.join(out, "report.json")
    cmd = [a.topconf, "drive", "--model", a.model, "--link", a.link, "--exec", exec_, "--jobs", "32",
           "--out", os.path.join(out, "run"), "--json", report, "-q", "--no-color"]
    for c in a.case:
        cmd += ["--case", c]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=240)
    print(" ".join(cmd))
    print(r.stdout)
    try:
        with open(report, encoding="utf-8") as f:
            j = json.load(f)
    except (OSError, ValueError) as e:
        print(f"FAIL: no JSON report ({e}); topconf exit {r.returncode}")
        return 1
    grades = {c["id"]: c for c in j["cases"]}
    failed = {i for i, c in grades.items() if c["grade"] == "fail"}
    want = set() if not a.bug or a.expect_none else EXPECT[a.bug]
    problems = []
    for i, c in sorted(grades.items()):
        if c["grade"] == "error":
            problems.append(f"{i} error: {c['reason']}")
        if not a.bug and c["grade"] == "unimplemented":
            problems.append(f"{i} unimplemented for the clean client: {c['reason']}")
    for i in sorted(failed - want):
        problems.append(f"{i} fails but should not: {grades[i]['reason']}")
    for i in sorted(want - failed):
        got = grades.get(i)
        problems.append(f"{i} should fail: " + (f"{got['grade']}: {got['reason']}" if got else "not run"))
    if j.get("exit_code") != r.returncode or r.returncode != (1 if want else 0):
        problems.append(f"exit {r.returncode} (report {j.get('exit_code')}), want {1 if want else 0}")
    for p in problems:
        print("FAIL:", p)
    print(f"{a.model}/{a.link} {a.bug or 'clean'}: {j['summary']}; failed {sorted(failed)}, want {sorted(want)}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
