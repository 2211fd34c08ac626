#!/usr/bin/env python3
"""The engine of the flywheel example and its high-precision flywheel reference.

One source of numbers: the design numbers below (DESIGN, GAS, OPERATING) define

    tests/data/engine.drawing.json   the drawing, schema planar-mechanism/1 (like
                                     tests/data/*.mechanism.json; named .drawing so that
                                     tools/to_dsl.py does not also put it in mechanisms.rs)
    tests/common/engine.rs           the part between the GENERATED markers: the
                                     `mechanism!` of the drawing (tools/to_dsl.py) and the
                                     gas-model / operating-point constants as f64 literals
    tests/data/engine.flywheel.json  the reference answers (this file's solver)

The flywheel reference is independent of mech: I*, dI*/dq and M* come from
tools/reference.py's absolute-coordinate solver (mpmath, here at 30 digits) and
the gas force from the same explicit pressure model as tests/common/engine.rs
(written again here, in mpmath):

  cycle angle  phi = q - q_TDC in [0, 4 pi)  (q_TDC: crank angle of the top dead
               centre that opens the intake stroke; q_BDC the next bottom dead centre,
               phi_B = q_BDC - q_TDC, slightly more than pi with the offset)
  volume       V = V_c + A (x_TDC - x_B(q)),  A = pi D^2 / 4,  V_c = A s / (r_c - 1)
  intake       phi in [0, phi_B):               p = p_in
  closed       phi in [phi_B, phi_B + 2 pi):    p = (1 - x_b) p_c(V) + x_b p_f(V)
               p_c = p_in (V_max / V)^n_c                 (compression polytrope)
               p_f = k p_in (V_max / V_c)^n_c (V_c / V)^n_e (expansion polytrope)
               x_b = 1 - exp(-a ((phi - phi_s) / dphi)^(m + 1)) for phi > phi_s, else 0
               (Wiebe burned fraction; phi_s = 2 pi - spark advance)
  exhaust      phi in [phi_B + 2 pi, 4 pi):     p = p_exh
  force        on the piston at B: (-(p - p_0) A, 0) (the head is on the +x side)

The cycle: q in [q_TDC, q_TDC + 4 pi], breakpoints at phi_B, phi_s, phi_B + 2 pi.
M*(q) = M*_gas(q) + T with the constant resisting torque T = -W_gas / (4 pi) on the
crank (the driver), W_gas = integral of M*_gas over the cycle.  S(q) = integral of
M* from q_TDC, F = 2 S / omega_a^2.  Wittenbauer, with a = (1 + eps/2)^2,
b = (1 - eps/2)^2:  I = (max(F - a I*) - min(F - b I*)) / (a - b); the tangent
points are the roots of F' - c dI*/dq = 2 M*/omega_a^2 - c dI*/dq (c = a, b) found
by a bracketed secant at 30 digits.  Approximate: I = (S_max - S_min) / (eps omega_a^2).
Integrals: Gauss-Legendre, 20 nodes per panel, panels of at most 2.5 deg aligned with
the breakpoints; the same integral with 5 deg panels is reported as the quadrature check.

Usage: python3 tools/flywheel_reference.py [--drawing-only] [--out-root DIR]
  --drawing-only   write the drawing JSON and tests/common/engine.rs only (seconds)
  --out-root DIR   write the three files under DIR (same relative paths) instead of the
                   repository; the generated block replaces the one of DIR/tests/common/engine.rs,
                   which must exist (tools/outroot.py)
Takes about a minute of CPU otherwise.  Needs mpmath.
"""

import math
import os
import sys
from collections import OrderedDict

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

import mpmath  # noqa: E402
from mpmath import mp, mpf  # noqa: E402

import drawings as D  # noqa: E402
import reference as R  # noqa: E402
import to_dsl  # noqa: E402

DATA = os.path.join(ROOT, "tests", "data")
DRAWING = os.path.join(DATA, "engine.drawing.json")
RUST = os.path.join(ROOT, "tests", "common", "engine.rs")
OUT = os.path.join(DATA, "engine.flywheel.json")

# ---------------------------------------------------------------------------
# the single source of numbers (SI units)

