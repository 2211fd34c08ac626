#!/usr/bin/env python3
"""High-precision reference solver for planar mechanisms (independent of mech).

Formulation: absolute coordinates.  Every moving link i has the unknowns
(x_i, y_i, phi_i): the position of its centre of gravity and its rotation since
the drawing.  A point P of link i sits at  r_i + R(phi_i) (P_ref - cg_ref_i).
The whole constraint system Phi(x; q) = 0 (joints + driver rows) is solved by
Newton's method at 50 significant digits (mpmath), continuing in small steps
along the inputs from the drawing's values, so the solution stays on the
drawing's assembly branch.  Velocities and accelerations come from

    Phi_x xd = rhs_v(qd),    Phi_x xdd = rhs_a(x, xd, qdd).

Kinetostatics (d'Alembert) with Lagrange multipliers, one dense system:

    Phi_x^T lambda = M xdd - Q_applied

where Q_applied holds gravity (at the cg) and the loads.  The multipliers are
the joint reactions on link b (see `reactions`) and the driver actions.

Conventions (docs/conventions.md, Reactions and Inputs): reaction at a joint
declared (a, b) is the force BY a ON b at the joint point; a prismatic joint
adds the moment, CCW on b, about the point's current position; a pin-in-slot
reports its normal force.
Revolute driver: q = theta_b - theta_a, action = torque by a on b (CCW on b).
Prismatic driver: q = displacement of P along the axis (fixed in a) from its
reference position, action = force along the axis on b.

Cross-checks computed for every configuration (see `verification`):
  * driver by virtual power (velocity coefficients) vs. the multiplier;
  * Zhukovski driver I* qdd + 1/2 dI*/dq qd^2 - M* vs. the multiplier (1 DOF);
  * Newton-Euler balance of every link with the reported reactions;
  * finite differences (at 50 digits) of positions / velocities vs. the
    analytic velocities / accelerations and of I* vs. dI*/dq.

Usage:
    python3 tools/reference.py MECH.mechanism.json CASES.json OUT.truth.json
    python3 tools/reference.py --sweep MECH.mechanism.json CASES.json OUT.sweep.json
CASES.json: {"loads": {name: value | {"value": value}}, "configs": [{"q","qd","qdd"}]}
(a truth file is a valid CASES file).
"""

import json
import math
import sys
from collections import OrderedDict

import mpmath
from mpmath import mp, mpf

mp.dps = 50
DIGITS_OUT = 25
CHOP = mpf("1e-35")


# --------------------------------------------------------------------------
# small 2-vector helpers (tuples of mpf)

def rot(phi, v):
    c, s = mpmath.cos(phi), mpmath.sin(phi)
    return (c * v[0] - s * v[1], s * v[0] + c * v[1])


def perp(v):  # J v, J = [[0,-1],[1,0]]
    return (-v[1], v[0])


def add(a, b):
    return (a[0] + b[0], a[1] + b[1])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def scale(k, v):
    return (k * v[0], k * v[1])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def norm(v):
    return mpmath.sqrt(dot(v, v))


def wrap(t):
    """wrap to (-pi, pi]"""
    twopi = 2 * mp.pi
    t = t - twopi * mpmath.floor(t / twopi)  # [0, 2pi)
    if t > mp.pi:
        t -= twopi
    return t


def solve(A, b):
    """dense solve, partial pivoting, lists of mpf"""
    n = len(A)
    M = [list(A[i]) + [b[i]] for i in range(n)]
    for k in range(n):
        p = max(range(k, n), key=lambda i: abs(M[i][k]))
        if M[p][k] == 0:
            raise ZeroDivisionError("singular constraint Jacobian")
        M[k], M[p] = M[p], M[k]
        piv = M[k][k]
        rowk = M[k]
        for i in range(k + 1, n):
            f = M[i][k] / piv
            if f:
                row = M[i]
                for j in range(k, n + 1):
                    row[j] -= f * rowk[j]
    x = [mpf(0)] * n
    for i in range(n - 1, -1, -1):
        s = M[i][n]
        for j in range(i + 1, n):
            s -= M[i][j] * x[j]
        x[i] = s / M[i][i]
    return x


def transpose(A):
    return [list(r) for r in zip(*A)]


