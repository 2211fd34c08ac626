#!/usr/bin/env python3
"""High-precision reference trajectories of the slider-crank (independent of mech).

The equation of motion of a one-DOF machine in Zhukovski's form,

    I*(q) q'' + 1/2 dI*/dq q'^2 = driver(t, q, q') + M*(q; loads(t, q, q')),

is integrated at 50 significant digits (mpmath).  I*, dI*/dq and M* come from the
machinery of tools/reference.py: the whole constraint system in absolute
coordinates, solved by Newton at 50 digits; the velocity field with q' = 1
(g = dx/dq) and the acceleration field with q' = 1, q'' = 0 (a = d2x/dq2):

    I* = sum_i M_i g_i^2,   dI*/dq = 2 sum_i M_i g_i a_i,   M* = sum_i Q_i g_i

(M the diagonal mass matrix of the absolute coordinates, Q the applied forces:
gravity at the cg and the loads).  Nothing of the Rust library is used.

Time integration: Gragg-Bulirsch-Stoer extrapolation (modified midpoint rule
with the step sequence n_j = 2j, j = 1..K, Aitken-Neville extrapolation in h^2,
order 2K = 16), with step-size control on the extrapolation tableau's error
estimate and steps that land on every output time.  Position analysis between
evaluations: a second-order Taylor predictor x + g dq + a dq^2/2 from the last
evaluation, then Newton to 1e-44.

Cases (all from t0 = 0):
  constant_torque   driver 3 N.m, no loads (gravity only), q0 = 0.3 rad, q'0 = 20 rad/s,
                    outputs every 0.05 s to 0.5 s.
  time_and_speed    driver 3 + 2 sin(8 t) N.m, shaft = -0.002 q' N.m (viscous, on the
                    crank), gas = (-(10 + 8 cos q), 0) N on the piston at B; same start,
                    outputs every 0.025 s to 0.25 s.

Checks written to the file's "verification" block:
  * constant_torque: the energy balance E(t) - E(0) = 3 (q(t) - q0) (E = T + V,
    gravity conservative), relative to E(0);
  * every case: a second run with a 1000x tighter tolerance (constant_torque: over its
    first 0.15 s); the largest difference in q and q' over the outputs.

Usage:  python3 tools/dynamics_reference.py [-j 2] [--out-root DIR] [OUT.json]
        (default OUT = tests/data/slider_crank.dynamics.json; about 7 minutes of CPU, 2026-11-27;
        -j 2 runs its four integrations on two processes)
        --out-root DIR: read DIR/tests/data/slider_crank.mechanism.json and write
        DIR/tests/data/slider_crank.dynamics.json (tools/outroot.py)
"""

import os
import sys
import time
from collections import OrderedDict
from multiprocessing import Pool

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

import mpmath  # noqa: E402
from mpmath import mp, mpf  # noqa: E402

import reference as R  # noqa: E402

mp.dps = 50
MECH_FILE = "slider_crank.mechanism.json"
K = 10  # extrapolation columns: order 2K
TOL = mpf("1e-20")  # local error per step, relative to max(1, |y|)
# output times of each case, s
T_OUT = {"constant_torque": [mpf(k) / 20 for k in range(11)],  # 0, 0.05, ..., 0.5
         "time_and_speed": [mpf(k) / 40 for k in range(11)]}  # 0, 0.025, ..., 0.25
# outputs covered by the check run at a 1000x tighter tolerance
CHECKED = {"constant_torque": 4, "time_and_speed": 11}


def case_actions(name):
    """(driver(t, q, qd), loads(t, q, qd)) of a case, in mpf"""
    if name == "constant_torque":
        return (lambda t, q, qd: mpf(3)), (lambda t, q, qd: {"gas": (mpf(0), mpf(0)), "shaft": mpf(0)})
    if name == "time_and_speed":
        return ((lambda t, q, qd: 3 + 2 * mpmath.sin(8 * t)),
                (lambda t, q, qd: {"gas": (-(10 + 8 * mpmath.cos(q)), mpf(0)), "shaft": mpf("-0.002") * qd}))
    raise ValueError(name)