DESIGN = OrderedDict([
    ("bore", "0.086"),            # m
    ("crank", "0.043"),           # m, crank radius (stroke 86 mm)
    ("rod", "0.143"),             # m, centre to centre
    ("offset", "0.006"),          # m, the piston guide line is 6 mm above the crank centre
    ("reference_crank_angle_deg", "30"),
    ("crank_mass", "3.6"), ("crank_inertia", "0.0068"),   # crankshaft with counterweights
    ("crank_cg_along", "-0.005"),                          # m along O2->A (overbalanced)
    ("rod_mass", "0.58"), ("rod_inertia", "0.0021"),
    ("rod_cg_along", "0.038"),                             # m from the crank pin along A->B
    ("piston_mass", "0.52"),                               # piston, rings and gudgeon pin
])

GAS = OrderedDict([
    ("compression_ratio", "10.5"),
    ("p_crankcase", "101300"),    # Pa, acts on the underside of the piston
    ("p_intake", "95000"),        # Pa
    ("p_exhaust", "108000"),      # Pa
    ("n_compression", "1.32"),
    ("n_expansion", "1.27"),
    ("pressure_rise", "3.2"),     # fired / motored pressure ratio at equal volume
    ("spark_advance_deg", "15"),
    ("burn_duration_deg", "60"),
    ("wiebe_a", "5"),
    ("wiebe_m", "2"),
])

OPERATING = OrderedDict([
    ("omega_mean", "100*pi"),     # rad/s (3000 rpm)
    ("irregularity", "0.02"),
])

FAMILY = ["0.2", "0.1", "0.05", "0.02", "0.01", "0.005", "0.002", "0.001"]

PANEL_DEG = 2.5
NODES = 20


# ---------------------------------------------------------------------------
# the drawing

def build_drawing():
    M = D.M
    d = D.Drawing("engine", "Single-cylinder four-stroke engine: offset slider-crank, "
                            "86 mm bore x 86 mm stroke, 143 mm rod, guide 6 mm above the crank centre")
    r, l, e = M(DESIGN["crank"]), M(DESIGN["rod"]), M(DESIGN["offset"])
    th = D.deg(DESIGN["reference_crank_angle_deg"])
    O2 = d.point("O2", D.P(0, 0), ground=True)
    A = d.point("A", D.polar(O2, r, th))
    B = d.point("B", (A[0] + mpmath.sqrt(l ** 2 - (e - A[1]) ** 2), e))
    d.link("crank", ["O2", "A"], DESIGN["crank_mass"], DESIGN["crank_inertia"],
           D.local(O2, A, DESIGN["crank_cg_along"], "0"))
    d.link("rod", ["A", "B"], DESIGN["rod_mass"], DESIGN["rod_inertia"],
           D.local(A, B, DESIGN["rod_cg_along"], "0"))
    d.link("piston", ["B"], DESIGN["piston_mass"], "0", B)
    d.rev("O2", "ground", "crank")
    d.rev("A", "crank", "rod")
    d.rev("B", "rod", "piston")
    d.slide("prismatic", "guide", "ground", "piston", "B", D.P("1.0", "0"))
    d.inputs = ["O2"]
    d.force("gas", "piston", "B")
    d.design.update(DESIGN)
    spec = d.to_json()
    # the piston has no rotational inertia: declare none (the DSL default 0)
    for link in spec["links"]:
        if link["name"] == "piston":
            del link["inertia"]
    return spec


def geometry():
    """dead centres and volumes from the design numbers, at mp precision"""
    r, l, e = mpf(DESIGN["crank"]), mpf(DESIGN["rod"]), mpf(DESIGN["offset"])
    bore = mpf(DESIGN["bore"])
    g = OrderedDict()
    g["x_tdc"] = mpmath.sqrt((l + r) ** 2 - e ** 2)
    g["x_bdc"] = mpmath.sqrt((l - r) ** 2 - e ** 2)
    g["q_tdc"] = mpmath.atan2(e, g["x_tdc"])
    g["q_bdc"] = mp.pi + mpmath.atan2(e, g["x_bdc"])
    g["piston_area"] = mp.pi * bore ** 2 / 4
    g["stroke"] = g["x_tdc"] - g["x_bdc"]
    g["clearance_volume"] = g["piston_area"] * g["stroke"] / (mpf(GAS["compression_ratio"]) - 1)
    return g


