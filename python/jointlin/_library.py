"""The library from Python: the linearization of a contact point (k*, d*), the
three-direction point's describing function, the screw preload and the time-domain
points, each one C-API call per element (``jointlin._native``).

Units are the caller's and must be consistent (the examples use N, mm, s): forces in
force, k_T0 in force/length, amplitudes in length, ω in rad per time unit.
"""

from __future__ import annotations

import dataclasses
import enum
from typing import NamedTuple

import numpy as np
import pandas as pd

from . import _native
from ._errors import check

_LAWS = {"mindlin": 0, "jenkins": 1}
_RULES = {"thesis": 0, "masing": 1}
_METHODS = {"graded": 0, "simpson": 1, "gauss": 2}
_NORMAL_LAWS = {"linear": 0, "hertz": 1}


class Regime(enum.IntEnum):
    """``JOINTLIN_REGIME_*``; -1 marks an element whose call failed (see its status)."""

    FAILED = -1
    OPEN = 0
    STICK = 1
    MICROSLIP = 2
    SLIDING = 3


def _code(kind: str, table: dict, value) -> int:
    if not isinstance(value, str) or value.lower() not in table:
        raise ValueError(f"{kind} must be one of {sorted(table)}, not {value!r}")
    return table[value.lower()]


def _floats(name: str, value) -> np.ndarray:
    """``value`` as a float64 array; None, strings, complex or object data raise
    TypeError naming the parameter (NaN and Inf pass: the library gives their status)."""
    if value is None:
        raise TypeError(f"{name} must be a number or an array of numbers, not None")
    a = np.asarray(value)
    if a.dtype.kind not in "fiub":
        raise TypeError(f"{name} must be real numbers, not {a.dtype} ({type(value).__name__})")
    return a.astype(np.float64, copy=False)


def _int(name: str, value) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name} must be an int, not {type(value).__name__}")
    if not -(2**31) <= int(value) < 2**31:
        raise ValueError(f"{name} = {value} is out of range")
    return int(value)


def _broadcast(**arrays: np.ndarray) -> tuple[tuple[int, ...], list[np.ndarray]]:
    """The common shape and each input as a flat contiguous float64 array of it."""
    try:
        shape = np.broadcast_shapes(*(a.shape for a in arrays.values()))
    except ValueError:
        shapes = ", ".join(f"{k} {a.shape}" for k, a in arrays.items())
        raise ValueError(f"shapes do not broadcast: {shapes}") from None
    return shape, [np.ascontiguousarray(np.broadcast_to(a, shape)).reshape(-1) for a in arrays.values()]


def _shaped(values: np.ndarray, shape: tuple[int, ...]):
    """A flat result in the inputs' shape; a NumPy scalar for scalar inputs."""
    out = values.reshape(shape)
    return out[()] if shape == () else out


class _Statuses:
    """Per-element statuses: ``ok`` and ``check()``."""

    status: np.ndarray
    first_failure: tuple | None = None

    @property
    def ok(self) -> bool:
        """True when every element succeeded."""
        return bool(np.all(self.status == 0))

    def check(self):
        """Raises the named error of the first failed element; returns self otherwise."""
        check(self.status, self.first_failure)
        return self


@dataclasses.dataclass(frozen=True)
class Linearization(_Statuses):
    """k*, d* and the loop of a contact point per element (the inputs' broadcast shape).
    Elements whose call failed hold NaN and ``regime`` -1; ``status`` says why."""

    k_star: np.ndarray
    """Equivalent stiffness k* (force/length), (3.8) on the Ersatzfunktion (4.3)."""
    d_star: np.ndarray
    """Equivalent viscous damping d* = A_hys/(π ω A²) (force·time/length), (3.14)."""
    eta: np.ndarray
    """Loss factor η = A_hys/(π k* A²)."""
    energy_per_cycle: np.ndarray
    """Energy dissipated per cycle A_hys (force·length)."""
    peak_force: np.ndarray
    """Peak force of the loop (force), ≤ μ F_N."""
    slip_limit: np.ndarray
    """Slip limit δ* (length); 0 when open."""
    amplitude_ratio: np.ndarray
    """A/δ*; 0 when open."""
    regime: np.ndarray
    """``Regime`` codes."""
    status: np.ndarray
    """``Status`` codes, 0 where the call succeeded."""
    first_failure: tuple | None = None
    """(flat index, status, the library's detail) of the first failed element."""

    def to_frame(self) -> pd.DataFrame:
        """One row per element, a column per field (flattened in C order)."""
        fields = [f.name for f in dataclasses.fields(self) if f.name != "first_failure"]
        return pd.DataFrame({f: np.ravel(getattr(self, f)) for f in fields})


