#!/usr/bin/env python3
"""`mech serve` in headless Chromium (tools/serve_check.sh installs what this needs).

Serves a temporary copy of examples/mech/four_bar.mech and checks, as a person would see
the page:
1. slider: the drawing moves when the slider moves; the pins read from the page's SVG
   are `mech solve`'s points at the slider's value;
2. chart: the values under the pointer on the driver torque, a reaction's magnitude and
   I* charts are `mech sweep`'s at that row;
3. edit: the file edited on disk is on the page within a second (a ground pivot moved);
4. error: a broken file shows its line and `mech check`'s message; the drawing stays;
5. drag: dragging point A on the page rewrites A's two numbers in the file, nothing else.
Prints PASS/FAIL per check and `serve_check: N passed, M failed`; exit status 1 on a
failure. Screenshots go to --out; with --docs the page is also saved as docs/img/serve.png.
"""

import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request

from playwright.sync_api import sync_playwright

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
FOUR_BAR = os.path.join(ROOT, "examples", "mech", "four_bar.mech")
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def csv_columns(text):
    lines = text.strip().splitlines()
    names = lines[0].split(",")
    rows = [[float(v) for v in l.split(",")] for l in lines[1:]]
    return {n: [r[i] for r in rows] for i, n in enumerate(names)}


