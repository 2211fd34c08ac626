"""Hostile input to the Python package (issue 28): every public function and method with
wrong dtypes, non-contiguous arrays, mismatched lengths, 0-d and 2-d arrays where 1-d is
expected, empty arrays, NaN and infinities, sizes that must not be attempted, pickling,
bad DSL text, bytes, None. Each case gives the right value or a clear exception — its type
and a key phrase are asserted — never a crash (a Rust panic surfacing as PanicException
counts as one), a hang or a silent wrong answer. The policy is the package docstring's
(``mech/__init__.py``): real dtypes are converted, other dtypes are a ``TypeError``, bad
values, shapes and sizes a ``mech.InvalidInput`` (a ``ValueError`` too)."""

import copy
import math
import pathlib
import pickle
import subprocess
import sys
import time

import numpy as np
import pytest

import mech

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples" / "mech"
ENGINE = (EXAMPLES / "engine.mech").read_text()
FIVE_BAR = (EXAMPLES / "five_bar.mech").read_text()
VALVE = (EXAMPLES / "valve_train.mech").read_text()
Q = np.linspace(0.1, 6.0, 12)

# A refusal takes milliseconds; this only separates it from an attempt or a hang.
QUICK = 10.0


def engine():
    return mech.Mechanism.from_dsl(ENGINE)


def five_bar():
    return mech.Mechanism.from_dsl(FIVE_BAR)


def quick(f, *args, **kwargs):
    """Call f; fail if it took longer than QUICK seconds (an attempt, not a refusal)."""
    start = time.monotonic()
    try:
        return f(*args, **kwargs)
    finally:
        took = time.monotonic() - start
        assert took < QUICK, "%s took %.1f s" % (getattr(f, "__name__", f), took)


def in_a_process(code, timeout=120):
    """Run ``code`` in a fresh interpreter (a crash there fails this test, not the run):
    its standard output, after asserting a clean exit."""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout)
    assert r.returncode == 0, "exit %d (a crash?):\n%s\n%s" % (r.returncode, r.stdout, r.stderr[-3000:])
    return r.stdout


# The one-input solvers, each as f(mechanism, q, **kw) -> dict of columns; `key` is a
# column to compare.
SOLVERS = {
    "pose": (lambda m, q, **k: m.pose(q, **k), "B.x"),
    "kinematics": (lambda m, q, **k: m.kinematics(q, 30.0, 2.0, **k), "B.ax"),
    "kinetostatics": (lambda m, q, **k: m.kinetostatics(q, 30.0, 2.0, loads={"gas": (-500.0, 0.0)}, **k), "A.fx"),
    "driver_action": (lambda m, q, **k: m.driver_action(q, 30.0, 2.0, loads={"gas": (-500.0, 0.0)}, **k), "driver"),
    "reduced": (lambda m, q, **k: m.reduced(q, **k), "inertia"),
    "reduced_moment": (lambda m, q, **k: m.reduced_moment(q, loads={"gas": (-500.0, 0.0)}, **k), "moment"),
    "acceleration": (lambda m, q, **k: m.acceleration(q, 30.0, 3.0, loads={"gas": (-500.0, 0.0)}, **k), "qdd"),
    "sweep": (lambda m, q, **k: {n: v[0] for n, v in mech.sweep(m, {"links.rod.mass": [0.58]}, q).items()}, "driver"),
}
IDS = sorted(SOLVERS)


def solve(name, m, q, **kw):
    f, key = SOLVERS[name]
    return f(m, q, **kw)[key]


# -- dtypes ----------------------------------------------------------------------------


@pytest.mark.parametrize("name", IDS)
def test_real_dtypes_are_converted_to_float64(name):
    m = engine()
    ints = np.arange(6)
    want = solve(name, m, ints.astype(np.float64))
    for a in [ints, ints.astype(np.int32), ints.astype(np.uint8), ints.astype(np.int16), list(range(6)), ints.astype(object)]:
        got = solve(name, m, a)
        assert np.array_equal(got, want), (name, np.asarray(a).dtype)
    f32 = np.linspace(0.1, 6, 7, dtype=np.float32)
    assert np.array_equal(solve(name, m, f32), solve(name, m, f32.astype(np.float64)))
    # A numpy scalar and a Python int are one configuration.
    assert np.array_equal(np.atleast_1d(solve(name, m, np.int64(2))), want[2:3])
    assert np.array_equal(np.atleast_1d(solve(name, m, 2)), want[2:3])


