"""Type stubs of the package `mech` (dynamics of planar machines)."""

from os import PathLike
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
Columns = Dict[str, Any]
LoadValue = Union[float, Sequence[float], npt.ArrayLike, Callable[[Any], Any]]

class MechError(Exception):
    """An error of mech: what is wrong, the numbers and the fix."""

class InvalidMechanism(MechError):
    """The description fails a check."""
    line: Optional[int]
    column: Optional[int]
    message: str

class NoAssembly(MechError):
    """The mechanism cannot be assembled at this input value."""

class Singular(MechError):
    """A dead point: not solvable to the requested accuracy."""

class InvalidInput(MechError, ValueError):
    """A bad number (NaN, infinite, out of range), shape or size: a MechError and a ValueError."""

def num_threads() -> int:
    """Threads of the solvers (MECH_NUM_THREADS)."""

class Mechanism:
    """A planar mechanism read from DSL text (a `.mech` file), checked like the macro."""

    def __init__(self, text: str, origin: Optional[str] = ..., params: Iterable[Tuple[str, Sequence[float]]] = ...) -> None: ...
    @classmethod
    def from_dsl(cls, text: str) -> "Mechanism":
        """The mechanism described by `text`."""
    @classmethod
    def load(cls, path: Union[str, "PathLike[str]"]) -> "Mechanism":
        """The mechanism of a `.mech` file."""
    @property
    def name(self) -> str: ...
    @property
    def dof(self) -> int: ...
    @property
    def inputs(self) -> List[Tuple[str, str]]: ...
    @property
    def load_names(self) -> List[Tuple[str, int]]: ...
    @property
    def text(self) -> str: ...
    def set_param(self, path: str, value: ArrayLike) -> None:
        """Change one number of the drawing (points.A, links.rod.mass, ...), re-checked."""
    def columns(self, parts: Optional[Sequence[str]] = ...) -> List[str]: ...
    def pose(self, q: ArrayLike, errors: str = ..., angles: bool = ...) -> Columns:
        """`<point>.x`, `<point>.y` (m), `<link>.angle` (rad)."""
    def kinematics(self, q: ArrayLike, qd: ArrayLike = ..., qdd: ArrayLike = ..., errors: str = ...) -> Columns:
        """Positions, velocities and accelerations of every point and link."""
    def kinetostatics(self, q: ArrayLike, qd: ArrayLike = ..., qdd: ArrayLike = ..., loads: Optional[Mapping[str, LoadValue]] = ..., errors: str = ...) -> Columns:
        """Every reaction (`<joint>.fx`, `.fy`, `.moment`) and `driver` by d'Alembert."""
    def driver_action(self, q: ArrayLike, qd: ArrayLike = ..., qdd: ArrayLike = ..., loads: Optional[Mapping[str, LoadValue]] = ..., errors: str = ...) -> Columns:
        """`driver` by virtual power, no reaction computed."""
    def balance(self, speed: float = ..., method: str = ..., fraction: float = ..., radius: Optional[float] = ..., weights: Sequence[float] = ...) -> "Mechanism":
        """The mechanism with counterweights that balance its shaking force (`mech balance`)."""
    def reduced(self, q: ArrayLike, errors: str = ...) -> Columns:
        """`inertia` I* (kg·m²) and `inertia_derivative` dI*/dq."""
    def reduced_moment(self, q: ArrayLike, loads: Optional[Mapping[str, LoadValue]] = ..., errors: str = ...) -> Columns:
        """`moment` M* (N·m)."""
    def acceleration(self, q: ArrayLike, qd: ArrayLike, driver: Union[ArrayLike, Callable[[float], float]], loads: Optional[Mapping[str, LoadValue]] = ..., errors: str = ...) -> Columns:
        """`qdd`: the direct problem's q̈."""
    def simulate(self, t_end: float, motor: str, ratio: float = ..., q0: float = ..., speed: float = ..., loads: Optional[Mapping[str, LoadValue]] = ..., flywheel: float = ..., samples: int = ...) -> Dict[str, np.ndarray]:
        """The motion under a motor: ``t``, ``q``, ``qd``, ``torque``."""
    def regime(self, motor: str, ratio: float = ..., loads: Optional[Mapping[str, LoadValue]] = ..., flywheel: float = ..., period: float = ..., start: float = ..., points: int = ...) -> Dict[str, Any]:
        """The periodic steady regime under a motor: the table and the motor check."""
    def strength(self, qd: float = ..., loads: Optional[Mapping[str, LoadValue]] = ..., steps: int = ..., period: float = ..., all: bool = ...) -> Dict[str, np.ndarray]:
        """The strength of every member over the cycle: member, criterion, stresses, safety, q."""
    def size(self, safety: float, qd: float = ..., loads: Optional[Mapping[str, LoadValue]] = ..., steps: int = ..., period: float = ..., irregularity: Optional[float] = ...) -> Dict[str, Any]:
        """Size the free(LO..HI) dimensions: the passes, the dims, the sized text."""
    def stop(self, qd0: float, brake: float = ..., q0: float = ..., dt: Optional[float] = ..., t_max: float = ..., loads: Optional[Mapping[str, LoadValue]] = ..., flywheel: float = ..., points: int = ...) -> Dict[str, Any]:
        """The coast or braked stop with the motor off: t, q, qd, torque, stop_time, stop_angle."""
    def flywheel(self, period: float, speed: float, irregularity: float, loads: Optional[Mapping[str, LoadValue]] = ..., start: float = ..., breakpoints: Sequence[float] = ..., driver: Union[None, float, Callable[[float], float]] = ..., rtol: float = ...) -> Dict[str, float]:
        """ΔE, the approximate and the exact (Wittenbauer) flywheel inertia, the simulated speeds."""
    def cam_profile(self, name: Optional[str] = ..., points: int = ...) -> Dict[str, Any]:
        """A cam's profile over a turn: lift, pitch and contact points, pressure angle, curvature; the design figures."""

