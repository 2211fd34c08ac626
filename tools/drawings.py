#!/usr/bin/env python3
"""The reference drawings and their test cases.

Builds every drawing from a handful of design numbers (lengths, angles,
offsets) at 50 significant digits and writes

    tests/data/<name>.mechanism.json   the drawing (schema planar-mechanism/1,
                                       "exact" = 40 significant digits, "float")
    tools/cases/<name>.cases.json      the load values and the configurations
                                       (q, qd, qdd) fed to tools/reference.py

The exact decimal strings are the definition: the truth files are computed from
them, not from the design numbers.

Usage: python3 tools/drawings.py [--survey] [--out-root DIR]
  --out-root DIR  write the files under DIR (same relative paths) instead of the
            repository (tools/outroot.py)
  --survey  also sweep each drawing over its input range (at 20 digits) and
            print the worst conditioning of the constraint Jacobian, to make
            sure no configuration is near a dead point.
"""

import json
import math
import os
import sys
from collections import OrderedDict

import mpmath
from mpmath import mp, mpf

mp.dps = 50

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data")
CASES = os.path.join(ROOT, "tools", "cases")

EXACT_DIGITS = 40


# --------------------------------------------------------------------------
# geometry helpers (mpf)

def M(s):
    return mpf(str(s))


def deg(a):
    return M(a) * mp.pi / 180


def P(x, y):
    return (M(x), M(y))


def add(a, b):
    return (a[0] + b[0], a[1] + b[1])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def mul(k, a):
    return (k * a[0], k * a[1])


def unit(v):
    n = mpmath.sqrt(v[0] ** 2 + v[1] ** 2)
    return (v[0] / n, v[1] / n)


def polar(o, length, angle):
    return (o[0] + M(length) * mpmath.cos(angle), o[1] + M(length) * mpmath.sin(angle))


def frame(a, b):
    """unit vector a->b and its left normal"""
    e = unit(sub(b, a))
    return e, (-e[1], e[0])


def local(a, b, along, normal):
    """point at `along` along a->b and `normal` to its left, from a"""
    e, n = frame(a, b)
    return add(a, add(mul(M(along), e), mul(M(normal), n)))


def circles(c1, r1, c2, r2, left=True):
    """intersection of circle(c1, r1) and circle(c2, r2); left: the point to the
    left of c1->c2"""
    r1, r2 = M(r1), M(r2)
    d = sub(c2, c1)
    L = mpmath.sqrt(d[0] ** 2 + d[1] ** 2)
    a = (r1 ** 2 - r2 ** 2 + L ** 2) / (2 * L)
    h2 = r1 ** 2 - a ** 2
    if h2 <= 0:
        raise ValueError("circles do not intersect")
    h = mpmath.sqrt(h2)
    e = (d[0] / L, d[1] / L)
    n = (-e[1], e[0])
    s = 1 if left else -1
    return add(c1, add(mul(a, e), mul(s * h, n)))


# --------------------------------------------------------------------------
# JSON building

def ex(v):
    """exact decimal string with 40 significant digits"""
    v = mpf(v)
    if v == 0:
        return "0"
    return mpmath.nstr(v, EXACT_DIGITS)


def block(v):
    if isinstance(v, (tuple, list)):
        e = [ex(c) for c in v]
        return OrderedDict(exact=e, float=[float(mpf(s)) for s in e])
    e = ex(v)
    return OrderedDict(exact=e, float=float(mpf(e)))