def operating():
    return mpmath.mpmathify(eval(OPERATING["omega_mean"], {"pi": mp.pi})), mpf(OPERATING["irregularity"])


# ---------------------------------------------------------------------------
# tests/common/engine.rs: the generated block

BEGIN = "// BEGIN GENERATED by tools/flywheel_reference.py"
END = "// END GENERATED"


# std::f64::consts that clippy's approx_constant lint looks for in a literal
STD_CONSTS = [math.pi, 2 * math.pi, math.pi / 2, math.pi / 3, math.pi / 4, math.pi / 6, math.pi / 8,
              1 / math.pi, 2 / math.pi, 2 / math.sqrt(math.pi), math.e, math.sqrt(2), 1 / math.sqrt(2),
              math.log(2), math.log(10), math.log2(math.e), math.log10(math.e), math.log2(10), math.log10(2)]


def near_std_constant(x):
    return x != 0 and any(abs(x - c) <= 4 * math.ulp(c) for c in STD_CONSTS)


def rust_block(spec, geo):
    lit = to_dsl.lit
    g = {k: mpf(v) for k, v in GAS.items()}
    deg = mp.pi / 180
    w, eps = operating()
    consts = [
        ("BORE", mpf(DESIGN["bore"]), "Cylinder bore D, m."),
        ("PISTON_AREA", geo["piston_area"], "Piston area A = pi D^2 / 4, m^2."),
        ("X_TDC", geo["x_tdc"], "Piston pin x at the top dead centre, sqrt((l + r)^2 - e^2), m."),
        ("X_BDC", geo["x_bdc"], "Piston pin x at the bottom dead centre, sqrt((l - r)^2 - e^2), m."),
        ("Q_TDC", geo["q_tdc"], "Crank angle of the top dead centre, atan2(e, X_TDC), rad: the cycle starts here (intake)."),
        ("Q_BDC", geo["q_bdc"], "Crank angle of the bottom dead centre, pi + atan2(e, X_BDC), rad."),
        ("CLEARANCE_VOLUME", geo["clearance_volume"], "V_c = A s / (r_c - 1), m^3 (s = X_TDC - X_BDC)."),
        ("COMPRESSION_RATIO", g["compression_ratio"], "r_c = V_max / V_c."),
        ("P_CRANKCASE", g["p_crankcase"], "Pressure under the piston, Pa."),
        ("P_INTAKE", g["p_intake"], "Pressure during intake and at the start of compression, Pa."),
        ("P_EXHAUST", g["p_exhaust"], "Pressure during the exhaust stroke, Pa."),
        ("N_COMPRESSION", g["n_compression"], "Polytropic exponent of compression."),
        ("N_EXPANSION", g["n_expansion"], "Polytropic exponent of expansion."),
        ("PRESSURE_RISE", g["pressure_rise"], "Fired / motored pressure ratio at equal volume (combustion)."),
        ("SPARK", 2 * mp.pi - g["spark_advance_deg"] * deg, "Cycle angle of the start of combustion, 2 pi - advance, rad."),
        ("BURN_DURATION", g["burn_duration_deg"] * deg,
         "Wiebe burn duration, rad: 60\u00b0 as the reference tables wrote it (1 ulp above \u03c0/3)."),
        ("WIEBE_A", g["wiebe_a"], "Wiebe efficiency parameter a."),
        ("WIEBE_M", g["wiebe_m"], "Wiebe form factor m."),
        ("OMEGA_MEAN", w, "Mean crank speed omega_a, rad/s (3000 rpm)."),
        ("IRREGULARITY", eps, "Requested irregularity eps = (omega_max - omega_min) / omega_a."),
    ]
    out = [BEGIN + " from its design numbers -- do not edit by hand;",
           "// regenerate with `python3 tools/flywheel_reference.py --drawing-only` (tests/data/engine.drawing.json).",
           "", to_dsl.to_dsl(spec), ""]
    for name, v, doc in consts:
        out.append("/// %s" % doc)
        if near_std_constant(float(v)):
            # clippy's approx_constant (deny by default) takes it for the std constant
            out.append("#[allow(clippy::approx_constant)]")
        out.append("pub const %s: f64 = %s;" % (name, lit(float(v))))
    out.append(END)
    return "\n".join(out)


