#!/usr/bin/env python3
"""High-precision references for the gear pairs and racks of tests/gears.rs (mpmath, 50
digits), by formulations independent of mech's:

- GearTrain and Epicyclic: the speed ratios by Willis written by hand for each train, and
  the kinetostatics as ONE linear system of every body's Newton-Euler equations (unknowns:
  every bearing force, every tangential tooth force, the driver torque), solved by LU; the
  tooth force along the line of action, F = f (t + s tan(alpha) n_sep) with the flank s =
  sign(f) found by re-solving until it is consistent. (mech solves gear by gear from the
  outermost inward.)
- GearedSliderCrank and RackSteering: the driver torque by the energy method, positions in
  closed form, velocity coefficients by numerical differentiation: driver = I* q'' +
  1/2 dI*/dq q'^2 - M*, M* the power of gravity and the loads per unit q'.

Writes tests/data/gears.json. Usage: python3 tools/gears_reference.py [--out-root DIR]
"""

import json
import os

from mpmath import mp, mpf, cos, sin, sqrt, atan2, diff, matrix, lu_solve, pi

mp.dps = 50
HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "data", "gears.json")


def out_path():
    """OUT, or the same path under `--out-root DIR` (tools/outroot.py)."""
    import sys
    import outroot
    root, _ = outroot.split(sys.argv[1:])
    return outroot.path(root, "tests", "data", "gears.json")


MM = mpf(1) / 1000
G = (mpf(0), mpf("-9.81"))


def add(a, b):
    return (a[0] + b[0], a[1] + b[1])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def mul(a, k):
    return (a[0] * k, a[1] * k)


def perp(a):
    return (-a[1], a[0])


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def norm(a):
    return sqrt(a[0] ** 2 + a[1] ** 2)


def rot(v, phi):
    c, s = cos(phi), sin(phi)
    return (c * v[0] - s * v[1], s * v[0] + c * v[1])


def s_(x):
    return str(x)


# ---------------------------------------------------------------------------------------
# Newton-Euler of a set of bodies: unknowns are named scalars; each body contributes
# 3 equations: sum F - m a_G = 0, sum M about G - I alpha = 0.


class System:
    def __init__(self, unknowns):
        self.names = unknowns
        self.rows = []  # (coefficients dict, constant): sum c_k x_k + const = 0

    def body(self, m, i, g, a_g, alpha, terms, known_forces, known_torque):
        """terms: list of (point, {unknown: vector coefficient}) forces linear in the
        unknowns, and ('torque', {unknown: scalar}) pure torques; known_forces: list of
        (point, vector); known_torque: scalar"""
        fx, fy, mz = {}, {}, {}
        cx, cy, cz = -m * a_g[0], -m * a_g[1], -i * alpha + known_torque
        for p, f in known_forces:
            cx += f[0]
            cy += f[1]
            cz += cross(sub(p, g), f)
        for p, coef in terms:
            for k, v in coef.items():
                if p == "torque":
                    mz[k] = mz.get(k, 0) + v
                    continue
                fx[k] = fx.get(k, 0) + v[0]
                fy[k] = fy.get(k, 0) + v[1]
                mz[k] = mz.get(k, 0) + cross(sub(p, g), v)
        self.rows += [(fx, cx), (fy, cy), (mz, cz)]

    def solve(self):
        n = len(self.names)
        a = matrix(n, n)
        b = matrix(n, 1)
        for r, (coef, const) in enumerate(self.rows):
            for k, v in coef.items():
                a[r, self.names.index(k)] = v
            b[r] = -const
        x = lu_solve(a, b)
        return {k: x[i] for i, k in enumerate(self.names)}


def tooth(f_name, t, nsep, tan_a, flank):
    """the tooth force by a on b as a linear term in the tangential unknown"""
    return {f_name: add(t, mul(nsep, flank * tan_a))}


def solve_flanks(build, names):
    flanks = {k: 1 for k in names}
    for _ in range(8):
        x = build(flanks)
        new = {k: (1 if x[k] >= 0 else -1) for k in names}
        if new == flanks:
            return x, flanks
        flanks = new
    raise RuntimeError("flanks do not settle")


