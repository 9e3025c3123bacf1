"""Status codes of the C API and the exceptions they become.

Every C-API call returns a status (``Status``); a failed call from Python raises the
exception ``error_for`` names for it, carrying the library's message and the offending
input. Vectorized calls never raise mid-array: they return a status per element, and
``check`` raises for the first failed one.
"""

from __future__ import annotations

import enum

import numpy as np

from . import _native


class Status(enum.IntEnum):
    """The C API's ``JOINTLIN_OK`` / ``JOINTLIN_ERR_*`` codes (include/jointlin.h)."""

    OK = 0
    NULL = 1
    NON_FINITE = 2
    OUT_OF_RANGE = 3
    OVERFLOW = 4
    PROPS = 5
    SIZE = 6
    NO_SOLUTION = 7
    NOT_CONVERGED = 8
    UNKNOWN_POINT = 9
    SEQUENCE = 10
    IO = 11
    PANIC = 12

    @property
    def message(self) -> str:
        """The library's English text of the code (``jointlin_status_message``)."""
        return _native.status_message(int(self))


class JointlinError(Exception):
    """A failed jointlin call; ``status`` is its ``Status`` (None for harness errors)."""

    status: Status | None = None

    def __init__(self, message: str, status: Status | None = None):
        super().__init__(message)
        if status is not None:
            self.status = status


class NonFiniteError(JointlinError, ValueError):
    """An input was NaN or infinite (``Status.NON_FINITE``)."""


class OutOfRangeError(JointlinError, ValueError):
    """A finite input or a code was outside its valid range (``Status.OUT_OF_RANGE``)."""


class ResultOverflowError(JointlinError, ArithmeticError):
    """A result would not be representable, e.g. d* at ω → 0 (``Status.OVERFLOW``)."""


class NoSolutionError(JointlinError, ArithmeticError):
    """A nonlinear problem has no solution for the data (``Status.NO_SOLUTION``)."""


class NotConvergedError(JointlinError, ArithmeticError):
    """An iteration did not converge within its limits (``Status.NOT_CONVERGED``)."""


class InputError(JointlinError, ValueError):
    """A scene, deck or override the harness refuses; the message names file:line:column
    and key (a deck's file:line and keyword), as the ``jointlin`` command prints it."""


class RunError(JointlinError, RuntimeError):
    """A harness command failed on a valid input (exit code 1 of the command)."""


_CLASSES = {
    Status.NON_FINITE: NonFiniteError,
    Status.OUT_OF_RANGE: OutOfRangeError,
    Status.OVERFLOW: ResultOverflowError,
    Status.NO_SOLUTION: NoSolutionError,
    Status.NOT_CONVERGED: NotConvergedError,
}


def error_for(code: int, message: str) -> JointlinError:
    """The exception of status ``code`` with ``message`` (its class per ``Status``)."""
    try:
        status = Status(code)
    except ValueError:
        return JointlinError(f"unknown status code {code}: {message}")
    return _CLASSES.get(status, JointlinError)(f"{status.name}: {message}", status)


def check(status, first_failure=None) -> None:
    """Raises the exception of the first element of ``status`` (an int or an array of
    status codes) that is not ``Status.OK``, with its index and how many failed; returns
    None when all are OK. ``first_failure`` (index, code, detail), as the vectorized calls
    give it, adds the library's detail."""
    codes = np.asarray(status)
    bad = np.flatnonzero(codes != Status.OK)
    if bad.size == 0:
        return
    flat = int(bad[0])
    code = int(codes.reshape(-1)[flat])
    where = np.unravel_index(flat, codes.shape) if codes.ndim else ()
    detail = Status(code).message if code in Status._value2member_map_ else "unknown"
    if first_failure is not None and int(first_failure[0]) == flat:
        detail = first_failure[2]
    raise error_for(
        code,
        f"{bad.size} of {codes.size} elements failed; the first at index {tuple(int(i) for i in where)}: {detail}",
    )
