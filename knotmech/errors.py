"""Exceptions and argument checks shared by every layer of knotmech.

This module is a leaf: it imports nothing else from knotmech, so ``analytic/``
stays usable on its own (the one import it makes of the package is this file).
Library code raises these exceptions; only ``knotmech.cli`` turns them into a
one-line message and exit status 2.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "KnotmechError",
    "InputError",
    "SolverError",
    "RecordingError",
    "DiagnoseError",
    "check_positive",
    "check_nonnegative",
    "check_finite",
    "check_bending_scale",
    "check_range",
]


class KnotmechError(Exception):
    """Base class of every error knotmech raises on purpose."""


class InputError(KnotmechError, ValueError):
    """An argument is out of its physical range, NaN, or of the wrong kind."""


class SolverError(KnotmechError, RuntimeError):
    """A solver could not advance; ``state`` holds the last good state (or None)."""

    def __init__(self, message: str, state=None):
        super().__init__(message)
        self.state = state


class RecordingError(InputError):
    """A recording file is malformed (the message names file and line)."""


class DiagnoseError(KnotmechError, ArithmeticError):
    """The mismatch engine cannot complete a step on this recording (the message names it).

    Raised when the numbers of a recording that passed the reader's checks still make
    a fit or a factorisation meaningless (NaN or infinity in a design matrix, a
    likelihood that is not finite); never a silent answer.
    """


def _as_array(name: str, value) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number or an array of numbers, got {value!r}") from None
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{name} must be finite (got NaN or infinity)")
    return arr


def check_finite(name: str, value) -> np.ndarray:
    """Return ``value`` as a float array, raising InputError on NaN/inf or non-numbers."""
    return _as_array(name, value)


def check_positive(name: str, value) -> np.ndarray:
    """Return ``value`` as a float array, raising InputError unless every entry is > 0."""
    arr = _as_array(name, value)
    if np.any(arr <= 0):
        raise InputError(f"{name} must be > 0, got {_show(arr)}")
    return arr


def check_nonnegative(name: str, value) -> np.ndarray:
    """Return ``value`` as a float array, raising InputError unless every entry is >= 0."""
    arr = _as_array(name, value)
    if np.any(arr < 0):
        raise InputError(f"{name} must be >= 0, got {_show(arr)}")
    return arr


def check_range(name: str, value, low=-np.inf, high=np.inf, *, low_open=False, high_open=False):
    """Return ``value`` as a float array, raising InputError outside [low, high]."""
    arr = _as_array(name, value)
    bad_low = arr <= low if low_open else arr < low
    bad_high = arr >= high if high_open else arr > high
    if np.any(bad_low) or np.any(bad_high):
        lo = "(" if low_open else "["
        hi = ")" if high_open else "]"
        raise InputError(f"{name} must lie in {lo}{low:g}, {high:g}{hi}, got {_show(arr)}")
    return arr


def _show(arr: np.ndarray) -> str:
    if arr.ndim == 0:
        return f"{float(arr):g}"
    bad = arr.ravel()
    return f"array with values in [{bad.min():g}, {bad.max():g}]"


def check_bending_scale(value) -> float:
    """``bending_scale`` kappa as a float, finite with 0 < kappa <= 1, else InputError."""
    try:
        k = float(value)
    except (TypeError, ValueError):
        raise InputError(f"bending_scale must be a number in (0, 1], got {value!r}") from None
    if not (np.isfinite(k) and 0.0 < k <= 1.0):
        raise InputError(f"bending_scale must be finite with 0 < bending_scale <= 1, got {value!r}")
    return k
