#!/usr/bin/env python3
"""Render `mech report` and `mech animate` in a real headless browser and check them.

    python3 tools/browser_check.py            # needs cargo and chromium (apt-get install chromium)

1. `mech report examples/mech/four_bar.mech` -> HTML; Chromium screenshots it at two
   input positions (`#frame=0` and `#frame=40`, which the page honours, paused). Checks:
   the linkage region differs between the two (the linkage moved), and each plot region
   has drawn (non-white) pixels (the plots are drawn).
2. `mech animate` -> SVG; screenshots after two virtual times (0.5 s and 2.5 s of a 4 s
   loop). Checks: the two differ (the SMIL animation plays).

Screenshots and the HTML/SVG go to target/browser-check/. Exit status 0 when every check
passes. PNGs are decoded with the standard library (zlib), 8-bit RGB or RGBA.
"""

import os
import shutil
import struct
import subprocess
import sys
import zlib

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
OUT = os.path.join(ROOT, "target", "browser-check")
MECH = os.path.join(ROOT, "examples", "mech", "four_bar.mech")


def browser():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    sys.exit("no Chromium: install it with `apt-get install -y chromium`")


def mech(*args):
    subprocess.run(["cargo", "run", "--quiet", "--release", "-p", "mech-cli", "--bin", "mech", "--", *args], cwd=ROOT, check=True)


def shoot(url, png, size="1200,1100", budget_ms=None):
    cmd = [browser(), "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--screenshot=" + png, "--window-size=" + size]
    if budget_ms is not None:
        cmd.append("--virtual-time-budget=%d" % budget_ms)
    subprocess.run(cmd + [url], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=120)


def read_png(path):
    """(width, height, rows of (r, g, b) tuples) of an 8-bit RGB/RGBA PNG."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            width, height, depth, color = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and color in (2, 6), "8-bit RGB or RGBA"
            bpp = 3 if color == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = width * bpp
    rows, prev = [], bytearray(stride)
    for y in range(height):
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
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(width)])
        prev = line
    return width, height, rows


def region(rows, x0, y0, x1, y1):
    return [px for row in rows[y0:y1] for px in row[x0:x1]]


def inked(pixels):
    return sum(1 for p in pixels if sum(p) < 600)


def main():
    os.makedirs(OUT, exist_ok=True)
    html, svg = os.path.join(OUT, "report.html"), os.path.join(OUT, "animate.svg")
    mech("report", MECH, "-o", html, "--speed", "10", "--point", "P")
    mech("animate", MECH, "-o", svg, "--frames", "120", "--seconds", "4")
    failures = []

    a, b = os.path.join(OUT, "report-0.png"), os.path.join(OUT, "report-40.png")
    shoot("file://%s#frame=0" % html, a)
    shoot("file://%s#frame=40" % html, b)
    (w, h, ra), (_, _, rb) = read_png(a), read_png(b)
    # The linkage is in the upper part of the page, the plots below it.
    link_a, link_b = region(ra, 0, 180, w, 520), region(rb, 0, 180, w, 520)
    changed = sum(1 for p, q in zip(link_a, link_b) if p != q)
    print("report: %d pixels of the linkage changed between frames 0 and 40" % changed)
    if changed < 500:
        failures.append("the linkage did not move in the report")
    plots = region(ra, 0, 540, w, h)
    print("report: %d inked pixels in the plots" % inked(plots))
    if inked(plots) < 2000:
        failures.append("the plots are blank")

    c, d = os.path.join(OUT, "animate-0.5s.png"), os.path.join(OUT, "animate-2.5s.png")
    shoot("file://%s" % svg, c, "820,600", 500)
    shoot("file://%s" % svg, d, "820,600", 2500)
    (_, _, rc), (_, _, rd) = read_png(c), read_png(d)
    moved = sum(1 for p, q in zip((px for row in rc for px in row), (px for row in rd for px in row)) if p != q)
    print("animate: %d pixels changed between 0.5 s and 2.5 s" % moved)
    if moved < 500:
        failures.append("the animated SVG did not move")
    if inked(region(rc, 0, 0, 820, 600)) < 500:
        failures.append("the animated SVG is blank")

    for f in failures:
        print("FAILED:", f)
    print("screenshots in", OUT)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
