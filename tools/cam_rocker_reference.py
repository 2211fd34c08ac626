#!/usr/bin/env python3
"""Reference for the oscillating cam followers (rockers) of tests/cam_rockers.rs, by routes
mech does not take:

* Profiles (sympy, 30 digits). The roller rocker's pitch curve seen from the cam,
  P(theta) = R(-theta) (A + R(sigma psi(theta)) (P0 - A)), and the flat-faced rocker's cam
  surface, the envelope of the face lines seen from the cam, found by solving
  L(x, theta) = 0, dL/dtheta = 0 for x, are differentiated SYMBOLICALLY; the radius of
  curvature is |P'|^3 / (P' x P'') with the sign of a clockwise traversal (> 0 convex).
  mech writes the derivatives out by hand (mech_core::cam::Profile::contact). The pressure
  angle comes from Aronhold-Kennedy: the common normal passes through the pitch point and
  the relative instant centre I of cam and rocker on the line of centres,
  I = A sigma psi' / (sigma psi' - 1).
* Dynamics (mpmath, 40 digits): the spring-loaded roller rocker at constant cam speed w,
  by the rocker's own moment equation about its pivot A (one equation, not mech's
  wrenches):
      I_A D'' = F_n (F - A) x n + M_spring + M_gravity,  D = sigma psi(theta), D'' = sigma psi'' w^2,
  with the torsion spring's moment -(T0 + k D) and gravity's (cg - A) x (0, -m g); the motor
  torque by the power balance, T w = (I_A D'' - M_spring - M_gravity) D'; the jump speed, the
  smallest w where F_n reaches 0 on a grid of 7 200 cam angles.

Writes tests/data/cam_rocker.json. Usage: python3 tools/cam_rocker_reference.py [--out-root DIR]
"""

import json
import os

import sympy as sp
from mpmath import mp, mpf

mp.dps = 40
HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "data", "cam_rocker.json")


def out_path():
    """OUT, or the same path under `--out-root DIR` (tools/outroot.py)."""
    import sys
    import outroot
    root, _ = outroot.split(sys.argv[1:])
    return outroot.path(root, "tests", "data", "cam_rocker.json")


th = sp.symbols("theta", real=True)
DEG = sp.pi / 180

# The roller rocker of tests/cam_rockers.rs: cam centre O at the origin, pivot A, the
# roller's centre P0 on the prime circle (R_b + r) straight above O in the drawing.
RB, ROLLER = sp.Rational(30, 1000), sp.Rational(8, 1000)
A = (sp.Rational(60, 1000), sp.Rational(50, 1000))
LIFT = 15 * DEG
SIGMA = -1  # the pivot to the right of O: the rocker turns clockwise to lift
MASS, I_CG = sp.Rational(15, 100), sp.Rational(6, 100000)
CG = (sp.Rational(40, 1000), sp.Rational(46, 1000))
K_T, T0, G = 20, -3, sp.Rational(981, 100)

# The flat-faced rocker (a profile only): base circle 30 mm, pivot (70 mm, 45 mm), the face
# tangent to the base circle at (0, 30 mm) in the drawing, lift 10 deg.
FLAT_A = (sp.Rational(70, 1000), sp.Rational(45, 1000))
FLAT_LIFT = 10 * DEG


def segments(lift):
    """(start, end, shape, h0, h1): dwell 90, cycloidal rise 90, dwell 60, 3-4-5 fall 120"""
    return [
        (0, 90 * DEG, "dwell", 0, 0),
        (90 * DEG, 180 * DEG, "cycloidal", 0, lift),
        (180 * DEG, 240 * DEG, "dwell", lift, lift),
        (240 * DEG, 360 * DEG, "poly345", lift, 0),
    ]


def psi_expr(lift, at):
    """The law's segment holding cam angle `at`, as an expression in theta."""
    for (t0, t1, shape, h0, h1) in segments(lift):
        if sp.N(t0) <= at < sp.N(t1):
            x = (th - t0) / (t1 - t0)
            u = {"dwell": sp.Integer(0),
                 "cycloidal": x - sp.sin(2 * sp.pi * x) / (2 * sp.pi),
                 "poly345": 10 * x**3 - 15 * x**4 + 6 * x**5}[shape]
            return h0 + (h1 - h0) * u
    raise ValueError(at)


def rot(a, v):
    return (sp.cos(a) * v[0] - sp.sin(a) * v[1], sp.sin(a) * v[0] + sp.cos(a) * v[1])