def num(v):
    """parse a JSON number given as a string/int/float/mpf into mpf"""
    if isinstance(v, mpmath.mpf):
        return v
    if isinstance(v, float):
        return mpf(repr(v))
    return mpf(str(v))


def exact(d):
    """value of an {"exact", "float"} block (scalar or list)"""
    e = d["exact"]
    if isinstance(e, list):
        return tuple(mpf(s) for s in e)
    return mpf(e)


def load_json(path):
    with open(path) as f:
        return json.load(f, parse_float=mpf, parse_int=mpf, object_pairs_hook=OrderedDict)


# --------------------------------------------------------------------------

class Mechanism:
    def __init__(self, spec):
        self.spec = spec
        self.name = spec["name"]
        self.gravity = exact(spec["gravity"]) if "gravity" in spec else (mpf(0), mpf(0))
        self.P = OrderedDict((k, exact(v)) for k, v in spec["points"].items())
        self.links = OrderedDict()
        for l in spec["links"]:
            pts = list(l["points"])
            cg = exact(l["cg"])
            if len(pts) >= 2:
                d = sub(self.P[pts[1]], self.P[pts[0]])
                th = mpmath.atan2(d[1], d[0])
            else:
                th = mpf(0)
            if "theta_ref" in l and abs(exact(l["theta_ref"]) - th) > mpf(10) ** (-min(30, mp.dps - 5)):
                raise ValueError("theta_ref of %s disagrees with its points" % l["name"])
            self.links[l["name"]] = dict(
                points=pts,
                mass=exact(l["mass"]) if "mass" in l else mpf(0),
                inertia=exact(l["inertia"]) if "inertia" in l else mpf(0),
                cg=cg, theta_ref=th)
        self.names = list(self.links)
        self.index = {n: i for i, n in enumerate(self.names)}
        self.n = 3 * len(self.names)
        self.joints = list(spec["joints"])
        self.jmap = OrderedDict((j["name"], j) for j in self.joints)
        self.inputs = list(spec["inputs"])
        self.dof = len(self.inputs)
        self.loads = list(spec.get("loads", []))
        for j in self.joints:
            if j["type"] in ("prismatic", "pin_in_slot"):
                u = exact(j["axis"])
                j["_u0"] = scale(1 / norm(u), u)
        # rows: list of (kind, joint, extra)
        self.rows = []
        for j in self.joints:
            t = j["type"]
            if t == "revolute":
                self.rows += [("rev", j, 0), ("rev", j, 1)]
            elif t == "prismatic":
                self.rows += [("normal", j, None), ("rot", j, None)]
            elif t == "pin_in_slot":
                self.rows += [("normal", j, None)]
            else:
                raise ValueError("unknown joint type " + t)
        for k, inp in enumerate(self.inputs):
            j = self.jmap[inp]
            if j["type"] == "revolute":
                self.rows.append(("drv_rot", j, k))
            elif j["type"] == "prismatic":
                self.rows.append(("drv_axial", j, k))
            else:
                raise ValueError("input %s is not revolute/prismatic" % inp)
        if len(self.rows) != self.n:
            raise ValueError("%d equations for %d unknowns" % (len(self.rows), self.n))
        self.q_ref = [self.q_of_ref(inp) for inp in self.inputs]
        self.x_ref = []
        for nm in self.names:
            cg = self.links[nm]["cg"]
            self.x_ref += [cg[0], cg[1], mpf(0)]

    # -- geometry ---------------------------------------------------------
    def q_of_ref(self, inp):
        j = self.jmap[inp]
        if j["type"] == "revolute":
            return self.theta_ref(j["b"]) - self.theta_ref(j["a"])
        return mpf(0)

    def theta_ref(self, link):
        return mpf(0) if link == "ground" else self.links[link]["theta_ref"]

    def local(self, link, P):
        """reference vector from the link's body origin (cg; ground: 0) to P"""
        if link == "ground":
            return self.P[P]
        return sub(self.P[P], self.links[link]["cg"])

    def state(self, x, link):
        """(r, phi) of a link"""
        if link == "ground":
            return (mpf(0), mpf(0)), mpf(0)
        i = 3 * self.index[link]
        return (x[i], x[i + 1]), x[i + 2]

    def rate(self, xd, link):
        if link == "ground":
            return (mpf(0), mpf(0)), mpf(0)
        i = 3 * self.index[link]
        return (xd[i], xd[i + 1]), xd[i + 2]

    def point(self, x, link, P):
        r, phi = self.state(x, link)
        return add(r, rot(phi, self.local(link, P)))

    def point_vel(self, x, xd, link, P):
        r, phi = self.state(x, link)
        rd, w = self.rate(xd, link)
        return add(rd, scale(w, perp(rot(phi, self.local(link, P)))))

    def point_acc(self, x, xd, xdd, link, P):
        r, phi = self.state(x, link)
        rd, w = self.rate(xd, link)
        rdd, al = self.rate(xdd, link)
        Rs = rot(phi, self.local(link, P))
        return add(rdd, sub(scale(al, perp(Rs)), scale(w * w, Rs)))

    # -- constraints ------------------------------------------------------
    def _add_cols(self, row, link, coeffs):
        if link == "ground":
            return
        i = 3 * self.index[link]
        for k in range(3):
            row[i + k] += coeffs[k]

    def phi_and_jac(self, x, q):
        """Phi(x; q) and Phi_x"""
        n = self.n
        Phi = []
        Jac = []
        for kind, j, extra in self.rows:
            a, b, P = j["a"], j["b"], j["point"]
            row = [mpf(0)] * n
            if kind == "rev":
                c = extra
                pa, pb = self.point(x, a, P), self.point(x, b, P)
                Phi.append(pb[c] - pa[c])
                _, phb = self.state(x, b)
                _, pha = self.state(x, a)
                Jb = perp(rot(phb, self.local(b, P)))
                Ja = perp(rot(pha, self.local(a, P)))
                cb = [mpf(1) if c == 0 else mpf(0), mpf(1) if c == 1 else mpf(0), Jb[c]]
                ca = [-(mpf(1) if c == 0 else mpf(0)), -(mpf(1) if c == 1 else mpf(0)), -Ja[c]]
                self._add_cols(row, b, cb)
                self._add_cols(row, a, ca)
            elif kind in ("normal", "drv_axial"):
                _, pha = self.state(x, a)
                _, phb = self.state(x, b)
                u0 = j["_u0"]
                v = rot(pha, perp(u0) if kind == "normal" else u0)  # n or u, fixed in a
                d = sub(self.point(x, b, P), self.point(x, a, P))
                val = dot(v, d)
                if kind == "drv_axial":
                    val -= q[extra]
                Phi.append(val)
                Rsb = rot(phb, self.local(b, P))
                Rsa = rot(pha, self.local(a, P))
                self._add_cols(row, b, [v[0], v[1], dot(v, perp(Rsb))])
                self._add_cols(row, a, [-v[0], -v[1], dot(perp(v), d) - dot(v, perp(Rsa))])
            elif kind in ("rot", "drv_rot"):
                _, pha = self.state(x, a)
                _, phb = self.state(x, b)
                val = phb - pha
                if kind == "drv_rot":
                    val += self.theta_ref(b) - self.theta_ref(a) - q[extra]
                Phi.append(val)
                self._add_cols(row, b, [0, 0, 1])
                self._add_cols(row, a, [0, 0, -1])
            Jac.append(row)
        return Phi, Jac

    def rhs_vel(self, qd):
        out = []
        for kind, j, extra in self.rows:
            out.append(qd[extra] if kind in ("drv_rot", "drv_axial") else mpf(0))
        return out

    def rhs_acc(self, x, xd, qdd):
        """Phi_x xdd = rhs: minus the velocity-quadratic terms of d2Phi/dt2"""
        out = []
        for kind, j, extra in self.rows:
            a, b, P = j["a"], j["b"], j["point"]
            if kind == "rev":
                c = extra
                _, pha = self.state(x, a)
                _, phb = self.state(x, b)
                _, wa = self.rate(xd, a)
                _, wb = self.rate(xd, b)
                Rsa = rot(pha, self.local(a, P))
                Rsb = rot(phb, self.local(b, P))
                out.append(wb * wb * Rsb[c] - wa * wa * Rsa[c])
            elif kind in ("normal", "drv_axial"):
                _, pha = self.state(x, a)
                _, phb = self.state(x, b)
                _, wa = self.rate(xd, a)
                _, wb = self.rate(xd, b)
                u0 = j["_u0"]
                v = rot(pha, perp(u0) if kind == "normal" else u0)
                d = sub(self.point(x, b, P), self.point(x, a, P))
                dd = sub(self.point_vel(x, xd, b, P), self.point_vel(x, xd, a, P))
                Rsa = rot(pha, self.local(a, P))
                Rsb = rot(phb, self.local(b, P))
                quad = (-wa * wa * dot(v, d) + 2 * wa * dot(perp(v), dd)
                        + dot(v, sub(scale(wa * wa, Rsa), scale(wb * wb, Rsb))))
                val = -quad
                if kind == "drv_axial":
                    val += qdd[extra]
                out.append(val)
            elif kind == "rot":
                out.append(mpf(0))
            elif kind == "drv_rot":
                out.append(qdd[extra])
        return out

    # -- position analysis ------------------------------------------------
    def newton(self, x, q, tol=None, maxit=60):
        tol = tol if tol is not None else mpf(10) ** (-(mp.dps - 6))
        x = list(x)
        for it in range(maxit):
            Phi, Jac = self.phi_and_jac(x, q)
            dx = solve(Jac, [-p for p in Phi])
            x = [xi + di for xi, di in zip(x, dx)]
            if max(abs(d) for d in dx) < tol:
                Phi, _ = self.phi_and_jac(x, q)
                return x, max(abs(p) for p in Phi)
        raise RuntimeError("Newton did not converge at q=%s" % ([mpmath.nstr(v, 10) for v in q],))

    def step_size(self):
        hs = []
        for inp in self.inputs:
            hs.append(mpf("0.05") if self.jmap[inp]["type"] == "revolute" else mpf("0.004"))
        return hs

    def continue_to(self, q, x0=None, q0=None):
        """solve positions at q, continuing from (x0, q0) (default: the drawing)"""
        if x0 is None:
            x0, q0 = list(self.x_ref), list(self.q_ref)
        hs = self.step_size()
        nsteps = max(1, max(int(mpmath.ceil(abs(qi - q0i) / h)) for qi, q0i, h in zip(q, q0, hs)))
        x = list(x0)
        loose = max(mpf(10) ** (-25), mpf(10) ** (-(mp.dps - 6)))
        qprev = list(q0)
        for s in range(1, nsteps + 1):
            qs = [q0i + (qi - q0i) * s / nsteps for qi, q0i in zip(q, q0)]
            # tangent predictor
            _, Jac = self.phi_and_jac(x, qprev)
            dq = [a - b for a, b in zip(qs, qprev)]
            t = solve(Jac, self.rhs_vel(dq))
            x = [xi + ti for xi, ti in zip(x, t)]
            x, _ = self.newton(x, qs, tol=None if s == nsteps else loose)
            qprev = qs
        x, res = self.newton(x, q)
        return x, res

    # -- kinematics -------------------------------------------------------
    def velocities(self, x, q, qd):
        _, Jac = self.phi_and_jac(x, q)
        return solve(Jac, self.rhs_vel(qd))

    def accelerations(self, x, q, xd, qdd):
        _, Jac = self.phi_and_jac(x, q)
        return solve(Jac, self.rhs_acc(x, xd, qdd))

    # -- dynamics ---------------------------------------------------------
    def mass_diag(self):
        m = []
        for nm in self.names:
            L = self.links[nm]
            m += [L["mass"], L["mass"], L["inertia"]]
        return m

    def applied(self, x, loadvals):
        """generalized applied forces: gravity at cg + loads"""
        Q = [mpf(0)] * self.n
        g = self.gravity
        for nm in self.names:
            i = 3 * self.index[nm]
            m = self.links[nm]["mass"]
            Q[i] += m * g[0]
            Q[i + 1] += m * g[1]
        for ld in self.loads:
            nm = ld["link"]
            if nm == "ground":
                continue
            i = 3 * self.index[nm]
            v = loadvals[ld["name"]]
            if ld["type"] == "force":
                r, phi = self.state(x, nm)
                arm = rot(phi, self.local(nm, ld["point"]))
                Q[i] += v[0]
                Q[i + 1] += v[1]
                Q[i + 2] += cross(arm, v)
            else:
                Q[i + 2] += v
        return Q

    def analyse(self, x, q, qd, qdd, loadvals, res_pos=None):
        M = self.mass_diag()
        _, Jac = self.phi_and_jac(x, q)
        xd = solve(Jac, self.rhs_vel(qd))
        xdd = solve(Jac, self.rhs_acc(x, xd, qdd))
        Q = self.applied(x, loadvals)
        rhs = [M[i] * xdd[i] - Q[i] for i in range(self.n)]
        lam = solve(transpose(Jac), rhs)
        ver = {}
        ver["constraint residual |Phi|"] = res_pos if res_pos is not None else mpf(0)
        Phi, _ = self.phi_and_jac(x, q)
        ver["constraint residual |Phi|"] = max(abs(p) for p in Phi)
        rv = self.rhs_vel(qd)
        ver["velocity residual"] = max(abs(sum(Jac[i][k] * xd[k] for k in range(self.n)) - rv[i])
                                       for i in range(self.n))
        ra = self.rhs_acc(x, xd, qdd)
        ver["acceleration residual"] = max(abs(sum(Jac[i][k] * xdd[k] for k in range(self.n)) - ra[i])
                                           for i in range(self.n))

        # reactions and drivers from the multipliers
        reactions = OrderedDict()
        drivers = [None] * self.dof
        for r, (kind, j, extra) in enumerate(self.rows):
            a, b, P = j["a"], j["b"], j["point"]
            name = j["name"]
            if kind in ("drv_rot", "drv_axial"):
                drivers[extra] = lam[r]
                continue
            ent = reactions.setdefault(name, OrderedDict(
                type=j["type"], a=a, b=b, force=[mpf(0), mpf(0)], moment=mpf(0)))
            if kind == "rev":
                ent["force"][extra] += lam[r]
            elif kind == "normal":
                _, pha = self.state(x, a)
                nvec = rot(pha, perp(j["_u0"]))
                ent["force"][0] += lam[r] * nvec[0]
                ent["force"][1] += lam[r] * nvec[1]
            elif kind == "rot":
                ent["moment"] += lam[r]
        for name, ent in reactions.items():
            ent["at"] = list(self.point(x, ent["b"], self.jmap[name]["point"]))

        # virtual power: one velocity field per input
        fields = []
        for k in range(self.dof):
            e = [mpf(0)] * self.dof
            e[k] = mpf(1)
            fields.append(solve(Jac, self.rhs_vel(e)))
        vp = [sum(rhs[i] * f[i] for i in range(self.n)) for f in fields]
        dscale = max([abs(d) for d in drivers] + [mpf("1e-30")])
        ver["virtual power vs multiplier: driver (rel)"] = max(abs(a - b) for a, b in zip(vp, drivers)) / dscale

        # Newton-Euler balance of each link from the reported reactions
        fscale = max([abs(c) for e in reactions.values() for c in e["force"]] + [mpf("1e-30")])
        ne = self.newton_euler_residual(x, xdd, loadvals, reactions, drivers)
        ver["Newton-Euler balance with reported reactions (rel to force scale)"] = ne / fscale

        zh = None
        if self.dof == 1:
            g = fields[0]
            Istar = sum(M[i] * g[i] * g[i] for i in range(self.n))
            a10 = solve(Jac, self.rhs_acc(x, g, [mpf(0)]))
            dI = 2 * sum(M[i] * g[i] * a10[i] for i in range(self.n))
            Mstar = sum(Q[i] * g[i] for i in range(self.n))
            Tz = Istar * qdd[0] + dI * qd[0] ** 2 / 2 - Mstar
            ver["Zhukovski vs multiplier: driver (rel)"] = abs(Tz - drivers[0]) / dscale
            zh = OrderedDict(I_star=Istar, dI_star_dq=dI, M_star=Mstar, driver_from_zhukovski=Tz)
        return dict(xd=xd, xdd=xdd, lam=lam, drivers=drivers, reactions=reactions,
                    zhukovski=zh, verification=ver, fields=fields)

    def newton_euler_residual(self, x, xdd, loadvals, reactions, drivers):
        """max |sum F - m a|, |sum M_G - I alpha| (moments divided by 1 m) over links"""
        F = {nm: [mpf(0), mpf(0), mpf(0)] for nm in self.names}

        def apply(link, f, at, moment=mpf(0)):
            if link == "ground":
                return
            r, _ = self.state(x, link)
            F[link][0] += f[0]
            F[link][1] += f[1]
            F[link][2] += cross(sub(at, r), f) + moment

        for name, e in reactions.items():
            f = e["force"]
            apply(e["b"], f, e["at"], e["moment"])
            apply(e["a"], (-f[0], -f[1]), e["at"], -e["moment"])
        for k, inp in enumerate(self.inputs):
            j = self.jmap[inp]
            if j["type"] == "revolute":
                apply(j["b"], (0, 0), (0, 0), drivers[k])
                apply(j["a"], (0, 0), (0, 0), -drivers[k])
            else:
                _, pha = self.state(x, j["a"])
                u = rot(pha, j["_u0"])
                at = self.point(x, j["b"], j["point"])
                apply(j["b"], scale(drivers[k], u), at)
                apply(j["a"], scale(-drivers[k], u), at)
        g = self.gravity
        worst = mpf(0)
        for nm in self.names:
            L = self.links[nm]
            r, phi = self.state(x, nm)
            apply(nm, scale(L["mass"], g), r)
        for ld in self.loads:
            v = loadvals[ld["name"]]
            if ld["type"] == "force":
                apply(ld["link"], v, self.point(x, ld["link"], ld["point"]))
            else:
                apply(ld["link"], (0, 0), (0, 0), v)
        for nm in self.names:
            i = 3 * self.index[nm]
            L = self.links[nm]
            res = [F[nm][0] - L["mass"] * xdd[i], F[nm][1] - L["mass"] * xdd[i + 1],
                   F[nm][2] - L["inertia"] * xdd[i + 2]]
            worst = max(worst, max(abs(v) for v in res))
        return worst

    def finite_difference_check(self, x, q, h=mpf("1e-15")):
        """FD of positions vs velocity fields and of the velocity fields vs
        the acceleration analysis (qd = e_k, qdd = 0), and of I* vs dI*/dq"""
        out = {}
        worst_v = worst_a = mpf(0)
        worst_I = mpf(0)
        M = self.mass_diag()
        for k in range(self.dof):
            e = [mpf(0)] * self.dof
            e[k] = mpf(1)
            qp = list(q); qp[k] += h
            qm = list(q); qm[k] -= h
            xp, _ = self.continue_to(qp, x, q)
            xm, _ = self.continue_to(qm, x, q)
            v = self.velocities(x, q, e)
            a = self.accelerations(x, q, v, [mpf(0)] * self.dof)
            vp = self.velocities(xp, qp, e)
            vm = self.velocities(xm, qm, e)
            fdv = [(p - m) / (2 * h) for p, m in zip(xp, xm)]
            fda = [(p - m) / (2 * h) for p, m in zip(vp, vm)]
            sv = max(abs(c) for c in v) or 1
            sa = max(abs(c) for c in a) or 1
            worst_v = max(worst_v, max(abs(p - m) for p, m in zip(fdv, v)) / sv)
            worst_a = max(worst_a, max(abs(p - m) for p, m in zip(fda, a)) / sa)
            if self.dof == 1:
                I = lambda vv: sum(M[i] * vv[i] ** 2 for i in range(self.n))
                dI = 2 * sum(M[i] * v[i] * a[i] for i in range(self.n))
                worst_I = max(worst_I, abs((I(vp) - I(vm)) / (2 * h) - dI) / I(v))
        out["finite differences: velocity (rel)"] = worst_v
        out["finite differences: acceleration (rel)"] = worst_a
        if self.dof == 1:
            out["finite differences: dI*/dq (rel to I*)"] = worst_I
        return out

    # -- output -------------------------------------------------------------
    def config_record(self, index, q, qd, qdd, x, an):
        xd, xdd = an["xd"], an["xdd"]
        rec = OrderedDict()
        rec["index"] = index
        if self.dof == 1:
            rec["q"], rec["qd"], rec["qdd"] = q[0], qd[0], qdd[0]
        else:
            rec["q"], rec["qd"], rec["qdd"] = list(q), list(qd), list(qdd)
        links = OrderedDict()
        for nm in self.names:
            L = self.links[nm]
            i = 3 * self.index[nm]
            e = OrderedDict()
            e["theta"] = wrap(L["theta_ref"] + x[i + 2])
            e["omega"] = xd[i + 2]
            e["alpha"] = xdd[i + 2]
            e["cg"] = OrderedDict(pos=[x[i], x[i + 1]], vel=[xd[i], xd[i + 1]], acc=[xdd[i], xdd[i + 1]])
            pts = OrderedDict()
            for P in L["points"]:
                pts[P] = OrderedDict(pos=list(self.point(x, nm, P)),
                                     vel=list(self.point_vel(x, xd, nm, P)),
                                     acc=list(self.point_acc(x, xd, xdd, nm, P)))
            e["points"] = pts
            links[nm] = e
        rec["links"] = links
        drv = []
        for k, inp in enumerate(self.inputs):
            t = "torque" if self.jmap[inp]["type"] == "revolute" else "force"
            drv.append(OrderedDict(joint=inp, type=t, value=an["drivers"][k]))
        rec["drivers"] = drv
        reac = OrderedDict()
        for name, ent in an["reactions"].items():
            r = OrderedDict(type=ent["type"], a=ent["a"], b=ent["b"], force=ent["force"])
            if ent["type"] == "prismatic":
                r["moment"] = ent["moment"]
            r["at"] = ent["at"]
            reac[name] = r
        rec["reactions"] = reac
        if an["zhukovski"] is not None:
            rec["zhukovski"] = an["zhukovski"]
        return rec


