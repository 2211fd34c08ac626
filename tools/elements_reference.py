#!/usr/bin/env python3
"""High-precision reference for the force elements: the spring-loaded four-bar of
tests/elements.rs, by the energy method (Lagrange), in mpmath at 50 digits.

A formulation independent of mech's: the four-bar's positions in closed form (circle
intersection), every velocity coefficient and its derivative by mpmath's numerical
differentiation of those positions, the springs through their potential energy
V(q) = sum(-m g.r_G) + sum 1/2 k (x - x0)^2, the dampers through Rayleigh's dissipation
function D = 1/2 sum c xdot^2 = 1/2 q'^2 sum c (dx/dq)^2. Then, for one input q,

    driver = I*(q) q'' + 1/2 dI*/dq q'^2 + dV/dq - T_resist dtheta4/dq + sum c (dx/dq)^2 q'

(the torque the motor applies, mech's sign), and

- the equilibrium q* (no driver, no load, at rest): dV/dq = 0, V'' > 0 (findroot);
- the natural frequency of small oscillations about it: w_n = sqrt(V''(q*) / I*(q*)).

Writes tests/data/spring_four_bar.json. Usage: python3 tools/elements_reference.py [--out-root DIR]
"""

import json
import os

from mpmath import mp, mpf, cos, sin, sqrt, atan2, diff, findroot, pi

mp.dps = 50
HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "data", "spring_four_bar.json")


def out_path():
    """OUT, or the same path under `--out-root DIR` (tools/outroot.py)."""
    import sys
    import outroot
    root, _ = outroot.split(sys.argv[1:])
    return outroot.path(root, "tests", "data", "spring_four_bar.json")


def v(x, y):
    return (mpf(x), mpf(y))


# The drawing (must match `SpringFourBar` in tests/elements.rs).
O2, O4 = v(0, 0), v("0.30", 0)
C, D = v("0.05", "0.25"), v("0.40", "0.20")
A0, B0, P0 = v(0, "0.10"), v("0.28", "0.22"), v("0.10", "0.20")
G = (0, mpf("-9.81"))
LINKS = {
    # name: (mass, inertia about cg, cg in the drawing)
    "crank": (mpf("0.8"), mpf("1.0e-3"), v(0, "0.05")),
    "coupler": (mpf("1.5"), mpf("9.0e-3"), v("0.14", "0.17")),
    "rocker": (mpf("1.1"), mpf("4.0e-3"), v("0.29", "0.11")),
}
K1, L01 = mpf(2000), mpf("0.080")  # spring(ground at C, coupler at P)
K2, PRELOAD2 = mpf(500), mpf(30)  # spring(crank at A, rocker at O4) preload 30 N
KT, PHI0 = mpf("1.5"), 60 * pi / 180  # torsion_spring(ground, crank)
C1 = mpf(40)  # damper(ground at D, rocker at B)
CT = mpf("0.05")  # rotary_damper(ground, crank)


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def norm(a):
    return sqrt(a[0] ** 2 + a[1] ** 2)


def rot(p, ref, phi):
    """p (a point of the drawing) carried by a rotation phi about ref's image"""
    d = sub(p, ref)
    c, s = cos(phi), sin(phi)
    return (c * d[0] - s * d[1], s * d[0] + c * d[1])


def angle(a, b):
    return atan2(b[1] - a[1], b[0] - a[0])


TH2, TH3, TH4 = angle(O2, A0), angle(A0, B0), angle(B0, O4)
R2, L3, L4 = norm(sub(A0, O2)), norm(sub(B0, A0)), norm(sub(O4, B0))
# The branch of B: the side of the line A -> O4 it is drawn on.
SIDE = 1 if ((O4[0] - A0[0]) * (B0[1] - A0[1]) - (O4[1] - A0[1]) * (B0[0] - A0[0])) > 0 else -1
L02 = norm(sub(O4, A0)) - PRELOAD2 / K2


def wrap(a):
    a = a - 2 * pi * mp.floor((a + pi) / (2 * pi))
    return a if a > -pi else a + 2 * pi


def pose(q):
    """A, B and the three link angles at crank angle q (q = theta_crank: no `from`)"""
    a = (R2 * cos(q), R2 * sin(q))
    d = sub(O4, a)
    dd = norm(d)
    x = (L3**2 - L4**2 + dd**2) / (2 * dd)
    h = sqrt(L3**2 - x**2)
    ux, uy = d[0] / dd, d[1] / dd
    b = (a[0] + x * ux - SIDE * h * uy, a[1] + x * uy + SIDE * h * ux)
    return a, b, q, angle(a, b), angle(b, O4)