def curvature(c):
    """The signed radius of curvature of a curve traversed clockwise (> 0 convex)."""
    d1 = [sp.diff(x, th) for x in c]
    d2 = [sp.diff(x, th) for x in d1]
    return -(d1[0] ** 2 + d1[1] ** 2) ** sp.Rational(3, 2) / (d1[0] * d2[1] - d1[1] * d2[0])


def angles():
    """Twelve cam angles, two in each dwell and four in each motion, off the joins."""
    return [sp.Rational(a, 1) * DEG for a in [20, 70, 100, 125, 150, 175, 200, 230, 255, 290, 320, 350]]


def n30(x):
    return str(sp.N(x, 30))


def roller_profile():
    rows = []
    for at in angles():
        psi = psi_expr(LIFT, sp.N(at))
        d = SIGMA * psi
        p0 = (0, RB + ROLLER)
        w = rot(d, (p0[0] - A[0], p0[1] - A[1]))
        f = (A[0] + w[0], A[1] + w[1])
        pc = rot(-th, f)  # the pitch curve seen from the cam
        rho = curvature(pc) - ROLLER
        # Kennedy: the normal through F and I = g A.
        dpsi = sp.diff(psi, th)
        g = SIGMA * dpsi / (SIGMA * dpsi - 1)
        nf = (f[0] - g * A[0], f[1] - g * A[1])
        sub = lambda e: sp.Float(sp.lambdify(th, sp.sympify(e), 'mpmath')(mpf(str(sp.N(at, 50)))), 40)
        nf = [sub(x) for x in nf]
        ln = sp.sqrt(nf[0] ** 2 + nf[1] ** 2)
        n = [nf[0] / ln, nf[1] / ln]
        fv = [sub(x) for x in f]
        arm = (fv[0] - A[0], fv[1] - A[1])
        la = sp.sqrt(arm[0] ** 2 + arm[1] ** 2)
        dvec = (-SIGMA * arm[1] / la, SIGMA * arm[0] / la)
        phi = sp.atan2(dvec[0] * n[1] - dvec[1] * n[0], dvec[0] * n[0] + dvec[1] * n[1])
        contact = (fv[0] - ROLLER * n[0], fv[1] - ROLLER * n[1])
        back = rot(-at, contact)
        rows.append({
            "theta": n30(at),
            "contact": [n30(back[0]), n30(back[1])],
            "pressure_angle": n30(phi),
            "curvature_radius": n30(sub(rho)),
        })
    return rows


def flat_profile():
    rows = []
    for at in angles():
        psi = psi_expr(FLAT_LIFT, sp.N(at))
        d = SIGMA * psi
        m = rot(d, (0, 1))
        q = rot(d, (0 - FLAT_A[0], RB - FLAT_A[1]))
        q = (FLAT_A[0] + q[0], FLAT_A[1] + q[1])  # a point of the face line
        # The line seen from the cam: mc . x = p, mc = R(-theta) m, p = m . q.
        mc = rot(-th, m)
        p = m[0] * q[0] + m[1] * q[1]
        # mc . x = p and mc' . x = p', by Cramer's rule.
        m1 = [sp.diff(c, th) for c in mc]
        p1 = sp.diff(p, th)
        det = mc[0] * m1[1] - mc[1] * m1[0]
        env = ((p * m1[1] - mc[1] * p1) / det, (mc[0] * p1 - p * m1[0]) / det)
        rho = curvature(env)
        sub = lambda e: sp.Float(sp.lambdify(th, sp.sympify(e), 'mpmath')(mpf(str(sp.N(at, 50)))), 40)
        kc = [sub(env[0]), sub(env[1])]
        # The contact in the fixed frame, and the pressure angle there: between the face's
        # normal m and the motion sigma perp(K - A) of the rocker's point at K.
        kf = rot(at, kc)
        mv = [sub(sp.sympify(m[0])), sub(sp.sympify(m[1]))]
        arm = (kf[0] - FLAT_A[0], kf[1] - FLAT_A[1])
        la = sp.sqrt(arm[0] ** 2 + arm[1] ** 2)
        dvec = (-SIGMA * arm[1] / la, SIGMA * arm[0] / la)
        phi = sp.atan2(dvec[0] * mv[1] - dvec[1] * mv[0], dvec[0] * mv[0] + dvec[1] * mv[1])
        rows.append({
            "theta": n30(at),
            "contact": [n30(kc[0]), n30(kc[1])],
            "pressure_angle": n30(phi),
            "curvature_radius": n30(sub(rho)),
        })
    return rows