# --------------------------------------------------------------------------
# JSON writer in the style of the reference files (1-space indent, number
# arrays inline, 25 significant digits)

def fmt(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):  # diagnostics (verification): plain double
        return repr(v)
    if isinstance(v, mpmath.mpf):
        if abs(v) < CHOP:
            return "0"
        s = mpmath.nstr(v, DIGITS_OUT)
        return s
    return json.dumps(v)


def dumps(obj, ind=0):
    pad = " " * (ind + 1)
    if isinstance(obj, dict):
        if not obj:
            return "{}"
        items = [pad + json.dumps(k) + ": " + dumps(v, ind + 1) for k, v in obj.items()]
        return "{\n" + ",\n".join(items) + "\n" + " " * ind + "}"
    if isinstance(obj, (list, tuple)):
        if all(not isinstance(v, (dict, list, tuple)) for v in obj):
            return "[" + ", ".join(fmt(v) for v in obj) + "]"
        items = [pad + dumps(v, ind + 1) for v in obj]
        return "[\n" + ",\n".join(items) + "\n" + " " * ind + "]"
    return fmt(obj)


def load_values(mech, cases):
    vals = OrderedDict()
    raw = cases["loads"]
    for ld in mech.loads:
        v = raw[ld["name"]]
        if isinstance(v, dict):
            v = v["value"]
        vals[ld["name"]] = tuple(num(c) for c in v) if ld["type"] == "force" else num(v)
    return vals


