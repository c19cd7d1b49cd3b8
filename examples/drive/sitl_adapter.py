#!/usr/bin/env python3
"""A topconf drive adapter for an ArduPilot SITL (docs/DRIVE.md, "Adapters").

topconf drive (docs/DRIVE.md) puts a simulated camera on a pty or a UDP port
and runs this script per case (or once, with --persistent). The SITL's mount
driver (MNT1_TYPE 12 Topotek, 15 SkyDroid) talks TOP to that camera; this
script talks MAVLink to the SITL:

  intents (TOPCONF_INTENT, JSON Lines)  ->  MAVLink commands to the autopilot
  MAVLink telemetry from the autopilot  ->  beliefs (JSON Lines on stdout)

Actions: rate/angle/stop as GIMBAL_MANAGER_SET_PITCHYAW (mount mode MAVLink
targeting first, MAV_CMD_DO_MOUNT_CONTROL param7 = 2); centre as
MAV_CMD_DO_MOUNT_CONTROL neutral (param7 = 1); photo MAV_CMD_IMAGE_START_CAPTURE;
record MAV_CMD_VIDEO_START/STOP_CAPTURE; zoom MAV_CMD_SET_CAMERA_ZOOM (type 1,
continuous); tracking MAV_CMD_CAMERA_TRACK_POINT/_RECTANGLE/STOP_TRACKING;
identity MAV_CMD_REQUEST_MESSAGE of CAMERA_INFORMATION; clock SYSTEM_TIME.
The range intent has no MAVLink command here: it is not acted on.

Beliefs: attitude from GIMBAL_DEVICE_ATTITUDE_STATUS (quaternion w, x, y, z)
or else MOUNT_STATUS (pointing_a pitch, _b roll, _c yaw, centidegrees);
healthy while one came within 1 s with no failure flag; model and version
from CAMERA_INFORMATION; tracking from CAMERA_TRACKING_IMAGE_STATUS.

--dry-run prints the MAVLink each intent becomes (JSON Lines on stdout) and
needs no pymavlink and no SITL. Everything else needs pymavlink.
"""
import argparse
import json
import math
import os
import signal
import sys
import time

TOOL = "sitl_adapter.py"

# MAVLink numbers (common.xml): commands and message ids used below.
MAV_CMD_DO_MOUNT_CONTROL = 205
MAV_CMD_REQUEST_MESSAGE = 512
MAV_CMD_SET_CAMERA_ZOOM = 531
MAV_CMD_IMAGE_START_CAPTURE = 2000
MAV_CMD_CAMERA_TRACK_POINT = 2004
MAV_CMD_CAMERA_TRACK_RECTANGLE = 2005
MAV_CMD_CAMERA_STOP_TRACKING = 2010
MAV_CMD_VIDEO_START_CAPTURE = 2500
MAV_CMD_VIDEO_STOP_CAPTURE = 2501
MSG_CAMERA_INFORMATION = 259
MAV_MOUNT_MODE_NEUTRAL = 1
MAV_MOUNT_MODE_MAVLINK_TARGETING = 2
GIMBAL_MANAGER_FLAGS_YAW_LOCK = 16  # yaw in the earth frame
NAN = float("nan")


def command(cmd, *params):
    """A COMMAND_LONG as (name, fields): params 1-7, the missing ones 0."""
    p = list(params) + [0.0] * (7 - len(params))
    return ("COMMAND_LONG", {"command": cmd, **{f"param{i + 1}": float(v) for i, v in enumerate(p)}})


def pitchyaw(pitch=NAN, yaw=NAN, pitch_rate=NAN, yaw_rate=NAN, earth=False):
    """GIMBAL_MANAGER_SET_PITCHYAW: angles in rad, rates in rad/s, NaN ignored;
    pitch positive up, yaw positive right."""
    return ("GIMBAL_MANAGER_SET_PITCHYAW", {
        "flags": GIMBAL_MANAGER_FLAGS_YAW_LOCK if earth else 0,
        "pitch": pitch, "yaw": yaw, "pitch_rate": pitch_rate, "yaw_rate": yaw_rate,
        "gimbal_device_id": 0})


