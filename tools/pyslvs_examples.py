#!/usr/bin/env python3
"""pyslvs's example mechanisms, with reference positions, for `mech import`'s tests.

    python3 tools/pyslvs_examples.py [--out-root DIR] [path/to/pyslvs/example.py]

Reads the examples (name -> (PMKS expression, inputs)) from pyslvs's `example.py` with
Python's `ast` (no import of pyslvs needed; without an argument the file comes from
`pip download pyslvs==22.7.0 --no-deps`), and writes tests/data/pyslvs/examples.json:
for each example its expression, its inputs (pairs of joint indices) and the positions
of every joint at three input angles: the drawing's own and ±20° from it (±10°, ±5°
when the mechanism does not reach that far).

Two references per configuration: "positions", from the independent solver below
(numpy): each link a rigid body (x, y, φ), the joints' equations (a pin: the same point
on each link; a slider: the pin on the slot's line; P: no relative turn), the input
link's angle fixed, Gauss-Newton from the drawing by continuation in the input angle (so
it stays on the drawing's assembly, as mech does); and "pyslvs", pyslvs's own solver
(`parse_vpoints`, `t_config`, `expr_solving`) when pyslvs can be imported (pip install
pyslvs needs `cython==3.0.0` and `--no-build-isolation` here). pyslvs's closed forms fix
each dyad's branch by its own rule, so at an input away from the drawing it may give the
other assembly; the test counts those configurations exactly.
"""

import ast
import json
import math
import os
import subprocess
import sys
import tarfile
import tempfile

import numpy as np

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
OUT = os.path.join(ROOT, "tests", "data", "pyslvs", "examples.json")
OFFSETS_DEG = (0.0, 20.0, -20.0, 10.0, -10.0, 5.0, -5.0)
CONFIGS = 3


def example_source(argv):
    if len(argv) > 1:
        return open(argv[1]).read()
    tmp = tempfile.mkdtemp()
    subprocess.run([sys.executable, "-m", "pip", "download", "pyslvs==22.7.0", "--no-deps", "--no-binary", ":all:", "-d", tmp, "-q"], check=True)
    tar = tarfile.open(os.path.join(tmp, "pyslvs-22.7.0.tar.gz"))
    return tar.extractfile("pyslvs-22.7.0/pyslvs/example.py").read().decode()


def examples(source):
    """name -> (expression, inputs) from the `_example_list` literal."""
    tree = ast.parse(source)
    for node in ast.walk(tree):
        target = getattr(node, "target", None) or (node.targets[0] if isinstance(node, ast.Assign) else None)
        if isinstance(target, ast.Name) and target.id == "_example_list":
            return ast.literal_eval(node.value)
    raise RuntimeError("no _example_list in example.py")


# ---------------------------------------------------------------------------------------
# A minimal PMKS reader (the grammar of pyslvs's expression_parser.py)

def parse(expr):
    import re
    joints = []
    for m in re.finditer(r"J\[\s*(RP|R|P)\s*,(.*?)P\[\s*([-+0-9.eE]+)\s*,\s*([-+0-9.eE]+)\s*\]\s*,\s*L\[([^\]]*)\]\s*\]", expr):
        kind, mid, x, y, links = m.groups()
        a = re.search(r"A\[\s*([-+0-9.eE]+)\s*\]", mid)
        joints.append({"type": kind, "angle": float(a.group(1)) if a else 0.0, "at": (float(x), float(y)),
                       "links": [l.strip() for l in links.split(",") if l.strip()]})
    return joints


# ---------------------------------------------------------------------------------------
# The independent solver