def write_rust(spec, geo, rust=RUST):
    block = rust_block(spec, geo)
    with open(rust, encoding="utf-8") as f:
        text = f.read()
    i, j = text.find(BEGIN), text.find(END)
    if i < 0 or j < 0:
        raise RuntimeError("%s has no GENERATED markers" % rust)
    j = j + len(END)
    with open(rust, "w", encoding="utf-8") as f:
        f.write(text[:i] + block + text[j:])


# ---------------------------------------------------------------------------
# the gas model (mpmath; the same formulas as tests/common/engine.rs)

class Gas:
    def __init__(self, geo):
        self.geo = geo
        g = {k: mpf(v) for k, v in GAS.items()}
        self.g = g
        deg = mp.pi / 180
        self.phi_b = geo["q_bdc"] - geo["q_tdc"]
        self.spark = 2 * mp.pi - g["spark_advance_deg"] * deg
        self.burn = g["burn_duration_deg"] * deg
        A, Vc = geo["piston_area"], geo["clearance_volume"]
        self.v_max = Vc + A * geo["stroke"]

    def breakpoints(self):
        q0 = self.geo["q_tdc"]
        return [q0 + self.phi_b, q0 + self.spark, q0 + self.phi_b + 2 * mp.pi]

    def pressure(self, q, x_b):
        g, geo = self.g, self.geo
        phi = q - geo["q_tdc"]
        phi = phi - 4 * mp.pi * mpmath.floor(phi / (4 * mp.pi))
        if phi < self.phi_b:
            return g["p_intake"]
        if phi >= self.phi_b + 2 * mp.pi:
            return g["p_exhaust"]
        V = geo["clearance_volume"] + geo["piston_area"] * (geo["x_tdc"] - x_b)
        pc = g["p_intake"] * (self.v_max / V) ** g["n_compression"]
        if phi <= self.spark:
            return pc
        pf = (g["pressure_rise"] * g["p_intake"] * (self.v_max / geo["clearance_volume"]) ** g["n_compression"]
              * (geo["clearance_volume"] / V) ** g["n_expansion"])
        xb = 1 - mpmath.exp(-g["wiebe_a"] * ((phi - self.spark) / self.burn) ** (g["wiebe_m"] + 1))
        return (1 - xb) * pc + xb * pf

    def force(self, q, x_b):
        return -(self.pressure(q, x_b) - self.g["p_crankcase"]) * self.geo["piston_area"]


# ---------------------------------------------------------------------------
# I*, dI*/dq, M*_gas at 30 digits with tools/reference.py's machinery

class Engine:
    def __init__(self, spec, gas):
        self.mech = R.Mechanism(spec)
        self.gas = gas
        self.M = self.mech.mass_diag()
        self.x, self.q = list(self.mech.x_ref), list(self.mech.q_ref)
        self.evals = 0

    def at(self, q):
        """(I*, dI*/dq, M*_gas, p) at crank angle q (continuing from the last solved q)"""
        mech = self.mech
        qq = [mpf(q)]
        x, _ = mech.continue_to(qq, self.x, self.q)
        self.x, self.q = x, qq
        _, Jac = mech.phi_and_jac(x, qq)
        g = R.solve(Jac, mech.rhs_vel([mpf(1)]))
        a10 = R.solve(Jac, mech.rhs_acc(x, g, [mpf(0)]))
        x_b = mech.point(x, "piston", "B")[0]
        p = self.gas.pressure(qq[0], x_b)
        loads = OrderedDict(gas=(self.gas.force(qq[0], x_b), mpf(0)))
        Q = mech.applied(x, loads)
        n = mech.n
        I = sum(self.M[i] * g[i] ** 2 for i in range(n))
        dI = 2 * sum(self.M[i] * g[i] * a10[i] for i in range(n))
        Ms = sum(Q[i] * g[i] for i in range(n))
        self.evals += 1
        return I, dI, Ms, p


