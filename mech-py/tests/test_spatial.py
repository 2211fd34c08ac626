"""Spatial mechanisms (SPEC 3i) from Python: mech.Mechanism.load of a `space` file gives a
mech.SpatialMechanism whose dicts carry the `mech` tool's spatial column names; the RSSR
against its closed-form geometry and virtual work, the double-wishbone suspension against
its 50-digit mpmath table (tests/data/spatial/double_wishbone.truth.json)."""

import json
import math
import pathlib
import pickle

import numpy as np
import pytest

import mech

ROOT = pathlib.Path(__file__).resolve().parents[2]
RSSR = ROOT / "examples" / "mech" / "rssr.mech"
WISHBONE = ROOT / "examples" / "mech" / "double_wishbone.mech"


def test_the_rssr_answers_with_the_spatial_columns():
    m = mech.Mechanism.load(str(RSSR))
    assert isinstance(m, mech.SpatialMechanism)
    assert repr(m) == "mech.SpatialMechanism('Rssr', dof=1)"
    assert (m.name, m.dof, m.text) == ("Rssr", 1, RSSR.read_text())
    assert m.idle_links == ["rod"]
    assert m.load_names == [("tool", "torque"), ("push", "force")]
    q = np.array([0.0, 0.7, 2.5])
    k = m.kinematics(q, qd=2.0, qdd=-1.0)
    # The crank turns A = (0, 0.05, 0) about x; the rocker keeps B at C's height; the rod
    # and the rocker keep their lengths.
    np.testing.assert_allclose(k["A.x"], 0.0, atol=1e-15)
    np.testing.assert_allclose(k["A.y"], 0.05 * np.cos(q), rtol=0, atol=1e-15)
    np.testing.assert_allclose(k["A.z"], 0.05 * np.sin(q), rtol=0, atol=1e-15)
    np.testing.assert_allclose(k["A.vz"], 0.05 * np.cos(q) * 2.0, rtol=0, atol=1e-14)
    np.testing.assert_allclose(k["B.z"], 0.08, rtol=0, atol=1e-14)
    rod = math.dist((0.0, 0.05, 0.0), (0.25, 0.02, 0.08))
    ab = np.sqrt(sum((k["B." + c] - k["A." + c]) ** 2 for c in "xyz"))
    np.testing.assert_allclose(ab, rod, rtol=1e-14)
    np.testing.assert_allclose(k["crank.omega_x"], 2.0, rtol=1e-14)
    np.testing.assert_allclose(k["crank.alpha_x"], -1.0, rtol=1e-14)
    quat = np.sqrt(sum(k["rocker." + c] ** 2 for c in ("qw", "qx", "qy", "qz")))
    np.testing.assert_allclose(quat, 1.0, rtol=1e-14)
    # Reactions: SPEC 3i's columns; a ball joint carries no moment.
    f = m.kinetostatics(0.7, loads={"push": (40.0, -30.0, 25.0)})
    for c in ("A.fx", "A.fy", "A.fz", "A.mx", "A.my", "A.mz", "O.mz", "driver"):
        assert c in f, c
    assert (f["A.mx"], f["A.my"], f["A.mz"]) == (0.0, 0.0, 0.0)
    # The load's share of the driver is minus its virtual work at q̇ = 1.
    bare = m.kinetostatics(0.7)["driver"]
    v = m.kinematics(0.7, qd=1.0)
    work = 40.0 * v["B.vx"] - 30.0 * v["B.vy"] + 25.0 * v["B.vz"]
    assert abs(work) > 0.1
    assert abs((f["driver"] - bare) + work) < 1e-10 * abs(work)
    # The three routes to the torque.
    vp = m.driver_action(0.7, qd=3.0, qdd=2.0, loads={"tool": (0.5, -1.0, 2.0)})["driver"]
    ne = m.kinetostatics(0.7, qd=3.0, qdd=2.0, loads={"tool": (0.5, -1.0, 2.0)})["driver"]
    z = m.reduced(0.7)
    zm = m.reduced_moment(0.7, loads={"tool": (0.5, -1.0, 2.0)})["moment"]
    assert abs(vp - ne) < 1e-10 * abs(ne)
    assert abs(z["inertia"] * 2.0 + 0.5 * z["inertia_derivative"] * 9.0 - zm - ne) < 1e-9 * abs(ne)
    # Pickles; the planar loader's rule for bad loads.
    assert pickle.loads(pickle.dumps(m)).kinetostatics(0.7)["driver"] == bare
    with pytest.raises(mech.InvalidInput, match="three components"):
        m.kinetostatics(0.7, loads={"push": (40.0, -30.0)})


def test_the_direct_problem_inverts_the_driver_torque():
    """q̈ from the direct problem, put back into d'Alembert's kinetostatics at that state,
    gives the driver torque it was computed from (row by row, loads per row)."""
    m = mech.Mechanism.load(str(RSSR))
    q = np.linspace(0.1, 6.0, 7)
    qd = np.linspace(-4.0, 9.0, 7)
    driver = np.linspace(-2.0, 3.0, 7)
    tool = np.column_stack([np.zeros(7), np.zeros(7), np.linspace(-1.0, 1.0, 7)])
    out = m.acceleration(q, qd, driver, loads={"tool": tool})
    qdd = out["qdd"]
    assert qdd.shape == (7,) and np.all(np.isfinite(qdd))
    for i in range(7):
        back = m.kinetostatics(q[i], qd=qd[i], qdd=qdd[i], loads={"tool": tuple(tool[i])})["driver"]
        assert abs(back - driver[i]) < 1e-10 * max(1.0, abs(driver[i])), (i, back, driver[i])
    # A callable driver and a scalar q, as for a planar mechanism.
    one = m.acceleration(0.7, 2.0, lambda x: 0.5)["qdd"]
    assert one == m.acceleration(0.7, 2.0, 0.5)["qdd"]
    bad = m.acceleration([0.7, float("nan")], 1.0, 0.0, errors="mask")
    assert list(bad["ok"]) == [True, False] and math.isnan(bad["qdd"][1])