def optimize(mechanism: Mechanism, vary: Mapping[str, Sequence[Any]], minimize: str, subject_to: Sequence[str] = ..., qd: float = ..., loads: Optional[Mapping[str, LoadValue]] = ..., steps: int = ..., period: float = ..., irregularity: Optional[float] = ..., targets: Optional[ArrayLike] = ..., point: Optional[str] = ..., evaluations: int = ..., seed: int = ...) -> Dict[str, Any]:
    """Vary named numbers of the mechanism's text to minimise an objective of its dynamics."""
def sweep(mechanism: Mechanism, params: Union[Mapping[str, ArrayLike], Sequence[Mapping[str, ArrayLike]]], q: ArrayLike, qd: ArrayLike = ..., qdd: ArrayLike = ..., loads: Optional[Mapping[str, LoadValue]] = ..., parts: Optional[Sequence[str]] = ...) -> Dict[str, np.ndarray]:
    """Columns over parameter variants × inputs, shape (V, n), with the mask `ok`."""

def synthesize_function(pairs: ArrayLike, frame: float = ...) -> Tuple[Mechanism, float]:
    """A four-bar through (input, output) angle pairs, rad: Freudenstein (3 exact, more least squares); (Mechanism, error rad²)."""

def synthesize_motion(poses: ArrayLike, circle_points: Optional[ArrayLike] = ..., full: bool = ...) -> Tuple[Any, ...]:
    """A four-bar through (x, y, angle) poses: Burmester (3 to 5 exact, more least squares); (Mechanism, error m²) [, {"offset", "q"}]."""
def engine(layout: str = ..., cylinders: int = ..., bank: float = ..., firing: Optional[Union[str, Sequence[int]]] = ..., phases: Optional[ArrayLike] = ..., radius: float = ..., rod: float = ..., mass: float = ..., spacing: float = ..., balance_couple: bool = ...) -> Tuple[Mechanism, List[Dict[str, object]]]:
    """An engine of several cylinders and its classical balance table (`mech engine`)."""
def synthesize_path(points: ArrayLike, closed: bool = ..., seed: int = ..., evaluations: int = ..., angles: Optional[ArrayLike] = ..., transmission: float = ..., ratio: float = ..., topology: str = ...) -> Tuple[Mechanism, float]:
    """A four-bar whose coupler point passes nearest to the points (SPEC 3f), and its error E (m²)."""
    ...
