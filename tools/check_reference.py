#!/usr/bin/env python3
"""Validate tools/reference.py against the published worked examples.

Runs the reference solver on tests/data/public_*.mechanism.json (the two published worked
examples, committed with their exact answers) with
the loads and configurations of the matching truth files and compares every
number of every configuration (kinematics, drivers, reactions, Zhukovski) with
the given truth.  Tolerance: 1e-20 relative to the number itself (or, for
numbers that are zero / far below the others of their kind, 1e-20 times
1e-6 x the largest number of the same kind in the configuration); angles modulo 2 pi.
Exits non-zero on any disagreement.

Usage: python3 tools/check_reference.py [REFERENCE_DIR]
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import mpmath  # noqa: E402
from mpmath import mp, mpf  # noqa: E402

import reference as R  # noqa: E402

TOL = mpf("1e-20")


def flatten(obj, path=()):
    """yield (path, value) for every scalar leaf"""
    if isinstance(obj, dict):
        for k, v in obj.items():
            yield from flatten(v, path + (k,))
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            yield from flatten(v, path + (i,))
    else:
        yield path, obj


def kind(path):
    """the kind of a number, for scaling: last non-index key(s)"""
    keys = [p for p in path if isinstance(p, str)]
    if "reactions" in keys:
        return "reaction." + keys[-1]
    if "zhukovski" in keys:
        return "zhukovski." + keys[-1]
    if "drivers" in keys:
        return "driver"
    if keys and keys[-1] in ("pos", "vel", "acc"):
        return keys[-1]
    return keys[-1] if keys else ""


def compare_config(mine, truth, label):
    fm = dict(flatten(mine))
    ft = dict(flatten(truth))
    problems = []
    missing = set(ft) - set(fm)
    extra = set(fm) - set(ft)
    for p in sorted(missing, key=str):
        problems.append("%s: missing %s" % (label, p))
    for p in sorted(extra, key=str):
        problems.append("%s: unexpected %s" % (label, p))
    scales = {}
    for p, v in ft.items():
        if isinstance(v, mpmath.mpf):
            k = kind(p)
            scales[k] = max(scales.get(k, mpf(0)), abs(v))
    worst = mpf(0)
    for p, t in ft.items():
        if p not in fm:
            continue
        m = fm[p]
        if not isinstance(t, mpmath.mpf):
            if t != m:
                problems.append("%s: %s is %r, truth %r" % (label, p, m, t))
            continue
        m = R.num(m)
        d = abs(m - t)
        if p and p[-1] == "theta":
            d = min(d, abs(d - 2 * mp.pi))
        ref = max(abs(t), mpf("1e-6") * scales[kind(p)])
        if ref == 0:
            ref = mpf(1)
        rel = d / ref
        worst = max(worst, rel)
        if rel > TOL:
            problems.append("%s: %s = %s, truth %s (rel %.2e)"
                            % (label, "/".join(map(str, p)), mpmath.nstr(m, 25), mpmath.nstr(t, 25), float(rel)))
    return worst, problems


def main(argv):
    refdir = argv[0] if argv else os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "tests", "data")
    names = sorted(f[:-len(".mechanism.json")] for f in os.listdir(refdir)
                   if f.startswith("public_") and f.endswith(".mechanism.json"))
    if not names:
        print("no mechanisms in", refdir)
        return 1
    failed = False
    for name in names:
        spec = R.load_json(os.path.join(refdir, name + ".mechanism.json"))
        truth = R.load_json(os.path.join(refdir, name + ".truth.json"))
        mech = R.Mechanism(spec)
        out = R.compute_truth(mech, truth, name + ".mechanism.json", fd_check=False)
        worst = mpf(0)
        problems = []
        # top-level bookkeeping
        for key in ("dof", "inputs", "gravity", "loads"):
            w, pr = compare_config(out[key], truth[key], name + "." + key)
            worst, problems = max(worst, w), problems + pr
        if len(out["configs"]) != len(truth["configs"]):
            problems.append("%s: %d configs, truth has %d" % (name, len(out["configs"]), len(truth["configs"])))
        for mine, tr in zip(out["configs"], truth["configs"]):
            w, pr = compare_config(mine, tr, "%s[config %s]" % (name, tr["index"]))
            worst = max(worst, w)
            problems += pr
        internal = max(out["verification"].values())
        print("%-22s %d configs: max relative disagreement with truth %.3e; internal cross-checks %.3e"
              % (name, len(truth["configs"]), float(worst), internal))
        for p in problems[:40]:
            print("   FAIL", p)
        if problems:
            failed = True
    print("FAILED" if failed else "OK: reference solver reproduces the published truth to 1e-20")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