@pytest.mark.parametrize("name", IDS)
@pytest.mark.parametrize("bad, phrase", [
    (np.array([True, False]), "q holds booleans"),
    (np.array([1.0 + 2.0j]), "q holds complex numbers: give real numbers"),
    (np.array([0.5 + 0j]), "q holds complex numbers"),
    ("1.0", "q is a str ('1.0'): give a number or an array of numbers"),
    (b"1.0", "q is a bytes"),
    (None, "q is None: give a number or an array of numbers"),
    (np.array(["0.1", "0.2"]), "q holds strings"),
    (np.array([0.1, "a"], dtype=object), "q holds a str ('a'): give real numbers"),
    (np.array([0.1, None], dtype=object), "q holds None"),
    (np.array(["2024-01-01"], dtype="datetime64[D]"), "q holds datetimes"),
], ids=["bool", "complex", "complex-real", "str", "bytes", "None", "str-array", "object-str", "object-None", "datetime"])
def test_other_dtypes_are_a_type_error(name, bad, phrase):
    with pytest.raises(TypeError) as e:
        solve(name, engine(), bad)
    assert phrase in str(e.value), str(e.value)
    with pytest.raises(mech.InvalidInput, match=r"q cannot be read as an array of numbers \(ragged nesting\?\)"):
        solve(name, engine(), [0.1, [0.2, 0.3]])


@pytest.mark.parametrize("rate", ["qd", "qdd"])
def test_rates_and_loads_of_other_dtypes_are_a_type_error(rate):
    m = engine()
    with pytest.raises(TypeError, match="%s is a str" % rate):
        m.kinematics(Q, **{rate: "fast"})
    with pytest.raises(TypeError, match="%s holds complex numbers" % rate):
        m.kinematics(Q, **{rate: np.ones(12) * 1j})
    with pytest.raises(TypeError, match=r"loads\['gas'\] is a str"):
        m.kinetostatics(Q, loads={"gas": "big"})
    with pytest.raises(TypeError, match=r"loads\['gas'\] holds booleans"):
        m.kinetostatics(Q, loads={"gas": np.array([True, False])})
    with pytest.raises(TypeError, match=r"loads\['gas'\]\(q\) is None"):
        m.kinetostatics(Q, loads={"gas": lambda q: None})
    with pytest.raises(TypeError, match="loads is a list: give a dict"):
        m.kinetostatics(Q, loads=[("gas", (1.0, 0.0))])
    with pytest.raises(TypeError, match="driver is a str"):
        m.acceleration(Q, 1.0, "strong")
    with pytest.raises(TypeError, match=r"driver\(q\) is a str"):
        m.acceleration(Q, 1.0, lambda q: "strong")


# -- layouts ---------------------------------------------------------------------------


@pytest.mark.parametrize("name", IDS)
def test_non_contiguous_arrays_give_the_contiguous_answer(name):
    m = engine()
    base = np.linspace(0.0, 6.2, 40)
    table = np.stack([base, base * 0.5, base * 2.0], axis=1)
    for a in [base[::2], base[::-3], base[5:30:4], table[:, 1], np.flip(base)]:
        assert not a.flags.c_contiguous
        assert np.array_equal(solve(name, m, a), solve(name, m, np.ascontiguousarray(a)))
    # A column (n, 1) is the same as (n,): strided (C order), or contiguous (Fortran).
    col = table[:, :1]
    assert np.array_equal(solve(name, m, col), solve(name, m, np.ascontiguousarray(col[:, 0])))
    col = np.asfortranarray(table)[:, 1:2]
    assert np.array_equal(solve(name, m, col), solve(name, m, np.ascontiguousarray(col[:, 0])))


def test_two_inputs_transposed_fortran_and_strided():
    m = five_bar()
    rows = np.array([[0.9, 1.6], [1.0, 1.7], [1.1, 1.8], [1.2, 1.9], [1.3, 2.0], [1.4, 2.1]])
    want = m.kinetostatics(rows, np.ones((6, 2)), 0.0, loads={"pen": (1.0, 2.0)})
    for q in [np.asfortranarray(rows), np.ascontiguousarray(rows.T).T, np.repeat(rows, 2, axis=0)[::2]]:
        got = m.kinetostatics(q, np.ones((6, 2))[::1], 0.0, loads={"pen": (1.0, 2.0)})
        for k in want:
            assert np.array_equal(got[k], want[k]), k
    # A number broadcasts to every input; a (G,) vector is one configuration.
    assert np.array_equal(m.pose(0.0)["C.x"], m.pose(np.zeros(2))["C.x"])
    one = m.pose(rows[0])
    assert np.ndim(one["C.x"]) == 0 and one["C.x"] == m.pose(rows)["C.x"][0]
    s = mech.sweep(m, {"links.upper.mass": [0.7, 0.8]}, np.asfortranarray(rows))
    # The sweep publishes points through the whole kinematics, `pose` through the points
    # alone: two routes, equal to a few ulp.
    assert s["C.x"].shape == (2, 6) and np.allclose(s["C.x"][0], m.pose(rows)["C.x"], rtol=4e-16, atol=0)
    with pytest.raises(mech.InvalidInput, match=r"inputs of shape \(3, 1\) for 2 input\(s\): q is \(3,\)"):
        m.pose(np.zeros(3))