class Check:
    def __init__(self, args):
        self.args = args
        self.dir = tempfile.mkdtemp(prefix="serve-check-")
        self.file = os.path.join(self.dir, "four_bar.mech")
        shutil.copy(FOUR_BAR, self.file)
        self.original = open(self.file).read()
        # Served by its name in its folder, as a designer would: the page shows `four_bar.mech`.
        self.server = subprocess.Popen([args.mech, "serve", "four_bar.mech", "--port", "0"], cwd=self.dir, stdin=subprocess.DEVNULL,
                                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        line = self.server.stderr.readline()
        m = re.search(r"http://127\.0\.0\.1:\d+/", line)
        if not m:
            raise SystemExit("serve_check: no address from mech serve: %r" % line)
        self.url = m.group(0)
        threading.Thread(target=lambda: [None for _ in self.server.stderr], daemon=True).start()

    def mech(self, *args):
        return subprocess.run([self.args.mech, *args], check=True, capture_output=True, text=True).stdout

    def api(self, path):
        with urllib.request.urlopen(self.url + path.lstrip("/"), timeout=20) as r:
            return json.load(r)

    def close(self):
        self.server.kill()
        self.server.wait()
        shutil.rmtree(self.dir, ignore_errors=True)

    # Reading the page.
    def pins(self, page):
        """The pins of the page's drawing, in the drawing's coordinates (m)."""
        v = self.api("/api/model")["view"]
        pins = page.eval_on_selector_all("#drawing circle.pin", "els => els.map(e => [e.dataset.name, +e.getAttribute('cx'), +e.getAttribute('cy')])")
        return {n: ((x - v["pad"]) / v["k"] + v["x_min"], v["y_max"] - (y - v["pad"]) / v["k"]) for n, x, y in pins}, v

    def page_q(self, page):
        return page.eval_on_selector("#drawing", "e => e.dataset.q")

    # The checks.
    def slider(self, page):
        before, _ = self.pins(page)
        page.fill("#slider-0", "2.2")
        page.wait_for_function("document.getElementById('drawing').dataset.q == document.getElementById('slider-0').value")
        q = self.page_q(page)
        after, v = self.pins(page)
        solved = csv_columns(self.mech("solve", self.file, "--at", q, "--level", "pose", "--format", "csv"))
        tol = 0.006 / v["k"]  # the picture's coordinates have 2 decimals (px)
        moved = max(math.dist(before[n], after[n]) for n in after)
        assert moved * v["k"] > 20, "the drawing did not move (%.1f px)" % (moved * v["k"])
        for name, (x, y) in after.items():
            sx, sy = solved[name + ".x"][0], solved[name + ".y"][0]
            assert abs(x - sx) < tol and abs(y - sy) < tol, "pin %s at (%g, %g), mech solve (%g, %g)" % (name, x, y, sx, sy)
        return "q = %s: %d pins within %.1e m of mech solve, moved %.0f px" % (q, len(after), tol, moved * v["k"])

    def chart(self, page):
        page.fill("#speed", "10")
        page.dispatch_event("#speed", "change")
        page.wait_for_function("document.getElementById('charts').dataset.speed == '10'")
        sweep = csv_columns(self.mech("sweep", self.file, "--from", "0", "--to", repr(2 * math.pi), "--steps", "360",
                                      "--speed", "10", "--format", "csv"))
        page.select_option("#joint", "A")
        out = []
        for chart, label, expected in (("driver", "driver", lambda i: sweep["driver"][i]),
                                       ("reaction", "|R A|", lambda i: math.hypot(sweep["A.fx"][i], sweep["A.fy"][i])),
                                       ("inertia", "I*", lambda i: sweep["inertia"][i])):
            box = page.locator("#plot-" + chart).bounding_box()
            page.mouse.move(box["x"] + 54 + 0.37 * (290 - 62), box["y"] + 60)
            r = page.eval_on_selector("#readout-" + chart, "e => ({i: +e.dataset.index, x: +e.dataset.x, v: +e.dataset.value})")
            i = r["i"]
            assert 100 < i < 260, r
            assert r["x"] == sweep["q"][i], (r, sweep["q"][i])
            want = expected(i)
            assert abs(r["v"] - want) <= 1e-12 * max(1.0, abs(want)), "%s at row %d: page %r, mech sweep %r" % (label, i, r["v"], want)
            out.append("%s row %d = %.6g" % (label, i, want))
        return ", ".join(out) + " as mech sweep"

    def version(self, page):
        m = re.search(r"version (\d+)", page.text_content("#status") or "")
        return int(m.group(1)) if m else -1

    def edit(self, page):
        v0 = self.version(page)
        text = self.original.replace("O4: (0.3, 0.04)", "O4: (0.33, 0.05)")
        t0 = time.monotonic()
        with open(self.file, "w") as f:
            f.write(text)
        page.wait_for_function("v => { const m = /version (\\d+)/.exec(document.getElementById('status').textContent); return m && +m[1] > v; }", arg=v0, timeout=1000)
        took = time.monotonic() - t0
        pins, v = self.pins(page)
        x, y = pins["O4"]
        assert abs(x - 0.33) < 0.01 / v["k"] and abs(y - 0.05) < 0.01 / v["k"], "O4 drawn at (%g, %g)" % (x, y)
        assert took < 1.0, took
        return "the new O4 drawn after %.2f s" % took

    def error(self, page):
        broken = self.original.replace("B: revolute(coupler, rocker)", "B: revolute(coupler, rockr)")
        line = 1 + next(i for i, l in enumerate(broken.splitlines()) if "rockr" in l)
        with open(self.file, "w") as f:
            f.write(broken)
        page.wait_for_function("l => document.getElementById('error').dataset.line == String(l)", arg=line, timeout=1000)
        shown = page.text_content("#error")
        check = subprocess.run([self.args.mech, "check", "four_bar.mech"], cwd=self.dir, capture_output=True, text=True)
        assert check.returncode == 1 and check.stderr.strip() in shown, (shown, check.stderr)
        assert page.is_visible("#error") and page.locator("#drawing circle.pin").count() >= 4, "the drawing went"
        page.screenshot(path=os.path.join(self.args.out, "serve-error.png"))
        with open(self.file, "w") as f:
            f.write(self.original)
        page.wait_for_function("() => document.getElementById('error').hidden", timeout=1000)
        return "line %d shown with mech check's message" % line

    def drag(self, page):
        page.click("#home")
        page.wait_for_timeout(300)
        # The handle is drawn again once the previous check's file is back (on a loaded
        # machine after the fixed pause): wait for it, then take its box.
        handle = page.locator('#handles circle[data-point="A"]')
        handle.wait_for(state="visible", timeout=5000)
        v0 = self.version(page)
        v = self.api("/api/model")["view"]  # the view the drag is made in
        before = open(self.file).read()
        h = handle.bounding_box()
        assert h, "no box for the handle of A"
        cx, cy = h["x"] + h["width"] / 2, h["y"] + h["height"] / 2
        page.mouse.move(cx, cy)
        page.mouse.down()
        for k in range(1, 11):
            page.mouse.move(cx + 3 * k, cy - 2 * k)
        page.mouse.up()
        page.wait_for_function("v => { const m = /version (\\d+)/.exec(document.getElementById('status').textContent); return m && +m[1] > v; }", arg=v0, timeout=3000)
        after = open(self.file).read()
        old = re.search(r"A: \(([^,]+), ([^)]+)\)", before)
        new = re.search(r"A: \(([^,]+), ([^)]+)\)", after)
        assert new, after
        assert after == before[:old.start()] + new.group(0) + before[old.end():], "more than A's numbers changed"
        # Where the pointer was released, in the drawing's coordinates.
        drawing = page.locator("#drawing svg")
        drawing.wait_for(state="visible", timeout=5000)  # redrawn after the new version
        svg = drawing.bounding_box()
        assert svg, "no box for the drawing"
        px, py = cx + 30 - svg["x"], cy - 20 - svg["y"]
        want = ((px - v["pad"]) / v["k"] + v["x_min"], v["y_max"] - (py - v["pad"]) / v["k"])
        got = (float(new.group(1)), float(new.group(2)))
        assert math.dist(want, got) < 2 / v["k"], (want, got)
        return "A: (%s, %s) -> (%s, %s), the rest of the file byte-identical" % (old.group(1), old.group(2), new.group(1), new.group(2))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--mech", required=True)
    ap.add_argument("--chromium", default="/usr/bin/chromium")
    ap.add_argument("--out", default=os.path.join(ROOT, "target", "serve-check"))
    ap.add_argument("--docs", action="store_true", help="also write docs/img/serve.png")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    c = Check(args)
    passed = failed = 0
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=args.chromium, headless=True, args=CHROMIUM_ARGS)
            page = browser.new_page(viewport={"width": 1200, "height": 710})
            page.goto(c.url)
            page.wait_for_function("document.getElementById('drawing').dataset.q && document.getElementById('charts').dataset.speed !== undefined", timeout=15000)
            for name, check in (("slider", c.slider), ("chart", c.chart), ("edit", c.edit), ("error", c.error), ("drag", c.drag)):
                try:
                    print("PASS %s: %s" % (name, check(page)), flush=True)
                    passed += 1
                except Exception as e:  # noqa: BLE001 - every check reports and the next runs
                    print("FAIL %s: %s: %s" % (name, type(e).__name__, e), flush=True)
                    page.screenshot(path=os.path.join(args.out, "fail-%s.png" % name))
                    failed += 1
                if name == "chart":
                    page.screenshot(path=os.path.join(args.out, "serve.png"))
                    if args.docs:
                        os.makedirs(os.path.join(ROOT, "docs", "img"), exist_ok=True)
                        shutil.copy(os.path.join(args.out, "serve.png"), os.path.join(ROOT, "docs", "img", "serve.png"))
            browser.close()
    finally:
        c.close()
    print("screenshots in", args.out, file=sys.stderr)
    print("serve_check: %d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