DESCRIPTIONS = {
    "constant_torque": {"driver": "3 N.m", "gas": "(0, 0) N", "shaft": "0 N.m"},
    "time_and_speed": {"driver": "3 + 2 sin(8 t) N.m", "gas": "(-(10 + 8 cos q), 0) N",
                       "shaft": "-0.002 q' N.m"},
}


class Zhukovski:
    """I*, dI*/dq, M* along a path of positions, with a warm-started position analysis"""

    def __init__(self, mech):
        self.mech = mech
        self.M = mech.mass_diag()
        self.q = list(mech.q_ref)
        self.x = list(mech.x_ref)
        self.g = None
        self.a = None
        self.evals = 0

    def position(self, q):
        m = self.mech
        if self.g is None or abs(q - self.q[0]) > mpf("0.5"):
            x, _ = m.continue_to([q], self.x, self.q)
        else:
            dq = q - self.q[0]
            guess = [xi + gi * dq + ai * dq * dq / 2 for xi, gi, ai in zip(self.x, self.g, self.a)]
            x, _ = m.newton(guess, [q], tol=mpf("1e-44"))
        return x

    def at(self, q, loadvals):
        m = self.mech
        x = self.position(q)
        _, jac = m.phi_and_jac(x, [q])
        g = R.solve(jac, m.rhs_vel([mpf(1)]))
        a = R.solve(jac, m.rhs_acc(x, g, [mpf(0)]))
        self.q, self.x, self.g, self.a = [q], x, g, a
        self.evals += 1
        Q = m.applied(x, loadvals)
        M = self.M
        i_star = sum(M[i] * g[i] * g[i] for i in range(m.n))
        di = 2 * sum(M[i] * g[i] * a[i] for i in range(m.n))
        m_star = sum(Q[i] * g[i] for i in range(m.n))
        return i_star, di, m_star, x, g

    def energy(self, q, qd):
        """T + V (J) at (q, q')"""
        m = self.mech
        i_star, _, _, x, _ = self.at(q, {"gas": (mpf(0), mpf(0)), "shaft": mpf(0)})
        v = mpf(0)
        for nm in m.names:
            i = 3 * m.index[nm]
            v -= m.links[nm]["mass"] * (m.gravity[0] * x[i] + m.gravity[1] * x[i + 1])
        return i_star * qd * qd / 2 + v


def make_rhs(z, name):
    driver, loads = case_actions(name)

    def rhs(t, y):
        q, qd = y
        i_star, di, m_star, _, _ = z.at(q, loads(t, q, qd))
        return [qd, (driver(t, q, qd) + m_star - di * qd * qd / 2) / i_star]

    return rhs


def gbs_step(f, t, y, H, f0):
    """one extrapolated modified-midpoint step: (y(t+H), error estimate)"""
    table = []
    ns = [2 * j for j in range(1, K + 1)]
    for j, n in enumerate(ns):
        h = H / n
        z0 = list(y)
        z1 = [a + h * b for a, b in zip(y, f0)]
        for m in range(1, n):
            fz = f(t + m * h, z1)
            z0, z1 = z1, [a + 2 * h * b for a, b in zip(z0, fz)]
        fz = f(t + H, z1)
        row = [[(a + b + h * c) / 2 for a, b, c in zip(z0, z1, fz)]]
        for k in range(1, j + 1):
            r = (mpf(ns[j]) / ns[j - k]) ** 2 - 1
            prev, up = row[k - 1], table[j - 1][k - 1]
            row.append([p + (p - u) / r for p, u in zip(prev, up)])
        table.append(row)
    best = table[-1][-1]
    err = max(abs(a - b) / max(1, abs(a)) for a, b in zip(best, table[-1][-2]))
    return best, err


def integrate(name, tol, n_out, mech_path):
    mech = R.Mechanism(R.load_json(mech_path))
    z = Zhukovski(mech)
    f = make_rhs(z, name)
    t = mpf(0)
    y = [mpf("0.3"), mpf(20)]
    H = mpf("0.002")
    out = [(t, list(y), f(t, y)[1])]
    steps = rejected = 0
    for t_next in T_OUT[name][1:n_out]:
        while t < t_next:
            h = min(H, t_next - t)
            f0 = f(t, y)
            y1, err = gbs_step(f, t, y, h, f0)
            if err <= tol:
                t, y = t + h, y1
                steps += 1
                fac = mpf(2) if err == 0 else min(mpf(2), mpf("0.8") * (tol / err) ** (mpf(1) / (2 * K - 1)))
                if h == H:
                    H = H * fac
            else:
                rejected += 1
                H = h * max(mpf("0.3"), mpf("0.8") * (tol / err) ** (mpf(1) / (2 * K - 1)))
        out.append((t, list(y), f(t, y)[1]))
    return out, dict(steps=steps, rejected=rejected, evals=z.evals)


