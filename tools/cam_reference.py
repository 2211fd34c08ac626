#!/usr/bin/env python3
"""Reference values of the cam motion laws of mech_core::cam, by sympy: each law's
displacement written from its definition (the textbook formula in the cam angle theta),
differentiated SYMBOLICALLY three times (mech writes the derivatives out by hand), and
evaluated at 30 digits at a dozen angles of a rise (90 deg -> 180 deg, 0 -> 10 mm) and a
fall (240 deg -> 360 deg, 10 mm -> 0) of a dwell-rise-dwell-fall cam.

Writes tests/data/cam_laws.json. Usage: python3 tools/cam_reference.py [--out-root DIR]
"""

import json
import os

import sympy as sp

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "data", "cam_laws.json")


def out_path():
    """OUT, or the same path under `--out-root DIR` (tools/outroot.py)."""
    import sys
    import outroot
    root, _ = outroot.split(sys.argv[1:])
    return outroot.path(root, "tests", "data", "cam_laws.json")


th = sp.symbols("theta", real=True)


def law(name, t0, t1, h0, h1):
    beta = t1 - t0
    x = (th - t0) / beta
    L = h1 - h0
    shapes = {
        "uniform": x,
        "harmonic": (1 - sp.cos(sp.pi * x)) / 2,
        "cycloidal": x - sp.sin(2 * sp.pi * x) / (2 * sp.pi),
        "poly345": 10 * x**3 - 15 * x**4 + 6 * x**5,
        "poly4567": 35 * x**4 - 84 * x**5 + 70 * x**6 - 20 * x**7,
    }
    return h0 + L * shapes[name]


def main():
    out = out_path()
    rise = (sp.pi / 2, sp.pi, sp.Rational(0), sp.Rational(1, 100))
    fall = (sp.Rational(4, 3) * sp.pi, 2 * sp.pi, sp.Rational(1, 100), sp.Rational(0))
    doc = {"about": "tools/cam_reference.py: sympy, symbolic derivatives, 30 digits", "laws": {}}
    for name in ["uniform", "harmonic", "cycloidal", "poly345", "poly4567"]:
        rows = []
        for (t0, t1, h0, h1) in [rise, fall]:
            s = law(name, t0, t1, h0, h1)
            ds = [s, sp.diff(s, th), sp.diff(s, th, 2), sp.diff(s, th, 3)]
            for k in range(1, 7):
                at = t0 + (t1 - t0) * sp.Rational(k, 7)
                rows.append({
                    "theta": str(sp.N(at, 30)),
                    "values": [str(sp.N(d.subs(th, at), 30)) for d in ds],
                })
        doc["laws"][name] = rows
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)
    print("wrote", out)


if __name__ == "__main__":
    main()