def linearize(
    law: str = "mindlin",
    rule: str = "thesis",
    mu=None,
    normal_force=None,
    k_t0=None,
    amplitude=None,
    omega=None,
    *,
    method: str = "graded",
    points: int = 0,
) -> Linearization:
    """k* and d* of a contact point (``jointlin_linearize``) for every element of the
    broadcast of ``mu``, ``normal_force`` (force, > 0 closed), ``k_t0`` (force/length),
    ``amplitude`` (length) and ``omega`` (rad/time).

    law: "mindlin" (Hertz–Mindlin microslip then Coulomb, (2.49)) or "jenkins";
    rule: "thesis" (elastic unloading, §2.3.3) or "masing"; method: "graded" (default,
    closed-form loop area, graded Gauss–Legendre for k*), "simpson" (the thesis's rule;
    points = intervals) or "gauss"; points 0 = the method's default.

    A bad element (NaN, a negative μ, …) does not raise: its status says why
    (``Linearization.check()`` raises it). Wrong types or shapes raise TypeError or
    ValueError at once.
    """
    law_c, rule_c = _code("law", _LAWS, law), _code("rule", _RULES, rule)
    method_c, points = _code("method", _METHODS, method), _int("points", points)
    shape, flat = _broadcast(
        mu=_floats("mu", mu),
        normal_force=_floats("normal_force", normal_force),
        k_t0=_floats("k_t0", k_t0),
        amplitude=_floats("amplitude", amplitude),
        omega=_floats("omega", omega),
    )
    r = _native.linearize(law_c, rule_c, *flat, method_c, points)
    first = r.pop("first_failure")
    return Linearization(**{k: _shaped(v, shape) for k, v in r.items()}, first_failure=first)


@dataclasses.dataclass(frozen=True)
class Linearization3d(_Statuses):
    """Describing function of a three-direction point on an elliptic path per element;
    the last axis of ``k_star`` and ``d_star`` is the tangential direction (1, 2)."""

    k_star: np.ndarray
    """k* per tangential direction (force/length), shape (..., 2)."""
    d_star: np.ndarray
    """d* per tangential direction (force·time/length), shape (..., 2), (3.14)."""
    energy_per_cycle: np.ndarray
    """Energy dissipated per cycle by the point (force·length)."""
    regime: np.ndarray
    status: np.ndarray
    first_failure: tuple | None = None


def linearize3d(
    law: str = "mindlin",
    mu=None,
    k_t0=None,
    normal_force=None,
    amplitude_1=None,
    amplitude_2=0.0,
    omega=None,
    *,
    cells: int = 0,
) -> Linearization3d:
    """Describing function of a three-direction point (``jointlin_linearize3d``) at the
    constant normal force ``normal_force`` (force) on the path u = (A1 cos ωt, A2 sin ωt)
    (lengths) from a virgin start, per element of the broadcast of the normal force,
    amplitudes and ``omega`` (rad/time). law "jenkins" (one cell) or "mindlin" (parallel
    Jenkins cells, Masing's rule; ``cells`` 0 = 32). μ and k_T0 (force/length) scalars.
    """
    law_c, cells = _code("law", _LAWS, law), _int("cells", cells)
    mu, k_t0 = float(_floats("mu", mu)), float(_floats("k_t0", k_t0))
    shape, flat = _broadcast(
        normal_force=_floats("normal_force", normal_force),
        amplitude_1=_floats("amplitude_1", amplitude_1),
        amplitude_2=_floats("amplitude_2", amplitude_2),
        omega=_floats("omega", omega),
    )
    r = _native.linearize3d(law_c, cells, mu, k_t0, *flat)
    pair = lambda a, b: _shaped(np.stack([r[a], r[b]], axis=-1), shape + (2,))  # noqa: E731
    return Linearization3d(
        k_star=pair("k_star_1", "k_star_2"),
        d_star=pair("d_star_1", "d_star_2"),
        energy_per_cycle=_shaped(r["energy_per_cycle"], shape),
        regime=_shaped(r["regime"], shape),
        status=_shaped(r["status"], shape),
        first_failure=r["first_failure"],
    )


class Preload(NamedTuple):
    """Screw preloads (force) and their statuses."""

    preload: np.ndarray
    status: np.ndarray

    def check(self) -> "Preload":
        check(self.status)
        return self


def screw_preload(torque, pitch, d2, mu_thread, mu_head, d_km) -> Preload:
    """Axial force of a screw tightened to ``torque`` (force·length), VDI 2230 R13
    (``jointlin_screw_preload``, thesis §5.4.1): F = T / (0.16 P + 0.58 d2 μ_thread +
    d_km/2 μ_head), lengths ``pitch`` P, flank diameter ``d2``, head diameter ``d_km``;
    per element of the inputs' broadcast."""
    shape, flat = _broadcast(
        torque=_floats("torque", torque),
        pitch=_floats("pitch", pitch),
        d2=_floats("d2", d2),
        mu_thread=_floats("mu_thread", mu_thread),
        mu_head=_floats("mu_head", mu_head),
        d_km=_floats("d_km", d_km),
    )
    r = _native.screw_preload(*flat)
    return Preload(_shaped(r["preload"], shape), _shaped(r["status"], shape))


