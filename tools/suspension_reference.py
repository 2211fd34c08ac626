#!/usr/bin/env python3
"""The double-wishbone suspension of issue 33 (spatial mechanisms): an independent 50-digit
reference (mpmath) of its kinematics and of every joint's reaction by Newton-Euler.

The mechanism (SI units; x forward, y outward, z up; the left front corner of a car):

- the lower arm turns about the chassis axis through its bushings LF, LR (a revolute joint
  at their midpoint Lo) and carries the ball joint Lb;
- the upper arm likewise about UF, UR (joint at Uo), ball joint Ub;
- the upright (knuckle, hub and wheel: one body) hangs on the two ball joints Lb, Ub and
  is steered by the tie rod, a binary link with a ball joint at each end (Ti on the
  chassis: the steering rack held still; Tb on the upright's steering arm). The wheel
  centre is W, the wheel's spin axis `axis` (unit), the tyre's contact point C (a point
  of the upright that the wheel load acts on).

Kutzbach: 5 bodies, 6 (5 - 1) = 24 equations; 2 revolute joints (5 each), 4 spherical
joints (3 each): 22; mobility 2 = the wheel travel (the input: the lower arm's rotation q
about its axis, from the drawing, right-handed about the unit axis (LF - LR)/|LF - LR|)
and the tie rod's idle spin about its own axis. The idle spin is fixed by the convention
that the tie rod's angular velocity is normal to its axis (ω = d × ḋ / |d|², d = Tb - Ti);
its inertia about its own axis is zero (a slender rod), so no equation depends on it.

Positions: the upper arm's rotation θ (about (UF - UR)/|UF - UR|, from the drawing) and
the point Tb solve |Ub - Lb| = l₁, |Tb - Ub| = l₂, |Tb - Lb| = l₃, |Tb - Ti| = l₄ (the
drawing's lengths), by mpmath's findroot continued from the drawing in steps of 0.01 rad
(the drawn assembly). The upright's rotation R is the frame of (Lb, Ub, Tb) now times its
transpose in the drawing. Rates: every position and rotation as a function of q,
differentiated by mpmath.diff at 60 digits (velocity = x'(q) q̇, acceleration = x''(q) q̇²
+ x'(q) q̈; ω from Ṙ Rᵀ).

Kinetostatics (d'Alembert, gravity and a wheel load F at C and a torque on the upright):
Newton-Euler of each moving body about its cg, Σ F = m a_G and Σ M_G = I α + ω × I ω with
I = R I₀ Rᵀ (I₀ the tensor about the cg in the drawing, [[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz],
[Ixz, Iyz, Izz]]). Unknowns (23): at each revolute joint a force (3) and a moment (the 2
components normal to its axis; at the input joint Lo also the driver torque about the
axis), at each spherical joint a force (3). The reaction at a joint is the force (and
moment, about the joint's point) by its first body on its second; the joints are
`Lo: revolute(ground, lower)`, `Uo: revolute(ground, upper)`, `Lb: spherical(lower,
upright)`, `Ub: spherical(upper, upright)`, `Ti: spherical(ground, tierod)`,
`Tb: spherical(tierod, upright)`. The tie rod's moment equation about its own axis is 0 = 0
and is left out (its two components normal to the axis are kept): 23 equations. The
driver torque is checked against virtual power (the power of the loads, gravity and the
inertia forces for a unit q̇), and every joint's reaction against the balance of the
ground (the sum of the reactions on the chassis equals minus the sum of the external
loads and inertia forces): both to 1e-40.

Output: tests/data/spatial/double_wishbone.truth.json: the drawing, the masses, the loads,
the mechanism's `space` declaration (SPEC section 3i), and for each case (q, q̇, q̈) the
points, camber and toe of the wheel, each body's rotation matrix, ω, α, cg motion, every
reaction and the driver torque, as decimal strings of 30 significant digits.

Run: python3 tools/suspension_reference.py [--out-root DIR]
"""

import argparse
import json
import os

import mpmath as mp

mp.mp.dps = 60