# ---------------------------------------------------------------------------------------
# GearTrain


def gear_train(q, qd, qdd, load):
    r1, r2, r3, r4 = 20 * MM, 60 * MM, 25 * MM, 75 * MM
    o1, o2, o4 = (mpf(0), mpf(0)), (80 * MM, mpf(0)), (80 * MM, 100 * MM)
    m1, i1 = mpf("0.2"), mpf("4.0e-5")
    m2, i2 = mpf("1.1"), mpf("2.2e-3")
    m4, i4 = mpf("2.0"), mpf("6.0e-3")
    g4_0 = (90 * MM, 100 * MM)
    tan12, tan34 = mp.tan(20 * pi / 180), mp.tan(25 * pi / 180)
    k2, k4 = -r1 / r2, (r1 * r3) / (r2 * r4)  # Willis: external pairs reverse the sense
    w = [(q, qd, qdd), (k2 * q, k2 * qd, k2 * qdd), (k4 * q, k4 * qd, k4 * qdd)]
    (p4, w4, a4) = w[2]
    r = rot(sub(g4_0, o4), p4)
    g4 = add(o4, r)
    a_g4 = add(mul(perp(r), a4), mul(r, -(w4**2)))
    # Pitch points, tangents, separating directions on b (external: from a's centre to b's).
    u12 = mul(sub(o2, o1), 1 / norm(sub(o2, o1)))
    u34 = mul(sub(o4, o2), 1 / norm(sub(o4, o2)))
    p12, t12 = add(o1, mul(u12, r1)), perp(u12)
    p34, t34 = add(o2, mul(u34, r3)), perp(u34)
    names = ["T", "R1x", "R1y", "R2x", "R2y", "R4x", "R4y", "f12", "f34"]
    ex, ey = (mpf(1), mpf(0)), (mpf(0), mpf(1))

    def build(fl):
        s = System(names)
        f12 = tooth("f12", t12, u12, tan12, fl["f12"])
        f34 = tooth("f34", t34, u34, tan34, fl["f34"])
        neg = lambda d: {k: mul(v, -1) for k, v in d.items()}  # noqa: E731
        s.body(m1, i1, o1, (0, 0), w[0][2],
               [(o1, {"R1x": ex, "R1y": ey}), (p12, neg(f12)), ("torque", {"T": 1})],
               [(o1, mul(G, m1))], 0)
        s.body(m2, i2, o2, (0, 0), w[1][2],
               [(o2, {"R2x": ex, "R2y": ey}), (p12, f12), (p34, neg(f34))],
               [(o2, mul(G, m2))], 0)
        s.body(m4, i4, g4, a_g4, w[2][2],
               [(o4, {"R4x": ex, "R4y": ey}), (p34, f34)],
               [(g4, mul(G, m4))], load)
        return s.solve()

    x, fl = solve_flanks(build, ["f12", "f34"])
    f12 = add(mul(t12, x["f12"]), mul(u12, abs(x["f12"]) * tan12))
    f34 = add(mul(t34, x["f34"]), mul(u34, abs(x["f34"]) * tan34))
    i_star = i1 + i2 * k2**2 + i4 * k4**2 + m4 * norm(sub(g4_0, o4)) ** 2 * k4**2
    return {
        "q": float(q), "qd": float(qd), "qdd": float(qdd), "load": float(load),
        "angles": {"g1": s_(w[0][0]), "cluster": s_(w[1][0]), "g4": s_(w[2][0])},
        "omegas": {"g1": s_(w[0][1]), "cluster": s_(w[1][1]), "g4": s_(w[2][1])},
        "I_star": s_(i_star),
        "driver": s_(x["T"]),
        "reactions": {
            "O1": [s_(x["R1x"]), s_(x["R1y"])],
            "O2": [s_(x["R2x"]), s_(x["R2y"])],
            "O4": [s_(x["R4x"]), s_(x["R4y"])],
            "m12": [s_(f12[0]), s_(f12[1])],
            "m34": [s_(f34[0]), s_(f34[1])],
        },
        "flanks": {"m12": fl["f12"], "m34": fl["f34"]},
    }


