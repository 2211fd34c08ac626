#!/usr/bin/env python3
"""Evaluations per second of path synthesis: `mech synth path` against pyslvs and pylinkage.

    python3 tools/synthesis_vs_others.py [--table]   # needs pyslvs and pylinkage importable,
                                                      # and cargo (builds the release `mech`)

The work: four-bar path synthesis on the 18-point closed path of
tests/data/synthesis/kunjur18.csv, each tool's own global search, one thread, timed from
its start to its end and divided by the number of candidates it evaluated:

- `mech synth path FILE --seed 1` with RAYON_NUM_THREADS=1 (the rate it prints on standard
  error): an evaluation is the candidate's constraints in closed form and, for a feasible
  one, its coupler curve at 360 crank angles and each target's squared distance to the
  nearest of those points (SPEC 3f's free-timing error).
- pyslvs (`pyslvs.optimization.FPlanar`, its four-bar of `pyslvs.collection`, differential
  evolution `pyslvs.metaheuristics.DE` with its defaults, 400 candidates per generation):
  an evaluation solves the four-bar at one crank angle per target (18 positions: the
  angles are variables of the search, prescribed timing) and sums the squared distances;
  the count is its own `FPlanar.callback`.
- pylinkage (`pylinkage.particle_swarm_optimization` with its defaults and the documented
  `kinematic_minimization` fitness: a simulation of the whole turn, 360 steps, then each
  target's squared distance to the nearest point of the locus, as for `mech`): the count
  is the fitness's calls, the candidates that do not assemble over the turn included.

The positions per second column counts four-bar configurations solved (360 per
evaluation for `mech` and pylinkage, 18 for pyslvs). The three searches differ (operators,
populations, what is a variable), so the errors they reach are not compared here: the
rate of the loop is. `--table` prints the markdown table of tools/report.py
`synthesis_rates`.
"""

import math
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
TARGETS = ROOT / "tests" / "data" / "synthesis" / "kunjur18.csv"
STEPS = 360


def targets():
    rows = [l for l in TARGETS.read_text().splitlines() if l.strip() and not l.startswith("#")]
    return [tuple(float(v) for v in l.split(",")[:2]) for l in rows[1:]]


def target_dir():
    out = subprocess.run(["cargo", "metadata", "--format-version", "1", "--no-deps"], cwd=ROOT,
                         capture_output=True, text=True, check=True).stdout
    return Path(re.search(r'"target_directory":"([^"]+)"', out).group(1))


def run_mech():
    subprocess.run(["cargo", "build", "--release", "-q", "-p", "mech-cli"], cwd=ROOT, check=True)
    exe = target_dir() / "release" / "mech"
    with tempfile.TemporaryDirectory() as tmp:
        r = subprocess.run([str(exe), "synth", "path", str(TARGETS), "--seed", "1", "--format", "csv",
                            "-o", str(Path(tmp) / "out.mech")], cwd=ROOT, capture_output=True,
                           text=True, env=dict(os.environ, RAYON_NUM_THREADS="1"))
    if r.returncode:
        sys.exit(f"mech synth path failed: {r.stderr}")
    rate = float(re.search(r"([0-9.]+) evaluations/s", r.stderr).group(1))
    count = int(re.search(r"search: ([0-9]+) evaluations", r.stderr).group(1))
    return count, rate, STEPS


def run_pyslvs(points):
    from pyslvs import parse_vpoints
    from pyslvs.collection import collection_list
    from pyslvs.metaheuristics import AlgorithmType, algorithm, default
    from pyslvs.optimization import FPlanar

    four_bar = collection_list("Four bar linkage mechanism")
    span = max(max(p[0] for p in points) - min(p[0] for p in points),
               max(p[1] for p in points) - min(p[1] for p in points))
    cx = sum(p[0] for p in points) / len(points)
    cy = sum(p[1] for p in points) / len(points)
    func = FPlanar({
        "expression": parse_vpoints(four_bar["expression"]),
        "input": list(four_bar["input"]),
        # the ground pivots within 2.5 spans of the path's centre, links up to 5 spans
        "placement": {0: (cx, cy, 2.5 * span), 1: (cx, cy, 2.5 * span)},
        "target": {4: points},
        "same": {},
        "upper": 5.0 * span,
        "lower": 0.01 * span,
        "shape_only": False,
    })
    settings = default(AlgorithmType.DE)
    settings.update(max_gen=500, report=0)
    t0 = time.perf_counter()
    algorithm(AlgorithmType.DE)(func, settings).run()
    elapsed = time.perf_counter() - t0
    return func.callback, func.callback / elapsed, len(points)


def run_pylinkage(points):
    import pylinkage as pl
    from pylinkage.actuators import Crank
    from pylinkage.components import Ground
    from pylinkage.dyads import FixedDyad, RRRDyad
    from pylinkage.simulation import Linkage

    o2, o4 = Ground(0.0, 0.0, name="O2"), Ground(1.0, 0.0, name="O4")
    crank = Crank(anchor=o2, radius=0.3, angular_velocity=2 * math.pi / STEPS, name="A")
    rocker = RRRDyad(anchor1=crank.output, anchor2=o4, distance1=1.0, distance2=0.8, name="B")
    coupler = FixedDyad(anchor1=crank.output, anchor2=rocker, distance=0.5, angle=0.5, name="P")
    linkage = Linkage([o2, o4, crank, rocker, coupler], name="four-bar")
    if linkage.get_rotation_period() != STEPS:
        sys.exit(f"pylinkage: {linkage.get_rotation_period()} steps per turn, expected {STEPS}")
    target = np.asarray(points)
    calls = [0]

    @pl.kinematic_minimization
    def error(loci, **_):
        path = np.asarray([frame[-1] for frame in loci], dtype=float)
        d = ((target[:, None, :] - path[None, :, :]) ** 2).sum(axis=2)
        return float(d.min(axis=1).sum())

    def fitness(*args, **kwargs):  # every candidate counted, the unbuildable ones included
        calls[0] += 1
        return error(*args, **kwargs)

    bounds = pl.generate_bounds(linkage.get_constraints())
    t0 = time.perf_counter()
    pl.particle_swarm_optimization(eval_func=fitness, linkage=linkage, bounds=bounds,
                                   order_relation=min, iterations=20, verbose=False)
    elapsed = time.perf_counter() - t0
    return calls[0], calls[0] / elapsed, STEPS


def main():
    points = targets()
    rows = [("`mech synth path` (differential evolution, 1 thread)", *run_mech()),
            ("pyslvs 22.7 (`FPlanar`, its DE)", *run_pyslvs(points)),
            ("pylinkage 1.3 (`particle_swarm_optimization`)", *run_pylinkage(points))]
    mech_rate = rows[0][2]
    if "--table" in sys.argv:
        print("| tool | evaluations timed | evaluations/s | positions per evaluation "
              "| positions/s | `mech`'s evaluations/s over this |")
        print("|---|---:|---:|---:|---:|---:|")
        for name, count, rate, per in rows:
            thousands = f"{rate:,.0f} | {per} | {rate * per:,.0f}".replace(",", " ")
            print(f"| {name} | {count} | {thousands} | {mech_rate / rate:.1f}× |")
    else:
        for name, count, rate, per in rows:
            print(f"{name}: {count} evaluations, {rate:.0f}/s, {rate * per:.0f} positions/s")


if __name__ == "__main__":
    main()