class Drawing:
    def __init__(self, name, description):
        self.name = name
        self.description = description
        self.points = OrderedDict()
        self.ground = []
        self.links = []
        self.joints = []
        self.inputs = []
        self.loads = []
        self.design = OrderedDict()

    def point(self, name, p, ground=False):
        self.points[name] = p
        if ground:
            self.ground.append(name)
        return p

    def link(self, name, points, mass, inertia, cg):
        self.links.append(dict(name=name, points=points, mass=M(mass), inertia=M(inertia), cg=cg))

    def rev(self, name, a, b, point=None):
        self.joints.append(OrderedDict(name=name, type="revolute", a=a, b=b, point=point or name))

    def slide(self, kind, name, a, b, point, axis):
        self.joints.append(OrderedDict(name=name, type=kind, a=a, b=b, point=point, axis=axis))

    def force(self, name, link, point):
        self.loads.append(OrderedDict(name=name, type="force", link=link, point=point))

    def torque(self, name, link):
        self.loads.append(OrderedDict(name=name, type="torque", link=link))

    def to_json(self):
        d = OrderedDict()
        d["schema"] = "planar-mechanism/1"
        d["name"] = self.name
        d["description"] = self.description
        d["units"] = "SI: m, kg, kg*m^2, rad, s, N, N*m"
        d["gravity"] = OrderedDict(exact=["0", "-9.81"], float=[0.0, -9.81])
        d["points"] = OrderedDict((k, block(v)) for k, v in self.points.items())
        d["ground"] = OrderedDict(points=list(self.ground))
        links = []
        for l in self.links:
            e = OrderedDict()
            e["name"] = l["name"]
            e["points"] = list(l["points"])
            e["mass"] = block(l["mass"])
            e["inertia"] = block(l["inertia"])
            e["cg"] = block(l["cg"])
            if len(l["points"]) >= 2:
                # from the exact (rounded) points, so theta_ref matches them
                p0 = [mpf(s) for s in block(self.points[l["points"][0]])["exact"]]
                p1 = [mpf(s) for s in block(self.points[l["points"][1]])["exact"]]
                th = mpmath.atan2(p1[1] - p0[1], p1[0] - p0[0])
            else:
                th = mpf(0)
            e["theta_ref"] = block(th)
            links.append(e)
        d["links"] = links
        joints = []
        for j in self.joints:
            e = OrderedDict((k, v) for k, v in j.items() if k != "axis")
            if "axis" in j:
                e["axis"] = block(j["axis"])
            joints.append(e)
        d["joints"] = joints
        d["inputs"] = list(self.inputs)
        d["loads"] = [OrderedDict(l) for l in self.loads]
        N = len(self.links) + 1
        PI = sum(1 for j in self.joints if j["type"] in ("revolute", "prismatic"))
        PII = sum(1 for j in self.joints if j["type"] == "pin_in_slot")
        G = 3 * (N - 1) - 2 * PI - PII
        d["structure"] = OrderedDict([
            ("N_links_including_ground", N), ("P_I", PI), ("P_II", PII), ("grubler_dof", G),
            ("equations_3N_minus_3", 3 * (N - 1)), ("unknowns_G_plus_2PI_plus_PII", G + 2 * PI + PII),
            ("inputs", len(self.inputs)), ("mobility", G), ("redundant", False)])
        d["design"] = self.design
        return d


def dumps(obj, ind=0):
    """1-space indent, scalar arrays inline (the style of the reference files)"""
    pad = " " * (ind + 1)
    if isinstance(obj, dict):
        items = [pad + json.dumps(k) + ": " + dumps(v, ind + 1) for k, v in obj.items()]
        return "{\n" + ",\n".join(items) + "\n" + " " * ind + "}" if items else "{}"
    if isinstance(obj, (list, tuple)):
        if all(not isinstance(v, (dict, list, tuple)) for v in obj):
            return "[" + ", ".join(dumps(v, ind + 1) for v in obj) + "]"
        items = [pad + dumps(v, ind + 1) for v in obj]
        return "[\n" + ",\n".join(items) + "\n" + " " * ind + "]"
    if isinstance(obj, float):
        return repr(obj)
    if isinstance(obj, mpmath.mpf):
        return mpmath.nstr(obj, 25) if obj != 0 else "0"
    return json.dumps(obj)


# --------------------------------------------------------------------------
# the configurations

QD = ["12.5", "-8.25", "17.75", "6.4", "-21.3", "9.9", "-4.75", "15.2", "-11.6", "7.05", "23.4", "-13.8"]
QDD = ["-37.0", "41.5", "12.0", "-55.5", "28.25", "-9.6", "63.0", "-24.4", "5.75", "-71.2", "33.3", "18.6"]


def full_turn(start, speed=1):
    """12 crank angles over a full revolution in [0, 2pi), 4 decimals"""
    out = []
    for k in range(12):
        q = start + 2 * math.pi * k / 12 + 0.037 * math.sin(1.7 * k)
        q = q % (2 * math.pi)
        out.append(OrderedDict(q="%.4f" % q, qd=str(mpf(QD[k]) * speed), qdd=str(mpf(QDD[k]) * speed)))
    return out