# ---------------------------------------------------------------------------------------
# Epicyclic: arm driven, ring fixed (the ground)


def epicyclic(q, qd, qdd, load, sun_driven=False):
    rs, rp, rr = 30 * MM, 30 * MM, 90 * MM
    o = (mpf(0), mpf(0))
    p0 = (60 * MM, mpf(0))
    ma, ia, ga0 = mpf("0.6"), mpf("4.0e-4"), (30 * MM, mpf(0))
    mp_, ip = mpf("0.3"), mpf("1.4e-4")
    ms, is_ = mpf("0.5"), mpf("2.3e-4")
    tan_a = mp.tan(20 * pi / 180)
    # Willis (carrier = arm): planet in the fixed ring, sun on the planet.
    kp = 1 - rr / rp
    ks = 1 + rr / rs
    if sun_driven:
        # The sun is the input: the arm turns q / ks.
        q, qd, qdd = q / ks, qd / ks, qdd / ks
    arm, planet, sun = (q, qd, qdd), (kp * q, kp * qd, kp * qdd), (ks * q, ks * qd, ks * qdd)
    p = rot(p0, q)
    a_p = add(mul(perp(p), qdd), mul(p, -(qd**2)))
    ga = rot(ga0, q)
    a_ga = add(mul(perp(ga), qdd), mul(ga, -(qd**2)))
    w = mul(p, 1 / norm(p))  # from O (sun, ring) to P (planet)
    # sun-planet (a = sun, b = planet), external: pitch point O + rs w, tangent perp(w),
    # the planet pushed along w. planet-ring (a = planet, b = ground ring), internal: pitch
    # point P + rp w, tangent perp(from P to O) = -perp(w), the ring pushed outward (+w).
    p_sp, t_sp, n_sp = add(o, mul(w, rs)), perp(w), w
    p_pr, t_pr, n_pr = add(p, mul(w, rp)), mul(perp(w), -1), w
    names = ["T", "ROx", "ROy", "RPx", "RPy", "RSx", "RSy", "fsp", "fpr"]
    ex, ey = (mpf(1), mpf(0)), (mpf(0), mpf(1))
    neg = lambda d: {k: mul(v, -1) for k, v in d.items()}  # noqa: E731

    def build(fl):
        s = System(names)
        fsp = tooth("fsp", t_sp, n_sp, tan_a, fl["fsp"])
        fpr = tooth("fpr", t_pr, n_pr, tan_a, fl["fpr"])
        arm_t, sun_t = ({}, {"T": 1}) if sun_driven else ({"T": 1}, {})
        arm_l, sun_l = (load, 0) if sun_driven else (0, load)
        s.body(ma, ia, ga, a_ga, arm[2],
               [(o, {"ROx": ex, "ROy": ey}), (p, {"RPx": mul(ex, -1), "RPy": mul(ey, -1)}),
                ("torque", arm_t)], [], arm_l)
        s.body(mp_, ip, p, a_p, planet[2],
               [(p, {"RPx": ex, "RPy": ey}), (p_sp, fsp), (p_pr, neg(fpr))], [], 0)
        s.body(ms, is_, o, (0, 0), sun[2],
               [(o, {"RSx": ex, "RSy": ey}), (p_sp, neg(fsp)), ("torque", sun_t)], [], sun_l)
        return s.solve()

    x, fl = solve_flanks(build, ["fsp", "fpr"])
    fsp = add(mul(t_sp, x["fsp"]), mul(n_sp, abs(x["fsp"]) * tan_a))
    fpr = add(mul(t_pr, x["fpr"]), mul(n_pr, abs(x["fpr"]) * tan_a))
    i_star = ia + ma * norm(ga0) ** 2 + (ip * kp**2 + mp_ * norm(p0) ** 2) + is_ * ks**2
    if sun_driven:
        i_star = i_star / ks**2
        q, qd, qdd = q * ks, qd * ks, qdd * ks
    return {
        "q": float(q), "qd": float(qd), "qdd": float(qdd), "load": float(load),
        "angles": {"arm": s_(arm[0]), "planet": s_(planet[0]), "sun": s_(sun[0])},
        "omegas": {"arm": s_(arm[1]), "planet": s_(planet[1]), "sun": s_(sun[1])},
        "I_star": s_(i_star),
        "driver": s_(x["T"]),
        "reactions": {
            "O": [s_(x["ROx"]), s_(x["ROy"])],
            "P": [s_(x["RPx"]), s_(x["RPy"])],
            "S": [s_(x["RSx"]), s_(x["RSy"])],
            "sp": [s_(fsp[0]), s_(fsp[1])],
            "pr": [s_(fpr[0]), s_(fpr[1])],
        },
        "flanks": {"sp": fl["fsp"], "pr": fl["fpr"]},
    }


