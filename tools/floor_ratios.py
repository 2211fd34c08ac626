#!/usr/bin/env python3
"""Tabulate `cargo bench --bench floor`: generated solvers against the hand-written floor.

Reads criterion 0.5's results, `<target>/criterion/<group>/<function>/new/estimates.json`
(the median's point estimate, ns) together with the `benchmark.json` beside it (criterion
writes the group `four_bar/pose` into the directory `four_bar_pose`, so the real group and
function names are taken from there). `<target>` is $CARGO_TARGET_DIR when set, else the
`target/` directory of the repository this script lives in; `--target DIR` overrides both.

Prints a markdown table: operation, generated median (ns), hand median (ns), the ratio
of those medians, and the interleaved ratio of the group `ratio` (`benches/floor.rs`:
generated and hand alternated in blocks within each sample, so that a shared machine's
drifting speed cancels; its median is the ratio itself). Exits non-zero when no floor
result is found.

    python3 tools/floor_ratios.py [--target DIR]
"""

import argparse
import json
import os
import sys
from pathlib import Path

# The groups of benches/floor.rs, in the order of the table.
# The four-bar and the slider-crank first, then the machines with all six operations.
OPERATIONS = (
    "pose",
    "kinematics",
    "kinematics+kinetostatics",
    "kinematics+driver_action",
    "reduced",
    "acceleration",
)
GROUPS = [
    "four_bar/pose",
    "four_bar/kinematics",
    "four_bar/kinematics+kinetostatics",
    "four_bar/kinematics+driver_action",
    "slider_crank/reduced",
    "slider_crank/acceleration",
] + [
    f"{machine}/{op}"
    for machine in (
        "quick_return",
        "scotch_yoke",
        "inverted_slider_crank",
        "geared_slider_crank",
        "roller_cam",
        "crank_rod_wheel",
        "block_scotch_yoke",
        "slotted_crank_ram",
        "planetary",
        "rack_pinion",
    )
    for op in OPERATIONS
]
FUNCTIONS = ("generated", "hand")


def target_dir(explicit):
    if explicit:
        return Path(explicit)
    env = os.environ.get("CARGO_TARGET_DIR")
    if env:
        return Path(env)
    return Path(__file__).resolve().parent.parent / "target"


def read_medians(criterion):
    """{(group, function): median} for every benchmark with a `new` estimate: ns for the
    pairs, the ratio itself for the group `ratio` (keyed (operation, "interleaved"))."""
    out = {}
    for bench in criterion.glob("*/*/new/benchmark.json"):
        try:
            meta = json.loads(bench.read_text())
            est = json.loads((bench.parent / "estimates.json").read_text())
        except (OSError, ValueError):
            continue
        group, function = meta.get("group_id"), meta.get("function_id")
        if group in GROUPS and function in FUNCTIONS:
            out[(group, function)] = est["median"]["point_estimate"]
        elif group == "ratio" and function in GROUPS:
            out[(function, "interleaved")] = est["median"]["point_estimate"]
    return out


def fmt(ns):
    return "—" if ns is None else f"{ns:,.1f}".replace(",", " ")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--target", help="cargo target directory (default: $CARGO_TARGET_DIR or ./target)")
    args = ap.parse_args()
    criterion = target_dir(args.target) / "criterion"
    medians = read_medians(criterion)
    if not medians:
        sys.exit(f"no floor results under {criterion}; run `cargo bench --bench floor` first")
    print("| operation | generated median (ns) | hand median (ns) | generated / hand | interleaved ratio |")
    print("|---|---:|---:|---:|---:|")
    for group in GROUPS:
        gen, hand = medians.get((group, "generated")), medians.get((group, "hand"))
        ratio = f"{gen / hand:.2f}×" if gen is not None and hand else "—"
        inter = medians.get((group, "interleaved"))
        inter = f"{inter:.2f}×" if inter is not None else "—"
        print(f"| `{group}` | {fmt(gen)} | {fmt(hand)} | {ratio} | {inter} |")


if __name__ == "__main__":
    main()