# -- shapes ----------------------------------------------------------------------------


@pytest.mark.parametrize("name", IDS)
def test_zero_d_one_d_two_d_and_three_d(name):
    m = engine()
    want = solve(name, m, Q)
    zero_d = solve(name, m, np.array(Q[3]))
    # One configuration: a scalar (a sweep keeps its (V, n) shape: one row).
    assert np.ndim(zero_d) == (1 if name == "sweep" else 0) and zero_d == want[3]
    assert np.array_equal(solve(name, m, Q.reshape(-1, 1)), want)
    with pytest.raises(mech.InvalidInput, match=r"inputs of shape \(6, 2\) for 1 input\(s\)"):
        solve(name, m, Q.reshape(6, 2))
    with pytest.raises(mech.InvalidInput, match=r"q of shape \(12, 1, 1\) has 3 dimensions"):
        solve(name, m, Q.reshape(12, 1, 1))


@pytest.mark.parametrize("name", IDS)
def test_empty_inputs_give_empty_columns(name):
    m = engine()
    for empty in [np.array([]), np.zeros((0, 1)), []]:
        got = solve(name, m, empty)
        assert isinstance(got, np.ndarray) and got.shape == (0,), (name, got)


def test_mismatched_lengths_name_both():
    m = engine()
    q3 = np.array([0.1, 0.2, 0.3])
    with pytest.raises(mech.InvalidInput, match="qd has 2 rows but q has 3: give one value, or one per row of q"):
        m.kinematics(q3, [1.0, 2.0])
    with pytest.raises(mech.InvalidInput, match="qdd has 4 rows but q has 3"):
        m.kinetostatics(q3, 1.0, np.ones(4))
    with pytest.raises(mech.InvalidInput, match="qd has 2 rows but q has 3"):
        m.acceleration(q3, [1.0, 2.0], 0.0)
    with pytest.raises(mech.InvalidInput, match="driver has 5 rows but q has 3"):
        m.acceleration(q3, 1.0, np.ones(5))
    with pytest.raises(mech.InvalidInput, match=r"loads\['gas'\] of shape \(2, 2\) for 3 rows: `gas` is a force, give \(fx, fy\) or an \(n, 2\) array"):
        m.kinetostatics(q3, loads={"gas": np.ones((2, 2))})
    with pytest.raises(mech.InvalidInput, match=r"loads\['gas'\] of shape \(3,\) for 3 rows: `gas` is a force"):
        m.reduced_moment(q3, loads={"gas": np.ones(3)})
    with pytest.raises(mech.InvalidInput, match=r"loads\['gas'\] of shape \(\) for 3 rows"):
        m.driver_action(q3, loads={"gas": 5.0})
    with pytest.raises(mech.InvalidInput, match="qd has 2 rows but q has 3"):
        mech.sweep(m, {"links.rod.mass": [0.5]}, q3, qd=[1.0, 2.0])
    with pytest.raises(mech.InvalidInput, match=r"every parameter needs the same number of variants, got \[1, 2\]"):
        mech.sweep(m, {"links.rod.mass": [0.5, 0.6], "links.crank.mass": [3.0]}, q3)
    # One value broadcasts; one per row is taken row by row.
    per_row = m.kinematics(q3, [1.0, 2.0, 3.0])["rod.omega"]
    assert per_row[1] == m.kinematics(q3[1], 2.0)["rod.omega"]


