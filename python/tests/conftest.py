"""Shared fixtures: the repository (scenes), the C library and the `jointlin` program
the tests compare with (built by scripts/test.sh before the Python tests run)."""

import ctypes
import os
from pathlib import Path

import pytest

REPO = Path(os.environ.get("JOINTLIN_REPO", Path(__file__).resolve().parents[2]))


@pytest.fixture(scope="session")
def repo() -> Path:
    return REPO


@pytest.fixture(scope="session")
def program() -> Path:
    """target/release/jointlin: the program the Python runs must equal."""
    p = REPO / "target" / "release" / "jointlin"
    assert p.is_file(), f"{p} is missing: cargo build --release -p jointlin-harness"
    return p


class Contact(ctypes.Structure):
    """jointlin_contact of include/jointlin.h."""

    _fields_ = [
        ("law", ctypes.c_int32),
        ("rule", ctypes.c_int32),
        ("mu", ctypes.c_double),
        ("normal_force", ctypes.c_double),
        ("k_t0", ctypes.c_double),
    ]


class Linearization(ctypes.Structure):
    """jointlin_linearization of include/jointlin.h."""

    _fields_ = [
        ("k_star", ctypes.c_double),
        ("d_star", ctypes.c_double),
        ("eta", ctypes.c_double),
        ("energy_per_cycle", ctypes.c_double),
        ("peak_force", ctypes.c_double),
        ("slip_limit", ctypes.c_double),
        ("amplitude_ratio", ctypes.c_double),
        ("regime", ctypes.c_int32),
    ]


@pytest.fixture(scope="session")
def capi():
    """target/release/libjointlin.so through ctypes: the C API as a C host calls it."""
    path = REPO / "target" / "release" / "libjointlin.so"
    assert path.is_file(), f"{path} is missing: cargo build --release"
    lib = ctypes.CDLL(str(path))
    lib.jointlin_linearize.argtypes = [
        ctypes.POINTER(Contact),
        ctypes.c_double,
        ctypes.c_double,
        ctypes.c_void_p,
        ctypes.POINTER(Linearization),
    ]
    lib.jointlin_linearize.restype = ctypes.c_int32
    return lib
