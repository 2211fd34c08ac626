#!/usr/bin/env python3
"""Per-configuration cost of the Python package against pyslvs, in one run.

    python3 tools/python_vs_pyslvs.py        # needs `mech` (pip install ./mech-py) and pyslvs

Jansen's leg (pyslvs's example "Jansen's linkage (Single)", imported as
examples/mech/jansen.mech): the positions of every joint at N crank angles over a turn,
(a) by pyslvs, one `expr_solving` call per angle (its API solves one configuration per
call), (b) by `mech`, one batched `Mechanism.pose(q)` over the N angles, and (c) the
throughput of `mech.sweep` (positions and the virtual-power driver torque over variants
of a pin position). Checks that both give the same positions first. Prints the times per
configuration and the ratio.

numpy's OpenBLAS starts one worker thread per core at import, and those spin-wait on the
cores mech's own thread pool works on (on this 2-core machine they took a third of the
batched call's time). The script runs as a program that does its own threading should:
with OPENBLAS_NUM_THREADS=1 (set here before numpy is imported; docs/python.md). pyslvs
is single-threaded and does not use BLAS.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import json  # noqa: E402
import math  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

import mech  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
N = 20_000


def best(f, repeat=3):
    t = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        t.append(time.perf_counter() - t0)
    return min(t)


def main():
    data = json.load(open(os.path.join(ROOT, "tests", "data", "pyslvs", "examples.json")))
    ex = next(e for e in data["examples"] if e["name"] == "Jansen's linkage (Single)")
    m = mech.Mechanism.load(os.path.join(ROOT, "examples", "mech", "jansen.mech"))
    q = np.linspace(0.0, 2 * math.pi, N, endpoint=False) + 0.123
    print("mech threads:", mech.num_threads(), "| OPENBLAS_NUM_THREADS =", os.environ.get("OPENBLAS_NUM_THREADS"))

    from pyslvs import expr_solving, parse_vpoints, t_config
    vpoints = parse_vpoints(ex["expression"])
    exprs = t_config(vpoints, [(0, 1)])

    def with_pyslvs():
        return [expr_solving(exprs, vpoints, {(0, 1): math.degrees(a)}) for a in q]

    ours = m.pose(q)
    theirs = with_pyslvs()
    err = max(math.hypot(ours["P%d.x" % i][k] - p[0], ours["P%d.y" % i][k] - p[1]) for k, res in enumerate(theirs[:200]) for i, p in enumerate(res))
    print("largest position difference over 200 angles: %.2e (units of the drawing)" % err)

    t_py = best(with_pyslvs, 1) / N
    t_mech = best(lambda: m.pose(q), 7) / N
    t_points = best(lambda: m.pose(q, angles=False), 7) / N
    print("pyslvs expr_solving, one call per configuration:     %.2f us per configuration" % (t_py * 1e6))
    print("mech Mechanism.pose, one batched call:                %.3f us per configuration (%.0fx)" % (t_mech * 1e6, t_py / t_mech))
    print("mech Mechanism.pose(angles=False), the same as pyslvs: %.3f us per configuration (%.0fx)" % (t_points * 1e6, t_py / t_points))

    variants = {"points.P2": np.array([-38.0, -7.8]) + np.random.default_rng(1).normal(0, 0.05, size=(200, 2))}
    qq = np.linspace(0, 2 * math.pi, 360, endpoint=False)
    t_sweep = best(lambda: mech.sweep(m, variants, qq, qd=1.0, parts=["positions", "virtual_power"]), 2)
    print("mech.sweep, 200 variants x 360 angles (positions + driver torque): %.0f configurations per second" % (200 * 360 / t_sweep))


if __name__ == "__main__":
    main()
