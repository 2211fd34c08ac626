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

What the solvers accept (``mech-py/tests/test_hostile.py``):

- **dtypes**: Python numbers and arrays of any integer or floating dtype (``int64``,
  ``uint8``, ``float32``, ...) are converted to float64; object arrays are converted when
  every element is a real number. ``bool``, complex, string and bytes values, ``None``,
  datetimes and object arrays holding anything else raise ``TypeError`` naming the
  argument — nothing is dropped silently (a complex value would lose its imaginary part).
- **layouts**: any strides — slices with a step, transposed and Fortran-ordered arrays —
  give the same answer as a C-contiguous copy.
- **shapes**: ``q`` is a number, ``(n,)`` for one input or ``(n, G)`` for G inputs (a
  ``(G,)`` vector is one configuration); ``qd``, ``qdd``, a driver and load arrays give
  one value (broadcast) or one per row of ``q``. Other shapes, and 3-D arrays, raise
  ``mech.InvalidInput`` naming the shapes. An empty ``q`` gives empty columns.
- **values**: a NaN or infinite input, rate or load raises ``mech.InvalidInput``; with
  ``errors="mask"`` its row is NaN with ``out["ok"]`` False instead, the other rows
  unaffected. ``mech.InvalidInput`` is both a ``mech.MechError`` and a ``ValueError``.
- **sizes**: a batch of more than 2²⁸ output values (2 GB), a cam profile of more than
  10⁶ points, a flywheel cycle of more than 1000 turns, and a DSL text of more than 4 MB
  or nested more than 64 brackets deep raise ``mech.InvalidInput`` before anything is
  allocated.
- **pickling**: a ``Mechanism`` and every result pickle and round-trip; the native core
  alone raises ``TypeError``.

>>> import mech
>>> m = mech.Mechanism.load("examples/mech/engine.mech")          # doctest: +SKIP
>>> m.reduced([0.0, 0.5])["inertia"]                                # doctest: +SKIP
"""

import numbers
import os
from collections.abc import Mapping

import numpy as np

from . import _mech
from ._mech import InvalidInput, InvalidMechanism, MechError, NoAssembly, Singular, num_threads

__all__ = [
    "Mechanism",
    "SpatialMechanism",
    "sweep",
    "optimize",
    "synthesize_function",
    "synthesize_motion",
    "synthesize_path",
    "engine",
    "num_threads",
    "MechError",
    "InvalidMechanism",
    "NoAssembly",
    "Singular",
    "InvalidInput",
]

_ALL = ["inputs", "positions", "rates", "reactions", "driver", "virtual_power", "zhukovski"]

# The most values one call returns (the native limit, checked here before any copy).
_MAX_VALUES = 1 << 28

# The largest mechanism file, bytes.
_MAX_TEXT = 4 << 20


def _kind(x):
    """A short description of a value's type, for messages."""
    if x is None:
        return "None"
    if isinstance(x, np.ndarray):
        return "an array of dtype %s" % x.dtype
    name = type(x).__name__
    return ("an %s" if name[0] in "aeiou" else "a %s") % name


def _floats(x, name):
    """``x`` as a float64 array (any shape), converting integer and floating dtypes;
    ``TypeError`` for bool, complex, str, bytes, None, datetimes and objects that are not
    real numbers."""
    if x is None:
        raise TypeError("%s is None: give a number or an array of numbers" % name)
    if isinstance(x, (str, bytes)):
        raise TypeError("%s is %s (%r): give a number or an array of numbers; convert text with float()" % (name, _kind(x), x[:40]))
    try:
        a = np.asarray(x)
    except (ValueError, TypeError) as e:
        raise InvalidInput("%s cannot be read as an array of numbers (ragged nesting?): %s" % (name, e)) from None
    if a.size > _MAX_VALUES:
        raise InvalidInput("%s has %d values, more than the limit of %d (2 GB); split the batch into chunks" % (name, a.size, _MAX_VALUES))
    k = a.dtype.kind
    if k == "f" and a.dtype == np.float64:
        return a
    if k in "iuf":
        return a.astype(np.float64)
    if k == "O":
        for v in a.flat:
            if isinstance(v, (bool, np.bool_)) or not isinstance(v, numbers.Real):
                raise TypeError("%s holds %s (%r): give real numbers" % (name, _kind(v), v))
        return a.astype(np.float64)
    what = {
        "b": "booleans: give numbers (0.0 and 1.0 if you meant them)",
        "c": "complex numbers: give real numbers (take .real if the imaginary parts are zero)",
        "U": "strings: give numbers; convert text with float()",
        "S": "bytes: give numbers",
        "M": "datetimes: give numbers (rad, m, s ...)",
        "m": "time deltas: give numbers of seconds",
    }.get(k, "values of dtype %s: give real numbers" % a.dtype)
    raise TypeError("%s holds %s" % (name, what))


def _number(x, name):
    """A finite real scalar ``x`` as a float (``TypeError`` for a non-number,
    ``InvalidInput`` for NaN or an infinity)."""
    a = _floats(x, name)
    if a.ndim != 0 and a.size != 1:
        raise InvalidInput("%s of shape %s: give one number" % (name, a.shape))
    v = float(a.reshape(()))
    if not np.isfinite(v):
        raise InvalidInput("%s = %r: not a finite number" % (name, v))
    return v


def _count(x, name):
    """A non-negative integer count."""
    if isinstance(x, bool) or not isinstance(x, numbers.Integral) or x < 0:
        raise TypeError("%s = %r: give a non-negative integer" % (name, x))
    return int(x)


def _motor(motor):
    """The motor's text for the core and, for ``table(FILE.csv)``, its (speeds, torques)."""
    if not isinstance(motor, str):
        raise TypeError("motor is %s: write it as text, e.g. \"dc(stall_torque 2, no_load_speed 300)\"" % _kind(motor))
    text = motor.strip()
    if not (text.startswith("table(") and text.endswith(")")):
        return text, None
    path = text[len("table("):-1].strip()
    data = np.genfromtxt(path, delimiter=",", names=True)
    names = data.dtype.names or ()
    if "torque" not in names or not ({"speed", "speed_rpm"} & set(names)):
        raise InvalidInput("%s: a motor table has the columns speed (rad/s) or speed_rpm, and torque (N·m); found %s" % (path, ", ".join(names)))
    speed = data["speed"] if "speed" in names else data["speed_rpm"] * np.pi / 30.0
    return "table()", ([float(v) for v in np.atleast_1d(speed)], [float(v) for v in np.atleast_1d(data["torque"])])