def mechanisms():
    out = []

    # ---------------------------------------------------------------- four_bar
    d = Drawing("four_bar", "Crank-rocker four-bar (Grashof) with a ternary coupler and a coupler point P")
    th2 = deg(60)
    O2 = d.point("O2", P(0, 0), ground=True)
    O4 = d.point("O4", P("0.30", "0.04"), ground=True)
    A = d.point("A", polar(O2, "0.08", th2))
    B = d.point("B", circles(A, "0.26", O4, "0.20", left=True))
    Pp = d.point("P", local(A, B, "0.13", "0.09"))
    d.link("crank", ["O2", "A"], "0.65", "0.00052", local(O2, A, "0.034", "0.006"))
    d.link("coupler", ["A", "B", "P"], "1.45", "0.0112", local(A, B, "0.125", "0.031"))
    d.link("rocker", ["O4", "B"], "0.95", "0.0036", local(O4, B, "0.094", "-0.008"))
    d.rev("O2", "ground", "crank")
    d.rev("A", "crank", "coupler")
    d.rev("B", "coupler", "rocker")
    d.rev("O4", "ground", "rocker")
    d.inputs = ["O2"]
    d.force("tool", "coupler", "P")
    d.torque("resist", "rocker")
    d.design.update(reference_crank_angle_deg=60, crank="0.08", coupler_AB="0.26", rocker="0.20",
                    ground_O2O4="(0.30, 0.04)", coupler_point="0.13 along AB, 0.09 left of AB",
                    assembly="B left of A->O4")
    cases = OrderedDict(loads=OrderedDict(tool=["-120.0", "-45.0"], resist="-6.5"),
                        configs=full_turn(0.21))
    out.append((d, cases))

    # ------------------------------------------------------------ slider_crank
    d = Drawing("slider_crank", "Offset slider-crank: piston on a horizontal guide 15 mm above the crank centre")
    th2 = deg(40)
    e = M("0.015")
    O2 = d.point("O2", P(0, 0), ground=True)
    A = d.point("A", polar(O2, "0.055", th2))
    l = M("0.19")
    B = d.point("B", (A[0] + mpmath.sqrt(l ** 2 - (e - A[1]) ** 2), e))
    d.link("crank", ["O2", "A"], "1.1", "0.00135", local(O2, A, "0.011", "0.0035"))
    d.link("rod", ["A", "B"], "0.85", "0.0032", local(A, B, "0.066", "0.004"))
    d.link("piston", ["B"], "0.62", "0.00036", add(B, P("-0.004", "-0.0025")))
    d.rev("O2", "ground", "crank")
    d.rev("A", "crank", "rod")
    d.rev("B", "rod", "piston")
    d.slide("prismatic", "guide", "ground", "piston", "B", P("1.0", "0"))
    d.inputs = ["O2"]
    d.force("gas", "piston", "B")
    d.torque("shaft", "crank")
    d.design.update(reference_crank_angle_deg=40, crank="0.055", rod="0.19", offset="0.015")
    cases = OrderedDict(loads=OrderedDict(gas=["-1850.0", "0"], shaft="-9.5"),
                        configs=full_turn(0.35, speed=2))
    out.append((d, cases))

    # ------------------------------------------------------------ quick_return
    d = Drawing("quick_return", "Crank-shaper quick-return: crank O2-A, block at A sliding in the slotted lever O4-C")
    O2 = d.point("O2", P(0, 0), ground=True)
    A = d.point("A", polar(O2, "0.10", deg(30)))
    O4 = d.point("O4", P("0", "-0.30"), ground=True)
    u = unit(sub(A, O4))
    C = d.point("C", add(O4, mul(M("0.55"), u)))
    d.link("crank", ["O2", "A"], "1.3", "0.0022", local(O2, A, "0.045", "0.005"))
    d.link("block", ["A"], "0.35", "0.00011", add(A, P("0.002", "0.003")))
    d.link("lever", ["O4", "C"], "2.6", "0.068", local(O4, C, "0.27", "0.012"))
    d.rev("O2", "ground", "crank")
    d.rev("A", "crank", "block")
    d.slide("prismatic", "slot", "lever", "block", "A", u)
    d.rev("O4", "ground", "lever")
    d.inputs = ["O2"]
    d.force("cut", "lever", "C")
    d.torque("friction", "crank")
    d.design.update(reference_crank_angle_deg=30, crank="0.10", O4="(0, -0.30)", lever="0.55",
                    slot_axis="unit(A - O4) in the drawing")
    cases = OrderedDict(loads=OrderedDict(cut=["-350.0", "-40.0"], friction="-2.5"),
                        configs=full_turn(0.13, speed=1))
    out.append((d, cases))

    # ------------------------------------------------------------------ watt2
    d = Drawing("watt2", "Watt II six-bar: crank-rocker O2-A-B-O4 whose ternary rocker drives a second four-bar O4-C-D-O6")
    O2 = d.point("O2", P(0, 0), ground=True)
    O4 = d.point("O4", P("0.26", "0.02"), ground=True)
    A = d.point("A", polar(O2, "0.07", deg(45)))
    B = d.point("B", circles(A, "0.24", O4, "0.17", left=True))
    thB = mpmath.atan2(B[1] - O4[1], B[0] - O4[0])
    C = d.point("C", polar(O4, "0.15", thB - deg(65)))
    O6 = d.point("O6", P("0.50", "0.16"), ground=True)
    D = d.point("D", circles(C, "0.21", O6, "0.15", left=True))
    d.link("crank", ["O2", "A"], "0.6", "0.00035", local(O2, A, "0.03", "0.005"))
    d.link("coupler", ["A", "B"], "1.1", "0.0058", local(A, B, "0.12", "0.007"))
    rcg = add(mul(M(1) / 3, add(add(O4, B), C)), P("0.004", "-0.003"))
    d.link("rocker", ["O4", "B", "C"], "1.6", "0.0061", rcg)
    d.link("link5", ["C", "D"], "0.9", "0.0036", local(C, D, "0.1", "-0.006"))
    d.link("rocker6", ["O6", "D"], "0.8", "0.0019", local(O6, D, "0.07", "0.009"))
    d.rev("O2", "ground", "crank")
    d.rev("A", "crank", "coupler")
    d.rev("B", "coupler", "rocker")
    d.rev("O4", "ground", "rocker")
    d.rev("C", "rocker", "link5")
    d.rev("D", "link5", "rocker6")
    d.rev("O6", "ground", "rocker6")
    d.inputs = ["O2"]
    d.force("output", "rocker6", "D")
    d.torque("resist", "rocker6")
    d.design.update(reference_crank_angle_deg=45, crank="0.07", coupler_AB="0.24", rocker_O4B="0.17",
                    rocker_O4C="0.15 at 65 deg clockwise from O4B", link5_CD="0.21", rocker6_O6D="0.15",
                    O6="(0.50, 0.16)")
    cases = OrderedDict(loads=OrderedDict(output=["-80.0", "-30.0"], resist="-3.5"),
                        configs=full_turn(0.29, speed=1))
    out.append((d, cases))

    # ------------------------------------------------------------ stephenson3
    d = Drawing("stephenson3", "Stephenson III six-bar: crank-rocker O2-A-B-O4 with a ternary coupler; dyad C-D-O6 on the coupler point C")
    O2 = d.point("O2", P(0, 0), ground=True)
    O4 = d.point("O4", P("0.28", "0"), ground=True)
    A = d.point("A", polar(O2, "0.075", deg(70)))
    B = d.point("B", circles(A, "0.25", O4, "0.20", left=True))
    C = d.point("C", local(A, B, "0.10", "0.10"))
    O6 = d.point("O6", P("-0.05", "0.36"), ground=True)
    D = d.point("D", circles(C, "0.22", O6, "0.18", left=False))
    d.link("crank", ["O2", "A"], "0.62", "0.00038", local(O2, A, "0.032", "-0.004"))
    ccg = add(mul(M(1) / 3, add(add(A, B), C)), P("-0.003", "0.002"))
    d.link("coupler", ["A", "B", "C"], "1.35", "0.0092", ccg)
    d.link("rocker", ["O4", "B"], "0.9", "0.0031", local(O4, B, "0.1", "0.007"))
    d.link("link5", ["C", "D"], "0.85", "0.0035", local(C, D, "0.11", "0.006"))
    d.link("link6", ["O6", "D"], "0.75", "0.0021", local(O6, D, "0.085", "-0.007"))
    d.rev("O2", "ground", "crank")
    d.rev("A", "crank", "coupler")
    d.rev("B", "coupler", "rocker")
    d.rev("O4", "ground", "rocker")
    d.rev("C", "coupler", "link5")
    d.rev("D", "link5", "link6")
    d.rev("O6", "ground", "link6")
    d.inputs = ["O2"]
    d.force("load", "link5", "D")
    d.torque("resist", "link6")
    d.design.update(reference_crank_angle_deg=70, crank="0.075", coupler_AB="0.25", rocker="0.20",
                    coupler_point_C="0.10 along AB, 0.10 left", link5_CD="0.22", link6_O6D="0.18",
                    O6="(-0.05, 0.36)")
    cases = OrderedDict(loads=OrderedDict(load=["-60.0", "-25.0"], resist="2.2"),
                        configs=full_turn(0.47, speed=1))
    out.append((d, cases))

    # ------------------------------------------------------------- scotch_yoke
    d = Drawing("scotch_yoke", "Scotch yoke: crank pin A in the vertical slot of a yoke guided horizontally at Y")
    O2 = d.point("O2", P(0, 0), ground=True)
    A = d.point("A", polar(O2, "0.06", deg(50)))
    Y = d.point("Y", P("0.20", "0"))
    d.link("crank", ["O2", "A"], "0.7", "0.00031", local(O2, A, "0.022", "0.004"))
    d.link("yoke", ["Y"], "1.9", "0.0068", P("0.13", "0.004"))
    d.rev("O2", "ground", "crank")
    d.slide("prismatic", "guide", "ground", "yoke", "Y", P("1.0", "0"))
    d.slide("pin_in_slot", "slot", "yoke", "crank", "A", P("0", "1.0"))
    d.inputs = ["O2"]
    d.force("resist", "yoke", "Y")
    d.torque("drag", "crank")
    d.design.update(reference_crank_angle_deg=50, crank="0.06", yoke_guide_y="0")
    cases = OrderedDict(loads=OrderedDict(resist=["-240.0", "15.0"], drag="-1.2"),
                        configs=full_turn(0.05, speed=2))
    out.append((d, cases))

    # ---------------------------------------------------------------- five_bar
    d = Drawing("five_bar", "Two-DOF five-bar: cranks at O1 and O5 driven independently, links meet at C")
    O1 = d.point("O1", P(0, 0), ground=True)
    O5 = d.point("O5", P("0.20", "0"), ground=True)
    A = d.point("A", polar(O1, "0.10", deg(110)))
    B = d.point("B", polar(O5, "0.11", deg(65)))
    C = d.point("C", circles(A, "0.24", B, "0.22", left=True))
    d.link("crank1", ["O1", "A"], "0.55", "0.0006", local(O1, A, "0.045", "0.005"))
    d.link("link2", ["A", "C"], "0.8", "0.0042", local(A, C, "0.11", "-0.006"))
    d.link("link3", ["B", "C"], "0.75", "0.0034", local(B, C, "0.1", "0.005"))
    d.link("crank4", ["O5", "B"], "0.6", "0.0007", local(O5, B, "0.05", "-0.004"))
    d.rev("O1", "ground", "crank1")
    d.rev("A", "crank1", "link2")
    d.rev("C", "link2", "link3")
    d.rev("B", "link3", "crank4")
    d.rev("O5", "ground", "crank4")
    d.inputs = ["O1", "O5"]
    d.force("pen", "link2", "C")
    d.torque("twist", "link3")
    d.design.update(reference_crank1_angle_deg=110, reference_crank4_angle_deg=65, crank1="0.10",
                    link2_AC="0.24", link3_BC="0.22", crank4="0.11", O5="(0.20, 0)",
                    assembly="C left of A->B (above the cranks)")
    q1r = 110 * math.pi / 180
    q2r = 65 * math.pi / 180
    offs = [(0.11, -0.07), (-0.23, 0.14), (0.31, 0.22), (-0.35, -0.18), (0.05, 0.33), (-0.12, -0.31),
            (0.27, -0.25), (-0.29, 0.29), (0.18, 0.09), (-0.06, -0.12), (0.34, 0.02), (-0.17, 0.24)]
    cfg = []
    for k, (a, b) in enumerate(offs):
        cfg.append(OrderedDict(q=["%.4f" % (q1r + a), "%.4f" % (q2r + b)],
                               qd=[QD[k], QD[(k + 5) % 12]], qdd=[QDD[k], QDD[(k + 7) % 12]]))
    cases = OrderedDict(loads=OrderedDict(pen=["35.0", "-60.0"], twist="1.8"), configs=cfg)
    out.append((d, cases))

    # --------------------------------------------------------- hydraulic_lever
    d = Drawing("hydraulic_lever", "Hydraulic lever: cylinder C0 (pinned to ground) and rod L (pinned to the lever) drive the lever O-L-E; input = stroke")
    O = d.point("O", P(0, 0), ground=True)
    L = d.point("L", P("0.26", "0.04"))
    E = d.point("E", P("0.72", "0.15"))
    C0 = d.point("C0", P("0.12", "-0.42"), ground=True)
    u = unit(sub(L, C0))
    d.link("lever", ["O", "L", "E"], "4.8", "0.23", local(O, E, "0.34", "0.021"))
    d.link("cylinder", ["C0"], "3.2", "0.045", add(C0, mul(M("0.16"), u)))
    d.link("rod", ["L"], "1.3", "0.012", sub(L, mul(M("0.15"), u)))
    d.rev("O", "ground", "lever")
    d.rev("C0", "ground", "cylinder")
    d.rev("L", "lever", "rod")
    d.slide("prismatic", "stroke", "cylinder", "rod", "L", u)
    d.inputs = ["stroke"]
    d.force("payload", "lever", "E")
    d.torque("damper", "lever")
    d.design.update(pin_to_pin_C0_L="0.4808 in the drawing", stroke_range="-0.12 .. +0.12 m",
                    axis="unit(L - C0) in the drawing", cylinder_cg="0.16 from C0 along the axis",
                    rod_cg="0.15 from L back along the axis")
    qs = ["-0.1", "-0.0815", "-0.062", "-0.0433", "-0.021", "-0.0072", "0.0125", "0.0318", "0.0507",
          "0.0736", "0.094", "0.118"]
    qds = ["0.12", "-0.085", "0.21", "0.064", "-0.18", "0.099", "-0.0475", "0.152", "-0.116", "0.0705",
           "0.234", "-0.138"]
    qdds = ["-0.37", "0.415", "0.12", "-0.555", "0.2825", "-0.096", "0.63", "-0.244", "0.0575",
            "-0.712", "0.333", "0.186"]
    cfg = [OrderedDict(q=a, qd=b, qdd=c) for a, b, c in zip(qs, qds, qdds)]
    cases = OrderedDict(loads=OrderedDict(payload=["0", "-900.0"], damper="-12.0"), configs=cfg)
    out.append((d, cases))
    return out


