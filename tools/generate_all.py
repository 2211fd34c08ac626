#!/usr/bin/env python3
"""Regenerate every reference table of the test suite, or check the committed ones.

    python3 tools/generate_all.py [-j N] [--fast] [--only NAME ...]            regenerate in place
    python3 tools/generate_all.py --check [-j N] [--fast] [--only NAME ...]    regenerate into a
                                  temporary directory and compare with the committed files
    python3 tools/generate_all.py --list                                       the tables

A *table* is one run of one generator of tools/ and the files it writes (TABLES below: the
generator, its arguments, its outputs, the tables it reads). Every generator takes
`--out-root DIR` (tools/outroot.py) and then writes its files at their repository paths under
DIR, reading the generated files it depends on from there too. In place, DIR is the
repository; with --check it is a fresh temporary directory, seeded only with the committed
files that no table writes (SOURCES: the published worked examples, the hand-written part of
tests/common/engine.rs) and, with --fast / --only, the committed outputs of the tables not
selected that a selected one reads.

Check mode prints one line per table: its name, its seconds, and
  OK            every output identical to the committed file, byte for byte
  OK ~          not identical, but every number within the table's tolerance (below)
  DIFF          the first difference: file, path in the file, committed vs regenerated value
  MISSING       an output not written, or not committed
  FAIL          the generator exited non-zero (its output follows)
  NEEDS         a Python module it needs is not installed (not run)
  SKIPPED       a table it reads failed
and exits non-zero unless every selected table is OK. It also fails when a file under
tests/data or tools/cases is neither a table's output nor a source.

Comparison when not byte-identical: JSON files are parsed with every key in its order and
compared as trees, structure, keys and strings exactly (0 tolerance); a number (a JSON number
or a string holding a decimal number) within
    |a - b| <= rtol * max(|a|, |b|, 1e-6 * m)
with m the largest magnitude of that key in the committed file (list indices ignored), rtol the
table's ("rtol" below: 1e-30 for 40- and 50-digit tables, 1e-27 for 30 digits, 1e-22 for 25
digits, 1e-14 for the 17-digit CSV, 1e-12 for pyslvs's float64 positions); the numbers of a
`verification` block (the generators' own residuals and counts) within 1e-6 relative, or both
below 1e-30. CSV files are compared cell by cell the same way; Rust files byte for byte only.
The tests compare with these tables to 1e-12 ... 1e-15 of a quantity's scale (pyslvs: 1e-9).

--fast selects the tables marked fast (they regenerate in about 80 s on one core; CI runs
`--check --fast`). -j N runs N generators at once (default 1). Needs Python >= 3.8 with mpmath
and sympy (pip install mpmath sympy); the pyslvs table also needs numpy and pyslvs 22.7.0
(tools/README.md). The slowest table, dynamics, takes about an hour of CPU.
"""

import argparse
import fnmatch
import importlib.util
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from decimal import Decimal, localcontext

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# the eight drawings of tools/drawings.py, in its order
DRAWINGS = ["four_bar", "slider_crank", "quick_return", "watt2", "stephenson3", "scotch_yoke",
            "five_bar", "hydraulic_lever"]
SWEEPS = ["slider_crank", "four_bar"]

# committed files that no table writes: the published worked examples with their exact answers
# (the independent truth tools/check_reference.py validates tools/reference.py against), and
# tests/common/engine.rs, of which tools/flywheel_reference.py writes only the GENERATED block.
SOURCES = ["tests/data/public_slider_crank.mechanism.json", "tests/data/public_slider_crank.truth.json",
           "tests/data/public_four_bar.mechanism.json", "tests/data/public_four_bar.truth.json",
           "tests/common/engine.rs"]


class Table:
    def __init__(self, name, args, outputs, rtol=None, deps=(), fast=False, needs=(), seconds=None,
                 reads=()):
        self.name = name
        self.args = args            # script and arguments; "{root}" is the output root
        self.outputs = outputs      # repository-relative paths
        self.rtol = rtol            # numeric tolerance of the outputs when not identical
        self.deps = list(deps)      # tables whose outputs it reads
        self.fast = fast
        self.needs = list(needs)    # Python modules
        self.seconds = seconds      # measured, one core (tools/README.md)
        self.reads = list(reads)    # sources it reads

    def argv(self, root, jobs):
        out = []
        for a in self.args:
            if a == "{jobs}":
                out.append(str(jobs))
            else:
                out.append(a.replace("{root}", root))
        return out