V = lambda *x: mp.matrix([mp.mpf(str(v)) for v in x])  # noqa: E731


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return mp.matrix([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def norm(a):
    return mp.sqrt(dot(a, a))


def unit(a):
    return a / norm(a)


def rodrigues(axis, angle):
    """Rotation matrix by `angle` about the unit vector `axis`."""
    k = axis
    K = mp.matrix([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return mp.eye(3) + mp.sin(angle) * K + (1 - mp.cos(angle)) * (K * K)


def frame(a, b, c):
    """An orthonormal frame (columns) of three points: e1 along b - a, e2 in the plane."""
    e1 = unit(b - a)
    w = c - a
    e2 = unit(w - dot(w, e1) * e1)
    e3 = cross(e1, e2)
    return mp.matrix([[e1[i], e2[i], e3[i]] for i in range(3)])


def vee(S):
    return mp.matrix([S[2, 1], S[0, 2], S[1, 0]])


# ---- the drawing -------------------------------------------------------------------------
P = {
    "LF": V(0.16, 0.26, 0.10), "LR": V(-0.14, 0.27, 0.115), "Lb": V(0.005, 0.715, 0.125),
    "UF": V(0.11, 0.41, 0.445), "UR": V(-0.13, 0.405, 0.47), "Ub": V(0.015, 0.665, 0.485),
    "Ti": V(-0.135, 0.31, 0.19), "Tb": V(-0.125, 0.695, 0.175),
    "W": V(0.0, 0.775, 0.29), "C": V(0.0, 0.79, -0.01),
}
P["Lo"] = (P["LF"] + P["LR"]) / 2
P["Uo"] = (P["UF"] + P["UR"]) / 2
AXIS_L = unit(P["LF"] - P["LR"])
AXIS_U = unit(P["UF"] - P["UR"])
WHEEL_AXIS = unit(V(0.004, 1.0, -0.02))
GRAVITY = V(0.0, 0.0, -9.81)

L1 = norm(P["Ub"] - P["Lb"])
L2 = norm(P["Tb"] - P["Ub"])
L3 = norm(P["Tb"] - P["Lb"])
L4 = norm(P["Tb"] - P["Ti"])


def tensor(ixx, iyy, izz, ixy, ixz, iyz):
    t = [mp.mpf(str(v)) for v in (ixx, iyy, izz, ixy, ixz, iyz)]
    return mp.matrix([[t[0], t[3], t[4]], [t[3], t[1], t[5]], [t[4], t[5], t[2]]])


TIE_MASS = mp.mpf("0.45")
_d0 = unit(P["Tb"] - P["Ti"])
_it = TIE_MASS * L4 ** 2 / 12
TIE_TENSOR = _it * (mp.eye(3) - _d0 * _d0.T)

BODIES = {
    # name: (mass kg, cg in the drawing m, inertia tensor about the cg in the drawing kg·m²)
    "lower": (mp.mpf("2.6"), V(0.0, 0.48, 0.115), tensor(0.045, 0.012, 0.054, 0.002, -0.0004, 0.0007)),
    "upper": (mp.mpf("1.3"), V(-0.005, 0.54, 0.465), tensor(0.012, 0.004, 0.015, 0.0006, 0.0001, -0.0003)),
    "upright": (mp.mpf("19.5"), V(0.0, 0.74, 0.29), tensor(0.55, 0.95, 0.56, 0.004, -0.002, 0.01)),
    "tierod": (TIE_MASS, (P["Ti"] + P["Tb"]) / 2, TIE_TENSOR),
}

# The wheel load at C (N) and a torque on the upright (N·m, a brake's reaction).
WHEEL_LOAD = V(-600.0, 900.0, 4200.0)
UPRIGHT_TORQUE = V(0.0, 150.0, 0.0)

CASES = [(-0.12, 0.0, 0.0), (-0.06, 1.5, -4.0), (0.0, 2.0, 3.0), (0.05, -2.5, 10.0), (0.1, 0.8, -1.0),
         (0.14, 3.0, 0.0)]


# ---- positions ---------------------------------------------------------------------------
def solve(q, guess):
    """(θ, Tb) at the lower arm's rotation q from the guess (θ, Tbx, Tby, Tbz)."""
    RL = rodrigues(AXIS_L, q)
    Lb = P["Lo"] + RL * (P["Lb"] - P["Lo"])

    def eqs(th, x, y, z):
        Ub = P["Uo"] + rodrigues(AXIS_U, th) * (P["Ub"] - P["Uo"])
        T = mp.matrix([x, y, z])
        return [dot(Ub - Lb, Ub - Lb) - L1 ** 2, dot(T - Ub, T - Ub) - L2 ** 2,
                dot(T - Lb, T - Lb) - L3 ** 2, dot(T - P["Ti"], T - P["Ti"]) - L4 ** 2]

    r = mp.findroot(eqs, guess, tol=mp.eps * 16, maxsteps=200)
    return [r[i] for i in range(4)]


_cache = {}
_solved = {}


def config(q):
    """Every body's rotation and position map at q, continued from the drawing."""
    q = mp.mpf(q)
    key = (q, mp.mp.prec)
    if key in _cache:
        return _cache[key]
    # continued from the drawing in steps of at most 0.01 rad (the drawn assembly), or from
    # a configuration already solved within 1e-3 rad (a derivative's neighbours)
    near = [k for k in _solved if abs(k - q) < mp.mpf("0.001")]
    if near:
        k = min(near, key=lambda k: abs(k - q))
        g = solve(q, _solved[k])
    else:
        n = max(1, int(mp.ceil(abs(q) / mp.mpf("0.01"))))
        g = [mp.mpf(0), P["Tb"][0], P["Tb"][1], P["Tb"][2]]
        for k in range(1, n + 1):
            g = solve(q * k / n, g)
    _solved[q] = g
    th, T = g[0], mp.matrix(g[1:])
    RL, RU = rodrigues(AXIS_L, q), rodrigues(AXIS_U, th)
    Lb = P["Lo"] + RL * (P["Lb"] - P["Lo"])
    Ub = P["Uo"] + RU * (P["Ub"] - P["Uo"])
    R = frame(Lb, Ub, T) * frame(P["Lb"], P["Ub"], P["Tb"]).T
    out = {"RL": RL, "RU": RU, "R": R, "Lb": Lb, "Ub": Ub, "Tb": T}
    _cache[key] = out
    return out


def points(q):
    c = config(q)
    R = c["R"]
    on_upright = lambda p: c["Lb"] + R * (p - P["Lb"])  # noqa: E731
    return {"Lb": c["Lb"], "Ub": c["Ub"], "Tb": c["Tb"], "W": on_upright(P["W"]), "C": on_upright(P["C"])}


def cg(q, body):
    c = config(q)
    g0 = BODIES[body][1]
    if body == "lower":
        return P["Lo"] + c["RL"] * (g0 - P["Lo"])
    if body == "upper":
        return P["Uo"] + c["RU"] * (g0 - P["Uo"])
    if body == "upright":
        return c["Lb"] + c["R"] * (g0 - P["Lb"])
    return (P["Ti"] + c["Tb"]) / 2


def rotation(q, body):
    """The body's rotation from the drawing (the tie rod: none, it is not needed)."""
    c = config(q)
    return {"lower": c["RL"], "upper": c["RU"], "upright": c["R"]}[body]


def d(f, q, n=1):
    """The n-th derivative of the vector or matrix function f at q."""
    v = f(q)
    if isinstance(v, mp.matrix):
        return mp.matrix([[mp.diff(lambda x, i=i, j=j: f(x)[i, j], q, n) for j in range(v.cols)]
                          for i in range(v.rows)])
    return mp.diff(f, q, n)


def omega_unit(q, body):
    """ω per unit q̇ (rad per rad): vee(R' Rᵀ); the tie rod's normal to its axis."""
    if body == "tierod":
        dd = lambda x: config(x)["Tb"] - P["Ti"]  # noqa: E731
        dv = dd(q)
        return cross(dv, d(dd, q)) / dot(dv, dv)
    R = rotation(q, body)
    return vee(d(lambda x: rotation(x, body), q) * R.T)


# ---- one case ----------------------------------------------------------------------------
def case(q, qd, qdd):
    q, qd, qdd = mp.mpf(str(q)), mp.mpf(str(qd)), mp.mpf(str(qdd))
    pts = points(q)
    motion = {}
    for name in pts:
        f = lambda x, n=name: points(x)[n]  # noqa: E731
        v1, v2 = d(f, q), d(f, q, 2)
        motion[name] = (pts[name], v1 * qd, v2 * qd ** 2 + v1 * qdd)
    bodies = {}
    for b in BODIES:
        f = lambda x, b=b: cg(x, b)  # noqa: E731
        g1, g2 = d(f, q), d(f, q, 2)
        w = omega_unit(q, b)
        w1 = d(lambda x, b=b: omega_unit(x, b), q)
        bodies[b] = {"cg": cg(q, b), "v": g1 * qd, "a": g2 * qd ** 2 + g1 * qdd,
                     "omega": w * qd, "alpha": w1 * qd ** 2 + w * qdd, "w_unit": w, "g_unit": g1}
        if b != "tierod":
            bodies[b]["R"] = rotation(q, b)
    # world inertia tensors: R I0 Rᵀ; the tie rod's from its current axis
    inertia = {}
    for b, (m, _, I0) in BODIES.items():
        if b == "tierod":
            dv = unit(pts["Tb"] - P["Ti"])
            inertia[b] = _it * (mp.eye(3) - dv * dv.T)
        else:
            R = bodies[b]["R"]
            inertia[b] = R * I0 * R.T
    # d'Alembert: the external and inertia wrench on each body about its cg
    ext = {}
    for b, (m, _, _) in BODIES.items():
        B = bodies[b]
        I = inertia[b]
        F = m * GRAVITY - m * B["a"]
        M = -(I * B["alpha"] + cross(B["omega"], I * B["omega"]))
        if b == "upright":
            F = F + WHEEL_LOAD
            M = M + cross(pts["C"] - B["cg"], WHEEL_LOAD) + UPRIGHT_TORQUE
        ext[b] = (F, M)
    # unknowns: Lo F(3) M⊥(2) τ(1); Uo F(3) M⊥(2); Lb, Ub, Ti, Tb F(3) each: 23
    def perp(axis):
        a = unit(cross(axis, V(0.0, 0.0, 1.0)))
        return a, cross(axis, a)
    nL, nU = perp(AXIS_L), perp(AXIS_U)
    Lo, Uo = P["Lo"], P["Uo"]

    # each unknown: a list of (body, force vector, moment vector about the body's cg) per unit
    def unknown_force(j, e, first, second, at):
        terms = []
        for body, s in ((second, 1), (first, -1)):
            if body != "ground":
                terms.append((body, s * e, s * cross(at - bodies[body]["cg"], e)))
        return terms

    def unknown_moment(e, first, second):
        return [(body, mp.matrix(3, 1), s * e) for body, s in ((second, 1), (first, -1)) if body != "ground"]

    E = [V(1, 0, 0), V(0, 1, 0), V(0, 0, 1)]
    joints = [("Lo", "ground", "lower", Lo, nL, AXIS_L), ("Uo", "ground", "upper", Uo, nU, None),
              ("Lb", "lower", "upright", pts["Lb"], None, None), ("Ub", "upper", "upright", pts["Ub"], None, None),
              ("Ti", "ground", "tierod", P["Ti"], None, None), ("Tb", "tierod", "upright", pts["Tb"], None, None)]
    unknowns = []
    for name, a, b, at, normals, drive in joints:
        for k in range(3):
            unknowns.append(((name, "f", k), unknown_force(name, E[k], a, b, at)))
        if normals is not None:
            for k, e in enumerate(normals):
                unknowns.append(((name, "m", k), unknown_moment(e, a, b)))
        if drive is not None:
            unknowns.append(((name, "driver", 0), unknown_moment(drive, a, b)))
    # equations: each body's force (3) and moment (3); the tie rod's moment along its axis left out
    order = ["lower", "upper", "upright", "tierod"]
    dtie = unit(pts["Tb"] - P["Ti"])
    tie_dirs = perp(dtie)
    rows = []
    rhs = []
    for b in order:
        for k in range(3):
            rows.append((b, "f", E[k]))
        dirs = tie_dirs if b == "tierod" else E
        for e in dirs:
            rows.append((b, "m", e))
    A = mp.matrix(len(rows), len(unknowns))
    for i, (b, kind, e) in enumerate(rows):
        F, M = ext[b]
        rhs.append(-dot(e, F if kind == "f" else M))
        for j, (_, terms) in enumerate(unknowns):
            for body, f, m in terms:
                if body == b:
                    A[i, j] += dot(e, f if kind == "f" else m)
    x = mp.lu_solve(A, mp.matrix(rhs))
    # the tie rod's axial moment equation, left out, holds
    Ft, Mt = ext["tierod"]
    axial = dot(dtie, Mt)
    for j, (_, terms) in enumerate(unknowns):
        for body, f, m in terms:
            if body == "tierod":
                axial += dot(dtie, m) * x[j]
    assert abs(axial) < mp.mpf(10) ** -40, axial
    sol = {u[0]: x[j] for j, u in enumerate(unknowns)}
    reactions = {}
    for name, a, b, at, normals, drive in joints:
        f = mp.matrix([sol[(name, "f", k)] for k in range(3)])
        m = mp.matrix(3, 1)
        if normals is not None:
            for k, e in enumerate(normals):
                m += sol[(name, "m", k)] * e
        reactions[name] = (f, m)
    driver = sol[("Lo", "driver", 0)]
    # virtual power: the driver's power equals minus the power of the loads, gravity and inertia
    power = mp.mpf(0)
    for b in order:
        F, M = ext[b]
        B = bodies[b]
        power += dot(F, B["g_unit"]) + dot(M, B["w_unit"])
    assert abs(driver + power) < mp.mpf(10) ** -40 * (1 + abs(driver)), (driver, power)
    # the ground's balance: Σ reactions on the moving bodies from the ground + Σ external = 0
    total = mp.matrix(3, 1)
    for b in order:
        total += ext[b][0]
    for name, a, b, at, normals, drive in joints:
        if a == "ground":
            total += reactions[name][0]
    assert norm(total) < mp.mpf(10) ** -40, total
    # camber and toe of the wheel's spin axis
    ax = bodies["upright"]["R"] * WHEEL_AXIS
    camber = mp.asin(ax[2])           # rad, the axis's rise (the wheel's top leaning in: negative)
    toe = mp.atan2(-ax[0], ax[1])     # rad, the axis turned about z (toe-in of a left wheel: positive)
    return {"motion": motion, "bodies": bodies, "reactions": reactions, "driver": driver,
            "camber": camber, "toe": toe, "axis": ax}


def s(x):
    return mp.nstr(x, 30, min_fixed=-1, max_fixed=-1) if abs(x) > mp.mpf(10) ** -45 else "0"


def vec(v):
    return [s(v[i]) for i in range(3)]


def mat(m):
    return [[s(m[i, j]) for j in range(3)] for i in range(3)]


def source():
    """The mechanism in the `space` DSL (SPEC section 3i)."""
    f = lambda v: "(" + ", ".join(mp.nstr(v[i], 17) for i in range(3)) + ")"  # noqa: E731

    def inertia(b):
        # (Ixx, Iyy, Izz, Ixy, Ixz, Iyz), the products Ixy = Σ m x y: the tensor's
        # off-diagonal entries negated (docs/spatial.md)
        t = BODIES[b][2]
        return "(" + ", ".join(mp.nstr(x, 17) for x in (t[0, 0], t[1, 1], t[2, 2], -t[0, 1], -t[0, 2], -t[1, 2])) + ")"

    m = lambda b: mp.nstr(BODIES[b][0], 17)  # noqa: E731
    return f"""pub struct DoubleWishbone {{
    space,
    gravity: {f(GRAVITY)},
    ground {{ Lo: {f(P['Lo'])}, Uo: {f(P['Uo'])}, Ti: {f(P['Ti'])} }},
    link lower {{ points {{ Lo, Lb: {f(P['Lb'])} }}, mass: {m('lower')}, cg: {f(BODIES['lower'][1])}, inertia: {inertia('lower')} }},
    link upper {{ points {{ Uo, Ub: {f(P['Ub'])} }}, mass: {m('upper')}, cg: {f(BODIES['upper'][1])}, inertia: {inertia('upper')} }},
    link upright {{ points {{ Lb, Ub, Tb: {f(P['Tb'])}, W: {f(P['W'])}, C: {f(P['C'])} }}, mass: {m('upright')}, cg: {f(BODIES['upright'][1])}, inertia: {inertia('upright')} }},
    link tierod {{ points {{ Ti, Tb }}, mass: {m('tierod')}, cg: {f(BODIES['tierod'][1])}, inertia: {inertia('tierod')} }},
    joints {{
        Lo: revolute(ground, lower) axis {f(AXIS_L)},
        Uo: revolute(ground, upper) axis {f(AXIS_U)},
        Lb: spherical(lower, upright),
        Ub: spherical(upper, upright),
        Ti: spherical(ground, tierod),
        Tb: spherical(tierod, upright),
    }},
    input: Lo,
    loads {{ wheel: force on upright at C, brake: torque on upright }},
}}
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out-root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    args = ap.parse_args()
    cases = []
    for q, qd, qdd in CASES:
        r = case(q, qd, qdd)
        cases.append({
            "q": str(q), "qd": str(qd), "qdd": str(qdd),
            "points": {n: {"pos": vec(p), "vel": vec(v), "acc": vec(a)} for n, (p, v, a) in r["motion"].items()},
            "links": {b: {k: (mat(v) if k == "R" else vec(v)) for k, v in B.items() if k in
                          ("cg", "v", "a", "omega", "alpha", "R")} for b, B in r["bodies"].items()},
            "reactions": {n: {"force": vec(f), "moment": vec(m)} for n, (f, m) in r["reactions"].items()},
            "driver": s(r["driver"]), "camber": s(r["camber"]), "toe": s(r["toe"]),
            "wheel_axis": vec(r["axis"]),
        })
    out = {
        "what": "double-wishbone suspension: kinematics and Newton-Euler reactions, 50-digit mpmath "
                "(tools/suspension_reference.py; conventions in its docstring)",
        "source": source(),
        "input": {"joint": "Lo", "axis": vec(AXIS_L), "q": "rotation of the lower arm from the drawing (rad)"},
        "loads": {"wheel": vec(WHEEL_LOAD), "brake": vec(UPRIGHT_TORQUE)},
        "inertia_convention": "the tensors of the script about the cg in the drawing; the source's tuples "
                              "(Ixx, Iyy, Izz, Ixy, Ixz, Iyz) are products Ixy = Σ m x y, the tensor's "
                              "off-diagonal entries negated (docs/spatial.md)",
        "idle_spin": "the tie rod's angular velocity is normal to its axis; its inertia about its axis is zero, "
                     "so only the tie rod's omega and alpha along its axis depend on the convention",
        "reaction_convention": "force and moment (about the joint's point) by the joint's first body on its "
                               "second; revolute joints: the moment's two components normal to the axis; "
                               "the driver torque (about Lo's axis, by the ground on the lower arm) apart",
        "camber_toe": "camber = asin(axis_z), toe = atan2(-axis_x, axis_y) of the wheel's spin axis (rad)",
        "cases": cases,
    }
    path = os.path.join(args.out_root, "tests", "data", "spatial", "double_wishbone.truth.json")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as fh:
        json.dump(out, fh, indent=1)
        fh.write("\n")
    print(f"wrote {path}: {len(cases)} cases")


if __name__ == "__main__":
    main()