def gauss_legendre(n):
    """nodes and weights on [-1, 1] at mp precision (Newton on P_n)"""
    xs, ws = [], []
    for i in range(1, n + 1):
        x = mpmath.cos(mp.pi * (i - mpf("0.25")) / (n + mpf("0.5")))
        for _ in range(100):
            p0, p1 = mpf(1), x
            for k in range(2, n + 1):
                p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
            dp = n * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < mpf(10) ** (-mp.dps + 3):
                break
        p0, p1 = mpf(1), x
        for k in range(2, n + 1):
            p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
        dp = n * (x * p1 - p0) / (x * x - 1)
        xs.append(x)
        ws.append(2 / ((1 - x * x) * dp * dp))
    order = sorted(range(n), key=lambda k: xs[k])
    return [xs[k] for k in order], [ws[k] for k in order]


class Cycle:
    """S_gas at the panel ends of the cycle [q0, q0 + 4 pi]"""

    def __init__(self, engine, q0, period, breakpoints, panel, nodes=NODES):
        self.engine = engine
        self.q0, self.period = q0, period
        self.gl = gauss_legendre(nodes)
        cuts = [q0] + sorted(breakpoints) + [q0 + period]
        self.edges = []
        for a, b in zip(cuts, cuts[1:]):
            k = int(mpmath.ceil((b - a) / panel))
            self.edges += [a + (b - a) * i / k for i in range(k)]
        self.edges.append(q0 + period)
        self.s_edges = [mpf(0)]
        for a, b in zip(self.edges, self.edges[1:]):
            self.s_edges.append(self.s_edges[-1] + self.integral(a, b))
        self.w_gas = self.s_edges[-1]

    def integral(self, a, b):
        xs, ws = self.gl
        h = (b - a) / 2
        c = (a + b) / 2
        return h * sum(w * self.engine.at(c + h * x)[2] for x, w in zip(xs, ws))

    def s_gas(self, q):
        k = max(i for i, e in enumerate(self.edges[:-1]) if e <= q)
        return self.s_edges[k] + (self.integral(self.edges[k], q) if q > self.edges[k] else 0)


class Flywheel:
    """Wittenbauer and the approximate method on one cycle, with T balancing it"""

    def __init__(self, cycle, omega):
        self.c = cycle
        self.omega = omega
        self.T = -cycle.w_gas / cycle.period
        self.grid = []
        for q, s in zip(cycle.edges, cycle.s_edges):
            I, dI, Ms, _ = cycle.engine.at(q)
            self.grid.append((q, s + self.T * (q - cycle.q0), I))

    def S(self, q):
        return self.c.s_gas(q) + self.T * (q - self.c.q0)

    def extremum(self, coef, sign):
        """max (sign=+1) or min (sign=-1) over the cycle of F - coef I*: (q, value)"""
        w2 = self.omega ** 2
        vals = [sign * (2 * s / w2 - coef * I) for _, s, I in self.grid]
        k = max(range(len(vals)), key=lambda i: vals[i])
        n = len(vals)

        def dg(q):
            I, dI, Ms, _ = self.c.engine.at(q)
            return sign * (2 * (Ms + self.T) / w2 - coef * dI)

        m = n - 1  # grid[0] and grid[m] are the same point of the periodic cycle
        k %= m
        qk = self.grid[k][0]
        lo = self.grid[k - 1][0] if k > 0 else self.grid[m - 1][0] - self.c.period
        hi = self.grid[k + 1][0]
        dk = dg(qk)
        bracket = (qk, hi) if dk > 0 else (lo, qk)
        if dk == 0:
            root = qk
        else:
            if dg(bracket[0]) * dg(bracket[1]) > 0:
                raise RuntimeError("extremum of F - %s I* is not smooth near q = %s" % (coef, qk))
            root = mpmath.findroot(dg, bracket, solver="anderson")
        if root < self.c.q0:
            root += self.c.period
        if root > self.c.q0 + self.c.period:
            root -= self.c.period
        I = self.c.engine.at(root)[0]
        s = self.S(root)
        return root, 2 * s / w2 - coef * I, s, I

    def solve(self, eps):
        a, b = (1 + eps / 2) ** 2, (1 - eps / 2) ** 2
        qa, ga, sa, Ia = self.extremum(a, +1)
        qb, gb, sb, Ib = self.extremum(b, -1)
        I = (ga - gb) / (a - b)
        C = a * I - ga
        return OrderedDict([
            ("irregularity", eps), ("exact_inertia", I),
            ("tangent_max", OrderedDict([("q", qa), ("I_star", Ia), ("F", 2 * sa / self.omega ** 2), ("slope", a)])),
            ("tangent_min", OrderedDict([("q", qb), ("I_star", Ib), ("F", 2 * sb / self.omega ** 2), ("slope", b)])),
            ("energy_constant_C", C),
        ])

    def approximate(self, eps):
        qM, _, sM, _ = self.extremum(0, +1)
        qm, _, sm, _ = self.extremum(0, -1)
        return OrderedDict([("q_s_max", qM), ("s_max", sM), ("q_s_min", qm), ("s_min", sm),
                            ("approximate_inertia", (sM - sm) / (eps * self.omega ** 2))])