def t(*parts):
    return "/".join(parts)


def tables():
    T = []
    T.append(Table("drawings", ["drawings.py", "--out-root", "{root}"],
                   [t("tests/data", n + ".mechanism.json") for n in DRAWINGS]
                   + [t("tools/cases", n + ".cases.json") for n in DRAWINGS],
                   rtol="1e-30", fast=True, seconds=0.2))
    # tools/reference.py on the published worked examples: writes nothing, must reproduce them
    T.append(Table("check_reference", ["check_reference.py", os.path.join(ROOT, "tests", "data")], [],
                   fast=True, seconds=3.8, reads=SOURCES[:4]))
    secs = {"four_bar": 5.4, "slider_crank": 5.4, "quick_return": 5.9, "watt2": 12.8, "stephenson3": 13.5,
            "scotch_yoke": 2.3, "five_bar": 2.6, "hydraulic_lever": 2.5}
    for n in DRAWINGS:
        T.append(Table("truth:" + n, ["reference.py", "{root}/tests/data/%s.mechanism.json" % n,
                                      "{root}/tools/cases/%s.cases.json" % n, "{root}/tests/data/%s.truth.json" % n],
                       [t("tests/data", n + ".truth.json")], rtol="1e-22",
                       deps=["drawings", "check_reference"], fast=True, seconds=secs[n]))
    for n, s in zip(SWEEPS, [8.3, 9.3]):
        T.append(Table("sweep:" + n, ["reference.py", "--sweep", "{root}/tests/data/%s.mechanism.json" % n,
                                      "{root}/tools/cases/%s.cases.json" % n, "{root}/tests/data/%s.sweep.json" % n],
                       [t("tests/data", n + ".sweep.json")], rtol="1e-22",
                       deps=["drawings", "check_reference"], fast=True, seconds=s))
    T.append(Table("mechanisms.rs", ["to_dsl.py", "--out-root", "{root}"], ["tests/common/mechanisms.rs"],
                   deps=["drawings"], fast=True, seconds=0.2, reads=SOURCES[:4]))
    T.append(Table("engine.rs", ["flywheel_reference.py", "--drawing-only", "--out-root", "{root}"],
                   ["tests/data/engine.drawing.json", "tests/common/engine.rs"], rtol="1e-30",
                   fast=True, seconds=0.2, reads=["tests/common/engine.rs"]))
    # rewrites the drawing and the block of engine.rs (the same) before its own table
    T.append(Table("flywheel", ["flywheel_reference.py", "--out-root", "{root}"],
                   ["tests/data/engine.flywheel.json"], rtol="1e-22", deps=["engine.rs"], seconds=88))
    T.append(Table("engine_gas.csv", ["engine_gas_table.py", "--out-root", "{root}"],
                   ["examples/mech/engine_gas.csv"], rtol="1e-14", fast=True, seconds=1.4))
    T.append(Table("dynamics", ["dynamics_reference.py", "-j", "{jobs}", "--out-root", "{root}"],
                   ["tests/data/slider_crank.dynamics.json"], rtol="1e-22", deps=["drawings"], seconds=None))
    T.append(Table("cam_laws", ["cam_reference.py", "--out-root", "{root}"], ["tests/data/cam_laws.json"],
                   rtol="1e-27", fast=True, needs=["sympy"], seconds=1.6))
    T.append(Table("cam_follower", ["cam_follower_reference.py", "--out-root", "{root}"],
                   ["tests/data/cam_follower.json"], rtol="1e-30", fast=True, seconds=2.1))
    T.append(Table("cam_rocker", ["cam_rocker_reference.py", "--out-root", "{root}"],
                   ["tests/data/cam_rocker.json"], rtol="1e-27", needs=["sympy"], seconds=51))
    T.append(Table("spring_four_bar", ["elements_reference.py", "--out-root", "{root}"],
                   ["tests/data/spring_four_bar.json"], rtol="1e-30", fast=True, seconds=0.5))
    T.append(Table("gears", ["gears_reference.py", "--out-root", "{root}"], ["tests/data/gears.json"],
                   rtol="1e-30", fast=True, seconds=0.5))
    T.append(Table("rolling", ["rolling_reference.py", "--out-root", "{root}"], ["tests/data/rolling.json"],
                   rtol="1e-30", fast=True, seconds=0.7))
    T.append(Table("large.rs", ["large_mechanisms.py", "--out-root", "{root}"], ["tests/large.rs"],
                   fast=True, seconds=0.1))
    # reads pyslvs's example list from the installed pyslvs (pyslvs_example_py below)
    T.append(Table("pyslvs", ["pyslvs_examples.py", "--out-root", "{root}", "{pyslvs_example}"],
                   ["tests/data/pyslvs/examples.json"], rtol="1e-12", needs=["numpy", "pyslvs"], seconds=None))
    return T


