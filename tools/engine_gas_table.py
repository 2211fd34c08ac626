#!/usr/bin/env python3
"""The four-stroke engine's gas force as a table for `mech flywheel --load gas=@...`.

Writes examples/mech/engine_gas.csv: the force on the piston pin (N, x and y) against the
crank angle q (rad) over one cycle [Q_TDC, Q_TDC + 4 pi], every 0.1 degree, from the gas
model of tools/flywheel_reference.py (the one source of the engine's numbers; mpmath),
with the piston position in closed form, x_B = r cos q + sqrt(l^2 - (e - r sin q)^2).
At the two valve events (bottom dead centres, where the pressure jumps) the table has a
row on each side, 1e-9 rad apart, so that linear interpolation keeps the jump.

    python3 tools/engine_gas_table.py [--out-root DIR]     (tools/outroot.py)
    mech flywheel examples/mech/engine.mech --period 4pi --start 0.032263661668246964 \\
        --speed 3000rpm --irregularity 0.02 --load gas=@examples/mech/engine_gas.csv
"""
import os
import sys

import mpmath
from mpmath import mp, mpf

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import flywheel_reference as F  # noqa: E402

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples", "mech", "engine_gas.csv")
STEP_DEG = mpf("0.1")


def main():
    import outroot
    root, _ = outroot.split(sys.argv[1:])
    out = outroot.path(root, "examples", "mech", "engine_gas.csv")
    mp.dps = 30
    geo = F.geometry()
    gas = F.Gas(geo)
    r, l, e = mpf(F.DESIGN["crank"]), mpf(F.DESIGN["rod"]), mpf(F.DESIGN["offset"])
    deg = mp.pi / 180
    q0 = geo["q_tdc"]
    jumps = [q0 + gas.phi_b, q0 + gas.phi_b + 2 * mp.pi]
    n = int(720 / STEP_DEG)
    qs = [q0 + k * STEP_DEG * deg for k in range(n + 1)]
    for j in jumps:
        qs += [j - mpf("1e-9"), j + mpf("1e-9")]
    qs.sort()
    with open(out, "w") as f:
        f.write("q, fx, fy\n")
        for q in qs:
            x_b = r * mpmath.cos(q) + mpmath.sqrt(l ** 2 - (e - r * mpmath.sin(q)) ** 2)
            # the last row closes the cycle on the first
            force = gas.force(q if q < q0 + 4 * mp.pi else q0, x_b)
            f.write("%s, %s, 0\n" % (mpmath.nstr(q, 17), mpmath.nstr(force, 17)))
    print("wrote", os.path.normpath(out), len(qs), "rows")


if __name__ == "__main__":
    main()