class Step(NamedTuple):
    """One step of a ``Point``: force (force), tangent dF/du (force/length), energy
    dissipated during the step (force·length)."""

    force: float
    tangent: float
    dissipated: float


class Point:
    """One tangential direction of a contact point in the time domain
    (``jointlin_point_step``, thesis §2.3.3): a virgin point at slip 0, moved by
    ``step`` or ``run``. Forces carry the slip's sign. Not shared between threads."""

    def __init__(self, law: str = "mindlin", rule: str = "thesis", mu=None, normal_force=None, k_t0=None):
        self._p = _native.Point(
            _code("law", _LAWS, law),
            _code("rule", _RULES, rule),
            float(_floats("mu", mu)),
            float(_floats("normal_force", normal_force)),
            float(_floats("k_t0", k_t0)),
        )

    def step(self, slip: float) -> Step:
        """Moves to ``slip`` (length)."""
        return Step(*self._p.step(float(_floats("slip", slip))))

    def run(self, slips) -> pd.DataFrame:
        """Steps through ``slips`` (a 1-D history, length) in order: a DataFrame with
        slip, force, tangent, dissipated per sample (a hysteresis loop: force against
        slip). A failing sample raises naming its index; the point stays at the last
        good one."""
        x = np.ascontiguousarray(_floats("slips", slips))
        if x.ndim != 1:
            raise ValueError(f"slips must be 1-D, not of shape {x.shape}")
        r = self._p.run(x)
        return pd.DataFrame({"slip": x, **r})

    @property
    def state(self) -> np.ndarray:
        """The C-API state array (a copy)."""
        return self._p.state

    def reset(self) -> None:
        """Back to the virgin state at slip 0."""
        self._p.reset()


class Step3d(NamedTuple):
    """One step of a ``Point3d``: force (t1, t2, N) (force), stiffness d force/d (u1, u2,
    h) (3×3, force/length), energy dissipated (force·length), ``Regime`` code."""

    force: np.ndarray
    stiffness: np.ndarray
    dissipated: float
    regime: int


class Point3dRun(NamedTuple):
    """A ``Point3d`` history: force (n, 3), stiffness (n, 3, 3), dissipated (n,),
    regime (n,)."""

    force: np.ndarray
    stiffness: np.ndarray
    dissipated: np.ndarray
    regime: np.ndarray


class Point3d:
    """A contact point in three directions (``jointlin_point3d_step``): two tangential
    displacements u1, u2 and the overclosure h (lengths; h > 0 pressed, h ≤ 0 open), a
    unilateral normal law ("linear": k_N in force/length, or "hertz": E* in
    force/length² with r* in length) and a circular slip limit μN in the tangent plane."""

    def __init__(
        self,
        law: str = "mindlin",
        mu=None,
        k_t0=None,
        normal_stiffness=None,
        *,
        normal_law: str = "linear",
        r_star: float = 1.0,
        cells: int = 0,
    ):
        self._p = _native.Point3d(
            _code("law", _LAWS, law),
            _int("cells", cells),
            float(_floats("mu", mu)),
            float(_floats("k_t0", k_t0)),
            _code("normal_law", _NORMAL_LAWS, normal_law),
            float(_floats("normal_stiffness", normal_stiffness)),
            float(_floats("r_star", r_star)),
        )

    def step(self, displacement) -> Step3d:
        """Moves to ``displacement`` = (u1, u2, h) (length)."""
        d = _floats("displacement", displacement)
        if d.shape != (3,):
            raise ValueError(f"displacement must be (u1, u2, h), not of shape {d.shape}")
        f, k, e, g = self._p.step(*map(float, d))
        return Step3d(np.array(f), np.array(k).reshape(3, 3), e, g)

    def run(self, history) -> Point3dRun:
        """Steps through the rows (u1, u2, h) of ``history`` (n, 3). A failing sample
        raises naming its index; the point stays at the last good one."""
        h = _floats("history", history)
        if h.ndim != 2 or h.shape[1] != 3:
            raise ValueError(f"history must be of shape (n, 3), not {h.shape}")
        r = self._p.run(np.ascontiguousarray(h).reshape(-1))
        n = h.shape[0]
        return Point3dRun(
            r["force"].reshape(n, 3), r["stiffness"].reshape(n, 3, 3), r["dissipated"], r["regime"]
        )

    @property
    def state(self) -> np.ndarray:
        return self._p.state

    def reset(self) -> None:
        self._p.reset()