def as_list(v):
    return [num(c) for c in v] if isinstance(v, list) else [num(v)]


def compute_truth(mech, cases, mechanism_file, fd_check=True, log=print):
    loadvals = load_values(mech, cases)
    out = OrderedDict()
    out["schema"] = "planar-mechanism-truth/1"
    out["mechanism"] = mech.name
    out["mechanism_file"] = mechanism_file
    out["dof"] = mech.dof
    out["inputs"] = list(mech.inputs)
    out["gravity"] = list(mech.gravity)
    lo = OrderedDict()
    for ld in mech.loads:
        e = OrderedDict(type=ld["type"], link=ld["link"])
        if ld["type"] == "force":
            e["point"] = ld["point"]
            e["value"] = list(loadvals[ld["name"]])
        else:
            e["value"] = loadvals[ld["name"]]
        lo[ld["name"]] = e
    out["loads"] = lo
    out["digits"] = "every number has 25 significant digits (computed with mpmath at 50 digits)"
    out["conventions"] = ("theta wrapped to (-pi, pi]; reaction = force BY joint link a ON link b; "
                          "prismatic moment is CCW on b about the joint point's current position ('at'); "
                          "pin_in_slot: force normal to the slot; drivers: torque by a on b (revolute) "
                          "or force along the axis on b (prismatic)")
    configs = []
    worst = OrderedDict()
    for idx, c in enumerate(cases["configs"]):
        q, qd, qdd = as_list(c["q"]), as_list(c["qd"]), as_list(c["qdd"])
        x, res = mech.continue_to(q)
        an = mech.analyse(x, q, qd, qdd, loadvals, res)
        ver = dict(an["verification"])
        if fd_check:
            ver.update(mech.finite_difference_check(x, q))
        for k, v in ver.items():
            worst[k] = max(worst.get(k, mpf(0)), v)
        configs.append(mech.config_record(idx, q, qd, qdd, x, an))
    out["configs"] = configs
    out["verification"] = OrderedDict((k, float(v)) for k, v in sorted(worst.items()))
    return out