def test_the_native_layer_refuses_bad_shapes_itself():
    """Past the Python layer (its checks removed), a mismatch is an InvalidInput, not a
    slice out of bounds (PanicException)."""
    core = engine()._core
    cols = ["positions"]
    z = lambda n, w: np.zeros((n, w))  # noqa: E731
    with pytest.raises(mech.InvalidInput, match=r"qd of shape \[2, 1\] but q of shape \[3, 1\]"):
        core.table(cols, z(3, 1), z(2, 1), z(3, 1), z(3, 2))
    with pytest.raises(mech.InvalidInput, match=r"inputs of shape \[3, 2\] for 1 input"):
        core.table(cols, z(3, 2), z(3, 2), z(3, 2), z(3, 2))
    with pytest.raises(mech.InvalidInput, match=r"loads of shape \[3, 1\] for 3 rows of 2 load value"):
        core.table(cols, z(3, 1), z(3, 1), z(3, 1), z(3, 1))
    with pytest.raises(mech.InvalidInput, match="q, qd and driver of lengths 3, 2 and 3"):
        core.acceleration([0.1, 0.2, 0.3], [1.0, 2.0], [0.0, 0.0, 0.0], z(3, 2))
    with pytest.raises(mech.InvalidInput, match=r"loads of shape \[1, 2\] for 3 rows"):
        core.acceleration([0.1, 0.2, 0.3], [1.0, 2.0, 3.0], [0.0, 0.0, 0.0], z(1, 2))
    with pytest.raises(mech.InvalidInput, match=r"qdd of shape \[1, 1\] but q of shape \[3, 1\]"):
        core.sweep([[]], cols, z(3, 1), z(3, 1), z(1, 1), z(3, 2))


# -- values ----------------------------------------------------------------------------


@pytest.mark.parametrize("name", IDS)
@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_nan_and_inf_raise_or_mask_their_row(name, bad):
    m = engine()
    q = Q.copy()
    q[4] = bad
    if name == "sweep":
        # A sweep always masks: the row is NaN, ok False, the others unaffected.
        out = mech.sweep(m, {"links.rod.mass": [0.58]}, q)
        assert not out["ok"][0, 4] and out["ok"][0, np.arange(12) != 4].all()
        assert np.isnan(out["driver"][0, 4])
        return
    with pytest.raises(mech.InvalidInput, match="must be finite, got") as e:
        solve(name, m, q)
    assert isinstance(e.value, ValueError) and isinstance(e.value, mech.MechError)
    f, key = SOLVERS[name]
    out = f(m, q, errors="mask")
    good = np.arange(12) != 4
    assert not out["ok"][4] and out["ok"][good].all()
    assert np.isnan(out[key][4])
    assert np.array_equal(out[key][good], f(m, Q)[key][good])


def test_nan_rates_loads_and_drivers():
    m = engine()
    with pytest.raises(mech.InvalidInput, match="q, qd, qdd must be finite, got"):
        m.kinematics(Q, qd=math.nan)
    with pytest.raises(mech.InvalidInput, match="q, qd, qdd must be finite"):
        m.kinematics(Q, qdd=np.full(12, math.inf))
    with pytest.raises(mech.InvalidInput, match="loads must be finite, got"):
        m.kinetostatics(Q, loads={"gas": (math.nan, 0.0)})
    with pytest.raises(mech.InvalidInput, match="q, qd, driver must be finite"):
        m.acceleration(Q, 1.0, math.inf)
    out = m.kinetostatics(Q, loads={"gas": lambda q: (math.nan if q > 3 else -100.0, 0.0)}, errors="mask")
    assert np.array_equal(out["ok"], Q <= 3)
    with pytest.raises(ValueError, match="errors='ignore': give \"raise\""):
        m.pose(Q, errors="ignore")
    with pytest.raises(ValueError, match="errors=None"):
        m.acceleration(Q, 1.0, 0.0, errors=None)


# -- sizes that must not be attempted ----------------------------------------------------


def test_huge_batches_are_refused_before_any_allocation():
    m = engine()
    # Broadcast views: no memory until copied; a copy of these would take gigabytes.
    with pytest.raises(mech.InvalidInput, match=r"the table: 134217728 rows × 9 columns = 1207959552 values \(9.7 GB\), more than the limit of 268435456"):
        quick(m.pose, np.broadcast_to(0.1, (1 << 27,)))
    with pytest.raises(mech.InvalidInput, match="q has 1000000000000 values, more than the limit of 268435456"):
        quick(m.reduced, np.broadcast_to(np.float64(0.1), (10**12,)))
    with pytest.raises(mech.InvalidInput, match=r"the sweep \(variants × rows\)"):
        quick(mech.sweep, m, {"links.rod.mass": np.broadcast_to(0.5, (10**6,))}, np.broadcast_to(0.1, (10**4,)))
    with pytest.raises(mech.InvalidInput, match="points = 1000000000000: give a whole number from 3 to 1000000"):
        quick(mech.Mechanism.from_dsl(VALVE).cam_profile, points=10**12)
    with pytest.raises(mech.InvalidInput, match=r"period = 1e\+?12 rad: 1.592e11 turns, more than the limit of 1000 turns"):
        quick(m.flywheel, 1e12, 100.0, 0.02)
    with pytest.raises(mech.InvalidInput, match="more than the 4 MB a mechanism may have"):
        quick(mech.Mechanism.from_dsl, "/// a comment\n" * 400_000)


