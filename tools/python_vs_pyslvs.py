#!/usr/bin/env python3
"""Per-configuration cost of the Python package against pyslvs: one core, then all cores.

    python3 tools/python_vs_pyslvs.py [--table]   # needs `mech` (pip install ./mech-py) and pyslvs

Jansen's leg (pyslvs's example "Jansen's linkage (Single)", imported as
examples/mech/jansen.mech): the position of every joint at N crank angles over a turn,
(a) by pyslvs, one `expr_solving` call per angle (its API solves one configuration per
call; it is single-threaded), (b) by `mech`, one batched `Mechanism.pose(q, angles=False)`
over the N angles — the same output as pyslvs, joint positions only — measured twice:
on ONE thread (`MECH_NUM_THREADS=1`, in a child process, since the pool is sized at its
first use) for the per-core cost, and on all the machine's cores for the all-core cost,
(c) the throughput of `mech.sweep` (positions and the virtual-power driver torque over
variants of a pin position), all cores.

Before any timing, the positions of both are compared at every one of the N angles; the
script exits with status 1 (and prints the worst joint) when they differ by more than
1e-9 of the leg's size. `--table` prints a markdown table (tools/report.py pyslvs).

numpy's OpenBLAS starts one worker thread per core at import, and those spin-wait on the
cores mech's own thread pool works on. The script runs as a program that does its own
threading should: with OPENBLAS_NUM_THREADS=1 (set here before numpy is imported;
docs/python.md). pyslvs does not use BLAS.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import json  # noqa: E402
import math  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

import mech  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
N = 20_000
JANSEN = os.path.join(ROOT, "examples", "mech", "jansen.mech")


def best(f, repeat=3):
    t = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        t.append(time.perf_counter() - t0)
    return min(t)


def angles():
    return np.linspace(0.0, 2 * math.pi, N, endpoint=False) + 0.123


def mech_pose_seconds():
    """Seconds per configuration of the batched `pose(q, angles=False)` on this process's pool."""
    m = mech.Mechanism.load(JANSEN)
    q = angles()
    return best(lambda: m.pose(q, angles=False), 7) / N


def main():
    if "--child" in sys.argv:  # the one-thread measurement, in a process of its own
        print(repr(mech_pose_seconds()))
        return
    table = "--table" in sys.argv
    data = json.load(open(os.path.join(ROOT, "tests", "data", "pyslvs", "examples.json")))
    ex = next(e for e in data["examples"] if e["name"] == "Jansen's linkage (Single)")
    m = mech.Mechanism.load(JANSEN)
    q = angles()

    from pyslvs import expr_solving, parse_vpoints, t_config
    vpoints = parse_vpoints(ex["expression"])
    exprs = t_config(vpoints, [(0, 1)])

    def with_pyslvs():
        return [expr_solving(exprs, vpoints, {(0, 1): math.degrees(a)}) for a in q]

    # The same positions first, at every angle that will be timed.
    ours = m.pose(q, angles=False)
    theirs = with_pyslvs()
    size = max(math.hypot(p[0], p[1]) for p in theirs[0])
    worst, where = 0.0, None
    for k, res in enumerate(theirs):
        for i, p in enumerate(res):
            d = math.hypot(ours["P%d.x" % i][k] - p[0], ours["P%d.y" % i][k] - p[1])
            if d > worst:
                worst, where = d, (i, k)
    if not worst <= 1e-9 * size:
        sys.exit("positions differ: P%d at angle %d by %.3e (leg size %.1f)" % (where[0], where[1], worst, size))

    t_py = best(with_pyslvs, 1) / N
    child = subprocess.run([sys.executable, __file__, "--child"], env=dict(os.environ, MECH_NUM_THREADS="1"),
                           capture_output=True, text=True, check=True)
    t_one = float(child.stdout.strip())
    t_all = mech_pose_seconds()
    variants = {"points.P2": np.array([-38.0, -7.8]) + np.random.default_rng(1).normal(0, 0.05, size=(200, 2))}
    qq = np.linspace(0, 2 * math.pi, 360, endpoint=False)
    t_sweep = best(lambda: mech.sweep(m, variants, qq, qd=1.0, parts=["positions", "virtual_power"]), 2)
    rate = 200 * 360 / t_sweep

    if table:
        print("Jansen's leg, the positions of its %d joints at %d crank angles; the largest difference "
              "between the two: %.1e (leg size %.0f)." % (len(theirs[0]), N, worst, size))
        print()
        print("| solver | threads | µs per configuration | pyslvs / this |")
        print("|---|---:|---:|---:|")
        print("| pyslvs `expr_solving`, one call per configuration | 1 | %.2f | 1× |" % (t_py * 1e6))
        print("| mech `Mechanism.pose(q, angles=False)`, one batched call | 1 | %.3f | %.0f× |" % (t_one * 1e6, t_py / t_one))
        print("| the same | %d | %.3f | %.0f× |" % (mech.num_threads(), t_all * 1e6, t_py / t_all))
        print()
        print("`mech.sweep`, 200 variants × 360 angles, positions and the driver torque, %d threads: "
              "%.2g configurations/s." % (mech.num_threads(), rate))
    else:
        print("positions agree at all %d angles: largest difference %.2e (leg size %.1f)" % (N, worst, size))
        print("pyslvs expr_solving, one call per configuration, 1 thread: %.2f us" % (t_py * 1e6))
        print("mech pose(angles=False), batched, 1 thread:  %.3f us (%.0fx)" % (t_one * 1e6, t_py / t_one))
        print("mech pose(angles=False), batched, %d threads: %.3f us (%.0fx)" % (mech.num_threads(), t_all * 1e6, t_py / t_all))
        print("mech.sweep, 200 variants x 360 angles: %.0f configurations per second" % rate)


if __name__ == "__main__":
    main()