def pyslvs_example_py():
    spec = importlib.util.find_spec("pyslvs")
    if spec is None or not spec.submodule_search_locations:
        return None
    p = os.path.join(list(spec.submodule_search_locations)[0], "example.py")
    return p if os.path.exists(p) else None


# ---------------------------------------------------------------------------------------------
# comparison

NUM = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")
VERIF_RTOL, VERIF_ATOL = Decimal("1e-6"), Decimal("1e-30")


def load_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f, object_pairs_hook=lambda pairs: ("obj", pairs), parse_float=Decimal,
                         parse_int=Decimal)


def as_number(v):
    if isinstance(v, Decimal):
        return v
    if isinstance(v, str) and NUM.match(v.strip()):
        return Decimal(v.strip())
    return None


def kind(path):
    return "/".join(p for p in path if not isinstance(p, int))


def magnitudes(node, path=(), acc=None):
    """largest |number| per kind (path without list indices)"""
    acc = {} if acc is None else acc
    if isinstance(node, tuple) and node and node[0] == "obj":
        for k, v in node[1]:
            magnitudes(v, path + (k,), acc)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            magnitudes(v, path + (i,), acc)
    else:
        x = as_number(node)
        if x is not None:
            k = kind(path)
            acc[k] = max(acc.get(k, Decimal(0)), abs(x))
    return acc


def show(path):
    s = ""
    for p in path:
        s += "[%d]" % p if isinstance(p, int) else ("." if s else "") + str(p)
    return s or "(top)"


class Compare:
    def __init__(self, rtol, mags):
        self.rtol = Decimal(rtol)
        self.mags = mags
        self.numbers = 0     # numbers that differ in their text but agree within the tolerance
        self.worst = Decimal(0)

    def close(self, a, b, path):
        if a == b:
            return True
        with localcontext() as ctx:
            ctx.prec = 120
            d = abs(a - b)
            if "verification" in path:
                ok = d <= VERIF_RTOL * max(abs(a), abs(b)) or max(abs(a), abs(b)) <= VERIF_ATOL
            else:
                scale = max(abs(a), abs(b), Decimal("1e-6") * self.mags.get(kind(path), Decimal(0)))
                ok = d <= self.rtol * scale
                if scale:
                    self.worst = max(self.worst, d / scale)
        self.numbers += 1
        return ok

    def tree(self, a, b, path=()):
        """None, or (path, committed, regenerated) of the first difference"""
        if isinstance(a, tuple) and isinstance(b, tuple):
            ka, kb = [k for k, _ in a[1]], [k for k, _ in b[1]]
            if ka != kb:
                extra = [k for k in kb if k not in ka] or ["(order)"]
                gone = [k for k in ka if k not in kb] or ["(order)"]
                return path, "keys %s" % gone, "keys %s" % extra
            for (k, va), (_, vb) in zip(a[1], b[1]):
                r = self.tree(va, vb, path + (k,))
                if r:
                    return r
            return None
        if isinstance(a, list) and isinstance(b, list):
            if len(a) != len(b):
                return path, "%d entries" % len(a), "%d entries" % len(b)
            for i, (va, vb) in enumerate(zip(a, b)):
                r = self.tree(va, vb, path + (i,))
                if r:
                    return r
            return None
        na, nb = as_number(a), as_number(b)
        if na is not None and nb is not None and type(a) is type(b):
            return None if self.close(na, nb, path) else (path, a, b)
        if a != b or type(a) is not type(b):
            return path, a, b
        return None


