#!/usr/bin/env python3
"""The reference table of a spatial slider-crank (issue 33), 50 digits, its own formulation.

    python3 tools/spatial_reference.py [--out-root DIR]

writes tests/data/spatial/slider_crank.truth.json: the mechanism's `space` text (the Rust
test loads it with SpatialMechanism::from_dsl) and, at eight crank angles with a speed and an
acceleration, the points' motion, the rod's angular velocity and acceleration, every
reaction (force and moment by the joint's first link on its second, the moment about the
joint's point) and the driver torque.

The mechanism: a crank turning about the skew axis u0 through O (revolute O, the input), a
rod with a spherical joint at the crank pin A and a universal joint at B to a slider that
translates along the skew line B0 + s w (prismatic `guide`). Kutzbach: 6·3 − (5 + 3 + 4 + 5)
= 1, no idle freedom (the universal joint holds the rod's spin).

The formulation is not mech's (absolute coordinates and constraint rows). Here:
- the rod's rotation is R = Rot(u2, β) Rot(u1, γ), u2 the cross's axis fixed in the slider
  (which does not turn) and u1 the one fixed in the rod, so the universal joint holds by
  construction; the loop A(θ) = B0 + s w + R (A0 − B0) is three equations in (s, β, γ),
  solved by mpmath's findroot (Newton), continued from the drawing in steps of 0.05 rad;
- velocities: v_A = ṡ w + ω × (A − B), ω = β̇ u2 + γ̇ R_β u1, a 3×3 linear solve;
  accelerations likewise, with α = β̈ u2 + γ̈ R_β u1 + β̇ γ̇ u2 × R_β u1;
- Newton–Euler of each body about its cg (m a_G, I α + ω × I ω, I = R I0 Rᵀ) with the 18
  reaction unknowns in the joints' own bases (O: force, two moments ⊥ u0, the driver torque
  along u0; A: force; B: force, the moment along R_β u1 × u2; guide: two forces ⊥ w, a
  moment), one 18×18 solve.
"""

import json
import sys

import mpmath as mp

import outroot

mp.mp.dps = 50
D = mp.mpf


