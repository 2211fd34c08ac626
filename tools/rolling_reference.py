#!/usr/bin/env python3
"""High-precision reference for the rolling wheel of tests/rolling.rs: a crank drives a
rod whose far end carries a wheel rolling on the ground (mpmath, 50 digits, the energy
method: positions in closed form, the wheel's turn -s/r from its centre's travel s,
velocity coefficients by numerical differentiation; driver = I* q'' + 1/2 dI*/dq q'^2 -
M*, M* the power of gravity and of the load torque on the wheel per unit q').

Writes tests/data/rolling.json. Usage: python3 tools/rolling_reference.py [--out-root DIR]
"""

import json
import os

from mpmath import mp, mpf, cos, sin, sqrt, atan2, diff

mp.dps = 50
HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "data", "rolling.json")


def out_path():
    """OUT, or the same path under `--out-root DIR` (tools/outroot.py)."""
    import sys
    import outroot
    root, _ = outroot.split(sys.argv[1:])
    return outroot.path(root, "tests", "data", "rolling.json")


MM = mpf(1) / 1000
G = (mpf(0), mpf("-9.81"))

# The drawing of `WheelRod` in tests/rolling.rs.
O2 = (mpf(0), mpf(0))
A0 = (40 * MM, 30 * MM)
C0 = (250 * MM, -20 * MM)  # the wheel's centre, rolling on y = -20 mm - r
R = 50 * MM
L = sqrt((C0[0] - A0[0]) ** 2 + (C0[1] - A0[1]) ** 2)
RA = sqrt(A0[0] ** 2 + A0[1] ** 2)
TH2 = atan2(A0[1], A0[0])
TH3 = atan2(C0[1] - A0[1], C0[0] - A0[0])
CRANK = (mpf("0.8"), mpf("6.0e-4"), (20 * MM, 15 * MM))
ROD = (mpf("1.1"), mpf("5.0e-3"), (140 * MM, 10 * MM))
WHEEL = (mpf("1.6"), mpf("2.2e-3"))


def rot(v, phi):
    c, s = cos(phi), sin(phi)
    return (c * v[0] - s * v[1], s * v[0] + c * v[1])


def pose(q):
    phi2 = q - TH2  # the crank's turn since the drawing (q = its angle θ_crank − θ_ground)
    a = rot(A0, phi2)
    dy = C0[1] - a[1]
    cx = a[0] + sqrt(L**2 - dy**2)
    c = (cx, C0[1])
    th3 = atan2(c[1] - a[1], c[0] - a[0])
    s = cx - C0[0]
    return phi2, a, c, th3, -s / R


def circle_pose(d, inside):
    """the crank-rod-wheel with the wheel rolling around the circle centred at d (outside,
    or inside a ring): C on the circle of radius rho = |C0 - D| about D"""
    rho = sqrt((C0[0] - d[0]) ** 2 + (C0[1] - d[1]) ** 2)
    k = (-1 if inside else 1) * rho / R
    psi0 = atan2(C0[1] - d[1], C0[0] - d[0])
    side = 1 if ((d[0] - A0[0]) * (C0[1] - A0[1]) - (d[1] - A0[1]) * (C0[0] - A0[0])) > 0 else -1

    def pose_c(q):
        a = rot(A0, q - TH2)
        dx, dy = d[0] - a[0], d[1] - a[1]
        dd = sqrt(dx**2 + dy**2)
        x = (L**2 - rho**2 + dd**2) / (2 * dd)
        h = sqrt(L**2 - x**2)
        ux, uy = dx / dd, dy / dd
        c = (a[0] + x * ux - side * h * uy, a[1] + x * uy + side * h * ux)
        th3 = atan2(c[1] - a[1], c[0] - a[0])
        psi = atan2(c[1] - d[1], c[0] - d[0]) - psi0
        return q - TH2, a, c, th3, k * psi

    return pose_c


POSES = {"line": None}


def parts(q):
    phi2, a, c, th3, phiw = POSES["line"](q) if POSES["line"] else pose(q)
    g2 = rot(CRANK[2], phi2)
    g3 = rot((ROD[2][0] - A0[0], ROD[2][1] - A0[1]), th3 - TH3)
    return [
        (CRANK[0], CRANK[1], g2, phi2),
        (ROD[0], ROD[1], (a[0] + g3[0], a[1] + g3[1]), th3),
        (WHEEL[0], WHEEL[1], c, phiw),
    ]


def inertia(t):
    tot = mpf(0)
    for k in range(3):
        gx = diff(lambda u: parts(u)[k][2][0], t)
        gy = diff(lambda u: parts(u)[k][2][1], t)
        w = diff(lambda u: parts(u)[k][3], t)
        m, i = parts(t)[k][0], parts(t)[k][1]
        tot += m * (gx**2 + gy**2) + i * w**2
    return tot


def gravity_power(t):
    return diff(lambda u: sum(m * (G[0] * g[0] + G[1] * g[1]) for (m, _, g, _) in parts(u)), t)


def config(q, qd, qdd, brake):
    pose_ = POSES["line"] or pose
    q, qd, qdd, brake = mpf(q), mpf(qd), mpf(qdd), mpf(brake)
    i_star = inertia(q)
    di = diff(inertia, q)
    m_star = gravity_power(q) + brake * diff(lambda u: pose_(u)[4], q)
    return {
        "q": float(q), "qd": float(qd), "qdd": float(qdd), "brake": float(brake),
        "I_star": str(i_star), "dI_star_dq": str(di), "M_star": str(m_star),
        "wheel_turn": str(pose_(q)[4]),
        "driver": str(i_star * qdd + di * qd**2 / 2 - m_star),
    }


CONFIGS = [
    ("0.0", "10.0", "5.0", "0.5"), ("1.3", "-20.0", "100.0", "-1.0"),
    ("2.9", "35.0", "0.0", "2.0"), ("-2.0", "7.0", "-50.0", "0.0"),
    ("14.0", "3.0", "1.0", "0.3")]


def main():
    out = out_path()
    doc = {
        "about": "tools/rolling_reference.py: the crank-rod-wheels of tests/rolling.rs by the energy method, mpmath 50 digits",
        "configs": [config(*c) for c in CONFIGS],
    }
    # The wheel around a circle: outside one centred 130 mm below C, inside a ring
    # centred 120 mm above it.
    for key, d, inside in [("outside", (250 * MM, -150 * MM), False),
                           ("inside", (250 * MM, 100 * MM), True)]:
        POSES["line"] = circle_pose(d, inside)
        doc[key] = [config(*c) for c in CONFIGS]
    POSES["line"] = None
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)
    print("wrote", out)


if __name__ == "__main__":
    main()