SWEEPS = ("slider_crank", "four_bar")


def survey(spec, cases):
    """worst conditioning of Phi_x over the configs and (1 DOF) a sweep"""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import reference as R
    old = mp.dps
    mp.dps = 20
    try:
        spec = json.loads(json.dumps(spec), parse_float=mpf, object_pairs_hook=OrderedDict)
        mech = R.Mechanism(spec)
        worst = None
        pts = []
        for c in cases["configs"]:
            q = c["q"]
            q = [mpf(v) for v in q] if isinstance(q, list) else [mpf(q)]
            x, _ = mech.continue_to(q)
            pts.append((q, x))
        if mech.dof == 1 and mech.jmap[mech.inputs[0]]["type"] == "revolute":
            x, q = mech.x_ref, mech.q_ref
            for k in range(1, 73):
                qk = [mech.q_ref[0] + 2 * mp.pi * k / 72]
                x, _ = mech.continue_to(qk, x, q)
                q = qk
                pts.append((q, x))
            closure = max(abs(a - b) for i, (a, b) in enumerate(zip(x, mech.x_ref)) if i % 3 != 2)
            if closure > mpf("1e-10"):
                raise RuntimeError("%s: not back at the drawing after a turn" % mech.name)
        for q, x in pts:
            _, J = mech.phi_and_jac(x, q)
            s = mp.svd_r(mpmath.matrix(J), compute_uv=False)
            c = max(s) / min(s)
            if worst is None or c > worst[0]:
                worst = (c, q)
        return worst
    finally:
        mp.dps = old


def main(argv):
    import outroot
    root, argv = outroot.split(argv)
    for d, cases in mechanisms():
        spec = d.to_json()
        with open(outroot.path(root, "tests", "data", d.name + ".mechanism.json"), "w") as f:
            f.write(dumps(spec) + "\n")
        with open(outroot.path(root, "tools", "cases", d.name + ".cases.json"), "w") as f:
            f.write(dumps(cases) + "\n")
        msg = "%-16s N=%d P_I=%d P_II=%d G=%d" % (
            d.name, spec["structure"]["N_links_including_ground"], spec["structure"]["P_I"],
            spec["structure"]["P_II"], spec["structure"]["grubler_dof"])
        if "--survey" in argv:
            c, q = survey(spec, cases)
            msg += "  worst cond(Phi_x) %.1f at q=%s" % (c, [mpmath.nstr(v, 6) for v in q])
        print(msg)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