# ---------------------------------------------------------------------------------------
# Energy method for the linkages


def energy_config(parts, q, qd, qdd, loads_power):
    """parts(q) -> list of (m, I, cg(q), angle(q)); loads_power(q) -> M* of the loads"""

    def inertia(t):
        tot = mpf(0)
        for k in range(len(parts(t))):
            gx = diff(lambda u: parts(u)[k][2][0], t)
            gy = diff(lambda u: parts(u)[k][2][1], t)
            w = diff(lambda u: parts(u)[k][3], t)
            m, i = parts(t)[k][0], parts(t)[k][1]
            tot += m * (gx**2 + gy**2) + i * w**2
        return tot

    def gravity(t):
        return sum(m * (G[0] * g[0] + G[1] * g[1]) for (m, _, g, _) in parts(t))

    q, qd, qdd = mpf(q), mpf(qd), mpf(qdd)
    i_star = inertia(q)
    di = diff(inertia, q)
    m_star = diff(gravity, q) + loads_power(q)
    return {
        "q": float(q), "qd": float(qd), "qdd": float(qdd),
        "I_star": s_(i_star), "dI_star_dq": s_(di), "M_star": s_(m_star),
        "driver": s_(i_star * qdd + di * qd**2 / 2 - m_star),
    }


def geared_slider_crank(q, qd, qdd, gas):
    r1, r2 = 25 * MM, 75 * MM
    o1, o2 = (mpf(0), mpf(0)), (100 * MM, mpf(0))
    a0, b0 = (140 * MM, mpf(0)), (300 * MM, 20 * MM)
    l = norm(sub(b0, a0))
    th3_0 = atan2(b0[1] - a0[1], b0[0] - a0[0])
    gc0, gr0 = (105 * MM, 5 * MM), (220 * MM, 12 * MM)

    def pose(t):
        phi2 = -(r1 / r2) * t
        a = add(o2, rot(sub(a0, o2), phi2))
        dy = b0[1] - a[1]
        bx = a[0] + sqrt(l**2 - dy**2)
        b = (bx, b0[1])
        th3 = atan2(b[1] - a[1], b[0] - a[0])
        return phi2, a, b, th3

    def parts(t):
        phi2, a, b, th3 = pose(t)
        return [
            (mpf("0.3"), mpf("1.0e-4"), o1, t),
            (mpf("1.5"), mpf("3.0e-3"), add(o2, rot(sub(gc0, o2), phi2)), phi2),
            (mpf("0.9"), mpf("2.5e-3"), add(a, rot(sub(gr0, a0), th3 - th3_0)), th3),
            (mpf("0.8"), mpf(0), b, mpf(0)),
        ]

    def loads_power(t):
        return gas * diff(lambda u: pose(u)[2][0], t)

    c = energy_config(parts, q, qd, qdd, loads_power)
    c["gas"] = float(gas)
    return c


