#!/usr/bin/env python3
"""Reference for the spring-loaded cam follower of tests/cams.rs (mpmath, 40 digits), by
the follower's own equation along its axis (one dimension, not mech's wrenches):

    m x'' = F_n cos(phi) - F_spring - m g,   x = s(theta), x'' = s''(theta) w^2 (constant w),

so the contact force F_n = (m s'' w^2 + F_spring + m g) / cos(phi), with the roller's pressure
angle tan(phi) = s' / (R_p + s) (no offset) and the compression spring's force
F_spring = F0 + k s. The motor torque at constant speed by the power balance:
T w = (m x'' + F_spring + m g) x'. The jump speed: the smallest w where F_n reaches 0,
w_jump^2 = min over s'' < 0 of (F_spring + m g) / (-m s''); the smallest preload that
keeps contact at w: F0 = max over theta of (-m s'' w^2 - k s - m g).

Writes tests/data/cam_follower.json. Usage: python3 tools/cam_follower_reference.py [--out-root DIR]
"""

import json
import os

from mpmath import mp, mpf, pi, sin, cos, atan, sqrt

mp.dps = 40
HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "data", "cam_follower.json")


def out_path():
    """OUT, or the same path under `--out-root DIR` (tools/outroot.py)."""
    import sys
    import outroot
    root, _ = outroot.split(sys.argv[1:])
    return outroot.path(root, "tests", "data", "cam_follower.json")


M, G, K, F0 = mpf("0.08"), mpf("9.81"), mpf(5000), mpf(50)
RP = mpf("0.05")  # base circle 40 mm + roller 10 mm
L = mpf("0.01")


def law(th):
    """s, s', s'' of: dwell 90, cycloidal rise 90 (10 mm), dwell 60, 3-4-5 fall 120"""
    d = pi / 180
    if th < 90 * d:
        return mpf(0), mpf(0), mpf(0)
    if th < 180 * d:
        b = 90 * d
        x = (th - 90 * d) / b
        return (L * (x - sin(2 * pi * x) / (2 * pi)), L / b * (1 - cos(2 * pi * x)),
                L / b**2 * 2 * pi * sin(2 * pi * x))
    if th < 240 * d:
        return L, mpf(0), mpf(0)
    b = 120 * d
    x = (th - 240 * d) / b
    return (L - L * (10 * x**3 - 15 * x**4 + 6 * x**5),
            -L / b * (30 * x**2 - 60 * x**3 + 30 * x**4),
            -L / b**2 * (60 * x - 180 * x**2 + 120 * x**3))


def point(th, w):
    s, s1, s2 = law(th)
    phi = atan(s1 / (RP + s))
    spring = F0 + K * s
    fn = (M * s2 * w**2 + spring + M * G) / cos(phi)
    torque = (M * s2 * w**2 + spring + M * G) * s1
    return {"theta": float(th), "s": str(s), "pressure_angle": str(phi),
            "normal_force": str(fn), "driver": str(torque)}


def main():
    out = out_path()
    w = mpf(150)
    thetas = [mpf(k) * 2 * pi / 72 + mpf("0.01") for k in range(72)]
    fine = [mpf(k) * 2 * pi / 7200 for k in range(7200)]
    jump = min(sqrt((F0 + K * law(t)[0] + M * G) / (-M * law(t)[2]))
               for t in fine if law(t)[2] < 0)
    w2 = mpf(400)
    preload = max(-M * law(t)[2] * w2**2 - K * law(t)[0] - M * G for t in fine)
    doc = {
        "about": "tools/cam_follower_reference.py: the follower's 1-D equation, mpmath 40 digits",
        "speed": float(w),
        "points": [point(t, w) for t in thetas],
        "jump_speed": str(jump),
        "preload_at": float(w2),
        "min_preload": str(preload),
    }
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)
    print("wrote", out, "jump speed", mp.nstr(jump, 12), "rad/s; min preload at 400 rad/s", mp.nstr(preload, 12), "N")


if __name__ == "__main__":
    main()