def compare_file(committed, regenerated, rtol):
    """(True, note) or (False, description of the first difference)"""
    with open(committed, "rb") as f:
        ca = f.read()
    with open(regenerated, "rb") as f:
        cb = f.read()
    if ca == cb:
        return True, ""
    if rtol is None or not (committed.endswith(".json") or committed.endswith(".csv")):
        la, lb = ca.decode("utf-8", "replace").split("\n"), cb.decode("utf-8", "replace").split("\n")
        for i, (x, y) in enumerate(zip(la, lb)):
            if x != y:
                return False, "line %d: committed %r, regenerated %r" % (i + 1, x.strip()[:100], y.strip()[:100])
        return False, "committed %d lines, regenerated %d" % (len(la), len(lb))
    if committed.endswith(".json"):
        a, b = load_json(committed), load_json(regenerated)
    else:
        def rows(text):
            return [[c.strip() for c in line.split(",")] for line in text.decode("utf-8").splitlines()]
        a, b = rows(ca), rows(cb)
    c = Compare(rtol, magnitudes(a))
    r = c.tree(a, b)
    if r:
        path, x, y = r
        return False, "%s: committed %s, regenerated %s" % (show(path), x, y)
    return True, "~ %d number%s differ%s in the text, at most %.1e relative (tolerance %s)" % (
        c.numbers, "" if c.numbers == 1 else "s", "s" if c.numbers == 1 else "", c.worst, rtol)


# ---------------------------------------------------------------------------------------------
# running

def run(table, root, jobs, extra):
    argv = [sys.executable, os.path.join(HERE, table.args[0])] + table.argv(root, jobs)[1:]
    argv = [a for a in (x.replace("{pyslvs_example}", extra.get("pyslvs_example") or "") for x in argv) if a]
    t0 = time.time()
    r = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr, time.time() - t0


def unclaimed(all_tables):
    """committed files under tests/data and tools/cases that no table writes and no source is"""
    claimed = set(SOURCES)
    for tb in all_tables:
        claimed.update(tb.outputs)
    out = []
    for top in ("tests/data", "tools/cases"):
        for dp, _, fns in os.walk(os.path.join(ROOT, top)):
            for fn in fns:
                rel = os.path.relpath(os.path.join(dp, fn), ROOT).replace(os.sep, "/")
                if rel not in claimed:
                    out.append(rel)
    return sorted(out)


