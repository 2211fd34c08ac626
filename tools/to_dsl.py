#!/usr/bin/env python3
"""Write tests/common/mechanisms.rs: one `mechanism! { ... }` per drawing in
tests/data/*.mechanism.json, in the DSL of docs/conventions.md (section DSL).

Numbers are the drawings' "float" values written as Rust f64 literals that
round-trip exactly (Python repr of the double, always with a '.' in the
mantissa).  Struct names are the CamelCase of the JSON names
(public_slider_crank -> PublicSliderCrank, watt2 -> Watt2).

Usage: python3 tools/to_dsl.py [--out-root DIR] [OUT.rs]
  --out-root DIR  read DIR/tests/data/*.mechanism.json and write DIR/tests/common/mechanisms.rs
                  (tools/outroot.py); OUT.rs, when given, is the file written
"""

import json
import os
import sys
from collections import OrderedDict

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data")
OUT = os.path.join(ROOT, "tests", "common", "mechanisms.rs")

# the order of the structs in the generated file
ORDER = ["public_slider_crank", "public_four_bar", "four_bar", "slider_crank", "quick_return",
         "watt2", "stephenson3", "scotch_yoke", "five_bar", "hydraulic_lever"]


def lit(x):
    """f64 literal that parses back to exactly x"""
    x = float(x)
    if x == 0:
        return "0.0"
    r = repr(x)
    if "e" in r:
        mant, exp = r.split("e")
        if "." not in mant:
            mant += ".0"
        r = "%se%d" % (mant, int(exp))
    elif "." not in r:
        r += ".0"
    assert float(r) == x
    return r


def vec(v):
    return "(%s, %s)" % (lit(v[0]), lit(v[1]))


def camel(name):
    return "".join(p[:1].upper() + p[1:] for p in name.split("_"))


def ident_ok(s):
    return s.isidentifier() and s not in {
        "as", "break", "const", "continue", "crate", "else", "enum", "extern", "false", "fn", "for",
        "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref", "return",
        "self", "Self", "static", "struct", "super", "trait", "true", "type", "unsafe", "use",
        "where", "while", "async", "await", "dyn", "abstract", "become", "box", "do", "final",
        "macro", "override", "priv", "typeof", "unsized", "virtual", "yield", "try"}


def to_dsl(spec):
    pts = spec["points"]
    for n in list(pts) + [l["name"] for l in spec["links"]] + [j["name"] for j in spec["joints"]] \
            + [l["name"] for l in spec.get("loads", [])]:
        if not ident_ok(n):
            raise ValueError("%s: %r is not a valid Rust identifier" % (spec["name"], n))
    I = "    "
    out = []
    out.append("mechanism! {")
    out.append(I + "/// " + spec.get("description", spec["name"]).strip())
    out.append(I + "pub struct %s {" % camel(spec["name"]))
    if "gravity" in spec:
        out.append(2 * I + "gravity: %s," % vec(spec["gravity"]["float"]))
    defined = set()
    gp = []
    for p in spec["ground"]["points"]:
        gp.append("%s: %s" % (p, vec(pts[p]["float"])))
        defined.add(p)
    out.append(2 * I + "ground { %s }," % ", ".join(gp))
    for l in spec["links"]:
        out.append(2 * I + "link %s {" % l["name"])
        ps = []
        for p in l["points"]:
            if p in defined:
                ps.append(p)
            else:
                ps.append("%s: %s" % (p, vec(pts[p]["float"])))
                defined.add(p)
        out.append(3 * I + "points { %s }," % ", ".join(ps))
        props = []
        if "mass" in l:
            props.append("mass: %s" % lit(l["mass"]["float"]))
        if "inertia" in l:
            props.append("inertia: %s" % lit(l["inertia"]["float"]))
        if "cg" in l:
            props.append("cg: %s" % vec(l["cg"]["float"]))
        if props:
            out.append(3 * I + ", ".join(props) + ",")
        out.append(2 * I + "},")
    undefined = set(pts) - defined
    if undefined:
        raise ValueError("%s: points %s belong to no link" % (spec["name"], sorted(undefined)))
    out.append(2 * I + "joints {")
    for j in spec["joints"]:
        s = "%s: %s(%s, %s)" % (j["name"], j["type"], j["a"], j["b"])
        if j["type"] == "revolute":
            if j["point"] != j["name"]:
                s += " at %s" % j["point"]
        else:
            s += " at %s along %s" % (j["point"], vec(j["axis"]["float"]))
        out.append(3 * I + s + ",")
    out.append(2 * I + "},")
    if len(spec["inputs"]) == 1:
        out.append(2 * I + "input: %s," % spec["inputs"][0])
    else:
        out.append(2 * I + "inputs: [%s]," % ", ".join(spec["inputs"]))
    if spec.get("loads"):
        out.append(2 * I + "loads {")
        for ld in spec["loads"]:
            if ld["type"] == "force":
                out.append(3 * I + "%s: force on %s at %s," % (ld["name"], ld["link"], ld["point"]))
            else:
                out.append(3 * I + "%s: torque on %s," % (ld["name"], ld["link"]))
        out.append(2 * I + "},")
    out.append(I + "}")
    out.append("}")
    return "\n".join(out)


def main(argv):
    import outroot
    root, argv = outroot.split(argv)
    DATA = os.path.join(root, "tests", "data")
    out_path = argv[0] if argv else os.path.join(root, "tests", "common", "mechanisms.rs")
    names = [n for n in ORDER if os.path.exists(os.path.join(DATA, n + ".mechanism.json"))]
    extra = sorted(f[:-len(".mechanism.json")] for f in os.listdir(DATA)
                   if f.endswith(".mechanism.json") and f[:-len(".mechanism.json")] not in ORDER)
    blocks = []
    for n in names + extra:
        with open(os.path.join(DATA, n + ".mechanism.json")) as f:
            spec = json.load(f, object_pairs_hook=OrderedDict)
        blocks.append("// tests/data/%s.mechanism.json\n" % n + to_dsl(spec))
    head = ("// Generated by tools/to_dsl.py from tests/data/*.mechanism.json -- do not edit by hand;\n"
            "// regenerate with `python3 tools/generate_all.py` (see tools/README.md).\n"
            "// Numbers are the drawings' f64 values (exact round-trip); the high-precision answers\n"
            "// are in tests/data/<name>.truth.json.\n\n"
            "use mech::prelude::*;\n")
    os.makedirs(os.path.dirname(out_path), exist_ok=True)
    with open(out_path, "w") as f:
        f.write(head + "\n" + "\n\n".join(blocks) + "\n")
    print("wrote %s (%d mechanisms: %s)" % (out_path, len(blocks), ", ".join(camel(n) for n in names + extra)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
