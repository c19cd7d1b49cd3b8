#!/usr/bin/env python3
"""Renders `topdump report` for captures and checks each page offline.

  report_check.py --topdump BIN --out DIR [--chromium] [--together NAME
                  [--every-diagnosis DIAGNOSES.md]] CAPTURE...

Every page: written (exit 0 or 1), at most 5 MB, no external URL (no
http:, https: or // in any src or href, no url( in styles, no <link>),
well-formed: parsed strictly as XML by python3's xml.etree (expat). With
--chromium, headless Chromium loads each page with the network resolver
off: no console message may appear, and the screenshot must not be blank
(enough non-white pixels, more than two colours). Exit 77 (skip) when
--chromium is given and /usr/bin/chromium is absent.

--together NAME: one page of every capture (NAME.html) instead of one page
each. --every-diagnosis: that page's "What went wrong" (report --json,
what_went_wrong[].code) must name every code of docs/DIAGNOSES.md's first table,
each with its evidence and remedy.
"""
import argparse
import concurrent.futures
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET
import zlib


def png_pixels(path):
    """Decodes an 8-bit RGB/RGBA non-interlaced PNG: (width, height, rows)."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or ctype not in (2, 6) or interlace:
                raise ValueError("unsupported PNG layout")
            bpp = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pr = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pr) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, bpp, rows


def check_offline(page, text):
    errors = []
    for m in re.finditer(r'\b(src|href)\s*=\s*"([^"]*)"', text):
        v = m.group(2).lower()
        if "http:" in v or "https:" in v or "//" in v:
            errors.append("%s: external %s=%r" % (page, m.group(1), m.group(2)))
    if re.search(r"url\(", text):
        errors.append("%s: a url( in a style" % page)
    if re.search(r"<link\b", text) or re.search(r"<script[^>]*\bsrc=", text):
        errors.append("%s: a <link> or an external script" % page)
    return errors


def page_check_args(ap):
    """Adds a page check's --out DIR and --chromium to `ap` (which holds the
    check's own arguments), parses them and makes DIR. Returns the arguments
    and Chromium's path; exits 77 (skip) when --chromium is given and
    Chromium is absent. report_check and tests/conformance/table_check."""
    ap.add_argument("--out", required=True)
    ap.add_argument("--chromium", action="store_true")
    a = ap.parse_args()
    chromium = shutil.which("chromium") or "/usr/bin/chromium"
    if a.chromium and not os.path.exists(chromium):
        print("chromium not installed: skipped")
        sys.exit(77)
    os.makedirs(a.out, exist_ok=True)
    return a, chromium


def verdict(errors, summary):
    """Prints each problem and the summary line; returns the exit status."""
    for e in errors:
        print("FAIL " + e)
    print(summary)
    return 1 if errors else 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--topdump", required=True)
    ap.add_argument("--together")
    ap.add_argument("--every-diagnosis")
    ap.add_argument("captures", nargs="+")
    a, chromium = page_check_args(ap)
    if a.together:
        errors = check(a, chromium, a.captures, a.together)
        if a.every_diagnosis:
            errors += every_diagnosis(a)
        return verdict(errors, "%d captures on one page, %d problems" %
                       (len(a.captures), len(errors)))
    # two pages at a time (the machine has two cores; Chromium waits a lot)
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        results = list(pool.map(lambda cap: check(a, chromium, cap), a.captures))
    errors = [e for r in results for e in r]
    return verdict(errors, "%d captures, %d problems" % (len(a.captures), len(errors)))


def every_diagnosis(a):
    """The table's codes missing from the page's "What went wrong"."""
    # the first table only: the diagnoses; the device notes' table after it
    # names no diagnosis (they are info notes, not in "What went wrong")
    rows = re.search(r"(?:^\| `[a-z-]+` \|.*\n)+", open(a.every_diagnosis).read(), re.M)
    table = re.findall(r"^\| `([a-z-]+)` \|", rows.group(0) if rows else "", re.M)
    r = subprocess.run([a.topdump, "report", "--json"] + a.captures, capture_output=True,
                       text=True)
    items = json.loads(r.stdout)["overview"]["what_went_wrong"]
    seen = {i["code"]: i for i in items if i.get("code")}
    errors = []
    if len(table) < 10:
        errors.append("%s: no diagnosis table found" % a.every_diagnosis)
    for code in table:
        if code not in seen:
            errors.append("%s: not in What went wrong" % code)
        elif not seen[code].get("evidence") or not seen[code].get("remedy"):
            errors.append("%s: no evidence or remedy" % code)
    print("every diagnosis: %d of %d codes on the page" % (len(table) - len(errors), len(table)))
    return errors


def check(a, chromium, cap, together=None):
    """The problems of one capture's page (of every capture's, `together`)."""
    errors = []
    caps = cap if together else [cap]
    name = together or os.path.basename(cap)
    page = os.path.join(a.out, name + ".html")
    r = subprocess.run([a.topdump, "report"] + caps + ["-o", page], capture_output=True)
    if r.returncode not in (0, 1) or not os.path.exists(page):
        errors.append("%s: topdump report exit %d: %s" % (name, r.returncode, r.stderr))
        return errors
    size = os.path.getsize(page)
    if size > 5 * 1024 * 1024:
        errors.append("%s: %d bytes, over 5 MB" % (name, size))
    text = open(page, encoding="ascii").read()
    errors += check_offline(name, text)
    try:
        root = ET.parse(page).getroot()
        if root.tag != "html" or root.find("body") is None:
            errors.append("%s: no html/body" % name)
        if len(root.findall(".//section")) != 7:
            errors.append("%s: not seven sections" % name)
    except ET.ParseError as e:
        errors.append("%s: not well-formed: %s" % (name, e))
    if not a.chromium:
        return errors
    errors += render_check(chromium, page, a.out, name, size)
    return errors


def render_check(chromium, page, out, name, size, want=()):
    """Headless Chromium loads `page` offline (the network resolver off): the
    problems, none when no console message appeared and the screenshot
    (OUT/NAME.png) is not blank and shows every colour of `want` (RGB
    bytes). Also used by tests/conformance/table_check.py."""
    errors = []
    shot = os.path.join(out, name + ".png")
    if os.path.exists(shot):
        os.remove(shot)
    profile = os.path.join(out, "chromium-profile-" + name)
    r = subprocess.run(
        [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
         "--user-data-dir=" + profile, "--host-resolver-rules=MAP * ~NOTFOUND",
         "--enable-logging=stderr", "--v=0", "--hide-scrollbars",
         "--window-size=1200,1600", "--screenshot=" + shot, "file://" + os.path.abspath(page)],
        capture_output=True, text=True, timeout=120)
    console = [l for l in r.stderr.splitlines() if "CONSOLE" in l]
    if console:
        errors.append("%s: console messages in Chromium: %s" % (name, console[:3]))
    if r.returncode != 0 or not os.path.exists(shot):
        errors.append("%s: chromium exit %d, no screenshot: %s" %
                      (name, r.returncode, r.stderr[-500:]))
        return errors
    w, h, bpp, rows = png_pixels(shot)
    colours, ink = set(), 0
    for row in rows[::4]:
        for x in range(0, w * bpp, bpp * 4):
            px = row[x:x + 3]
            colours.add(px)
            if px != b"\xff\xff\xff":
                ink += 1
    total = len(rows[::4]) * len(range(0, w * bpp, bpp * 4))
    if len(colours) < 3 or ink < total // 50:
        errors.append("%s: blank screenshot (%d colours, %d of %d sampled pixels not white)" %
                      (name, len(colours), ink, total))
    for c in want:
        if c not in colours:
            errors.append("%s: the screenshot has no #%s" % (name, c.hex()))
    print("%s: %d bytes, screenshot %dx%d, %d colours" % (name, size, w, h, len(colours)))
    return errors


if __name__ == "__main__":
    sys.exit(main())
