#!/usr/bin/env python3
"""Regenerate every reference file of the test suite.

  1. tools/drawings.py        -> tests/data/<name>.mechanism.json, tools/cases/<name>.cases.json
  2. copy the public examples -> tests/data/public_*.{mechanism,truth}.json
                                 (the public examples already in tests/data)
  3. tools/check_reference.py -> the solver must reproduce the public truth to 1e-20
  4. tools/reference.py       -> tests/data/<name>.truth.json (12 configurations each)
                                 tests/data/{slider_crank,four_bar}.sweep.json (361 points)
  5. tools/to_dsl.py          -> tests/common/mechanisms.rs

Usage: python3 tools/generate_all.py [-j N]     (N worker processes, default 1)
Needs Python >= 3.8 with mpmath (pip install mpmath).  Takes a few minutes.
"""

import os
import shutil
import subprocess
import sys
from multiprocessing import Pool

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DATA = os.path.join(ROOT, "tests", "data")
CASES = os.path.join(HERE, "cases")
PUBLIC = DATA  # the published worked examples live in tests/data as public_*

sys.path.insert(0, HERE)


def run(args):
    r = subprocess.run([sys.executable] + args, cwd=ROOT, capture_output=True, text=True)
    return args, r.returncode, r.stdout + r.stderr


def main(argv):
    jobs = 1
    if argv[:1] == ["-j"] and len(argv) > 1:
        jobs = int(argv[1])
    import drawings
    names = [d.name for d, _ in drawings.mechanisms()]

    steps = [[os.path.join(HERE, "drawings.py")]]
    for args in steps:
        _, rc, out = run(args)
        print(out, end="")
        if rc:
            return rc

    # The published worked examples (tests/data/public_*) re-validate the solver first.
    _, rc, out = run([os.path.join(HERE, "check_reference.py"), PUBLIC])
    print(out, end="")
    if rc:
        return rc

    work = []
    for n in names:
        work.append([os.path.join(HERE, "reference.py"), os.path.join(DATA, n + ".mechanism.json"),
                     os.path.join(CASES, n + ".cases.json"), os.path.join(DATA, n + ".truth.json")])
    for n in drawings.SWEEPS:
        work.append([os.path.join(HERE, "reference.py"), "--sweep", os.path.join(DATA, n + ".mechanism.json"),
                     os.path.join(CASES, n + ".cases.json"), os.path.join(DATA, n + ".sweep.json")])
    failed = False
    with Pool(jobs) as pool:
        for args, rc, out in pool.imap(run, work):
            print(out, end="")
            if rc:
                failed = True
    if failed:
        print("FAILED")
        return 1

    _, rc, out = run([os.path.join(HERE, "to_dsl.py")])
    print(out, end="")
    return rc


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