def test_the_native_layer_refuses_huge_batches_itself():
    """Past the Python layer: the native sweep counts variants × rows × columns before it
    allocates (10⁶ empty variants × 400 rows, 10¹⁰ values)."""
    core = engine()._core
    z = np.zeros((400, 1))
    with pytest.raises(mech.InvalidInput, match="the sweep: 400000000 rows"):
        quick(core.sweep, [[]] * 10**6, ["positions", "rates", "reactions"], z, z, z, np.zeros((400, 2)))


def test_a_huge_cam_profile_does_not_end_the_process():
    """The native layer alone: 10¹² points was an allocation of 80 TB (the process
    aborted)."""
    out = in_a_process(
        "import mech\n"
        "m = mech.Mechanism.from_dsl(open(%r).read())\n"
        "try:\n"
        "    m._core.cam_profile(None, 10**12)\n"
        "except mech.InvalidInput as e:\n"
        "    print('refused:', e)\n" % str(EXAMPLES / "valve_train.mech"))
    assert "refused: points = 1000000000000: a profile needs from 3 to 1000000 points" in out


@pytest.mark.parametrize("points, phrase", [
    (-1, "points = -1: give a whole number from 3 to 1000000"),
    (2, "points = 2"),
    (3.7, "points = 3.7"),
    (math.nan, "points = nan"),
    (2**64, "points = 18446744073709551616"),
])
def test_cam_points_out_of_range(points, phrase):
    with pytest.raises(mech.InvalidInput, match=phrase.replace(".", r"\.")):
        mech.Mechanism.from_dsl(VALVE).cam_profile(points=points)


def test_cam_arguments_of_other_types():
    cam = mech.Mechanism.from_dsl(VALVE)
    with pytest.raises(TypeError, match="points is a str"):
        cam.cam_profile(points="360")
    with pytest.raises(TypeError, match="points is a bool"):
        cam.cam_profile(points=True)
    with pytest.raises(TypeError, match="name is an int: give the cam joint's name as a str"):
        cam.cam_profile(name=5)
    with pytest.raises(mech.InvalidInput, match="no cam `nope`; its cams: `lobe`"):
        cam.cam_profile(name="nope")
    a, b = cam.cam_profile(points=36.0), cam.cam_profile(points=np.int16(36))
    assert np.array_equal(a["lift"], b["lift"]) and a["lift"].shape == (36,)


# -- flywheel ----------------------------------------------------------------------------


def test_flywheel_arguments():
    m = engine()
    args = (4 * math.pi, 100.0, 0.02)
    for i, name in enumerate(["period", "speed", "irregularity"]):
        bad = list(args)
        bad[i] = math.nan
        with pytest.raises(mech.InvalidInput, match="%s = nan: not a finite number" % name):
            m.flywheel(*bad)
        bad[i] = "x"
        with pytest.raises(TypeError, match="%s is a str" % name):
            m.flywheel(*bad)
        bad[i] = None
        with pytest.raises(TypeError, match="%s is None" % name):
            m.flywheel(*bad)
    with pytest.raises(mech.InvalidInput, match="the irregularity must be in"):
        m.flywheel(4 * math.pi, 100.0, 0.0)
    with pytest.raises(mech.InvalidInput, match="start = 1e\\+?300 rad: so large beside the period"):
        m.flywheel(*args, start=1e300)
    with pytest.raises(mech.InvalidInput, match=r"breakpoints must be finite, got \[NaN\]"):
        m.flywheel(*args, breakpoints=[math.nan])
    with pytest.raises(TypeError, match="loads is a list"):
        m.flywheel(*args, loads=[1.0])
    with pytest.raises(mech.InvalidInput, match="flywheel sizing needs one revolute input"):
        five_bar().flywheel(*args)
    # A callable's own exception comes back as it is, not as a NaN or a message.
    with pytest.raises(ZeroDivisionError):
        m.flywheel(*args, driver=lambda q: 1 / 0)
    with pytest.raises(ZeroDivisionError):
        m.flywheel(*args, loads={"gas": lambda q: (1 / 0, 0.0)})
    with pytest.raises(TypeError, match=r"driver\(q\) is a str"):
        m.flywheel(*args, driver=lambda q: "x")
    with pytest.raises(mech.InvalidInput, match=r"driver\(q\) = nan: not a finite number"):
        m.flywheel(*args, driver=lambda q: math.nan)