def _check_errors(errors):
    if errors not in ("raise", "mask"):
        raise ValueError("errors=%r: give \"raise\" (the default: a row that does not solve raises) or \"mask\" (its values are NaN, out[\"ok\"] False)" % (errors,))


def _text(text, what="text"):
    """The DSL text: a str (``TypeError`` for bytes or anything else)."""
    if isinstance(text, (bytes, bytearray)):
        raise TypeError("%s is bytes: give a str; decode it first, e.g. text.decode(\"utf-8\")" % what)
    if not isinstance(text, str):
        raise TypeError("%s is %s: give the mechanism's DSL text as a str" % (what, _kind(text)))
    return text


def _parts(parts):
    """The list of parts: default all; a str is one part."""
    if parts is None:
        return list(_ALL)
    if isinstance(parts, str):
        return [parts]
    parts = list(parts)
    for p in parts:
        if not isinstance(p, str):
            raise TypeError("a part is %s: give part names as str (%s)" % (_kind(p), ", ".join(_ALL)))
    return parts or list(_ALL)


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

    The solvers take numbers or arrays of any real dtype (converted to float64) and any
    strides; bool, complex, str, bytes and ``None`` are a ``TypeError``; bad values,
    shapes and sizes a ``mech.InvalidInput`` (also a ``ValueError``). See the package
    docstring for the whole policy.
    """

    def __init__(self, text, origin=None, params=()):
        text = _text(text)
        if origin is not None and not isinstance(origin, str):
            raise TypeError("origin is %s: give a str (a file name for the messages) or None" % _kind(origin))
        self._text = text
        self._origin = origin
        self._core = _mech._Mechanism.from_dsl(text, origin)
        self._params = []
        for path, value in params:
            self.set_param(path, value)

    @classmethod
    def from_dsl(cls, text):
        """The mechanism described by ``text`` (a str; ``TypeError`` for bytes, ``None``
        or anything else); ``InvalidMechanism`` (with ``line``, ``column`` and
        ``message``) when a check fails; ``InvalidInput`` for a text of more than 4 MB or
        nested more than 64 brackets deep."""
        if cls is Mechanism and _mech.is_spatial(_text(text)):
            return SpatialMechanism(text)
        return cls(text)

    @classmethod
    def load(cls, path):
        """The mechanism of a ``.mech`` file; messages name the file. ``OSError`` when it
        cannot be read; ``InvalidInput`` for a file of more than 4 MB, a binary file or
        one that is not UTF-8 text."""
        if path is None or not isinstance(path, (str, bytes, os.PathLike)):
            raise TypeError("path is %s: give a file name (str or os.PathLike)" % _kind(path))
        size = os.stat(path).st_size
        if size > _MAX_TEXT:
            raise InvalidInput("%s is %.1f MB, more than the %d MB a mechanism file may have; is it the right file?" % (os.fsdecode(path), size / 2**20, _MAX_TEXT >> 20))
        with open(path, "rb") as f:
            data = f.read(_MAX_TEXT + 1)
        name = os.fsdecode(path)
        if len(data) > _MAX_TEXT:
            raise InvalidInput("%s holds more than the %d MB a mechanism file may have; is it the right file?" % (name, _MAX_TEXT >> 20))
        if b"\0" in data:
            raise InvalidInput("%s is a binary file (a NUL byte at offset %d), not a mechanism's text" % (name, data.index(b"\0")))
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as e:
            raise InvalidInput("%s is not UTF-8 text (byte 0x%02x at offset %d); save it as UTF-8" % (name, data[e.start], e.start)) from None
        if cls is Mechanism and _mech.is_spatial(text):
            return SpatialMechanism(text, origin=name)
        return cls(text, origin=name)

    def __reduce__(self):
        return (_restore, (self._text, self._origin, tuple(self._params)))

    def __repr__(self):
        return "mech.%s(%r, dof=%d)" % (type(self).__name__, self.name, self.dof)

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
        if not isinstance(path, str):
            raise TypeError("path is %s: give a parameter path as a str, e.g. \"links.rod.mass\"" % _kind(path))
        value = [float(v) for v in np.atleast_1d(_floats(value, "value")).ravel()]
        self._core.set_param(path, value)
        self._params.append((path, value))

    def columns(self, parts=None):
        """The names of the columns of ``parts`` (default: all; a str is one part)."""
        return self._core.columns(_parts(parts))

    # -- inputs and loads --------------------------------------------------------------

    def _count(self, a):
        """The number of configurations in a float array of inputs (no copy)."""
        if a.ndim == 0:
            return 1
        if a.ndim == 1:
            return 1 if (self.dof > 1 and a.shape[0] == self.dof) else a.shape[0]
        return a.shape[0]

    def _check_size(self, rows, parts, what="the table"):
        """Refuse an output beyond the limit before anything is allocated."""
        width = max(len(self._core.columns(list(parts))), 1)
        if rows * width > _MAX_VALUES:
            raise InvalidInput("%s: %d rows × %d columns = %d values (%.1f GB), more than the limit of %d (2 GB); split the batch into chunks (docs/scale-out.md) or ask for fewer parts" % (what, rows, width, rows * width, rows * width * 8e-9, _MAX_VALUES))

    def _rows(self, x, n=None, name="q"):
        """x as C-contiguous (n, G) float64 (any dtype of real numbers, any strides);
        whether it was a scalar (one configuration). With ``n``, one row is repeated to
        n and any other count than n is refused."""
        a = _floats(x, name)
        g = self.dof
        scalar = a.ndim == 0 or (g > 1 and a.ndim == 1 and a.shape[0] == g)
        if a.ndim > 2:
            raise InvalidInput("%s of shape %s has %d dimensions: give a number, (n,) for one input or (n, G) for G" % (name, a.shape, a.ndim))
        shape = a.shape
        if a.ndim == 0:
            # A number: every input (several inputs: the same value for each).
            a = np.full((1, g), float(a))
        elif a.ndim == 1:
            a = a.reshape(1, g) if (g > 1 and a.shape[0] == g) else a.reshape(-1, 1)
        if a.shape[1] != g:
            raise InvalidInput("inputs of shape %s for %d input(s): %s is %s; give (n,) for one input, (n, G) for G" % (a.shape, g, name, shape))
        if n is not None and a.shape[0] != n:
            if a.shape[0] != 1:
                raise InvalidInput("%s has %d rows but q has %d: give one value, or one per row of q" % (name, a.shape[0], n))
            a = np.repeat(a, n, axis=0)
        return np.ascontiguousarray(a), scalar

    def _loads(self, loads, q):
        """The flat loads (n, L) in declaration order from a dict of name -> value: a
        number (torque), a pair (force), an array over the rows, or a callable of q."""
        n = q.shape[0]
        spec = self.load_names
        width = sum(w for _, w in spec)
        out = np.zeros((n, width))
        if loads is not None and not isinstance(loads, Mapping):
            raise TypeError("loads is %s: give a dict of load name -> value (a number, a pair, an array over the rows, or a callable of q)" % _kind(loads))
        loads = dict(loads or {})
        at = 0
        for name, w in spec:
            if name in loads:
                v = loads.pop(name)
                what = "loads[%r]" % name
                if callable(v):
                    v = np.array([_floats(v(qk[0] if self.dof == 1 else qk), what + "(q)") for qk in q])
                v = _floats(v, what)
                shape = "(fx, fy) or an (n, 2) array" if w == 2 else "a number or an (n,) array"
                kind = "a force" if w == 2 else "a torque"
                if v.size == w:
                    v = v.reshape(w)
                elif v.ndim >= 1 and v.size == n * w and (v.shape == (n, w) or (w == 1 and v.shape == (n,))):
                    v = v.reshape(n, w)
                else:
                    raise InvalidInput("%s of shape %s for %d rows: `%s` is %s, give %s" % (what, v.shape, n, name, kind, shape))
                out[:, at:at + w] = np.broadcast_to(v, (n, w))
            at += w
        if loads:
            raise InvalidInput("no load named %s: the mechanism's loads are %s" % (", ".join(sorted(loads)), ", ".join(n for n, _ in spec) or "none"))
        return out

    def _table(self, parts, q, qd=0.0, qdd=0.0, loads=None, errors="raise", rename=None):
        _check_errors(errors)
        q = _floats(q, "q")
        self._check_size(self._count(q), parts)
        q, scalar = self._rows(q)
        n = q.shape[0]
        qd, _ = self._rows(qd, n, "qd")
        qdd, _ = self._rows(qdd, n, "qdd")
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

    def shaking(self, q, qd=0.0, qdd=0.0, errors="raise"):
        """The shaking force and moment on the frame (no loads, no gravity): ``shaking.fx``,
        ``shaking.fy`` = −Σ m a_G (N) and ``shaking.moment`` = −Σ (r_G × m a_G + I_G α)
        about the origin (N·m), with ``q``; with links in several planes (``plane: z``)
        also ``shaking.mx`` = Σ z m a_y and ``shaking.my`` = −Σ z m a_x (N·m), the
        couples about the x and y axes."""
        return self._table(["inputs", "shaking"], q, qd, qdd, None, errors)

    def balance(self, speed=0.0, method="force", fraction=0.5, radius=None, weights=(1.0, 1.0, 1.0)):
        """The mechanism with counterweights that balance its shaking force (SPEC 3g, as
        ``mech balance`` does it): ``method="force"`` balances the force exactly where the
        topology allows (a four-bar by two counterweights on its ground-pinned links; a
        slider-crank's crank counterweight takes the rotating masses and the fraction
        ``fraction`` of the reciprocating one); ``"optimal"`` minimises
        ``weights`` = (w_F, w_M, w_T) on the RMS of shaking force, shaking moment and
        driver torque over a turn at ``speed`` (rad/s). ``radius`` (m): the counterweights'
        distance from their pivots (``None``: each link's own length). Returns a new
        :class:`Mechanism` whose text carries the ``counterweight:`` entries."""
        if method not in ("force", "optimal"):
            raise InvalidInput("method = %r: give \"force\" or \"optimal\"" % (method,))
        speed = _number(speed, "speed")
        fraction = _number(fraction, "fraction")
        if not 0.0 <= fraction <= 1.0:
            raise InvalidInput("fraction = %r: give a number from 0 to 1" % (fraction,))
        if radius is not None:
            radius = _number(radius, "radius")
        w = tuple(_number(v, "weights") for v in weights)
        if len(w) != 3:
            raise InvalidInput("weights = %r: give three numbers, force, moment, driver" % (weights,))
        return Mechanism(_mech.balance(self.text, speed, method, fraction, radius, w))

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
        _check_errors(errors)
        if self.dof != 1:
            raise InvalidInput("the direct problem by Zhukovski needs one input; this mechanism has %d" % self.dof)
        q, scalar = self._rows(q)
        n = q.shape[0]
        qd, _ = self._rows(qd, n, "qd")
        if callable(driver):
            driver = [_number(driver(x), "driver(q)") for x in q[:, 0]]
        d, _ = self._rows(driver, n, "driver")
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
        period, speed, irregularity = _number(period, "period"), _number(speed, "speed"), _number(irregularity, "irregularity")
        start, rtol = _number(start, "start"), _number(rtol, "rtol")
        breakpoints = [float(b) for b in np.atleast_1d(_floats(breakpoints, "breakpoints")).ravel()]
        if self.dof != 1:
            raise InvalidInput("flywheel sizing needs one revolute input; this mechanism has %d inputs" % self.dof)
        flat = self._loads_of_q(loads)
        drv = None
        if driver is not None:
            if callable(driver):
                def drv(q):
                    return _number(driver(q), "driver(q)")
            else:
                c = _number(driver, "driver")
                drv = lambda q: c  # noqa: E731
        return dict(self._core.flywheel(start, period, breakpoints, speed, irregularity, flat, drv, rtol))

    def _loads_of_q(self, loads):
        """The flat loads at one q, for the Rust integrators (a dict as elsewhere)."""
        if loads is not None and not isinstance(loads, Mapping):
            raise TypeError("loads is %s: give a dict of load name -> value" % _kind(loads))

        def flat(q):
            return [float(v) for v in self._loads(loads, np.array([[q]]))[0]]

        return flat

    def simulate(self, t_end, motor, ratio=1.0, q0=0.0, speed=0.0, loads=None, flywheel=0.0, samples=100):
        """The motion under a motor over [0, ``t_end``] s from ``q0`` (rad) at ``speed``
        (rad/s; 0, the default, starts from rest after checking that the motor can start
        the machine there). ``motor`` is written as on the command line:
        ``"dc(stall_torque 2, no_load_speed 3000 rpm)"``, ``"induction(rated_power 1500,
        synchronous_speed 1500 rpm, rated_speed 1420 rpm, breakdown_ratio 2.5)"``,
        ``"table(FILE.csv)"`` (columns ``speed`` rad/s or ``speed_rpm``, and ``torque`` N·m),
        ``"constant(T)"``; ``ratio`` n = motor speed / input speed; ``flywheel`` (kg·m²) on
        the input shaft. Returns a dict of arrays ``t``, ``q``, ``qd`` and ``torque`` (the
        motor's action on the input, N·m) at ``samples`` + 1 even times."""
        text, table = _motor(motor)
        t, q, qd, torque = self._core.simulate_motor(
            text, table, _number(ratio, "ratio"), _number(q0, "q0"), _number(speed, "speed"),
            _number(t_end, "t_end"), _count(samples, "samples"), self._loads_of_q(loads),
            _number(flywheel, "flywheel"))
        return {"t": np.array(t), "q": np.array(q), "qd": np.array(qd), "torque": np.array(torque)}

    def regime(self, motor, ratio=1.0, loads=None, flywheel=0.0, period=2 * np.pi, start=0.0, points=360):
        """The periodic steady regime ω(q) = ω(q + period) under a motor (written as in
        :meth:`simulate`), found directly by shooting. Returns a dict: the arrays ``q``,
        ``qd``, ``t`` (s from ``start``) and ``torque`` over one period at ``points`` + 1
        positions, and the numbers ``mean_speed`` (rad/s), ``epsilon`` = (ω_max − ω_min)/ω_a,
        ``period_time`` (s), ``motor_peak_torque``, ``motor_rms_torque`` (N·m, on the
        motor's shaft), ``motor_mean_power`` (W), ``motor_rated_torque`` (NaN when the
        curve states none) and ``within_rating`` (bool)."""
        text, table = _motor(motor)
        q, qd, t, torque, summary = self._core.regime(
            text, table, _number(ratio, "ratio"), _number(start, "start"), _number(period, "period"),
            _count(points, "points"), self._loads_of_q(loads), _number(flywheel, "flywheel"))
        out = {"q": np.array(q), "qd": np.array(qd), "t": np.array(t), "torque": np.array(torque)}
        for k, v in summary:
            out[k] = bool(v) if k == "within_rating" else v
        return out

    def strength(self, qd=0.0, loads=None, steps=360, period=2 * np.pi, all=False):
        """The strength of every member over one period at the constant input speed ``qd``
        (rad/s; 0 checks the loads and gravity alone), from the reactions at ``steps``
        instants. A member is a link declared by a beam ``shape:`` with a ``material:``,
        or a joint declared with a ``pin``. Returns a dict of arrays, one entry per member
        (its governing criterion; with ``all=True`` one per criterion): ``member``
        (``<link>`` or ``<joint>.pin``), ``criterion`` (``axial``, ``bending``, ``shear``,
        ``bearing``, ``buckling``, ``fatigue``), ``stress_max``, ``stress_mean``,
        ``stress_alt`` (Pa), ``safety`` (the smallest factor over the cycle) and ``q`` (rad,
        where it is smallest)."""
        members, criteria, rows = self._core.strength(
            _number(qd, "qd"), _number(period, "period"), _count(steps, "steps"),
            self._loads_of_q(loads), bool(all))
        rows = np.array(rows, dtype=float).reshape(-1, 5)
        out = {"member": np.array(members, dtype=object), "criterion": np.array(criteria, dtype=object)}
        for k, name in enumerate(("stress_max", "stress_mean", "stress_alt", "safety", "q")):
            out[name] = rows[:, k]
        return out

    def size(self, safety, qd=0.0, loads=None, steps=180, period=2 * np.pi, irregularity=None):
        """Size the dimensions written ``free(LO..HI)`` in the mechanism's text so that every
        member's factor of safety is at least ``safety``, re-running the dynamics with each
        change until a fixed point (as ``mech size``). Returns a dict: the passes as arrays
        ``total_mass`` (kg), ``peak_torque`` (N·m), ``flywheel`` (kg·m² for the
        ``irregularity`` ε at the mean speed ``qd``; NaN without one) and ``worst``; ``dims``,
        a dict ``"link.dimension"`` -> the sized value (m); ``text``, the sized DSL text (load
        it with ``Mechanism(text)``); ``converged``; and ``unmet``, the members that cannot
        meet the factor."""
        eps = None if irregularity is None else _number(irregularity, "irregularity")
        rows, dims, text, converged, unmet = self._core.size(
            self._text, _number(safety, "safety"), _number(qd, "qd"), _number(period, "period"),
            _count(steps, "steps"), eps, self._loads_of_q(loads))
        rows = np.array(rows, dtype=float).reshape(-1, 4)
        out = {name: rows[:, k] for k, name in enumerate(("total_mass", "peak_torque", "flywheel", "worst"))}
        out["dims"] = {"%s.%s" % (link, name): value for link, name, value in dims}
        out["text"] = text
        out["converged"] = converged
        out["unmet"] = list(unmet)
        return out
    def stop(self, qd0, brake=0.0, q0=0.0, dt=None, t_max=600.0, loads=None, flywheel=0.0, points=100):
        """The stop with the motor switched off at ``q0`` (rad) and the input turning at
        ``qd0`` > 0 (rad/s): coasting (``brake`` = 0, the loads, gravity and the elements
        stop it) or braked by a constant torque ``brake`` (N·m ≥ 0) against the motion, until
        the machine is at rest; ``loads`` a dict as in :meth:`simulate`, ``flywheel`` (kg·m²)
        on the input shaft. Sampled every ``dt`` seconds (the last sample at rest), or, with
        ``dt`` None, at ``points`` + 1 even times from 0 to rest. Returns a dict: the arrays
        ``t`` (s), ``q`` (rad), ``qd`` (rad/s) and ``torque`` (the brake's action on the input,
        N·m), and the numbers ``stop_time`` (s) and ``stop_angle`` (rad, the angle turned).
        ``InvalidInput`` when the machine still moves at ``t_max`` seconds (coasting with no
        loss never stops: give a brake)."""
        if dt is not None:
            dt = _number(dt, "dt")
        t, q, qd, torque, time, travel = self._core.stop(
            _number(q0, "q0"), _number(qd0, "qd0"), _number(brake, "brake"), dt,
            _count(points, "points"), _number(t_max, "t_max"), self._loads_of_q(loads),
            _number(flywheel, "flywheel"))
        return {"t": np.array(t), "q": np.array(q), "qd": np.array(qd), "torque": np.array(torque),
                "stop_time": time, "stop_angle": travel}

    def cam_profile(self, name=None, points=360):
        """A cam's profile at ``points`` cam angles over a turn (``name``: the cam joint;
        omitted, the mechanism's only cam), for drawing and manufacturing. Returns a dict
        of arrays: ``theta`` (rad), the law's ``lift``, ``lift_velocity``,
        ``lift_acceleration`` (per radian of cam angle; m, or rad for an oscillating
        follower), ``pitch_x``, ``pitch_y``, ``contact_x``, ``contact_y`` (the cam's own
        frame, m), ``pressure_angle`` (rad) and ``curvature_radius`` (m, > 0 convex); and
        the design figures ``max_pressure_angle`` and ``at`` (rad), ``min_convex_radius``
        (m) and ``at`` (rad), ``undercut``."""
        if name is not None and not isinstance(name, str):
            raise TypeError("name is %s: give the cam joint's name as a str, or None for the only cam" % _kind(name))
        if isinstance(points, (bool, np.bool_)) or not isinstance(points, (int, np.integer, float, np.floating)):
            raise TypeError("points is %s: give a whole number from 3 to 1000000" % _kind(points))
        whole = isinstance(points, (int, np.integer)) or (np.isfinite(points) and float(points).is_integer())
        if not (whole and 3 <= points <= 1_000_000):
            raise InvalidInput("points = %r: give a whole number from 3 to 1000000" % (points,))
        cam, names, rows, (phi, phi_at, rho, rho_at, undercut) = self._core.cam_profile(name, int(points))
        out = {n: rows[:, k] for k, n in enumerate(names)}
        out["name"] = cam
        out["max_pressure_angle"] = (phi, phi_at)
        out["min_convex_radius"] = (rho, rho_at)
        out["undercut"] = undercut
        return out


def _restore_spatial(text, origin, params=()):
    """Rebuild a pickled SpatialMechanism from its text and its changed parameters."""
    m = SpatialMechanism(text, origin=origin)
    for path, value in params:
        m.set_param(path, value)
    return m


class SpatialMechanism:
    """A spatial mechanism (SPEC 3i): a text whose first item is ``space``
    (``docs/spatial.md``), checked at load time (Kutzbach's count with the idle links, the
    constraints' rank). ``Mechanism.from_dsl`` and ``Mechanism.load`` return one for such
    a text.

    The solvers take q as ``Mechanism``'s do and return dicts keyed like the ``mech``
    tool's spatial CSV columns (``docs/cli.md``, "Spatial mechanisms"): ``"B.x"``,
    ``"B.y"``, ``"B.z"``, ``"rod.qw"`` … ``"rod.qz"`` (the rotation from the drawing, a unit
    quaternion), ``"B.vz"``, ``"rod.omega_x"``, ``"rod.alpha_z"``, ``"A.fx"`` … ``"A.fz"``,
    ``"A.mx"`` … ``"A.mz"``, ``"driver"``, ``"inertia"``, ``"moment"``. Loads are a dict of
    name -> (x, y, z) (N for a force, N·m for a torque, global axes), or an (n, 3) array.
    """

    def __init__(self, text, origin=None):
        text = _text(text)
        if origin is not None and not isinstance(origin, str):
            raise TypeError("origin is %s: give a str (a file name for the messages) or None" % _kind(origin))
        self._text = text
        self._origin = origin
        self._params = []
        self._core = _mech._SpatialMechanism.from_dsl(text, origin)

    @classmethod
    def from_dsl(cls, text):
        """The spatial mechanism described by ``text``."""
        return cls(text)

    @classmethod
    def load(cls, path):
        """The spatial mechanism of a ``.mech`` file (``Mechanism.load``'s checks)."""
        m = Mechanism.load(path)
        if not isinstance(m, SpatialMechanism):
            raise InvalidInput("%s is a planar mechanism (its first item is not `space`): load it with mech.Mechanism.load" % os.fsdecode(path))
        return m

    def __reduce__(self):
        return (_restore_spatial, (self._text, self._origin, tuple(self._params)))

    def set_param(self, path, value):
        """Change one number of the drawing, re-checked like the text: ``points.B`` =
        (x, y, z) m, ``links.rod.mass`` kg, ``links.rod.cg`` (x, y, z) m,
        ``links.rod.inertia`` (Ixx, Iyy, Izz, Ixy, Ixz, Iyz) kg·m², ``axes.C`` (ux, uy, uz)
        (six numbers for a universal joint), ``pitch.nut`` m per turn, ``gravity``
        (gx, gy, gz) m/s². ``mech.sweep`` varies these."""
        if not isinstance(path, str):
            raise TypeError("path is %s: give a parameter path as a str, e.g. \"links.rod.mass\"" % _kind(path))
        value = [float(v) for v in np.atleast_1d(_floats(value, "value")).ravel()]
        self._core.set_param(path, value)
        self._params.append((path, value))

    # What both kinds share: the name, G, the text, the representation.
    __repr__ = Mechanism.__repr__
    name = Mechanism.name
    dof = Mechanism.dof
    text = Mechanism.text

    @property
    def inputs(self):
        """The inputs as (joint name, kind: "revolute", "prismatic" or "helical")."""
        return self._core.inputs

    @property
    def load_names(self):
        """The declared loads as (name, "force" | "torque"), three components each."""
        return self._core.loads

    @property
    def idle_links(self):
        """The links that spin idly between two spherical joints."""
        return self._core.idle_links

    def columns(self, parts=None):
        """The names of the columns of ``parts`` (default: all; a str is one part)."""
        return self._core.columns(_parts(parts))

    _count = Mechanism._count
    _check_size = Mechanism._check_size
    _rows = Mechanism._rows
    _table = Mechanism._table

    def _loads(self, loads, q):
        """The loads (n, 3 L): each load's x, y, z in declaration order, from a dict of
        name -> (x, y, z) or an (n, 3) array."""
        n = q.shape[0]
        spec = self.load_names
        out = np.zeros((n, 3 * len(spec)))
        if loads is not None and not isinstance(loads, Mapping):
            raise TypeError("loads is %s: give a dict of load name -> (x, y, z)" % _kind(loads))
        loads = dict(loads or {})
        for k, (name, kind) in enumerate(spec):
            if name in loads:
                what = "loads[%r]" % name
                v = _floats(loads.pop(name), what)
                if v.size == 3:
                    v = v.reshape(3)
                elif v.shape == (n, 3):
                    pass
                else:
                    raise InvalidInput("%s of shape %s: `%s` is a %s of a spatial mechanism, give its three components (x, y, z) or an (%d, 3) array" % (what, v.shape, name, kind, n))
                out[:, 3 * k:3 * k + 3] = np.broadcast_to(v, (n, 3))
        if loads:
            raise InvalidInput("no load named %s: the mechanism's loads are %s" % (", ".join(sorted(loads)), ", ".join(n for n, _ in spec) or "none"))
        return out

    def pose(self, q, errors="raise"):
        """Positions: ``<point>.x``, ``.y``, ``.z`` (m) and each link's rotation
        ``<link>.qw``, ``.qx``, ``.qy``, ``.qz``."""
        return self._table(["positions"], q, errors=errors)

    def kinematics(self, q, qd=0.0, qdd=0.0, errors="raise"):
        """Positions, velocities (``.vx``, ``.vy``, ``.vz``, ``<link>.omega_x`` …) and
        accelerations (``.ax``, ``.ay``, ``.az``, ``<link>.alpha_x`` …)."""
        return self._table(["positions", "rates"], q, qd, qdd, errors=errors)

    def kinetostatics(self, q, qd=0.0, qdd=0.0, loads=None, errors="raise"):
        """Newton–Euler: every reaction (``<joint>.fx``, ``.fy``, ``.fz`` N, ``.mx``,
        ``.my``, ``.mz`` N·m about the joint's point, by its first link on its second) and
        the motor action ``driver``."""
        return self._table(["reactions", "driver"], q, qd, qdd, loads, errors)

    def driver_action(self, q, qd=0.0, qdd=0.0, loads=None, errors="raise"):
        """The motor actions by virtual power: ``driver`` (``driver.<joint>``)."""
        return self._table(["virtual_power"], q, qd, qdd, loads, errors, rename=lambda n: n.replace("virtual_power", "driver"))

    def reduced(self, q, errors="raise"):
        """Zhukovski's ``inertia`` I* and ``inertia_derivative`` dI*/dq (one input)."""
        out = self._table(["zhukovski"], q, errors=errors)
        out.pop("moment", None)
        return out

    def reduced_moment(self, q, loads=None, errors="raise"):
        """Zhukovski's reduced moment ``moment`` M* of the loads and gravity."""
        out = self._table(["zhukovski"], q, loads=loads, errors=errors)
        return {k: v for k, v in out.items() if k in ("moment", "ok")}

    # The direct problem ``qdd`` (one input) and the flywheel over a cycle (one revolute
    # input), as ``Mechanism``'s: loads as (x, y, z) per name, or callables of q.
    acceleration = Mechanism.acceleration
    flywheel = Mechanism.flywheel
    _loads_of_q = Mechanism._loads_of_q


def optimize(mechanism, vary, minimize, subject_to=(), qd=0.0, loads=None, steps=180, period=2 * np.pi,
             irregularity=None, targets=None, point=None, evaluations=300, seed=0):
    """Vary named numbers of ``mechanism``'s text within bounds to minimise an objective of
    its dynamics (as ``mech optimize``). ``vary``: a dict name -> (lo, hi) in SI, or
    (lo, hi, unit) with the unit word the file writes (``{"l": (120, 180, "mm")}``); a name
    is a constant of ``consts { .. }`` or ``links.<l>.mass`` / ``links.<l>.inertia``.
    ``minimize``: ``"peak_driver"``, ``"rms_driver"``, ``"flywheel"`` (with
    ``irregularity``), ``"peak_reaction(J)"``, ``"rms_shaking"`` or ``"path"`` (with
    ``targets``, an (n, 2) array in m, and ``point``, the point's name). ``subject_to``:
    constraints written as on the command line (``"grashof"``, ``"transmission >= 40
    deg"``). Over one period at the constant speed ``qd`` (rad/s) at ``steps`` instants;
    ``loads`` a dict as in :meth:`Mechanism.simulate`. Returns a dict: ``mechanism`` (the
    optimised Mechanism), ``text``, ``values`` (name -> SI), ``objective``, ``initial``
    (the objective as given), ``history`` (an (k, 2) array of evaluations and best
    objective) and ``evaluations``."""
    if not isinstance(mechanism, (Mechanism, SpatialMechanism)):
        raise TypeError("mechanism is %s: give a mech.Mechanism or a mech.SpatialMechanism" % _kind(mechanism))
    if not isinstance(vary, Mapping) or not vary:
        raise TypeError("vary is %s: give a dict name -> (lo, hi) or (lo, hi, unit)" % _kind(vary))
    spec = []
    for name, b in vary.items():
        if not isinstance(b, (tuple, list)) or len(b) not in (2, 3):
            raise TypeError("vary[%r] is %s: give (lo, hi) or (lo, hi, unit)" % (name, _kind(b)))
        unit = b[2] if len(b) == 3 else None
        spec.append((str(name), _number(b[0], "lo"), _number(b[1], "hi"), unit))
    t = None if targets is None else [[float(x), float(y)] for x, y in np.asarray(targets, dtype=float).reshape(-1, 2)]
    eps = None if irregularity is None else _number(irregularity, "irregularity")
    values, obj, initial, history, text, n = _mech.optimize(
        mechanism.text, spec, str(minimize), t, point, eps, [str(c) for c in subject_to],
        _number(qd, "qd"), _number(period, "period"), _count(steps, "steps"),
        _count(evaluations, "evaluations"), _count(seed, "seed"), mechanism._loads_of_q(loads))
    return {"mechanism": Mechanism(text), "text": text, "values": dict(zip([s[0] for s in spec], values)),
            "objective": obj, "initial": initial, "history": np.array(history, dtype=float).reshape(-1, 2),
            "evaluations": n}


def sweep(mechanism, params, q, qd=0.0, qdd=0.0, loads=None, parts=None):
    """The columns of ``parts`` (default all) for every variant of the parameters and
    every input: ``params`` is a dict of parameter path -> array of V values (shape
    ``(V,)``, or ``(V, 2)`` for points and vectors — ``(V, 3)`` for a spatial mechanism's,
    ``(V, 6)`` for its inertia tensors) or a list of V dicts (``set_param``'s paths). Returns a dict of
    arrays of shape ``(V, n)`` and ``ok`` (V, n): a variant whose drawing fails a check, or
    a configuration that does not assemble, is NaN with ``ok`` False, never an exception."""
    if not isinstance(mechanism, (Mechanism, SpatialMechanism)):
        raise TypeError("mechanism is %s: give a mech.Mechanism or a mech.SpatialMechanism" % _kind(mechanism))
    if isinstance(params, Mapping):
        for k in params:
            if not isinstance(k, str):
                raise TypeError("params key %r is %s: give parameter paths as str" % (k, _kind(k)))
        arrays = {k: np.atleast_1d(_floats(v, "params[%r]" % k)) for k, v in params.items()}
        sizes = {a.shape[0] for a in arrays.values()}
        if len(sizes) > 1:
            raise InvalidInput("every parameter needs the same number of variants, got %s" % sorted(sizes))
        nv = sizes.pop() if sizes else 1
    elif isinstance(params, (list, tuple)) and all(isinstance(p, Mapping) for p in params):
        nv = len(params)
    else:
        raise TypeError("params is %s: give a dict of parameter path -> V values, or a list of V such dicts" % _kind(params))
    m = mechanism
    parts = _parts(parts)
    qa = _floats(q, "q")
    # The size first: a refused sweep builds nothing per variant.
    m._check_size(nv * m._count(qa), parts, "the sweep (variants × rows)")
    if isinstance(params, Mapping):
        variants = [[(k, [float(x) for x in np.atleast_1d(a[i])]) for k, a in arrays.items()] for i in range(nv)]
    else:
        variants = [[(k, [float(x) for x in np.atleast_1d(_floats(v, "params[%d][%r]" % (i, k))).ravel()]) for k, v in p.items()] for i, p in enumerate(params)]
    qa, _ = m._rows(qa)
    n = qa.shape[0]
    qd, _ = m._rows(qd, n, "qd")
    qdd, _ = m._rows(qdd, n, "qdd")
    flat = m._loads(loads, qa)
    names, data, ok = m._core.sweep(variants, parts, qa, qd, qdd, flat)
    out = {name: data[:, :, k] for k, name in enumerate(names)}
    out["ok"] = ok
    return out


def _targets(x, name, width, what):
    """``x`` as a list of rows of ``width`` finite floats (an array-like of shape
    ``(n, width)``)."""
    a = _floats(x, name)
    if a.ndim != 2 or a.shape[1] != width:
        raise InvalidInput("%s of shape %s: give an array of shape (n, %d), one row of %s per target" % (name, a.shape, width, what))
    if not np.all(np.isfinite(a)):
        i = int(np.argwhere(~np.isfinite(a))[0][0])
        raise InvalidInput("%s row %d %s is not finite: give finite numbers" % (name, i + 1, list(a[i])))
    return a.tolist()


def synthesize_function(pairs, frame=1.0):
    """A four-bar function generator: the output angle (O4 → B) at given input angles
    (O2 → A), both rad counter-clockwise from the frame line O2 → O4 (SPEC §3f).

    ``pairs`` is an array-like of shape ``(n, 2)``: (input, output) rows. Three pairs are
    met exactly (Freudenstein's equation K₁ cos θ₄ − K₂ cos θ₂ + K₃ = cos(θ₂ − θ₄),
    K₁ = d/a, K₂ = d/c, K₃ = (a² − b² + c² + d²)/(2ac)); more by least squares on K.
    ``frame`` is the frame length d (m): O2 at the origin, O4 at (d, 0), so the run-time
    input q is the input angle itself.

    Returns ``(Mechanism, error)``: the four-bar (points ``O2``, ``O4``, ``A``, ``B``,
    ``P``, input ``O2``) and error = Σ (θ₄(θ₂ᵢ) − θ₄ᵢ)² (rad²). Bad pairs (fewer than
    three, not finite, two with one input, a singular system, no four-bar) raise
    ``mech.InvalidInput`` naming the fix."""
    rows = _targets(pairs, "pairs", 2, "(input, output)")
    text, error = _mech.synthesize_function(rows, _number(frame, "frame"))
    return Mechanism.from_dsl(text), error


def synthesize_motion(poses, circle_points=None, full=False):
    """A four-bar motion generator: the coupler through given poses (SPEC §3f).

    ``poses`` is an array-like of shape ``(n, 3)``: (x, y, angle) rows, P's position (m)
    and the coupler's direction A → B (rad). Three to five poses are met exactly (Burmester
    theory: circumcentres for three, the circle-point curve for four, the Burmester points
    for five), more by least squares. ``circle_points`` (three poses only) is
    ``((xA, yA), (xB, yB))``, the circle points of A and B in the moving frame (m; origin
    P, x along the pose's angle); by default the best pair on one line along the pose's
    angle (so that A → B points along it).

    Returns ``(Mechanism, error)``: the four-bar (points ``O2``, ``O4``, ``A``, ``B``,
    ``P``, input ``O2`` whose q is the crank's absolute angle) and error = Σ |P(θᵢ) − Pᵢ|² +
    L² |e(φᵢ − γ) − e(angleᵢ)|² (m²; φᵢ the direction of A → B at the pose's crank angle θᵢ,
    L = |AB|). The coupler's direction A → B is angleᵢ + γ at every pose: γ = 0 unless the
    Burmester points of five poses force it. With ``full=True``, ``(Mechanism, error,
    {"offset": γ, "q": the crank angle θᵢ of each pose})``. Bad poses raise
    ``mech.InvalidInput`` naming the fix."""
    rows = _targets(poses, "poses", 3, "(x, y, angle)")
    cp = None
    if circle_points is not None:
        c = _floats(circle_points, "circle_points")
        if c.shape != (2, 2):
            raise InvalidInput("circle_points of shape %s: give ((xA, yA), (xB, yB)), m in the moving frame" % (c.shape,))
        cp = c.tolist()
    text, error, offset, q = _mech.synthesize_motion(rows, cp)
    m = Mechanism.from_dsl(text)
    if full:
        return m, error, {"offset": offset, "q": np.array(q)}
    return m, error
def engine(layout="inline", cylinders=4, bank=np.pi / 2, firing=None, phases=None,
           radius=0.045, rod=0.15, mass=0.5, spacing=0.09, balance_couple=False):
    """An engine of several cylinders on one crankshaft, as ``mech engine`` writes it
    (docs/cli.md): ``layout`` ``"inline"``, ``"v"`` (bank angle ``bank``, rad) or
    ``"boxer"``; the crank throws from the four-stroke ``firing`` order (a list of cylinder
    numbers from 1, or a string ``"1-3-4-2"``) or given as ``phases`` (rad, one per crank
    pin); ``radius``, ``rod`` (m), the reciprocating ``mass`` of each cylinder (kg) and the
    pin ``spacing`` along the shaft (m). With ``balance_couple`` two crankshaft
    counterweights at the end planes cancel a primary couple that rotates with the crank
    (a cross-plane V8's).

    Returns ``(mechanism, table)``: the engine as a :class:`Mechanism` (links in their
    planes, ``plane: z``) and the classical balance table, a list of dicts (one row, two
    with ``balance_couple``: before and after) with ``engine``, ``firing``, ``throws``
    and, as ``(exact, first_order)`` pairs, ``primary_force`` and ``secondary_force``
    over m r w^2 and m r w^2 (r/l), ``primary_couple`` and ``secondary_couple`` over the
    same times the pin spacing."""
    if isinstance(firing, str):
        try:
            firing = [int(c) for c in firing.replace(",", "-").split("-")]
        except ValueError:
            raise InvalidInput("firing = %r: give cylinder numbers like \"1-3-4-2\"" % (firing,))
    if firing is not None:
        firing = [_count(c, "firing") for c in firing]
    if phases is not None:
        phases = [float(v) for v in np.atleast_1d(_floats(phases, "phases")).ravel()]
    text, rows = _mech.engine(
        str(layout), _count(cylinders, "cylinders"), _number(bank, "bank"), firing, phases,
        _number(radius, "radius"), _number(rod, "rod"), _number(mass, "mass"),
        _number(spacing, "spacing"), bool(balance_couple))
    return Mechanism(text), rows


def synthesize_path(points, closed=True, seed=1, evaluations=200000, angles=None,
                    transmission=30.0, ratio=10.0, topology="four-bar"):
    """A four-bar whose coupler point P passes nearest to ``points`` (an (n, 2) array of
    x, y in m, n >= 3): SPEC 3f's path synthesis, as ``mech synth path`` does it
    (docs/cli.md). ``closed``: the crank turns fully (else it rocks within one arc);
    ``angles``: the crank angle O2 -> A of each point (rad, from the frame line O2 -> O4)
    for prescribed timing, ``None`` for free timing; ``seed``: one seed, one result;
    ``evaluations``: the global search's budget; ``transmission``: the smallest
    transmission angle allowed, degrees; ``ratio``: the longest link over the shortest;
    ``topology``: ``"four-bar"`` or ``"six-bar"`` (a Stephenson III six-bar: the four-bar's
    coupler point C drives a second dyad C D O6 and P is on the link C D; closed paths).

    Returns ``(mechanism, error)``: a :class:`Mechanism` with the points O2, O4, A, B, P
    (a six-bar adds C, D, O6) and input O2, and E = sum of the squared distances of the points to its coupler curve
    (m^2; with prescribed timing, to P at their angles). ``InvalidInput`` for bad points
    (too few, coincident, not finite, the wrong shape); ``MechError`` naming the binding
    constraint when no four-bar meets the constraints.
    """
    pts = _floats(points, "points")
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise InvalidInput("points of shape %s: give n points as an (n, 2) array of x, y (m)" % (pts.shape,))
    if angles is not None:
        angles = [float(v) for v in np.atleast_1d(_floats(angles, "angles")).ravel()]
    if not isinstance(closed, (bool, np.bool_)):
        raise TypeError("closed = %r: give True or False" % (closed,))
    seed = _count(seed, "seed")
    evaluations = _count(evaluations, "evaluations")
    transmission = _number(transmission, "transmission")
    ratio = _number(ratio, "ratio")
    if topology not in ("four-bar", "six-bar"):
        raise InvalidInput("topology = %r: give \"four-bar\" or \"six-bar\"" % (topology,))
    text, error, _info = _mech.synthesize_path(
        np.ascontiguousarray(pts), angles, bool(closed), seed, evaluations, transmission, ratio,
        topology == "six-bar")
    return Mechanism.from_dsl(text), error