def run_case(args):
    name, tol, n_out, mech_path = args
    t0 = time.time()
    out, st = integrate(name, tol, n_out, mech_path)
    st["seconds"] = time.time() - t0
    return name, tol, out, st


def main(argv):
    import outroot
    root, argv = outroot.split(argv)
    jobs = 1
    if argv[:1] == ["-j"]:
        jobs = int(argv[1])
        argv = argv[2:]
    path = argv[0] if argv else outroot.path(root, "tests", "data", "slider_crank.dynamics.json")
    mech_path = os.path.join(root, "tests", "data", MECH_FILE)
    names = ["constant_torque", "time_and_speed"]
    work = ([(n, TOL, len(T_OUT[n]), mech_path) for n in names]
            + [(n, TOL / 1000, CHECKED[n], mech_path) for n in names])
    if jobs > 1:
        with Pool(jobs) as p:
            results = p.map(run_case, work)
    else:
        results = [run_case(w) for w in work]
    by = {(n, tol): (out, st) for n, tol, out, st in results}
    for n, tol, out, st in results:
        print("%s at tolerance %s: %d steps, %d rejected, %d evaluations, %.0f s"
              % (n, mpmath.nstr(tol, 2), st["steps"], st["rejected"], st["evals"], st["seconds"]))

    doc = OrderedDict()
    doc["schema"] = "mech-dynamics-reference/1"
    doc["mechanism"] = "SliderCrank"
    doc["mechanism_file"] = MECH_FILE
    doc["equation"] = "I*(q) q'' + 1/2 dI*/dq q'^2 = driver + M*(q; loads), gravity included in M*"
    doc["method"] = ("mpmath at 50 digits; I*, dI*/dq, M* from tools/reference.py (absolute coordinates); "
                     "Gragg-Bulirsch-Stoer extrapolation of order %d, local tolerance %s" % (2 * K, mpmath.nstr(TOL, 3)))
    doc["digits"] = "every number has 25 significant digits"
    cases = []
    ver = OrderedDict()
    mech = R.Mechanism(R.load_json(mech_path))
    for n in names:
        out, st = by[(n, TOL)]
        fine, st_fine = by[(n, TOL / 1000)]
        c = OrderedDict()
        c["name"] = n
        c["actions"] = DESCRIPTIONS[n]
        c["t0"], c["q0"], c["qd0"] = mpf(0), mpf("0.3"), mpf(20)
        c["samples"] = [OrderedDict(t=t, q=y[0], qd=y[1], qdd=a) for t, y, a in out]
        c["work"] = OrderedDict((k, v) for k, v in st.items() if k != "seconds")
        cases.append(c)
        dq = max(abs(a[1][0] - b[1][0]) / max(1, abs(b[1][0])) for a, b in zip(out, fine))
        dqd = max(abs(a[1][1] - b[1][1]) / max(1, abs(b[1][1])) for a, b in zip(out, fine))
        span = mpmath.nstr(out[len(fine) - 1][0], 3)
        ver["%s: q vs 1000x tighter run to t = %s s (rel)" % (n, span)] = float(dq)
        ver["%s: q' vs 1000x tighter run to t = %s s (rel)" % (n, span)] = float(dqd)
        if n == "constant_torque":
            z = Zhukovski(mech)
            e0 = z.energy(out[0][1][0], out[0][1][1])
            worst = max(abs(z.energy(y[0], y[1]) - e0 - 3 * (y[0] - out[0][1][0])) for _, y, _ in out)
            ver["constant_torque: energy balance E(t) - E(0) - 3 (q - q0), rel to E(0)"] = float(worst / abs(e0))
    doc["cases"] = cases
    doc["verification"] = ver
    R.write(path, doc)
    print("wrote", path)
    for k, v in ver.items():
        print("   %-72s %.3e" % (k, v))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