# -- pickling ----------------------------------------------------------------------------


def test_mechanisms_results_and_errors_pickle_and_round_trip():
    m = engine()
    m.set_param("links.crank.mass", 4.2)
    for other in [pickle.loads(pickle.dumps(m, protocol=p)) for p in range(2, pickle.HIGHEST_PROTOCOL + 1)] + [copy.deepcopy(m), copy.copy(m)]:
        assert np.array_equal(other.reduced(Q)["inertia"], m.reduced(Q)["inertia"])
        assert other.text == m.text and other.name == m.name
    out = m.kinetostatics(Q, loads={"gas": (-10.0, 0.0)}, errors="mask")
    back = pickle.loads(pickle.dumps(out))
    assert back.keys() == out.keys() and all(np.array_equal(back[k], out[k]) for k in out)
    s = mech.sweep(m, {"links.rod.mass": [0.5, 0.6]}, Q)
    assert np.array_equal(pickle.loads(pickle.dumps(s))["driver"], s["driver"])
    # Exceptions travel back from a worker: each class pickles by its module, mech._mech.
    for E in [mech.MechError, mech.InvalidMechanism, mech.NoAssembly, mech.Singular, mech.InvalidInput]:
        e = pickle.loads(pickle.dumps(E("boom")))
        assert type(e) is E and str(e) == "boom"
    with pytest.raises(mech.InvalidMechanism) as e:
        mech.Mechanism.from_dsl("pub struct X {")
    back = pickle.loads(pickle.dumps(e.value))
    assert (back.line, back.column) == (e.value.line, e.value.column) == (1, 14)


def test_the_native_core_refuses_pickling_with_a_type_error():
    core = engine()._core
    with pytest.raises(TypeError, match="cannot pickle the native core mech._mech._Mechanism: pickle the mech.Mechanism"):
        pickle.dumps(core)
    with pytest.raises(TypeError, match="cannot pickle the native core"):
        copy.deepcopy(core)


def test_a_corrupted_pickle_is_a_clear_error():
    """A pickle whose state is not a mechanism (edited, or from another version): the
    check's error on loading, not a crash."""
    data = pickle.dumps(engine()).replace(b"pub struct Engine", b"pub strukt Engine")
    with pytest.raises(mech.InvalidMechanism, match="expected `struct`"):
        pickle.loads(data)
    data = pickle.dumps(engine()).replace(b"links.crank.mass", b"links.crank.mess")
    pickle.loads(data)  # no parameter set: nothing to replay
    m = engine()
    m.set_param("links.crank.mass", 4.0)
    data = pickle.dumps(m).replace(b"links.crank.mass", b"links.crank.mess")
    with pytest.raises(mech.InvalidInput, match="no parameter `links.crank.mess`"):
        pickle.loads(data)


# -- the DSL text and files --------------------------------------------------------------


@pytest.mark.parametrize("text, error, phrase", [
    (ENGINE.encode(), TypeError, "text is bytes: give a str; decode it first"),
    (None, TypeError, "text is None: give the mechanism's DSL text as a str"),
    (42, TypeError, "text is an int"),
    (["pub struct X {}"], TypeError, "text is a list"),
    ("", mech.InvalidMechanism, "unexpected end of input, expected `pub`"),
    ("pub struct X {", mech.InvalidMechanism, "1:14:"),
    ("\0\0\0", mech.InvalidInput, "a NUL character at offset 0: binary data"),
    (ENGINE.replace("stroke: 86 mm", "stroke: %s86%s mm" % ("(" * 100_000, ")" * 100_000)), mech.InvalidInput, "the text:4:84: brackets nested more than 64 deep"),
    (ENGINE.replace("stroke: 86 mm", "stroke: %s86 mm" % ("-" * 100_000)), mech.InvalidInput, "more than 64 signs in a row"),
    ("/// x\n" * 1_000_000, mech.InvalidInput, "5.7 MB of text, more than the 4 MB"),
], ids=["bytes", "None", "int", "list", "empty", "unclosed", "NUL", "nested", "signs", "huge"])
def test_bad_dsl_text(text, error, phrase):
    for build in [mech.Mechanism.from_dsl, mech.Mechanism]:
        with pytest.raises(error) as e:
            quick(build, text)
        assert phrase in str(e.value), str(e.value)[:500]