def rack_steering(q, qd, qdd, align):
    r = 20 * MM
    k1o, k2o = (-300 * MM, -150 * MM), (300 * MM, -150 * MM)
    e10, e20 = (-150 * MM, -100 * MM), (150 * MM, -100 * MM)
    t10, t20 = (-280 * MM, -100 * MM), (280 * MM, -100 * MM)

    def rrr(a, la, c, lc, side):
        d = sub(c, a)
        dd = norm(d)
        x = (la**2 - lc**2 + dd**2) / (2 * dd)
        h = sqrt(la**2 - x**2)
        u = mul(d, 1 / dd)
        return add(add(a, mul(u, x)), mul(perp(u), side * h))

    def side0(a, c, b):
        return 1 if cross(sub(c, a), sub(b, a)) > 0 else -1

    l_tie1, l_k1 = norm(sub(t10, e10)), norm(sub(t10, k1o))
    l_tie2, l_k2 = norm(sub(t20, e20)), norm(sub(t20, k2o))
    s1, s2 = side0(e10, k1o, t10), side0(e20, k2o, t20)

    def pose(t):
        s = r * t  # the pinion turning CCW moves the rack (below it) to +x
        e1, e2 = add(e10, (s, 0)), add(e20, (s, 0))
        t1, t2 = rrr(e1, l_tie1, k1o, l_k1, s1), rrr(e2, l_tie2, k2o, l_k2, s2)
        return s, e1, e2, t1, t2

    def ang(a, b):
        return atan2(b[1] - a[1], b[0] - a[0])

    def parts(t):
        s, e1, e2, t1, t2 = pose(t)
        return [
            (mpf("0.2"), mpf("5.0e-5"), (mpf(0), mpf(0)), t),
            (mpf("1.2"), mpf(0), (s, -20 * MM), mpf(0)),
            (mpf("0.3"), mpf("4.0e-4"), mul(add(e1, t1), mpf("0.5")), ang(e1, t1)),
            (mpf("0.3"), mpf("4.0e-4"), mul(add(e2, t2), mpf("0.5")), ang(e2, t2)),
            (mpf("0.8"), mpf("2.0e-3"), mul(add(k1o, t1), mpf("0.5")), ang(k1o, t1)),
            (mpf("0.8"), mpf("2.0e-3"), mul(add(k2o, t2), mpf("0.5")), ang(k2o, t2)),
        ]

    def loads_power(t):
        return align * (
            diff(lambda u: ang(k1o, pose(u)[3]), t) + diff(lambda u: ang(k2o, pose(u)[4]), t)
        )

    c = energy_config(parts, q, qd, qdd, loads_power)
    c["align"] = float(align)
    c["rack_slide"] = s_(pose(mpf(q))[0])
    return c


def main():
    out = out_path()
    doc = {
        "about": "tools/gears_reference.py: mpmath 50 digits; trains by one Newton-Euler linear system, linkages by the energy method",
        "gear_train": [gear_train(mpf(q), mpf(qd), mpf(qdd), mpf(t)) for (q, qd, qdd, t) in [
            ("0.3", "2.0", "1.0", "1.0"), ("5.0", "-30.0", "200.0", "-4.0"),
            ("40.0", "150.0", "-900.0", "2.5"), ("-2.2", "0.0", "50.0", "0.0")]],
        "epicyclic": [epicyclic(mpf(q), mpf(qd), mpf(qdd), mpf(t)) for (q, qd, qdd, t) in [
            ("7.0", "2.0", "1.0", "1.0"), ("0.4", "-25.0", "300.0", "-2.0"),
            ("-13.0", "60.0", "-40.0", "0.5")]],
        "planetary": [epicyclic(mpf(q), mpf(qd), mpf(qdd), mpf(t), sun_driven=True) for (q, qd, qdd, t) in [
            ("7.0", "2.0", "1.0", "-1.0"), ("0.4", "-25.0", "300.0", "2.0"),
            ("-53.0", "160.0", "-40.0", "-0.5")]],
        "geared_slider_crank": [geared_slider_crank(mpf(q), mpf(qd), mpf(qdd), mpf(f)) for (q, qd, qdd, f) in [
            ("0.5", "30.0", "10.0", "-200.0"), ("4.0", "-60.0", "500.0", "150.0"),
            ("11.0", "90.0", "0.0", "-800.0")]],
        "rack_steering": [rack_steering(mpf(q), mpf(qd), mpf(qdd), mpf(t)) for (q, qd, qdd, t) in [
            ("0.0", "3.0", "5.0", "1.5"), ("1.2", "-2.0", "20.0", "-3.0"),
            ("-1.0", "4.0", "-10.0", "0.7")]],
    }
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)
    print("wrote", out)


if __name__ == "__main__":
    main()
