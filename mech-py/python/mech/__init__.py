"""mech: dynamics of planar machines, from Python.

A mechanism is described in the DSL of the Rust crate (the text between the braces of
``mechanism! { ... }``, a ``.mech`` file) and solved by the same Rust code as the
generated structs: positions, velocities and accelerations, every reaction, the motor
actions by d'Alembert and by virtual power, Zhukovski's I* and M*, the direct problem,
the flywheel. Every solver takes a scalar or a NumPy array of inputs (shape ``(n,)`` for
one input, ``(n, G)`` for G inputs) and returns a dict of NumPy arrays keyed like the
``mech`` tool's CSV columns (``"B.x"``, ``"rod.omega"``, ``"A.fx"``, ``"driver"``,
``"inertia"``, ...). The loop runs in Rust, in parallel, with the GIL released;
``MECH_NUM_THREADS`` sets the number of threads.

Units are SI: m, kg, kg·m², rad, s, N, N·m.

>>> import mech
>>> m = mech.Mechanism.load("examples/mech/engine.mech")          # doctest: +SKIP
>>> m.reduced([0.0, 0.5])["inertia"]                                # doctest: +SKIP
"""

import numpy as np

from . import _mech
from ._mech import InvalidInput, InvalidMechanism, MechError, NoAssembly, Singular, num_threads

__all__ = [
    "Mechanism",
    "sweep",
    "num_threads",
    "MechError",
    "InvalidMechanism",
    "NoAssembly",
    "Singular",
    "InvalidInput",
]

_ALL = ["inputs", "positions", "rates", "reactions", "driver", "virtual_power", "zhukovski"]


def _raise(message):
    """The exception of a failed row, by the message's kind."""
    low = message.lower()
    if low.startswith("no assembly"):
        raise NoAssembly(message)
    if low.startswith("singular"):
        raise Singular(message)
    if low.startswith("invalid input"):
        raise InvalidInput(message)
    raise MechError(message)


def _restore(text, origin, params):
    """Rebuild a pickled Mechanism from its text and parameters."""
    return Mechanism(text, origin=origin, params=params)


