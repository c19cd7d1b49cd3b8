#!/usr/bin/env python3
"""Checks examples/drive/sitl_adapter.py without a SITL (ctest drive.adapter):
it byte-compiles; --help works without pymavlink; --dry-run maps each intent
of the drive contract to the MAVLink the adapter documents (values, units,
signs); a bad intents line is an error naming file and line; without
pymavlink a real run says so and exits 2 (pymavlink is hidden behind a
module that fails to import, so the check holds where it is installed too);
a failed write on stdout exits 2.

usage: drive_adapter_check.py ADAPTER WORKDIR
"""
import json
import math
import os
import py_compile
import subprocess
import sys

adapter, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def run(args, env=None, stdout=subprocess.PIPE):
    return subprocess.run([sys.executable, adapter] + args, stdout=stdout, stderr=subprocess.PIPE,
                          text=True, env={**os.environ, **(env or {})}, timeout=60)


py_compile.compile(adapter, cfile=os.path.join(work, "sitl_adapter.pyc"), doraise=True)

# pymavlink hidden: a package of that name whose import fails.
hide = os.path.join(work, "nopymavlink", "pymavlink")
os.makedirs(hide, exist_ok=True)
with open(os.path.join(hide, "__init__.py"), "w") as f:
    f.write("raise ImportError('hidden by drive_adapter_check.py')\n")
no_mav = {"PYTHONPATH": os.path.dirname(hide)}

r = run(["--help"], no_mav)
check(r.returncode == 0 and "--dry-run" in r.stdout and "--mavlink" in r.stdout, f"--help: {r}")

intents = os.path.join(work, "intents.jsonl")
with open(intents, "w") as f:
    for line in [
        {"t": 0.2, "do": "identity"},
        {"t": 0.2, "do": "clock", "utc": "2026-12-06T12:00:00Z"},
        {"t": 0.5, "do": "rate", "frame": "earth", "pitch_dps": 10, "yaw_dps": -5},
        {"t": 1.0, "do": "angle", "frame": "body", "pitch_deg": -30, "yaw_deg": 15},
        {"t": 1.5, "do": "stop"}, {"t": 1.6, "do": "centre"}, {"t": 2.0, "do": "photo"},
        {"t": 2.1, "do": "record", "on": True}, {"t": 2.2, "do": "zoom", "rate": -1},
        {"t": 3.0, "do": "track_box", "x": 0.4, "y": 0.4, "w": 0.2, "h": 0.2},
        {"t": 3.5, "do": "track_stop"}, {"t": 4.0, "do": "range"}, {"t": 4.0, "do": "case", "id": "2.1"},
    ]:
        f.write(json.dumps(line) + "\n")
r = run(["--dry-run", "--intents", intents], no_mav)
check(r.returncode == 0, f"--dry-run exit {r.returncode}: {r.stderr}")
sent = [json.loads(x) for x in r.stdout.splitlines()]
by = {}
for s in sent:
    by.setdefault(s["do"], []).append(s)


def near(a, b):
    return a is not None and abs(a - b) < 1e-9


check(by["identity"][0]["command"] == 512 and by["identity"][0]["param1"] == 259, "identity: REQUEST_MESSAGE 259")
check(by["clock"][0]["send"] == "SYSTEM_TIME" and by["clock"][0]["time_unix_usec"] == 1796558400 * 10**6,
      f"clock: {by['clock']}")
mode, rate = by["rate"]
check(mode["command"] == 205 and mode["param7"] == 2, "rate: mount mode MAVLink targeting first")
check(rate["send"] == "GIMBAL_MANAGER_SET_PITCHYAW" and near(rate["pitch_rate"], math.radians(10))
      and near(rate["yaw_rate"], math.radians(-5)) and rate["pitch"] is None and rate["flags"] == 16,
      f"rate: {rate}")
angle = by["angle"][1]
check(near(angle["pitch"], math.radians(-30)) and near(angle["yaw"], math.radians(15))
      and angle["pitch_rate"] is None and angle["flags"] == 0, f"angle: {angle}")
check(near(by["stop"][0]["pitch_rate"], 0) and near(by["stop"][0]["yaw_rate"], 0), "stop: zero rates")
check(by["centre"][0]["command"] == 205 and by["centre"][0]["param7"] == 1, "centre: neutral")
check(by["photo"][0]["command"] == 2000 and by["photo"][0]["param3"] == 1, "photo: one image")
check(by["record"][0]["command"] == 2500, "record on: VIDEO_START_CAPTURE")
check(by["zoom"][0]["command"] == 531 and by["zoom"][0]["param1"] == 1 and by["zoom"][0]["param2"] == -1,
      "zoom: continuous, out")
box = by["track_box"][0]
check(box["command"] == 2005 and near(box["param3"], 0.6) and near(box["param4"], 0.6), f"track_box: {box}")
check(by["track_stop"][0]["command"] == 2010, "track_stop")
check("range" not in by and "case" not in by, "range and case: nothing sent")

bad = os.path.join(work, "bad.jsonl")
with open(bad, "w") as f:
    f.write('{"t":0.1,"do":"stop"}\n{"do":"stop"}\n')
r = run(["--dry-run", "--intents", bad], no_mav)
check(r.returncode != 0 and f"{bad}:2: not an intent" in r.stderr, f"bad intents: {r.returncode} {r.stderr}")

r = run(["--intents", intents], no_mav)
check(r.returncode == 2 and "pymavlink is not installed" in r.stderr, f"no pymavlink: {r.returncode} {r.stderr}")

with open("/dev/full", "w") as full:
    r = run(["--dry-run", "--intents", intents], no_mav, stdout=full)
check(r.returncode == 2 and "No space left" in r.stderr, f"/dev/full: {r.returncode} {r.stderr}")

print("drive adapter:", "ok" if not failures else f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
