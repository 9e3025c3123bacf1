"""jointlin: frequency-domain linearization of bolted and clamped joint contact.

Per contact point and vibration amplitude, the Hertz–Mindlin–Coulomb hysteresis is
replaced by an equivalent spring k* (first-order harmonic balance) and damper d*
(energy balance), so a linear steady-state analysis gives amplitude responses and joint
losses directly (Tianyi Yu, KIT 2012; the method: docs/model.md of the repository).

The library (one C-API call per element, statuses per element):
``linearize``, ``linearize3d``, ``screw_preload``, ``Point``, ``Point3d``, ``Status``,
``Regime``, ``check``. The harness: ``Scene`` (scenes and Abaqus-format decks),
``Result``, ``backbone``, ``reduce``. Errors: ``JointlinError`` and its subclasses.
"""

from ._errors import (
    InputError,
    JointlinError,
    NoSolutionError,
    NonFiniteError,
    NotConvergedError,
    OutOfRangeError,
    ResultOverflowError,
    RunError,
    Status,
    check,
)
from ._library import (
    Linearization,
    Linearization3d,
    Point,
    Point3d,
    Point3dRun,
    Preload,
    Regime,
    Step,
    Step3d,
    linearize,
    linearize3d,
    screw_preload,
)
from ._native import abi_version
from ._scene import Result, Scene, backbone, reduce

__version__ = "0.1.0"

__all__ = [
    "InputError",
    "JointlinError",
    "Linearization",
    "Linearization3d",
    "NoSolutionError",
    "NonFiniteError",
    "NotConvergedError",
    "OutOfRangeError",
    "Point",
    "Point3d",
    "Point3dRun",
    "Preload",
    "Regime",
    "Result",
    "ResultOverflowError",
    "RunError",
    "Scene",
    "Status",
    "Step",
    "Step3d",
    "abi_version",
    "backbone",
    "check",
    "linearize",
    "linearize3d",
    "reduce",
    "screw_preload",
]