def select(all_tables, fast, only):
    chosen = [tb for tb in all_tables if (not fast or tb.fast)]
    if only:
        chosen = [tb for tb in chosen if any(fnmatch.fnmatch(tb.name, pat) for pat in only)]
        unknown = [p for p in only if not any(fnmatch.fnmatch(tb.name, p) for tb in all_tables)]
        if unknown:
            raise SystemExit("no table named %s (--list)" % ", ".join(unknown))
    return chosen


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--check", action="store_true", help="regenerate into a temporary directory and compare")
    ap.add_argument("--fast", action="store_true", help="only the fast tables (tools/README.md)")
    ap.add_argument("--only", nargs="+", metavar="NAME", help="only these tables (names or globs, e.g. 'truth:*')")
    ap.add_argument("-j", type=int, default=1, metavar="N", help="generators run at once (default 1)")
    ap.add_argument("--keep", action="store_true", help="--check: keep the temporary directory")
    ap.add_argument("--list", action="store_true", help="list the tables and exit")
    a = ap.parse_args(argv)

    all_tables = tables()
    by = {tb.name: tb for tb in all_tables}
    if a.list:
        for tb in all_tables:
            print("%-22s %-6s %8s  %s -> %s" % (tb.name, "fast" if tb.fast else "", 
                                               "%.1f s" % tb.seconds if tb.seconds else "?",
                                               " ".join(tb.args), ", ".join(tb.outputs) or "(a check)"))
        return 0
    chosen = select(all_tables, a.fast, a.only)
    names = {tb.name for tb in chosen}

    tmp = None
    if a.check:
        tmp = tempfile.mkdtemp(prefix="mech-reftables-")
        root = tmp
        seed = set()
        for tb in chosen:
            seed.update(tb.reads)
            for d in tb.deps:
                if d not in names:
                    seed.update(by[d].outputs)
        for rel in sorted(seed):
            dst = os.path.join(root, rel)
            os.makedirs(os.path.dirname(dst), exist_ok=True)
            shutil.copyfile(os.path.join(ROOT, rel), dst)
    else:
        root = ROOT
    extra = {"pyslvs_example": pyslvs_example_py()}

    status = {}   # name -> "ok" | "bad"
    bad = 0
    t_start = time.time()
    # longest path first: a table's seconds plus the longest chain of tables that read it
    prio = {}

    def path_secs(tb):
        if tb.name not in prio:
            kids = [c for c in chosen if tb.name in c.deps]
            prio[tb.name] = (tb.seconds or 60) + max([path_secs(c) for c in kids] or [0])
        return prio[tb.name]
    pending = sorted(chosen, key=lambda tb: -path_secs(tb))
    running = {}

    def report(tb, secs, verdict, detail=""):
        print("%-22s %7.1f s  %s%s" % (tb.name, secs, verdict, ("  " + detail) if detail else ""), flush=True)

    with ThreadPoolExecutor(max_workers=max(1, a.j)) as pool:
        while pending or running:
            # start what is ready
            for tb in list(pending):
                if len(running) >= max(1, a.j):
                    break
                deps = [d for d in tb.deps if d in names]
                if any(status.get(d) == "bad" for d in deps):
                    pending.remove(tb)
                    status[tb.name] = "bad"
                    bad += 1
                    report(tb, 0.0, "SKIPPED", "(%s failed)" % ", ".join(d for d in deps if status.get(d) == "bad"))
                    continue
                if not all(status.get(d) == "ok" for d in deps):
                    continue
                missing = [m for m in tb.needs if importlib.util.find_spec(m) is None]
                if missing:
                    pending.remove(tb)
                    status[tb.name] = "bad"
                    bad += 1
                    report(tb, 0.0, "NEEDS", " ".join(missing) + " (tools/README.md)")
                    continue
                pending.remove(tb)
                if a.check:
                    for rel in tb.outputs:   # a seeded copy must not pass for a regenerated file
                        p = os.path.join(root, rel)
                        if os.path.exists(p) and rel not in tb.reads:
                            os.remove(p)
                running[pool.submit(run, tb, root, a.j, extra)] = tb
            if not running:
                continue
            done, _ = wait(list(running), return_when=FIRST_COMPLETED)
            for fut in done:
                tb = running.pop(fut)
                rc, out, secs = fut.result()
                if rc != 0:
                    status[tb.name] = "bad"
                    bad += 1
                    report(tb, secs, "FAIL", "exit %d" % rc)
                    print("    " + out.strip().replace("\n", "\n    "), flush=True)
                    continue
                if not a.check:
                    status[tb.name] = "ok"
                    if tb.outputs:
                        report(tb, secs, "written", ", ".join(tb.outputs) if len(tb.outputs) <= 3 else
                               "%d files" % len(tb.outputs))
                    else:
                        report(tb, secs, "OK")
                    continue
                verdict, notes = "OK", []
                for rel in tb.outputs:
                    com, reg = os.path.join(ROOT, rel), os.path.join(root, rel)
                    if not os.path.exists(reg):
                        verdict, notes = "MISSING", ["%s not written" % rel]
                        break
                    if not os.path.exists(com):
                        verdict, notes = "MISSING", ["%s not committed" % rel]
                        break
                    ok, note = compare_file(com, reg, tb.rtol)
                    if not ok:
                        verdict, notes = "DIFF", ["%s %s" % (rel, note)]
                        break
                    if note:
                        verdict = "OK ~"
                        notes.append("%s %s" % (rel, note))
                status[tb.name] = "ok" if verdict.startswith("OK") else "bad"
                if status[tb.name] == "bad":
                    bad += 1
                report(tb, secs, verdict, "; ".join(notes))

    if a.check:
        orphans = unclaimed(all_tables)
        for rel in orphans:
            print("%-22s %7s    NO GENERATOR  %s is neither a table's output nor a source" % ("-", "", rel))
        bad += len(orphans)
        if a.keep:
            print("regenerated files kept in", tmp)
        else:
            shutil.rmtree(tmp, ignore_errors=True)
    print("%d tables, %.0f s, %s" % (len(chosen), time.time() - t_start,
                                     "all reproduce the committed files" if a.check and not bad else
                                     "%d failed" % bad if bad else "done"))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