class Mechanism:
    """A planar mechanism read from DSL text, checked like the ``mechanism!`` macro.

    Picklable: the text and the parameters set since loading travel, so Dask and Ray can
    ship it to workers.
    """

    def __init__(self, text, origin=None, params=()):
        self._text = text
        self._origin = origin
        self._core = _mech._Mechanism.from_dsl(text, origin)
        self._params = []
        for path, value in params:
            self.set_param(path, value)

    @classmethod
    def from_dsl(cls, text):
        """The mechanism described by ``text``; ``InvalidMechanism`` (with ``line``,
        ``column`` and ``message``) when a check fails."""
        return cls(text)

    @classmethod
    def load(cls, path):
        """The mechanism of a ``.mech`` file; messages name the file."""
        with open(path, encoding="utf-8") as f:
            return cls(f.read(), origin=str(path))

    def __reduce__(self):
        return (_restore, (self._text, self._origin, tuple(self._params)))

    def __repr__(self):
        return "mech.Mechanism(%r, dof=%d)" % (self.name, self.dof)

    # -- description -------------------------------------------------------------------

    @property
    def name(self):
        """The mechanism's (struct) name."""
        return self._core.name

    @property
    def dof(self):
        """G, the number of inputs."""
        return self._core.dof

    @property
    def inputs(self):
        """The inputs as (joint name, "revolute" or "prismatic")."""
        return self._core.inputs

    @property
    def load_names(self):
        """The declared loads as (name, components): 2 for a force, 1 for a torque."""
        return self._core.loads

    @property
    def text(self):
        """The DSL text the mechanism was read from."""
        return self._text

    def set_param(self, path, value):
        """Change one number of the drawing, re-checked: ``points.A`` = (x, y) m,
        ``links.rod.mass`` kg, ``links.rod.inertia`` kg·m², ``links.rod.cg`` (x, y) m,
        ``axes.guide`` (ux, uy), ``gravity`` (gx, gy) m/s²."""
        value = [float(v) for v in np.atleast_1d(np.asarray(value, dtype=float))]
        self._core.set_param(path, value)
        self._params.append((path, value))

    def columns(self, parts=None):
        """The names of the columns of ``parts`` (default: all)."""
        return self._core.columns(list(parts or _ALL))

    # -- inputs and loads --------------------------------------------------------------

    def _rows(self, x, n=None):
        """x as (n, G) floats; whether it was a scalar (one configuration)."""
        a = np.asarray(x, dtype=float)
        g = self.dof
        scalar = a.ndim == 0 or (g > 1 and a.ndim == 1 and a.shape[0] == g)
        if a.ndim == 0:
            a = a.reshape(1, 1)
        elif a.ndim == 1:
            a = a.reshape(1, g) if (g > 1 and a.shape[0] == g) else a.reshape(-1, 1)
        if a.shape[1] != g:
            raise InvalidInput("inputs of shape %s for %d input(s): give (n,) for one input, (n, G) for G" % (a.shape, g))
        if n is not None and a.shape[0] == 1 and n > 1:
            a = np.repeat(a, n, axis=0)
        return np.ascontiguousarray(a), scalar

    def _loads(self, loads, q):
        """The flat loads (n, L) in declaration order from a dict of name -> value: a
        number (torque), a pair (force), an array over the rows, or a callable of q."""
        n = q.shape[0]
        spec = self.load_names
        width = sum(w for _, w in spec)
        out = np.zeros((n, width))
        loads = dict(loads or {})
        at = 0
        for name, w in spec:
            if name in loads:
                v = loads.pop(name)
                if callable(v):
                    v = np.array([np.asarray(v(qk[0] if self.dof == 1 else qk), dtype=float) for qk in q])
                v = np.asarray(v, dtype=float)
                out[:, at:at + w] = np.broadcast_to(v.reshape(-1, w) if v.size > w else v.reshape(w), (n, w))
            at += w
        if loads:
            raise InvalidInput("no load named %s: the mechanism's loads are %s" % (", ".join(sorted(loads)), ", ".join(n for n, _ in spec) or "none"))
        return out

    def _table(self, parts, q, qd=0.0, qdd=0.0, loads=None, errors="raise", rename=None):
        q, scalar = self._rows(q)
        n = q.shape[0]
        qd, _ = self._rows(qd, n)
        qdd, _ = self._rows(qdd, n)
        flat = self._loads(loads, q)
        names, data, ok, first = self._core.table(list(parts), q, qd, qdd, flat)
        if first is not None and errors == "raise":
            _raise(first)
        out = {}
        for k, name in enumerate(names):
            key = rename(name) if rename else name
            col = data[:, k]
            out[key] = col[0] if scalar else col
        if errors != "raise":
            out["ok"] = ok[0] if scalar else ok
        return out

    # -- solvers -----------------------------------------------------------------------

    def pose(self, q, errors="raise", angles=True):
        """Positions: ``<point>.x``, ``<point>.y`` (m), ``<link>.angle`` (rad);
        ``angles=False`` leaves the links' angles out (and their cost, an ``atan2`` each).

        ``errors="mask"``: a row that does not solve is NaN and ``out["ok"]`` is False
        there, instead of an exception."""
        return self._table(["positions" if angles else "points"], q, errors=errors)

    def kinematics(self, q, qd=0.0, qdd=0.0, errors="raise"):
        """Positions, velocities (``.vx``, ``.vy``, ``.omega``) and accelerations (``.ax``,
        ``.ay``, ``.alpha``) of every point and link."""
        return self._table(["positions", "rates"], q, qd, qdd, errors=errors)

    def kinetostatics(self, q, qd=0.0, qdd=0.0, loads=None, errors="raise"):
        """d'Alembert: every reaction (``<joint>.fx``, ``.fy`` N, force by the joint's first
        link on its second; ``.moment`` N·m for a prismatic joint) and the motor action
        ``driver`` (``driver.<joint>`` for several inputs): the torque (N·m) or force (N)
        the motor applies."""
        return self._table(["reactions", "driver"], q, qd, qdd, loads, errors)

    def driver_action(self, q, qd=0.0, qdd=0.0, loads=None, errors="raise"):
        """The motor actions by virtual power, no reaction computed: ``driver``
        (``driver.<joint>``)."""
        return self._table(["virtual_power"], q, qd, qdd, loads, errors, rename=lambda n: n.replace("virtual_power", "driver"))

    def reduced(self, q, errors="raise"):
        """Zhukovski's reduced inertia: ``inertia`` I* (kg·m²) and ``inertia_derivative``
        dI*/dq (one input)."""
        out = self._table(["zhukovski"], q, errors=errors)
        out.pop("moment", None)
        return out

    def reduced_moment(self, q, loads=None, errors="raise"):
        """Zhukovski's reduced moment ``moment`` M* (N·m) of the loads and gravity."""
        out = self._table(["zhukovski"], q, loads=loads, errors=errors)
        return {k: v for k, v in out.items() if k in ("moment", "ok")}

    def acceleration(self, q, qd, driver, loads=None, errors="raise"):
        """The direct problem: ``qdd`` = q̈ from I* q̈ + ½ dI*/dq q̇² = driver + M* (one
        input; ``driver`` N·m, a number, an array or a callable of q)."""
        q, scalar = self._rows(q)
        n = q.shape[0]
        qd, _ = self._rows(qd, n)
        if callable(driver):
            driver = [driver(x) for x in q[:, 0]]
        d, _ = self._rows(driver, n)
        flat = self._loads(loads, q)
        qdd, ok, first = self._core.acceleration(list(q[:, 0]), list(qd[:, 0]), list(d[:, 0]), flat)
        if first is not None and errors == "raise":
            _raise(first)
        out = {"qdd": qdd[0] if scalar else qdd}
        if errors != "raise":
            out["ok"] = ok[0] if scalar else ok
        return out

    def flywheel(self, period, speed, irregularity, loads=None, start=0.0, breakpoints=(), driver=None, rtol=1e-10):
        """Flywheel sizing over one cycle of period ``period`` (rad) from ``start``: the
        loads (a dict as elsewhere: numbers, or callables of q) and the driver (a number
        or a callable of q; omitted: the constant torque that balances the cycle). Returns
        the net work, the balancing torque, S_max, S_min, ``fluctuation`` ΔE, the inertia
        by the approximate formula and by Wittenbauer's exact method (kg·m²), and the
        speeds of one simulated cycle with the exact flywheel."""
        def flat(q):
            return [float(v) for v in self._loads(loads, np.array([[q]]))[0]]

        drv = None
        if driver is not None:
            drv = driver if callable(driver) else (lambda q, c=float(driver): c)
        return dict(self._core.flywheel(float(start), float(period), [float(b) for b in breakpoints], float(speed), float(irregularity), flat, drv, float(rtol)))

    def cam_profile(self, name=None, points=360):
        """A cam's profile at ``points`` cam angles over a turn (``name``: the cam joint;
        omitted, the mechanism's only cam), for drawing and manufacturing. Returns a dict
        of arrays: ``theta`` (rad), the law's ``lift``, ``lift_velocity``,
        ``lift_acceleration`` (per radian of cam angle; m, or rad for an oscillating
        follower), ``pitch_x``, ``pitch_y``, ``contact_x``, ``contact_y`` (the cam's own
        frame, m), ``pressure_angle`` (rad) and ``curvature_radius`` (m, > 0 convex); and
        the design figures ``max_pressure_angle`` and ``at`` (rad), ``min_convex_radius``
        (m) and ``at`` (rad), ``undercut``."""
        cam, names, rows, (phi, phi_at, rho, rho_at, undercut) = self._core.cam_profile(name, int(points))
        out = {n: rows[:, k] for k, n in enumerate(names)}
        out["name"] = cam
        out["max_pressure_angle"] = (phi, phi_at)
        out["min_convex_radius"] = (rho, rho_at)
        out["undercut"] = undercut
        return out