def cgs(q):
    a, b, t2, t3, t4 = pose(q)
    out = {}
    for name, (m, i, g) in LINKS.items():
        if name == "crank":
            r, th = rot(g, O2, t2 - TH2), t2
            out[name] = ((O2[0] + r[0], O2[1] + r[1]), th)
        elif name == "coupler":
            r = rot(g, A0, t3 - TH3)
            out[name] = ((a[0] + r[0], a[1] + r[1]), t3)
        else:
            r = rot(g, B0, t4 - TH4)
            out[name] = ((b[0] + r[0], b[1] + r[1]), t4)
    return out


def coupler_p(q):
    a, b, t2, t3, t4 = pose(q)
    r = rot(P0, A0, t3 - TH3)
    return (a[0] + r[0], a[1] + r[1])


def extensions(q):
    """x of each element: k1, k2, kt (wrapped deflection + phi0), c1, ct"""
    a, b, t2, t3, t4 = pose(q)
    return {
        "k1": norm(sub(coupler_p(q), C)),
        "k2": norm(sub(O4, a)),
        "kt": t2,
        "c1": norm(sub(b, D)),
        "ct": t2,
    }


def potential(q):
    e = extensions(q)
    vg = mpf(0)
    for name, (g, _) in cgs(q).items():
        vg -= LINKS[name][0] * (G[0] * g[0] + G[1] * g[1])
    return (
        vg
        + K1 * (e["k1"] - L01) ** 2 / 2
        + K2 * (e["k2"] - L02) ** 2 / 2
        + KT * wrap(e["kt"] - PHI0) ** 2 / 2
    )


def inertia(q):
    total = mpf(0)
    for name, (m, i, _) in LINKS.items():
        gx = diff(lambda t: cgs(t)[name][0][0], q)
        gy = diff(lambda t: cgs(t)[name][0][1], q)
        w = diff(lambda t: cgs(t)[name][1], q)
        total += m * (gx**2 + gy**2) + i * w**2
    return total


def damping(q):
    """sum c (dx/dq)^2: the dampers' reduced damping coefficient (N.m.s/rad)"""
    return C1 * diff(lambda t: extensions(t)["c1"], q) ** 2 + CT * diff(
        lambda t: extensions(t)["ct"], q
    ) ** 2


def config(q, qd, qdd, resist):
    q, qd, qdd, resist = mpf(q), mpf(qd), mpf(qdd), mpf(resist)
    i_star = inertia(q)
    di = diff(inertia, q)
    dv = diff(potential, q)
    g4 = diff(lambda t: pose(t)[4], q)
    c_star = damping(q)
    m_star = -dv + resist * g4  # position part of M* (loads, gravity, springs)
    driver = i_star * qdd + di * qd**2 / 2 - m_star + c_star * qd
    return {
        "q": float(q),
        "qd": float(qd),
        "qdd": float(qdd),
        "resist": float(resist),
        "I_star": str(i_star),
        "dI_star_dq": str(di),
        "M_star": str(m_star),
        "damping_star": str(c_star),
        "potential": str(potential(q)),
        "driver": str(driver),
    }


def main():
    out = out_path()
    configs = [
        config(q, qd, qdd, r)
        for (q, qd, qdd, r) in [
            ("0.3", "4.0", "-20.0", "2.0"),
            ("1.0", "-7.5", "35.0", "-1.5"),
            ("1.7", "12.0", "0.0", "0.0"),
            ("2.6", "-3.0", "-60.0", "4.0"),
            ("3.9", "9.0", "15.0", "-3.0"),
            ("-0.8", "2.5", "80.0", "1.0"),
        ]
    ]
    # Equilibrium: dV/dq = 0 with V'' > 0, from a scan of the stable minima.
    qs = [mpf(k) / 50 * 2 * pi - pi / 3 for k in range(50)]
    vals = [potential(q) for q in qs]
    k = min(range(50), key=lambda j: vals[j])
    q_star = findroot(lambda t: diff(potential, t), qs[k])
    v2 = diff(potential, q_star, 2)
    assert v2 > 0
    wn = sqrt(v2 / inertia(q_star))
    doc = {
        "about": "tools/elements_reference.py: the spring-loaded four-bar of tests/elements.rs by the energy method, mpmath 50 digits",
        "free_length_k2": str(L02),
        "configs": configs,
        "equilibrium": {
            "q": str(q_star),
            "stiffness_star": str(v2),
            "I_star": str(inertia(q_star)),
            "natural_frequency": str(wn),
        },
    }
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)
    print(f"wrote {out}: q* = {mp.nstr(q_star, 20)}, w_n = {mp.nstr(wn, 20)} rad/s")


if __name__ == "__main__":
    main()