def test_deep_nesting_does_not_end_the_process():
    """The native layer alone (the parser is recursive: 10⁵ brackets overflowed its stack,
    a segmentation fault of the interpreter)."""
    out = in_a_process(
        "import mech\n"
        "t = open(%r).read().replace('stroke: 86 mm', 'stroke: ' + '(' * 100000 + '86' + ')' * 100000 + ' mm')\n"
        "try:\n"
        "    mech._mech._Mechanism.from_dsl(t, None)\n"
        "except mech.InvalidInput as e:\n"
        "    print('refused:', e)\n" % str(EXAMPLES / "engine.mech"))
    assert "refused: the text:4:84: brackets nested more than 64 deep" in out


def test_bad_files(tmp_path):
    def write(name, data):
        p = tmp_path / name
        p.write_bytes(data)
        return p
    with pytest.raises(FileNotFoundError):
        mech.Mechanism.load(tmp_path / "missing.mech")
    with pytest.raises(IsADirectoryError):
        mech.Mechanism.load(tmp_path)
    with pytest.raises(mech.InvalidInput, match=r"binary.mech is a binary file \(a NUL byte at offset 3\)"):
        mech.Mechanism.load(write("binary.mech", b"pub\0struct"))
    with pytest.raises(mech.InvalidInput, match=r"latin1.mech is not UTF-8 text \(byte 0xe9 at offset 7\); save it as UTF-8"):
        mech.Mechanism.load(write("latin1.mech", b"/// caf\xe9\n" + ENGINE.encode()))
    huge = tmp_path / "huge.mech"
    with open(huge, "wb") as f:
        f.truncate(100 << 20)  # sparse: no time, no disk
    with pytest.raises(mech.InvalidInput, match=r"huge.mech is 100.0 MB, more than the 4 MB a mechanism file may have"):
        quick(mech.Mechanism.load, huge)
    with pytest.raises(mech.InvalidMechanism, match="unexpected end of input"):
        mech.Mechanism.load(write("empty.mech", b""))
    with pytest.raises(TypeError, match="path is None"):
        mech.Mechanism.load(None)
    with pytest.raises(TypeError, match="path is an int"):
        mech.Mechanism.load(3)
    good = write("engine.mech", ENGINE.encode())
    for path in [good, str(good), bytes(good)]:
        assert mech.Mechanism.load(path).name == "Engine"
    with pytest.raises(mech.InvalidMechanism) as e:
        mech.Mechanism.load(write("bad.mech", b"pub struct X {"))
    assert str(e.value).startswith(str(tmp_path / "bad.mech") + ":1:14:")


# -- the other methods ---------------------------------------------------------------------


def test_set_param_and_columns():
    m = engine()
    with pytest.raises(mech.InvalidInput, match="links.rod.mass must be finite, got"):
        m.set_param("links.rod.mass", math.nan)
    with pytest.raises(TypeError, match="value is a str"):
        m.set_param("links.rod.mass", "heavy")
    with pytest.raises(TypeError, match="value is None"):
        m.set_param("links.rod.mass", None)
    with pytest.raises(TypeError, match="path is None: give a parameter path as a str"):
        m.set_param(None, 1.0)
    with pytest.raises(TypeError, match="path is a bytes"):
        m.set_param(b"links.rod.mass", 1.0)
    with pytest.raises(mech.InvalidInput, match="no parameter `nope`"):
        m.set_param("nope", 1.0)
    with pytest.raises(mech.InvalidMechanism):
        m.set_param("links.rod.mass", -1.0)
    m.set_param("links.rod.mass", np.float32(0.5))
    m.set_param("points.A", np.array([[0.03, 0.03]], order="F"))  # any shape of 2 values
    assert m.columns("positions") == m.columns(["positions"])
    assert m.columns() == m.columns(None)
    with pytest.raises(mech.InvalidInput, match="unknown part `nope`: the parts are inputs, positions"):
        m.columns(["nope"])
    with pytest.raises(TypeError, match="a part is an int"):
        m.columns([1])
    assert (m.name, m.dof, m.inputs, m.load_names) == ("Engine", 1, [("O2", "revolute")], [("gas", 2)])
    assert repr(m) == "mech.Mechanism('Engine', dof=1)"
    assert isinstance(mech.num_threads(), int) and mech.num_threads() >= 1
    with pytest.raises(TypeError, match="origin is an int"):
        mech.Mechanism(ENGINE, origin=3)


