#!/usr/bin/env python3
"""A small SkyDroid driver over UDP for topconf drive's own tests (issue 50).

  drive_fake_driver.py HOST:PORT [--wrong-sign] [--no-stop] [--follow] [--quiet]

It does what the drive contract asks of a driver (docs/DRIVE.md), no more:
switches the GAC stream on (GAA, every second), turns the gimbal with GSY
and GSP at 20 Hz while a rate intent holds and its attitude is fresh, sends
zero rates on a stop, and prints its beliefs (attitude from GAC, healthy
while a GAC came within 1 s) every 0.2 s. Switches put in the bugs the
harness must catch: --wrong-sign (pitch rates negated: case 2.1),
--no-stop (no zero rate: case 2.4). --follow reads the intents file as it
grows (--persistent). It checks its environment (TOPCONF_CASE, _INTENT,
_MODEL, _LINK, _T0_US, _PORT against the command line) and says what is wrong as
a belief "error". One line that is not JSON comes first (counted by the
harness). SIGTERM ends it (exit 0).
"""
import json
import os
import select
import signal
import socket
import sys
import time


def frame(ident, data, dst="G"):
    body = "#TPU%s2w%s%s" % (dst, ident, data)
    return (body + "%02X" % (sum(body.encode()) % 256)).encode()


def rate_data(dps):
    steps = max(-127, min(127, int(round(dps / 0.5))))
    return "%02X" % (steps & 0xFF)


def s16(h):
    v = int(h, 16)
    return v - 0x10000 if v >= 0x8000 else v


class Intents:
    def __init__(self, path, follow):
        self.path, self.follow, self.pos, self.items = path, follow, 0, []
        self.read()

    def read(self):
        if not self.path or not os.path.exists(self.path):
            return
        with open(self.path) as f:
            f.seek(self.pos)
            text = f.read()
        # Whole lines only: a line being written waits for its end.
        cut = text.rfind("\n") + 1
        self.pos += len(text[:cut].encode())
        for line in text[:cut].splitlines():
            if line.strip():
                self.items.append(json.loads(line))
        self.items.sort(key=lambda i: i["t"])

    def due(self, t):
        if self.follow:
            self.read()
        out = [i for i in self.items if i["t"] <= t]
        self.items = [i for i in self.items if i["t"] > t]
        return out


def started():
    """time.monotonic() when this process started (the driver's time 0 of the
    contract, which Python's start-up must not shift): /proc's start time."""
    with open("/proc/self/stat") as f:
        start = int(f.read().rsplit(")", 1)[1].split()[19]) / os.sysconf("SC_CLK_TCK")
    since = time.clock_gettime(time.CLOCK_BOOTTIME) - start
    # Another clock (a time namespace): take now as the start.
    return time.monotonic() - (since if 0 <= since < 5 else 0.0)


def main():
    args = sys.argv[1:]
    host, port = args[0].rsplit(":", 1)
    wrong, nostop = "--wrong-sign" in args, "--no-stop" in args
    quiet = "--quiet" in args
    stop = []
    signal.signal(signal.SIGTERM, lambda *_: stop.append(1))
    errors = []
    for key in ("TOPCONF_CASE", "TOPCONF_INTENT", "TOPCONF_MODEL", "TOPCONF_LINK",
                "TOPCONF_T0_US"):
        if not os.environ.get(key):
            errors.append(key + " missing")
    if os.environ.get("TOPCONF_PORT") != port:
        errors.append("TOPCONF_PORT %r is not {port} %r" % (os.environ.get("TOPCONF_PORT"), port))
    if os.environ.get("TOPCONF_LINK") != "udp":
        errors.append("TOPCONF_LINK is not udp")
    intents = Intents(os.environ.get("TOPCONF_INTENT"), "--follow" in args)
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    dev = (host, int(port))
    print("hello: this line is not JSON", flush=True)
    # Time 0: topconf's (TOPCONF_T0_US, CLOCK_MONOTONIC as time.monotonic),
    # else this process's start.
    t0 = started()
    given = os.environ.get("TOPCONF_T0_US", "")
    if given.isdigit() and 0 <= time.monotonic() - int(given) / 1e6 < 10:
        t0 = int(given) / 1e6
    elif given:
        errors.append("TOPCONF_T0_US %r is not a recent CLOCK_MONOTONIC time" % given)
    att, att_t = None, -10.0
    rate = None  # (yaw, pitch) deg/s while a rate intent holds
    next_gaa = next_rate = next_belief = 0.0
    while not stop:
        now = time.monotonic() - t0
        r, _, _ = select.select([sock], [], [], 0.01)
        if r:
            data = sock.recv(2048).decode("latin-1")
            i = data.find("GAC")
            if i >= 7 and len(data) >= i + 15 and data[i - 1] == "r":
                try:
                    yaw, pitch, roll = (s16(data[i + 3 + k:i + 7 + k]) / 100.0 for k in (0, 4, 8))
                    att, att_t = {"yaw": yaw, "pitch": pitch, "roll": roll}, now
                except ValueError:
                    pass
        for it in intents.due(now):
            if it["do"] == "rate":
                rate = (it.get("yaw_dps", 0), it.get("pitch_dps", 0))
            elif it["do"] in ("stop", "angle", "centre"):
                if rate is not None and not nostop:
                    sock.sendto(frame("GSY", "00"), dev)
                    sock.sendto(frame("GSP", "00"), dev)
                rate = None
        if now >= next_gaa:
            sock.sendto(frame("GAA", "0A"), dev)
            next_gaa = now + 1.0
        fresh = now - att_t < 1.0
        if rate is not None and fresh and now >= next_rate:
            pitch = -rate[1] if wrong else rate[1]
            sock.sendto(frame("GSY", rate_data(rate[0])), dev)
            sock.sendto(frame("GSP", rate_data(pitch)), dev)
            next_rate = now + 0.05
        if not quiet and now >= next_belief:
            b = {"healthy": fresh}
            if att:
                b["attitude"] = att
            if errors:
                b["error"] = "; ".join(errors)
            print(json.dumps(b), flush=True)
            next_belief = now + 0.2
    return 0


if __name__ == "__main__":
    sys.exit(main())
