#!/usr/bin/env python3
"""Compares tshark running the generated top.lua with `topdump read --json`.

For each capture, frame by frame in capture order: identifier, header,
addresses, control, lengths, checksum verdict, role, dialect, every field
value (numbers within half the last digit topdump shows), the one-line
summary and the findings (code and severity, as expert infos). Any
difference fails, naming the capture, topdump's frame number and record and
tshark's packet number.

Usage: compare.py --tshark T --topdump D --lua top.lua [--tshark-opt -o ...]
                  [--topdump-opt ...] [--expect-role IDENT=ROLE] CAPTURE...
Exit status: 0 equal, 1 a difference, 77 (ctest's SKIP_RETURN_CODE) when
tshark is not installed.
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

SKIP = 77


def topdump_frames(topdump, cap, opts):
    out = subprocess.run([topdump, "read", "--json", *opts, cap], capture_output=True, check=False)
    if out.returncode not in (0, 1):
        raise RuntimeError(f"topdump read --json {cap}: exit {out.returncode}: {out.stderr.decode()}")
    frames = []
    for line in out.stdout.decode().splitlines():
        o = json.loads(line)
        if o.get("type") == "frame":
            frames.append(o)
    return frames


def parse_pdml(text):
    try:
        return ET.fromstring(text)
    except ET.ParseError:
        # tshark stops inside a truncated capture: close what it opened
        cut = text.rfind("</packet>")
        return ET.fromstring(text[: cut + len("</packet>")] + "\n</pdml>\n")


def descendants(el):
    for c in el:
        yield c
        yield from descendants(c)


def tshark_frames(tshark, lua, cap, opts):
    cmd = [tshark, "-n", "-X", "lua_script:" + lua, *opts, "-r", cap, "-T", "pdml"]
    out = subprocess.run(cmd, capture_output=True, check=False)
    err = out.stderr.decode(errors="replace")
    if "Lua: Error" in err or "Lua: Error" in out.stdout.decode(errors="replace"):
        raise RuntimeError(f"{' '.join(cmd)}: {err}")
    if not out.stdout.strip():
        raise RuntimeError(f"{' '.join(cmd)}: exit {out.returncode}: {err}")
    root = parse_pdml(out.stdout.decode(errors="replace"))
    frames = []
    for packet in root.iter("packet"):
        number = None
        ep = {}
        for proto in packet.findall("proto"):
            if proto.get("name") == "frame":
                for f in proto.iter("field"):
                    if f.get("name") == "frame.number":
                        number = int(f.get("show"))
            for f in proto.iter("field"):
                n = f.get("name")
                if n in ("ip.src", "ip.dst", "udp.srcport", "udp.dstport", "tcp.srcport",
                         "tcp.dstport") and n not in ep:
                    ep[n] = f.get("show")
                elif n in ("ipv6.src", "ipv6.dst") and n not in ep:
                    ep[n] = "[" + f.get("show") + "]"
        direction = None
        host_s, host_d = ep.get("ip.src", ep.get("ipv6.src")), ep.get("ip.dst", ep.get("ipv6.dst"))
        port_s = ep.get("udp.srcport", ep.get("tcp.srcport"))
        port_d = ep.get("udp.dstport", ep.get("tcp.dstport"))
        if host_s and port_s:
            direction = f"{host_s}:{port_s} > {host_d}:{port_d}"
        # a frame completed by TCP reassembly may sit in a wrapper proto
        for proto in packet.iter("proto"):
            if proto.get("name") != "top":
                continue
            items = list(descendants(proto))
            for f in items:
                if f.get("name") == "_ws.lua.error":
                    raise RuntimeError(f"{cap}: packet {number}: Lua error: {f.get('showname')}")
            if any(f.get("name") == "top.garbage" for f in items):
                continue
            fr = {"packet": number, "fields": [], "findings": [], "hdr": {}, "dir": direction}
            for f in items:
                name = f.get("name") or ""
                if name.startswith("top.finding."):
                    parts = name[len("top.finding."):].split(".")
                    fr["findings"].append((parts[0], parts[1] if len(parts) > 1 else None))
                elif name.count(".") == 2 and re.match(r"^top\.[A-Z0-9]{3}\.", name):
                    fr["fields"].append((name.split(".")[2], f.get("show"), f.get("showname")))
                elif name.startswith("top.") and name not in fr["hdr"]:
                    fr["hdr"][name] = f.get("show")
            frames.append(fr)
    return frames


def half_last_digit(text):
    m = re.match(r"^-?\d+(?:\.(\d+))?", text or "")
    if not m:
        return 1e-9
    return 0.5 * 10 ** -(len(m.group(1)) if m.group(1) else 0) + 1e-9


def compare_frame(t, w, defaults):
    """Differences between topdump frame t and tshark frame w, as strings."""
    diffs = []
    h = w["hdr"]

    def same(what, a, b):
        if str(a) != str(b):
            diffs.append(f"{what}: topdump {a!r}, tshark {b!r}")

    same("ident", t["ident"], h.get("top.ident"))
    same("header", t["header"], h.get("top.header"))
    same("src", t["src"], h.get("top.src"))
    same("dst", t["dst"], h.get("top.dst"))
    same("control", t["control"] or "", h.get("top.control", ""))
    same("declared length", t["declared_length"], h.get("top.length"))
    same("data length", t["length"], h.get("top.data_length"))
    same("checksum ok", t["checksum_ok"], h.get("top.checksum.status") == "1")
    same("role", t["role"], h.get("top.role"))
    same("dialect", t["dialect"], h.get("top.dialect"))
    summary = ", ".join(f"{k} {v['text']}" for k, v in t["fields"].items())
    if t["fields"] and all(v.get("none") for v in t["fields"].values()):
        summary = None  # the form's note may stand in for the fields
    if summary is not None:
        same("summary", summary, h.get("top.summary", ""))
    # field values, in order; a null value (none, invalid) has no field item
    got = [(n, s, sn) for (n, s, sn) in w["fields"]]
    want = [(k, v) for k, v in t["fields"].items() if v.get("value") is not None]
    # a record's field is "x[1]" in topdump, top.<ident>.x in the dissector
    if [re.sub(r"\[\d+\]$", "", k) for k, _ in want] != [n for n, _, _ in got]:
        diffs.append(f"fields: topdump {[k for k, _ in want]}, tshark {[n for n, _, _ in got]}")
    else:
        for (k, v), (_, show, showname) in zip(want, got):
            val = v["value"]
            if isinstance(val, (int, float)) and not isinstance(val, bool):
                try:
                    x = float(int(show, 0)) if show.startswith("0x") else float(show)
                except (TypeError, ValueError):
                    diffs.append(f"field {k}: topdump {val}, tshark {show!r}")
                    continue
                if not math.isclose(x, float(val), abs_tol=half_last_digit(v["text"])):
                    diffs.append(f"field {k}: topdump {val} ({v['text']}), tshark {show}")
            elif all(0x20 <= ord(c) < 0x7F for c in str(val)):
                if str(val) != show:
                    diffs.append(f"field {k}: topdump {val!r}, tshark {show!r}")
            if showname != f"{k}: {v['text']}" and all(0x20 <= ord(c) < 0x7F for c in v["text"]):
                diffs.append(f"field {k} label: topdump {k}: {v['text']!r}, tshark {showname!r}")
    # TCP: CR/LF that arrives in the segment after its frame is not seen with
    # the frame (docs/WIRESHARK.md, Limits)
    want_f = sorted((x["code"], x["severity"]) for x in t["findings"]
                    if not (t["transport"] == "tcp" and x["code"] == "crlf"))
    got_f = sorted((c, s or defaults.get(c, "?")) for c, s in w["findings"]
                   if not (t["transport"] == "tcp" and c == "crlf"))
    if want_f != got_f:
        diffs.append(f"findings: topdump {want_f}, tshark {got_f}")
    return diffs


def finding_defaults(lua):
    d = {}
    with open(lua, encoding="ascii") as f:
        for m in re.finditer(r'^FINDINGS\["([a-z0-9-]+)"\] = "(\w+)"', f.read(), re.M):
            d[m.group(1)] = m.group(2)
    return d


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tshark", default="tshark")
    ap.add_argument("--topdump", required=True)
    ap.add_argument("--lua", required=True)
    ap.add_argument("--tshark-opt", action="append", default=[])
    ap.add_argument("--topdump-opt", action="append", default=[])
    ap.add_argument("--reference", help="topdump reads this capture instead (same frames, "
                    "another link: the DLT_USER0 serial dump)")
    ap.add_argument("--expect-fields", help="file of '<ident> <field>...' lines, one per frame: "
                    "tshark must show each top.<ident>.<field>")
    ap.add_argument("--expect-role", action="append", default=[], metavar="IDENT=ROLE",
                    help="tshark must show every frame of IDENT with this role (and at least one)")
    ap.add_argument("captures", nargs="+")
    a = ap.parse_args()
    tshark = shutil.which(a.tshark) if not os.path.isabs(a.tshark) else a.tshark
    if not tshark or not os.path.exists(tshark):
        print("SKIP: tshark not found (scripts/install-deps.sh installs it)")
        return SKIP
    defaults = finding_defaults(a.lua)
    failed = 0
    for cap in a.captures:
        name = os.path.basename(cap)
        td = topdump_frames(a.topdump, a.reference or cap, a.topdump_opt)
        ws = tshark_frames(tshark, a.lua, cap, a.tshark_opt)
        bad = 0
        if a.expect_fields:
            with open(a.expect_fields, encoding="ascii") as f:
                expected = [line.split() for line in f if line.strip()]
            if len(expected) != len(ws):
                print(f"{name}: {len(expected)} frames built, tshark shows {len(ws)}")
                bad += 1
            for i, (want, w) in enumerate(zip(expected, ws)):
                shown = [n for n, _, _ in w["fields"]]
                if w["hdr"].get("top.ident") != want[0] or shown != want[1:]:
                    print(f"{name}: frame {i + 1} (tshark packet {w['packet']}): built {want[0]} "
                          f"with {want[1:]}, tshark shows {w['hdr'].get('top.ident')} with {shown}")
                    bad += 1
        for want in a.expect_role:
            ident, role = want.split("=", 1)
            shown = [w for w in ws if w["hdr"].get("top.ident") == ident]
            if not shown:
                print(f"{name}: no {ident} frame in tshark's dissection")
                bad += 1
            for w in shown:
                if w["hdr"].get("top.role") != role:
                    print(f"{name}: tshark packet {w['packet']}: {ident} shown as "
                          f"{w['hdr'].get('top.role')!r}, want {role!r}")
                    bad += 1
        # Compared per direction (a TCP frame is reported when its segment is
        # complete, so the directions interleave differently), in capture
        # order when tshark shows no endpoints (DLT_USER0).
        if all(w["dir"] for w in ws) and not a.reference:
            td = sorted(td, key=lambda t: (f"{t['from']} > {t['to']}", t["n"]))
            ws = sorted(ws, key=lambda w: (w["dir"], w["packet"]))
        for i in range(max(len(td), len(ws))):
            if i >= len(td) or i >= len(ws):
                extra = ws[i] if i >= len(td) else td[i]
                side = "tshark" if i >= len(td) else "topdump"
                where = f"packet {extra['packet']}" if side == "tshark" else \
                        f"frame #{extra['n']} (record {extra['record']}.{extra['index']})"
                print(f"{name}: {side} has a frame the other lacks: {where}"
                      f" ({len(td)} topdump frames, {len(ws)} tshark frames)")
                bad += 1
                continue
            diffs = compare_frame(td[i], ws[i], defaults)
            if diffs:
                bad += 1
                t = td[i]
                print(f"{name}: frame #{t['n']} (record {t['record']}.{t['index']}, tshark packet "
                      f"{ws[i]['packet']}) {t['raw']}:")
                for d in diffs:
                    print("    " + d)
            if bad >= 20:
                print(f"{name}: stopping after 20 differing frames")
                break
        print(f"{name}: {len(td)} topdump frames, {len(ws)} tshark frames, "
              f"{'OK' if bad == 0 else f'{bad} differ'}")
        failed += bad > 0
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