def test_loads_by_name_and_callables():
    m = engine()
    with pytest.raises(mech.InvalidInput, match="no load named wind: the mechanism's loads are gas"):
        m.kinetostatics(Q, loads={"wind": 3.0})
    with pytest.raises(ZeroDivisionError):
        m.kinetostatics(Q, loads={"gas": lambda q: (1 / 0, 0.0)})
    with pytest.raises(mech.InvalidInput, match=r"loads\['gas'\] of shape \(12, 3\)"):
        m.kinetostatics(Q, loads={"gas": lambda q: (1.0, 0.0, 0.0)})
    a = m.kinetostatics(Q, loads={"gas": np.array([[-100.0, 0.0]] * 12, order="F")})
    b = m.kinetostatics(Q, loads={"gas": (-100, 0)})
    c = m.kinetostatics(Q, loads={"gas": lambda q: np.array([-100.0, 0.0], dtype=np.float32)})
    assert all(np.array_equal(a[k], b[k]) and np.array_equal(a[k], c[k]) for k in a)


def test_acceleration_needs_one_input():
    with pytest.raises(mech.InvalidInput, match="the direct problem by Zhukovski needs one input; this mechanism has 2"):
        five_bar().acceleration(np.ones(2), np.ones(2), 0.0)


def test_sweep_arguments():
    m = engine()
    with pytest.raises(TypeError, match="params is None: give a dict of parameter path"):
        mech.sweep(m, None, Q)
    with pytest.raises(TypeError, match="params is a str"):
        mech.sweep(m, "links.rod.mass", Q)
    with pytest.raises(TypeError, match=r"params\['links.rod.mass'\] holds strings"):
        mech.sweep(m, {"links.rod.mass": ["heavy"]}, Q)
    with pytest.raises(TypeError, match="params key 3 is an int"):
        mech.sweep(m, {3: [1.0]}, Q)
    with pytest.raises(TypeError, match="mechanism is a str: give a mech.Mechanism"):
        mech.sweep(ENGINE, {"links.rod.mass": [1.0]}, Q)
    # A number is one variant; a variant that fails a check, or NaN, is masked.
    one = mech.sweep(m, {"links.rod.mass": 0.58}, Q, parts="zhukovski")
    assert one["inertia"].shape == (1, 12) and np.array_equal(one["inertia"][0], m.reduced(Q)["inertia"])
    out = mech.sweep(m, [{"links.rod.mass": math.nan}, {"links.rod.mass": -1.0}, {"nope": 1.0}, {"links.rod.mass": 0.58}], Q)
    assert not out["ok"][:3].any() and out["ok"][3].all() and np.isnan(out["driver"][:3]).all()


def test_stop_arguments():
    """`Mechanism.stop`: bad numbers, counts and types are clear errors, a stop of too many
    rows is refused before it is attempted, and a machine of two inputs has no stop."""
    wheel = mech.Mechanism.from_dsl("""pub struct Wheel {
        ground { O: (0.0, 0.0) },
        link wheel { points { O, A: (0.1, 0.0) }, mass: 2.0, inertia: 0.03, cg: (0.0, 0.0) },
        joints { O: revolute(ground, wheel) },
        input: O,
    }""")
    for kwargs, phrase in [
        ({"qd0": float("nan")}, "not a finite number"),
        ({"qd0": 10.0, "brake": float("inf")}, "not a finite number"),
        ({"qd0": -10.0, "brake": 1.0}, "q̇0 > 0"),
        ({"qd0": 10.0, "brake": 1.0, "points": 0}, "1 to"),
        ({"qd0": 10.0, "brake": 1.0, "points": 10**8}, "1 to"),
        ({"qd0": 10.0, "brake": 1.0, "dt": 0.0}, "0 < dt < t_max"),
        ({"qd0": 10.0, "brake": 1.0, "t_max": -1.0}, "t_max > 0"),
    ]:
        start = time.time()
        with pytest.raises(mech.InvalidInput) as e:
            wheel.stop(**kwargs)
        assert phrase in str(e.value), (kwargs, str(e.value))
        assert time.time() - start < QUICK
    start = time.time()
    with pytest.raises(mech.InvalidInput) as e:
        wheel.stop(qd0=10.0, brake=1.0, dt=1e-12)
    assert "give a larger dt" in str(e.value) and time.time() - start < QUICK
    with pytest.raises(TypeError):
        wheel.stop(qd0="fast")
    with pytest.raises(TypeError):
        wheel.stop(qd0=10.0, brake=1.0, points=2.5)
    with pytest.raises(mech.InvalidInput) as e:
        five_bar().stop(qd0=10.0, brake=1.0)
    assert "one revolute input" in str(e.value)