def main(argv):
    import outroot
    root, argv = outroot.split(argv)
    drawing = outroot.path(root, "tests", "data", "engine.drawing.json")
    rust = os.path.join(root, "tests", "common", "engine.rs")
    out_path = outroot.path(root, "tests", "data", "engine.flywheel.json")
    mp.dps = 50
    spec = build_drawing()
    geo = geometry()
    with open(drawing, "w") as f:
        f.write(D.dumps(spec) + "\n")
    write_rust(spec, geo, rust)
    print("wrote", drawing, "and the generated block of", rust)
    if "--drawing-only" in argv:
        return 0

    mp.dps = 30
    spec = R.load_json(drawing)
    geo = geometry()
    gas = Gas(geo)
    eng = Engine(spec, gas)
    omega, eps = operating()
    q0, period = geo["q_tdc"], 4 * mp.pi
    deg = mp.pi / 180
    cyc = Cycle(eng, q0, period, gas.breakpoints(), PANEL_DEG * deg)
    coarse = Cycle(Engine(spec, gas), q0, period, gas.breakpoints(), 2 * PANEL_DEG * deg, nodes=12)
    fw = Flywheel(cyc, omega)
    main_result = fw.solve(eps)
    approx = fw.approximate(eps)
    family = []
    for e in FAMILY:
        e = mpf(e)
        r = fw.solve(e)
        family.append(OrderedDict([("irregularity", e), ("exact_inertia", r["exact_inertia"]),
                                   ("approximate_inertia", (approx["s_max"] - approx["s_min"]) / (e * omega ** 2))]))
    samples = []
    for k in range(0, 721, 30):
        q = q0 + k * deg
        I, dI, Ms, p = eng.at(q)
        samples.append(OrderedDict([("crank_angle_deg", k), ("q", q), ("pressure", p), ("I_star", I),
                                    ("dI_star_dq", dI), ("M_star", Ms + fw.T), ("S", fw.S(q))]))

    out = OrderedDict()
    out["schema"] = "mech-flywheel-reference/1"
    out["mechanism_file"] = "engine.drawing.json"
    out["digits"] = "25 significant digits, computed with mpmath at 30 digits"
    out["model"] = OrderedDict([
        ("gas", GAS), ("geometry", geo), ("cycle_start", q0), ("period", period),
        ("breakpoints", gas.breakpoints()), ("omega_mean", omega), ("irregularity", eps),
        ("driver", "constant torque T on the crank (the input), T = -W_gas / period"),
    ])
    res = OrderedDict()
    res["net_work_gas"] = cyc.w_gas
    res["balancing_torque"] = fw.T
    res.update(approx)
    res.update(main_result)
    out["results"] = res
    out["family"] = family
    out["samples"] = samples
    out["verification"] = OrderedDict([
        ("quadrature: |W_gas(2.5 deg, 20 nodes) - W_gas(5 deg, 12 nodes)| / |W_gas|",
         float(abs(cyc.w_gas - coarse.w_gas) / abs(cyc.w_gas))),
        ("evaluations of I*, M*", eng.evals),
    ])
    with open(out_path, "w") as f:
        f.write(R.dumps(out) + "\n")
    print("wrote", out_path)
    for k in ("net_work_gas", "balancing_torque", "s_max", "s_min", "approximate_inertia", "exact_inertia"):
        print("  %-22s %s" % (k, mpmath.nstr(res[k], 15)))
    for k, v in out["verification"].items():
        print("  %s: %s" % (k, v))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