def commands_for(intent):
    """The MAVLink an intent becomes: a list of (name, fields); [] when it has
    no MAVLink counterpart here (not acted on)."""
    do = intent.get("do")
    earth = intent.get("frame") == "earth"
    targeting = command(MAV_CMD_DO_MOUNT_CONTROL, 0, 0, 0, 0, 0, 0, MAV_MOUNT_MODE_MAVLINK_TARGETING)
    if do == "rate":
        return [targeting, pitchyaw(pitch_rate=math.radians(intent.get("pitch_dps", 0)),
                                    yaw_rate=math.radians(intent.get("yaw_dps", 0)), earth=earth)]
    if do == "angle":
        return [targeting, pitchyaw(pitch=math.radians(intent.get("pitch_deg", 0)),
                                    yaw=math.radians(intent.get("yaw_deg", 0)), earth=earth)]
    if do == "stop":
        return [pitchyaw(pitch_rate=0.0, yaw_rate=0.0)]
    if do == "centre":
        return [command(MAV_CMD_DO_MOUNT_CONTROL, 0, 0, 0, 0, 0, 0, MAV_MOUNT_MODE_NEUTRAL)]
    if do == "photo":  # id 0, interval 0, one image
        return [command(MAV_CMD_IMAGE_START_CAPTURE, 0, 0, 1)]
    if do == "record":
        return [command(MAV_CMD_VIDEO_START_CAPTURE if intent.get("on") else MAV_CMD_VIDEO_STOP_CAPTURE)]
    if do == "zoom":  # zoom type 1: continuous, value -1 out, 0 stop, 1 in
        return [command(MAV_CMD_SET_CAMERA_ZOOM, 1, intent.get("rate", 0))]
    if do == "track_point":
        return [command(MAV_CMD_CAMERA_TRACK_POINT, intent.get("x", 0.5), intent.get("y", 0.5), 0.05)]
    if do == "track_box":
        x, y = intent.get("x", 0.4), intent.get("y", 0.4)
        return [command(MAV_CMD_CAMERA_TRACK_RECTANGLE, x, y, x + intent.get("w", 0.2),
                        y + intent.get("h", 0.2))]
    if do == "track_stop":
        return [command(MAV_CMD_CAMERA_STOP_TRACKING)]
    if do == "identity":
        return [command(MAV_CMD_REQUEST_MESSAGE, MSG_CAMERA_INFORMATION)]
    if do == "clock":
        t = time.strptime(intent["utc"], "%Y-%m-%dT%H:%M:%SZ")
        import calendar
        return [("SYSTEM_TIME", {"time_unix_usec": calendar.timegm(t) * 1000000, "time_boot_ms": 0})]
    return []


class Intents:
    """The intents file, followed as it grows (--persistent appends to it)."""

    def __init__(self, path):
        self.path, self.offset, self.partial, self.line, self.pending = path, 0, "", 0, []

    def poll(self):
        if not self.path or not os.path.exists(self.path):
            return
        with open(self.path, encoding="utf-8") as f:
            f.seek(self.offset)
            text = f.read(1 << 20)
            self.offset = f.tell()
        self.partial += text
        *lines, self.partial = self.partial.split("\n")
        for text in lines:
            self.line += 1
            if not text.strip():
                continue
            try:
                intent = json.loads(text)
                float(intent["t"])
            except (ValueError, KeyError, TypeError) as e:
                raise SystemExit(f"{TOOL}: error: {self.path}:{self.line}: not an intent ({e})")
            self.pending.append(intent)
        self.pending.sort(key=lambda i: float(i["t"]))

    def due(self, t):
        out = [i for i in self.pending if float(i["t"]) <= t]
        self.pending = [i for i in self.pending if float(i["t"]) > t]
        return out


def euler_deg(q):
    """(roll, pitch, yaw) in degrees of the quaternion w, x, y, z."""
    w, x, y, z = q
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return tuple(math.degrees(a) for a in (roll, pitch, yaw))