class Model:
    def __init__(self, joints, inputs):
        self.j = joints
        names = []
        for jt in joints:
            for l in jt["links"]:
                if l != "ground" and l not in names:
                    names.append(l)
        self.links = names
        self.index = {l: i for i, l in enumerate(names)}
        # each link's reference frame: origin at its first point, φ = 0 in the drawing
        self.origin = {}
        for jt in joints:
            for l in jt["links"]:
                if l != "ground" and l not in self.origin:
                    self.origin[l] = np.array(jt["at"])
        self.inputs = inputs

    def pos(self, z, link, local):
        if link == "ground":
            return local
        i = self.index[link]
        x, y, p = z[3 * i:3 * i + 3]
        c, s = math.cos(p), math.sin(p)
        return np.array([x + c * local[0] - s * local[1], y + s * local[0] + c * local[1]])

    def phi(self, z, link):
        return 0.0 if link == "ground" else z[3 * self.index[link] + 2]

    def local(self, link, p):
        return np.array(p) - (self.origin[link] if link != "ground" else 0.0)

    def residual(self, z, angles):
        r = []
        for jt in self.j:
            at, links = jt["at"], jt["links"]
            if jt["type"] == "R":
                base = links[0]
                for l in links[1:]:
                    r.extend(self.pos(z, base, self.local(base, at)) - self.pos(z, l, self.local(l, at)))
            elif len(links) >= 2:
                slot, pins = links[0], links[1:]
                u = np.array([math.cos(math.radians(jt["angle"])), math.sin(math.radians(jt["angle"]))])
                ps = self.phi(z, slot)
                c, s = math.cos(ps), math.sin(ps)
                n = np.array([-(s * u[0] + c * u[1]), c * u[0] - s * u[1]])
                q0 = self.pos(z, slot, self.local(slot, at))
                p0 = self.pos(z, pins[0], self.local(pins[0], at))
                r.append(n @ (p0 - q0))
                if jt["type"] == "P":
                    r.append(self.phi(z, pins[0]) - ps)
                for l in pins[1:]:
                    r.extend(p0 - self.pos(z, l, self.local(l, at)))
        for (b, d), ang in zip(self.inputs, angles):
            if b == d:
                continue
            link = next(l for l in self.j[b]["links"] if l in self.j[d]["links"] and l != "ground")
            pb = self.pos(z, link, self.local(link, self.j[b]["at"]))
            pd = self.pos(z, link, self.local(link, self.j[d]["at"]))
            v = pd - pb
            r.append(math.atan2(v[1] * math.cos(ang) - v[0] * math.sin(ang), v[0] * math.cos(ang) + v[1] * math.sin(ang)))
        return np.array(r)

    def z0(self):
        z = np.zeros(3 * len(self.links))
        for l, i in self.index.items():
            z[3 * i:3 * i + 2] = self.origin[l]
        return z

    def solve(self, z, angles):
        scale = max(1.0, max(abs(c) for jt in self.j for c in jt["at"]))
        for _ in range(100):
            r = self.residual(z, angles)
            if np.max(np.abs(r)) < 1e-13 * scale:
                return z
            h = 1e-7
            J = np.empty((len(r), len(z)))
            for k in range(len(z)):
                e = np.zeros(len(z))
                e[k] = h
                J[:, k] = (self.residual(z + e, angles) - self.residual(z - e, angles)) / (2 * h)
            dz = np.linalg.lstsq(J, -r, rcond=None)[0]
            z = z + dz
        raise RuntimeError("no convergence")

    def points(self, z):
        out = []
        for jt in self.j:
            holder = next((l for l in (jt["links"][1:] if jt["type"] != "R" else jt["links"]) if l != "ground"), None)
            out.append(list(self.pos(z, holder, self.local(holder, jt["at"]))) if holder else list(jt["at"]))
        return out


def drawing_angle(joints, b, d):
    (xb, yb), (xd, yd) = joints[b]["at"], joints[d]["at"]
    return math.atan2(yd - yb, xd - xb)


def independent(expr, inputs):
    joints = parse(expr)
    m = Model(joints, inputs)
    base = [drawing_angle(joints, b, d) for b, d in inputs]
    out = []
    for off in OFFSETS_DEG:
        z = m.z0()
        target = [a + math.radians(off) for a in base]
        try:
            for t in np.linspace(0.0, 1.0, 21)[1:] if off else [1.0]:
                z = m.solve(z, [a + t * math.radians(off) for a in base])
        except RuntimeError:
            continue  # this input does not assemble from the drawing: try a smaller step
        out.append({"angles": target, "positions": m.points(z)})
        if len(out) == CONFIGS:
            break
    return out


def with_pyslvs(expr, inputs):
    from pyslvs import expr_solving, parse_vpoints, t_config
    vpoints = parse_vpoints(expr)
    exprs = t_config(vpoints, inputs)
    joints = parse(expr)
    base = [drawing_angle(joints, b, d) for b, d in inputs]
    out = []
    for off in OFFSETS_DEG:
        angles = {pair: math.degrees(a) + off for pair, a in zip(inputs, base)}
        try:
            res = expr_solving(exprs, vpoints, angles)
        except Exception:
            continue
        pts = [list(c[1]) if isinstance(c[0], (tuple, list)) else list(c) for c in res]
        out.append({"angles": [math.radians(angles[p]) for p in inputs], "positions": pts})
        if len(out) == CONFIGS:
            break
    return out


def main(argv):
    import outroot
    root, argv = outroot.split(argv)
    out_path = outroot.path(root, "tests", "data", "pyslvs", "examples.json")
    ex = examples(example_source(argv))
    try:
        import pyslvs  # noqa: F401
        have_pyslvs = True
    except Exception:
        have_pyslvs = False
    how = "pyslvs 22.7.0 expr_solving" if have_pyslvs else "none: pyslvs could not be built here"
    out = {"source": "pyslvs 22.7.0 pyslvs/example.py", "reference": how,
           "continuation": "independent Gauss-Newton solver of tools/pyslvs_examples.py, by continuation from the drawing",
           "examples": []}
    for name, (expr, inputs) in ex.items():
        entry = {"name": name, "expression": expr, "inputs": [list(p) for p in inputs]}
        pairs = [tuple(p) for p in inputs]
        configs = independent(expr, pairs)
        if have_pyslvs:
            theirs = {tuple(c["angles"]): c["positions"] for c in with_pyslvs(expr, pairs)}
            for c in configs:
                # pyslvs's own positions at the same input angles (None where it has none)
                c["pyslvs"] = theirs.get(tuple(c["angles"]))
        entry["configs"] = configs
        out["examples"].append(entry)
    with open(out_path, "w") as f:
        json.dump(out, f, indent=1)
    print("wrote", out_path, len(out["examples"]), "examples;", how)


if __name__ == "__main__":
    main(sys.argv)