# ---- dynamics, mpmath -------------------------------------------------------------------

def mpv(x):
    return mpf(str(sp.N(x, 50)))


def law_mp(t):
    """psi, psi', psi'' (rad, per rad) in mpmath, the same law written again."""
    d = mp.pi / 180
    lift = 15 * d
    if t < 90 * d or 180 * d <= t < 240 * d:
        return (mpf(0) if t < 90 * d else lift), mpf(0), mpf(0)
    if t < 180 * d:
        b = 90 * d
        x = (t - 90 * d) / b
        return (lift * (x - mp.sin(2 * mp.pi * x) / (2 * mp.pi)), lift / b * (1 - mp.cos(2 * mp.pi * x)),
                lift / b**2 * 2 * mp.pi * mp.sin(2 * mp.pi * x))
    b = 120 * d
    x = (t - 240 * d) / b
    return (lift - lift * (10 * x**3 - 15 * x**4 + 6 * x**5),
            -lift / b * (30 * x**2 - 60 * x**3 + 30 * x**4),
            -lift / b**2 * (60 * x - 180 * x**2 + 120 * x**3))


def state(t):
    """(a, b, lever, phi, s'): F_n = (a w^2 + b) / lever; the motor torque is (a w^2 + b) D'."""
    ax, ay = mpv(A[0]), mpv(A[1])
    psi, p1, p2 = law_mp(t)
    d = SIGMA * psi
    c, s = mp.cos(d), mp.sin(d)
    rp = mpv(RB + ROLLER)
    wx, wy = -ax, rp - ay
    f = (ax + c * wx - s * wy, ay + s * wx + c * wy)
    g = SIGMA * p1 / (SIGMA * p1 - 1)
    nf = (f[0] - g * ax, f[1] - g * ay)
    ln = mp.sqrt(nf[0] ** 2 + nf[1] ** 2)
    n = (nf[0] / ln, nf[1] / ln)
    lever = (f[0] - ax) * n[1] - (f[1] - ay) * n[0]
    cgx, cgy = mpv(CG[0]) - ax, mpv(CG[1]) - ay
    cg = (c * cgx - s * cgy, s * cgx + c * cgy)
    m, icg = mpv(MASS), mpv(I_CG)
    i_a = icg + m * (cgx**2 + cgy**2)
    m_spring = -(T0 + K_T * d)
    m_grav = cg[0] * (-m * mpv(G))
    a = i_a * SIGMA * p2
    b = -m_spring - m_grav
    arm = (f[0] - ax, f[1] - ay)
    la = mp.sqrt(arm[0] ** 2 + arm[1] ** 2)
    dvec = (-SIGMA * arm[1] / la, SIGMA * arm[0] / la)
    phi = mp.atan2(dvec[0] * n[1] - dvec[1] * n[0], dvec[0] * n[0] + dvec[1] * n[1])
    return a, b, lever, phi, SIGMA * p1


def dynamics():
    w = mpf(60)
    rows = []
    for k in range(36):
        t = mpf(k) * 2 * mp.pi / 36 + mpf("0.013")
        a, b, lever, phi, d1 = state(t)
        rows.append({
            "theta": float(t),
            "theta_exact": mp.nstr(t, 40),
            "normal_force": mp.nstr((a * w**2 + b) / lever, 30),
            "pressure_angle": mp.nstr(phi, 30),
            "driver": mp.nstr((a * w**2 + b) * d1, 30),
        })
    jump = mp.inf
    for k in range(7200):
        t = mpf(k) * 2 * mp.pi / 7200
        a, b, lever, _, _ = state(t)
        # F_n lever = a w^2 + b with b / lever > 0 at rest: zero at w^2 = -b / a.
        if a / lever < 0:
            jump = min(jump, mp.sqrt(-b / a))
    return w, rows, jump


def main():
    out = out_path()
    w, rows, jump = dynamics()
    doc = {
        "about": "tools/cam_rocker_reference.py: sympy (symbolic derivatives, envelopes) and mpmath (the rocker's moment equation)",
        "roller_profile": roller_profile(),
        "flat_profile": flat_profile(),
        "speed": float(w),
        "points": rows,
        "jump_speed": mp.nstr(jump, 30),
    }
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)
    print("wrote", out, "jump speed", mp.nstr(jump, 12), "rad/s")


if __name__ == "__main__":
    main()