def compute_sweep(mech, cases, mechanism_file, npts=361):
    assert mech.dof == 1
    loadvals = load_values(mech, cases)
    out = OrderedDict()
    out["schema"] = "planar-mechanism-sweep/1"
    out["mechanism"] = mech.name
    out["mechanism_file"] = mechanism_file
    out["input"] = mech.inputs[0]
    out["gravity"] = list(mech.gravity)
    lo = OrderedDict()
    for ld in mech.loads:
        e = OrderedDict(type=ld["type"], link=ld["link"])
        if ld["type"] == "force":
            e["point"] = ld["point"]
            e["value"] = list(loadvals[ld["name"]])
        else:
            e["value"] = loadvals[ld["name"]]
        lo[ld["name"]] = e
    out["loads"] = lo
    out["qd"] = mpf(1)
    out["qdd"] = mpf(0)
    out["description"] = ("q = theta_ref + 2*pi*k/360, k = 0..360 (theta_ref = q in the drawing); "
                          "I_star, dI_star_dq, M_star (gravity and loads included) at each q")
    out["digits"] = "every number has 25 significant digits (computed with mpmath at 50 digits)"
    pts = []
    x, q = list(mech.x_ref), list(mech.q_ref)
    worst = mpf(0)
    for k in range(npts):
        qk = [mech.q_ref[0] + 2 * mp.pi * k / (npts - 1)]
        x, _ = mech.continue_to(qk, x, q)
        q = qk
        an = mech.analyse(x, q, [mpf(1)], [mpf(0)], loadvals)
        z = an["zhukovski"]
        worst = max(worst, an["verification"]["Zhukovski vs multiplier: driver (rel)"],
                    an["verification"]["virtual power vs multiplier: driver (rel)"])
        pts.append(OrderedDict(q=qk[0], I_star=z["I_star"], dI_star_dq=z["dI_star_dq"], M_star=z["M_star"]))
    # closure: after a full turn we must be back at the drawing
    closure = max(abs(a - b) for i, (a, b) in enumerate(zip(x, mech.x_ref)) if i % 3 != 2)
    out["points"] = pts
    out["verification"] = OrderedDict([("driver: Zhukovski/virtual power vs multiplier (rel)", float(worst)),
                                       ("closure after one revolution: cg positions |x(2pi) - x(0)| (m)", float(closure))])
    return out


def write(path, obj):
    with open(path, "w") as f:
        f.write(dumps(obj) + "\n")


def main(argv):
    sweep = False
    if argv and argv[0] == "--sweep":
        sweep = True
        argv = argv[1:]
    if len(argv) != 3:
        print(__doc__)
        return 2
    mpath, cpath, opath = argv
    spec = load_json(mpath)
    cases = load_json(cpath)
    mech = Mechanism(spec)
    import os
    mfile = os.path.basename(mpath)
    if sweep:
        out = compute_sweep(mech, cases, mfile)
    else:
        out = compute_truth(mech, cases, mfile)
    write(opath, out)
    worst = max(out["verification"].values()) if out["verification"] else 0.0
    print("%s: wrote %s" % (mech.name, opath))
    for k, v in out["verification"].items():
        print("   %-70s %.3e" % (k, v))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