def v(*xs):
    return mp.matrix([D(x) for x in xs])


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return mp.matrix([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def unit(a):
    return a / mp.sqrt(dot(a, a))


def rot(u, t):
    """Rodrigues: the rotation by t about the unit u."""
    c, s = mp.cos(t), mp.sin(t)
    k = mp.matrix([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return mp.eye(3) + s * k + (1 - c) * (k * k)


def tensor(six):
    xx, yy, zz, xy, xz, yz = [D(x) for x in six]
    return mp.matrix([[xx, -xy, -xz], [-xy, yy, -yz], [-xz, -yz, zz]])


def f(x):
    return repr(float(x))


def vec_text(a):
    return "(" + ", ".join(f(x) for x in a) + ")"


# The drawing, as f64 values (written into the text exactly).
O = (0.0, 0.0, 0.0)
U0 = (0.2, -0.1, 1.0)
A0 = (0.06, 0.01, -0.01)
B0 = (0.28, 0.05, 0.12)
W = (1.0, 0.15, 0.3)
G = (0.0, -9.81, -2.0)
CRANK = dict(mass=1.3, cg=(0.02, 0.004, -0.002), inertia=(2e-3, 1.5e-3, 9e-4, 2e-4, -1e-4, 3e-4))
ROD = dict(mass=0.6, cg=(0.16, 0.028, 0.05), inertia=(3e-4, 4e-3, 3.6e-3, 2e-4, 5e-4, -1e-4))
SLIDER = dict(mass=2.2, cg=(0.3, 0.06, 0.11), inertia=(1e-3, 2e-3, 3e-3, 0.0, 0.0, 0.0))
LOADS = dict(gas=(-40.0, 6.0, 3.0), twist=(0.4, -0.7, 0.25), pin=(2.0, -5.0, 1.5))


def drawing_axes():
    """The universal joint's axes as f64: u2 ⊥ the rod's line in the drawing and ⊥ z, u1 ⊥
    both (so the cross blocks the rod's spin)."""
    a0, b0 = v(*A0), v(*B0)
    e = unit(b0 - a0)
    u2 = unit(cross(e, v(0, 0, 1)))
    u1 = unit(cross(u2, e))
    return tuple(float(x) for x in u1), tuple(float(x) for x in u2)


U1, U2 = drawing_axes()


def text():
    def link(name, pts, d):
        return ("    link %s { points { %s }, mass: %s, cg: %s, inertia: %s },\n"
                % (name, pts, f(d["mass"]), vec_text(d["cg"]), vec_text(d["inertia"])))
    return ("pub struct SpatialSliderCrank {\n    space,\n"
            + "    gravity: %s,\n" % vec_text(G)
            + "    ground { O: %s },\n" % vec_text(O)
            + link("crank", "O, A: %s" % vec_text(A0), CRANK)
            + link("rod", "A, B: %s" % vec_text(B0), ROD)
            + link("slider", "B", SLIDER)
            + "    joints {\n"
            + "        O: revolute(ground, crank) axis %s,\n" % vec_text(U0)
            + "        A: spherical(crank, rod),\n"
            + "        B: universal(rod, slider) axes %s %s,\n" % (vec_text(U1), vec_text(U2))
            + "        guide: prismatic(ground, slider) at B along %s,\n" % vec_text(W)
            + "    },\n    input: O,\n"
            + "    loads { gas: force on slider at B, twist: torque on rod, pin: force on crank at A },\n}\n")


u0, w, u1, u2 = unit(v(*U0)), unit(v(*W)), unit(v(*U1)), unit(v(*U2))
a0, b0, g = v(*A0), v(*B0), v(*G)


def loop(theta, x):
    s, beta, gamma = x
    a = rot(u0, theta) * a0
    r = rot(u2, beta) * rot(u1, gamma)
    return list(a - (b0 + s * w + r * (a0 - b0)))


def solve_path(thetas):
    """(s, β, γ) at each θ (increasing from 0), continued from the drawing."""
    out, x, t = [], [D(0), D(0), D(0)], D(0)
    for target in thetas:
        while t < target:
            t = min(t + D("0.05"), target)
            x = list(mp.findroot(lambda s, b, c: loop(t, [s, b, c]), x, tol=D(10) ** -45))
        out.append(x)
    return out


def case(theta, qd, qdd, x):
    s, beta, gamma = x
    rc = rot(u0, theta)
    rb = rot(u2, beta)
    rr = rb * rot(u1, gamma)
    u1t = rb * u1
    a = rc * a0
    b = b0 + s * w
    # crank
    wc, ac = qd * u0, qdd * u0
    va = cross(wc, a)
    aa = cross(ac, a) + cross(wc, cross(wc, a))
    # rod and slider rates: v_A = ṡ w + ω × (A − B)
    d = a - b
    m = mp.matrix(3, 3)
    cols = [w, cross(u2, d), cross(u1t, d)]
    for i in range(3):
        for j in range(3):
            m[i, j] = cols[j][i]
    sd, bd, gd = mp.lu_solve(m, va)
    wr = bd * u2 + gd * u1t
    rest = cross(bd * u2, gd * u1t)  # α = β̈ u2 + γ̈ u1t + β̇ γ̇ u2 × u1t
    rhs = aa - cross(rest, d) - cross(wr, cross(wr, d))
    sdd, bdd, gdd = mp.lu_solve(m, rhs)
    ar = bdd * u2 + gdd * u1t + rest
    # the cgs
    gc = rc * v(*CRANK["cg"])
    gr = b + rr * (v(*ROD["cg"]) - b0)
    gs = b + (v(*SLIDER["cg"]) - b0)
    agc = cross(ac, gc) + cross(wc, cross(wc, gc))
    agr = sdd * w + cross(ar, gr - b) + cross(wr, cross(wr, gr - b))
    ags = sdd * w
    ic = rc * tensor(CRANK["inertia"]) * rc.T
    ir = rr * tensor(ROD["inertia"]) * rr.T
    # Newton–Euler: unknowns in order
    # 0-2 F_O, 3-4 M_O (n1, n2 ⊥ u0), 5 τ, 6-8 F_A, 9-11 F_B, 12 μ, 13-14 F_P (p1, p2 ⊥ w), 15-17 M_P
    n1 = unit(cross(u0, v(1, 0, 0)))
    n2 = cross(u0, n1)
    p1 = unit(cross(w, v(0, 0, 1)))
    p2 = cross(w, p1)
    ub = cross(u1t, u2)
    gas, twist, pin = (v(*LOADS[k]) for k in ("gas", "twist", "pin"))
    A = mp.matrix(18, 18)
    rhs = mp.matrix(18, 1)

    def put(row, col, vec, sign=1):
        for i in range(3):
            A[row + i, col] += sign * vec[i]

    def put_force(rowf, rowm, col, at, cg, sign=1):
        """Three force unknowns at `col` acting at `at` on the body with cg `cg`."""
        for k in range(3):
            e = mp.matrix([1 if i == k else 0 for i in range(3)])
            put(rowf, col + k, e, sign)
            put(rowm, col + k, cross(at - cg, e), sign)

    # crank: rows 0-2 forces, 3-5 moments about its cg
    put_force(0, 3, 0, v(*O), gc)
    put(3, 3, n1), put(3, 4, n2), put(3, 5, u0)
    put_force(0, 3, 6, a, gc, -1)
    # rod: rows 6-11
    put_force(6, 9, 6, a, gr)
    put_force(6, 9, 9, b, gr, -1)
    put(9, 12, ub, -1)
    # slider: rows 12-17
    put_force(12, 15, 9, b, gs)
    put(15, 12, ub)
    put(12, 13, p1), put(12, 14, p2)
    put(15, 13, cross(b - gs, p1)), put(15, 14, cross(b - gs, p2))
    for k in range(3):
        A[15 + k, 15 + k] += 1
    # right-hand sides: inertia − applied
    m_c, m_r, m_s = D(CRANK["mass"]), D(ROD["mass"]), D(SLIDER["mass"])
    blocks = [
        (0, m_c * agc - m_c * g - pin, ic * ac + cross(wc, ic * wc) - cross(a - gc, pin)),
        (6, m_r * agr - m_r * g, ir * ar + cross(wr, ir * wr) - twist),
        (12, m_s * ags - m_s * g - gas, mp.matrix([0, 0, 0]) - cross(b - gs, gas)),
    ]
    for row, fo, mo in blocks:
        for i in range(3):
            rhs[row + i] = fo[i]
            rhs[row + 3 + i] = mo[i]
    x = mp.lu_solve(A, rhs)
    resid = mp.norm(A * x - rhs)
    fo = x[0:3]
    reactions = {
        "O": (mp.matrix(fo), x[3] * n1 + x[4] * n2),
        "A": (mp.matrix(x[6:9]), mp.matrix([0, 0, 0])),
        "B": (mp.matrix(x[9:12]), x[12] * ub),
        "guide": (x[13] * p1 + x[14] * p2, mp.matrix(x[15:18])),
    }
    num = lambda z: mp.nstr(z, 30, min_fixed=-1, max_fixed=-1)
    vec = lambda z: [num(z[i]) for i in range(3)]
    return {
        "q": num(theta), "qd": num(qd), "qdd": num(qdd),
        "points": {"A": [vec(a), vec(va), vec(aa)],
                   "B": [vec(b), vec(sd * w), vec(sdd * w)]},
        "links": {"rod": {"omega": vec(wr), "alpha": vec(ar), "cg_acceleration": vec(agr)},
                  "crank": {"omega": vec(wc), "alpha": vec(ac), "cg_acceleration": vec(agc)}},
        "reactions": {k: {"force": vec(fv), "moment": vec(mv)} for k, (fv, mv) in reactions.items()},
        "driver": num(x[5]),
    }, resid, mp.norm(mp.matrix(loop(theta, [s, beta, gamma])))


def main(argv):
    root, _ = outroot.split(argv)
    thetas = [D(k) * 2 * mp.pi / 8 + D("0.2") for k in range(8)]
    rates = [(D(15), D(-40)), (D(-6), D(25)), (D(0), D(0)), (D(30), D(100)),
             (D(12), D(-7)), (D(-20), D(0)), (D(3), D(60)), (D(9), D(-90))]
    cases, worst_ne, worst_loop = [], D(0), D(0)
    for theta, x, (qd, qdd) in zip(thetas, solve_path(thetas), rates):
        c, r1, r2 = case(theta, qd, qdd, x)
        cases.append(c)
        worst_ne, worst_loop = max(worst_ne, r1), max(worst_loop, r2)
    out = {
        "name": "slider_crank",
        "about": "a spatial slider-crank (R-S-U-P) by tools/spatial_reference.py, 50 digits",
        "dsl": text(),
        "loads": {k: list(vv) for k, vv in LOADS.items()},
        "cases": cases,
        "verification": {"newton_euler_residual": mp.nstr(worst_ne, 3), "loop_residual": mp.nstr(worst_loop, 3)},
    }
    with open(outroot.path(root, "tests", "data", "spatial", "slider_crank.truth.json"), "w") as fh:
        json.dump(out, fh, indent=1)
        fh.write("\n")


if __name__ == "__main__":
    main(sys.argv[1:])