class Beliefs:
    TRACKING = {0: "off", 1: "tracking", 2: "refused"}  # CAMERA_TRACKING_STATUS_FLAGS

    def __init__(self):
        self.attitude, self.at, self.failure, self.extra = None, 0.0, 0, {}

    def take(self, msg, now):
        """Updates from one MAVLink message; True when the attitude changed."""
        kind = msg.get_type()
        if kind == "GIMBAL_DEVICE_ATTITUDE_STATUS":
            self.attitude, self.at, self.failure = euler_deg(msg.q), now, msg.failure_flags
            return True
        if kind == "MOUNT_STATUS" and now - self.at > 1.0:
            self.attitude = (msg.pointing_b / 100.0, msg.pointing_a / 100.0, msg.pointing_c / 100.0)
            self.at, self.failure = now, 0
            return True
        if kind == "CAMERA_INFORMATION":
            name = bytes(msg.model_name).split(b"\0")[0].decode("ascii", "replace")
            v = msg.firmware_version  # major | minor << 8 | patch << 16 | dev << 24
            self.extra["model"] = name or "unknown"
            self.extra["version"] = f"{v & 0xFF}.{(v >> 8) & 0xFF}.{(v >> 16) & 0xFF}" if v else "unknown"
        if kind == "CAMERA_TRACKING_IMAGE_STATUS":
            self.extra["tracking"] = self.TRACKING.get(msg.tracking_status, "lost")
        return False

    def line(self, now):
        b = {"healthy": self.attitude is not None and now - self.at < 1.0 and self.failure == 0}
        if self.attitude is not None:
            r, p, y = self.attitude
            b["attitude"] = {"roll": round(r, 2), "pitch": round(p, 2), "yaw": round(y, 2)}
        b.update(self.extra)
        return json.dumps(b)


def send(master, target, name, fields):
    m = master.mav
    if name == "COMMAND_LONG":
        p = [fields[f"param{i}"] for i in range(1, 8)]
        m.command_long_send(target[0], target[1], fields["command"], 0, *p)
    elif name == "GIMBAL_MANAGER_SET_PITCHYAW":
        m.gimbal_manager_set_pitchyaw_send(target[0], target[1], fields["flags"], fields["gimbal_device_id"],
                                           fields["pitch"], fields["yaw"], fields["pitch_rate"],
                                           fields["yaw_rate"])
    elif name == "SYSTEM_TIME":
        m.system_time_send(fields["time_unix_usec"], fields["time_boot_ms"])


def main():
    ap = argparse.ArgumentParser(prog=TOOL, description=__doc__.split("\n\n")[0])
    ap.add_argument("--mavlink", default="udpin:127.0.0.1:14550",
                    help="pymavlink connection string of the SITL (default %(default)s)")
    ap.add_argument("--target", default="1/1", help="SYSID/COMPID of the autopilot (default %(default)s)")
    ap.add_argument("--intents", default=os.environ.get("TOPCONF_INTENT"),
                    help="the intents file (default $TOPCONF_INTENT)")
    ap.add_argument("--belief-hz", type=float, default=5.0, help="beliefs a second (default %(default)s)")
    ap.add_argument("--dry-run", action="store_true",
                    help="print the MAVLink each intent becomes, then exit (no pymavlink, no SITL)")
    args = ap.parse_args()
    intents = Intents(args.intents)
    intents.poll()
    if args.dry_run:
        for i in intents.pending:
            for name, fields in commands_for(i):
                fields = {k: None if isinstance(v, float) and math.isnan(v) else v for k, v in fields.items()}
                print(json.dumps({"t": i["t"], "do": i["do"], "send": name, **fields}))
        return 0
    try:
        from pymavlink import mavutil
    except ImportError:
        print(f"{TOOL}: error: pymavlink is not installed: it is needed to talk to the SITL "
              "(python3 -m pip install pymavlink); --help and --dry-run work without it", file=sys.stderr)
        return 2
    target = tuple(int(x) for x in args.target.split("/"))
    stop = []
    signal.signal(signal.SIGTERM, lambda *_: stop.append(1))
    master = mavutil.mavlink_connection(args.mavlink, source_system=255, source_component=190)
    start = time.monotonic()
    beliefs, next_belief, holding = Beliefs(), 0.0, None
    while not stop:
        now = time.monotonic() - start
        intents.poll()
        for i in intents.due(now):
            for name, fields in commands_for(i):
                send(master, target, name, fields)
            if i.get("do") in ("rate", "angle", "stop", "centre"):
                holding = commands_for(i)[-1] if i.get("do") == "rate" else None
        msg = master.recv_match(blocking=True, timeout=0.05)
        changed = msg is not None and beliefs.take(msg, now)
        if changed or now >= next_belief:
            next_belief = now + 1.0 / args.belief_hz
            if holding:  # a rate is held: re-sent with the beliefs, not left to time out
                send(master, target, *holding)
            print(beliefs.line(now), flush=True)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except OSError as e:  # a failed write on stdout (a full disk, a closed pipe)
        print(f"{TOOL}: error: {e}", file=sys.stderr)
        sys.exit(2)