def test_the_flywheel_of_a_spatial_machine():
    """The fluctuation of energy against a trapezoid of M* over the turn (4000 points), the
    simulated irregularity the one asked; a prismatic-input or bad call refused."""
    m = mech.Mechanism.load(str(RSSR))
    tool = (0.0, 0.0, -1.5)
    fw = m.flywheel(2 * np.pi, 2 * np.pi, 0.05, loads={"tool": tool})
    q = np.linspace(0.0, 2 * np.pi, 4001)
    moment = m.reduced_moment(q, loads={"tool": np.tile(tool, (4001, 1))})["moment"]
    s = np.concatenate([[0.0], np.cumsum(0.5 * (moment[1:] + moment[:-1]) * np.diff(q))])
    assert abs(s[-1]) < 1e-9 and abs(fw["net_work"]) < 1e-9
    assert abs(fw["fluctuation"] - (s.max() - s.min())) < 1e-6 * fw["fluctuation"]
    assert abs(fw["irregularity_simulated"] - 0.05) < 1e-6
    assert fw["inertia_exact"] > 0.0
    with pytest.raises(mech.InvalidInput):
        m.flywheel(2 * np.pi, 2 * np.pi, 5.0)


def test_a_bad_spatial_text_names_its_line():
    text = RSSR.read_text().replace("revolute(ground, rocker)", "revolute(ground, rocket)")
    with pytest.raises(mech.InvalidMechanism) as e:
        mech.Mechanism.from_dsl(text)
    line = next(i for i, l in enumerate(text.splitlines(), 1) if "rocket" in l)
    assert e.value.line == line
    assert "unknown link `rocket`" in str(e.value)


def test_the_double_wishbone_matches_the_mpmath_table():
    truth = json.loads((ROOT / "tests" / "data" / "spatial" / "double_wishbone.truth.json").read_text())
    m = mech.Mechanism.load(str(WISHBONE))
    cases = truth["cases"]
    q = np.array([float(c["q"]) for c in cases])
    qd = np.array([float(c["qd"]) for c in cases])
    qdd = np.array([float(c["qdd"]) for c in cases])
    loads = {n: tuple(float(x) for x in v) for n, v in truth["loads"].items()}
    k = m.kinematics(q, qd, qdd)
    f = m.kinetostatics(q, qd, qdd, loads=loads)
    for i, c in enumerate(cases):
        for p, v in c["points"].items():
            for j, s in enumerate("xyz"):
                assert abs(k["%s.%s" % (p, s)][i] - float(v["pos"][j])) < 1e-12
        scale = max(abs(float(c["driver"])), 1e3)
        assert abs(f["driver"][i] - float(c["driver"])) < 1e-12 * scale
        for jn, r in c["reactions"].items():
            for j, s in enumerate("xyz"):
                assert abs(f["%s.f%s" % (jn, s)][i] - float(r["force"][j])) < 1e-12 * scale
                assert abs(f["%s.m%s" % (jn, s)][i] - float(r["moment"][j])) < 1e-12 * scale


def test_sweep_varies_a_spatial_mechanism_as_edited_texts():
    """mech.sweep over a spatial mechanism: each variant's columns are those of the text
    edited by hand (the rod's mass, the rocker's pivot C); a variant whose drawing fails a
    check (the rocker's axis through B) is NaN with ok False; set_param pickles."""
    m = mech.Mechanism.load(str(RSSR))
    text = RSSR.read_text()
    q = np.array([0.3, 1.7, 4.0])
    loads = {"push": (4.0, -3.0, 2.5)}
    masses = np.array([0.5, 0.8, 1.3])
    out = mech.sweep(m, {"links.rod.mass": masses}, q, qd=3.0, qdd=-1.0, loads=loads, parts=["driver"])
    assert out["driver"].shape == (3, 3) and out["ok"].all()
    for v, mass in enumerate(masses):
        edited = mech.Mechanism.from_dsl(text.replace("mass: 0.5", "mass: %r" % float(mass), 1))
        want = edited.kinetostatics(q, qd=3.0, qdd=-1.0, loads=loads)["driver"]
        np.testing.assert_allclose(out["driver"][v], want, rtol=1e-13, atol=0)
    pivots = np.array([[0.25, 0.12, 0.08], [0.26, 0.12, 0.07]])
    out = mech.sweep(m, [{"points.C": pivots[0]}, {"points.C": pivots[1]}, {"axes.C": (0.0, 1.0, 0.0)}], q, parts=["positions"])
    edited = mech.Mechanism.from_dsl(text.replace("C: (250 mm, 120 mm, 80 mm)", "C: (0.26, 0.12, 0.07)", 1))
    np.testing.assert_allclose(out["B.x"][1], edited.pose(q)["B.x"], rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(out["B.x"][0], m.pose(q)["B.x"], rtol=1e-13, atol=1e-15)
    assert list(out["ok"][2]) == [False] * 3 and np.isnan(out["B.x"][2]).all()
    changed = mech.Mechanism.load(str(RSSR))
    changed.set_param("links.rod.mass", 0.8)
    back = pickle.loads(pickle.dumps(changed))
    assert back.kinetostatics(0.7)["driver"] == changed.kinetostatics(0.7)["driver"]
    assert back.kinetostatics(0.7)["driver"] != m.kinetostatics(0.7)["driver"]
    with pytest.raises(mech.InvalidInput, match="unknown point"):
        changed.set_param("points.Z", (0.0, 0.0, 0.0))