def sweep(mechanism, params, q, qd=0.0, qdd=0.0, loads=None, parts=None):
    """The columns of ``parts`` (default all) for every variant of the parameters and
    every input: ``params`` is a dict of parameter path -> array of V values (shape
    ``(V,)``, or ``(V, 2)`` for points and vectors) or a list of V dicts. Returns a dict of
    arrays of shape ``(V, n)`` and ``ok`` (V, n): a variant whose drawing fails a check, or
    a configuration that does not assemble, is NaN with ``ok`` False, never an exception."""
    if isinstance(params, dict):
        arrays = {k: np.asarray(v, dtype=float) for k, v in params.items()}
        sizes = {a.shape[0] for a in arrays.values()}
        if len(sizes) > 1:
            raise InvalidInput("every parameter needs the same number of variants, got %s" % sorted(sizes))
        nv = sizes.pop() if sizes else 1
        variants = [[(k, [float(x) for x in np.atleast_1d(a[i])]) for k, a in arrays.items()] for i in range(nv)]
    else:
        variants = [[(k, [float(x) for x in np.atleast_1d(np.asarray(v, dtype=float))]) for k, v in p.items()] for p in params]
    m = mechanism
    qa, _ = m._rows(q)
    n = qa.shape[0]
    qd, _ = m._rows(qd, n)
    qdd, _ = m._rows(qdd, n)
    flat = m._loads(loads, qa)
    names, data, ok = m._core.sweep(variants, list(parts or _ALL), qa, qd, qdd, flat)
    out = {name: data[:, :, k] for k, name in enumerate(names)}
    out["ok"] = ok
    return out
