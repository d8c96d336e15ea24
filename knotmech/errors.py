"""Exceptions and argument checks shared by every layer of knotmech.

This module is a leaf: it imports nothing else from knotmech, so ``analytic/``
stays usable on its own (the one import it makes of the package is this file).
Library code raises these exceptions; only ``knotmech.cli`` turns them into a
one-line message and exit status 2.

The rule for a physical quantity (applied by :func:`check_finite`,
:func:`check_positive`, :func:`check_nonnegative` and :func:`check_range`, which
every closed form and everything above them calls):

- a real number is accepted: ``int``, ``float``, any :class:`numbers.Real`, a numpy
  integer or floating scalar, and (only where the function is documented as
  vectorised, ``array_like``) a non-empty numpy array of integer or floating dtype or a
  (nested) list or tuple of such numbers; the value is returned as a float ndarray;
- where a function takes one number (``scalar=True``) an array, list or tuple is
  refused: ``rod_diameter must be one number, got a list``;
- ``True``/``False`` (and bool arrays, or a bool inside a list) are refused: a bool is
  not a physical quantity, and ``mu=True`` read as 1.0 is a confident wrong answer;
- strings are refused, never coerced: ``mu must be a number, got the string '0.3'``
  (text with units is read at the edges by :func:`knotmech.units.parse_quantity`);
- ``None``, complex numbers and any other object are refused, naming the type;
- NaN and infinity are refused with the name and the allowed range:
  ``mu must be a finite number >= 0, got nan``.

Every message is one line (values are shown by a short, single-line repr) and starts
with the name of the argument. A vectorised function is decorated with :func:`vectorised`,
which refuses, naming them, array arguments whose shapes do not broadcast together.
"""

from __future__ import annotations

import functools
import inspect
import math
import numbers

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
    "check_count",
    "check_range",
    "check_broadcast",
    "vectorised",
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


_MAX_SHOWN = 40  # characters of a bad value shown in a message


def _short(value) -> str:
    """One-line repr of ``value``, at most about :data:`_MAX_SHOWN` characters."""
    text = " ".join(repr(value).split())
    return text if len(text) <= _MAX_SHOWN else text[: _MAX_SHOWN - 3] + "..."


def _kind_of(value) -> str:
    """What ``value`` is, for a message (``"the string '0.3'"``, ``"a bool"``, ...)."""
    if isinstance(value, (str, bytes)):
        return f"the string {_short(value)}"
    if isinstance(value, (bool, np.bool_)):
        return f"the bool {bool(value)!r}"
    if value is None:
        return "None"
    if isinstance(value, (complex, np.complexfloating)):
        return f"the complex number {_short(value)}"
    return f"{_short(value)} (a {type(value).__name__})"


def _is_real_scalar(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def _bad_items(items) -> list:
    """The entries of a (nested) list/tuple that are not real numbers (empty if none)."""
    bad = []
    for item in items:
        if isinstance(item, (list, tuple)):
            bad.extend(_bad_items(item))
        elif not _is_real_scalar(item):
            bad.append(item)
    return bad


def _array_of_reals(name: str, value, what: str) -> np.ndarray:
    """A list, tuple or array of real numbers as a float ndarray, else InputError."""
    if isinstance(value, (list, tuple)):
        bad = _bad_items(value)
        if bad:
            raise InputError(
                f"{name} must be {what}, got {_kind_of(bad[0])} in a {type(value).__name__}"
            )
    try:
        arr = np.asarray(value)
    except (TypeError, ValueError):
        raise InputError(
            f"{name} must be {what}, got {_short(value)} (not a regular array)"
        ) from None
    if arr.dtype.kind not in "iuf":
        raise InputError(f"{name} must be {what}, got an array of dtype {arr.dtype}")
    if arr.size == 0:
        raise InputError(f"{name} must be {what}, got an empty array")
    return np.asarray(arr, dtype=float)


def _as_array(
    name: str, value, rule: str = "", *, scalar: bool = False, allow_inf: bool = False
) -> np.ndarray:
    """``value`` as a float ndarray after the checks of the module docstring.

    ``rule`` (e.g. ``">= 0"``) is quoted in the message on NaN or infinity; ``scalar``
    refuses arrays, lists and tuples; ``allow_inf`` admits +-inf (never NaN).
    """
    what = "a number" if scalar else "a number or an array of numbers"
    if _is_real_scalar(value):
        arr = np.asarray(float(value))
    elif scalar and isinstance(value, (list, tuple, np.ndarray)) and np.ndim(value) > 0:
        raise InputError(f"{name} must be one number, got a {type(value).__name__} {_short(value)}")
    elif isinstance(value, (list, tuple, np.ndarray)):
        arr = _array_of_reals(name, value, what)
    else:
        raise InputError(f"{name} must be {what}, got {_kind_of(value)}")
    finite = ~np.isnan(arr) if allow_inf else np.isfinite(arr)
    if not np.all(finite):
        bad = arr[~finite].ravel()[0]
        rule = f" {rule}" if rule else ""
        what = "a number" if allow_inf else "a finite number"
        raise InputError(f"{name} must be {what}{rule}, got {bad}")
    return arr


def _out(arr: np.ndarray, scalar: bool):
    return float(arr.reshape(())) if scalar else arr


def check_finite(name: str, value, *, scalar: bool = False):
    """``value`` as a float ndarray (a float if ``scalar``), refusing NaN, inf and non-numbers.

    Parameters
    ----------
    name : str
        Argument name, the first word of any message.
    value : float or array_like
        The quantity, in SI units.
    scalar : bool
        Refuse arrays, lists and tuples and return a float.

    Raises
    ------
    InputError
        Under the rule of the module docstring.
    """
    return _out(_as_array(name, value, scalar=scalar), scalar)


def check_positive(name: str, value, *, scalar: bool = False, allow_inf: bool = False):
    """As :func:`check_finite`, and every entry must be > 0; ``allow_inf`` admits +inf
    (e.g. the modulus of a rigid body)."""
    if allow_inf:
        return check_range(name, value, 0.0, np.inf, low_open=True, scalar=scalar, allow_inf=True)
    arr = _as_array(name, value, "> 0", scalar=scalar)
    if np.any(arr <= 0):
        raise InputError(f"{name} must be > 0, got {_show(arr)}")
    return _out(arr, scalar)


def check_nonnegative(name: str, value, *, scalar: bool = False):
    """As :func:`check_finite`, and every entry must be >= 0."""
    arr = _as_array(name, value, ">= 0", scalar=scalar)
    if np.any(arr < 0):
        raise InputError(f"{name} must be >= 0, got {_show(arr)}")
    return _out(arr, scalar)


def check_range(
    name: str,
    value,
    low=-np.inf,
    high=np.inf,
    *,
    low_open=False,
    high_open=False,
    scalar=False,
    allow_inf=False,
):
    """As :func:`check_finite`, and every entry must lie in [low, high] (ends open on request);
    ``allow_inf`` admits the infinite ends of a closed interval."""
    lo = "(" if low_open else "["
    hi = ")" if high_open else "]"
    interval = f"in {lo}{low:g}, {high:g}{hi}"
    arr = _as_array(name, value, interval, scalar=scalar, allow_inf=allow_inf)
    bad_low = arr <= low if low_open else arr < low
    bad_high = arr >= high if high_open else arr > high
    if np.any(bad_low) or np.any(bad_high):
        raise InputError(f"{name} must lie {interval}, got {_show(arr)}")
    return _out(arr, scalar)


def _show(arr: np.ndarray) -> str:
    if arr.ndim == 0:
        return f"{float(arr):g}"
    bad = arr.ravel()
    return f"array with values in [{bad.min():g}, {bad.max():g}]"


def check_bending_scale(value) -> float:
    """``bending_scale`` kappa as a float, finite with 0 < kappa <= 1, else InputError.

    Follows the rule of the module docstring (no bools, no strings); every refusal reads
    ``bending_scale must be a number in (0, 1], got ...``.
    """
    if not _is_real_scalar(value):
        raise InputError(f"bending_scale must be a number in (0, 1], got {_kind_of(value)}")
    k = float(value)
    if not (np.isfinite(k) and 0.0 < k <= 1.0):
        raise InputError(f"bending_scale must be a number in (0, 1], got {value!r}")
    return k


def check_count(name: str, value, minimum: int = 0, maximum: int | None = None) -> int:
    """``value`` as an int: a whole number (``80``, ``80.0``, a numpy integer) in
    [minimum, maximum], else InputError.

    Follows the rule of the module docstring: bools, strings, None, lists, arrays, NaN,
    infinity and fractions are refused, each in one line starting with ``name``
    (``n_nodes must be an integer >= 40, got a list [80, 90]``).

    Parameters
    ----------
    name : str
        Argument name, the first word of any message.
    value : int
        The count.
    minimum, maximum : int
        Its allowed range (``maximum`` None: no upper bound).
    """
    rule = f">= {minimum}" if maximum is None else f"in [{minimum}, {maximum}]"
    if isinstance(value, (list, tuple, np.ndarray)) and np.ndim(value) > 0:
        raise InputError(
            f"{name} must be an integer {rule}, got a {type(value).__name__} {_short(value)}"
        )
    if not _is_real_scalar(value) and not (isinstance(value, np.ndarray) and value.ndim == 0):
        raise InputError(f"{name} must be an integer {rule}, got {_kind_of(value)}")
    x = float(value)
    if not (math.isfinite(x) and x == int(x)):
        raise InputError(f"{name} must be an integer {rule}, got {_short(value)}")
    n = int(x)
    if n < minimum or (maximum is not None and n > maximum):
        raise InputError(f"{name} must be {rule}, got {n}")
    return n


def _shape(value):
    """Shape of an array, list or tuple argument; None for anything else (or a ragged list,
    which the argument's own check refuses by name)."""
    if not isinstance(value, (list, tuple, np.ndarray)):
        return None
    try:
        return np.shape(value)
    except ValueError:
        return None


def check_broadcast(**arguments) -> None:
    """Refuse, naming them, array arguments whose shapes do not broadcast together.

    Parameters
    ----------
    **arguments
        Argument name -> value; scalars and non-arrays are skipped.

    Raises
    ------
    InputError
        ``mu (shape (2,)) and wrap_angle (shape (3,)) do not broadcast together``.
    """
    seen: dict[str, tuple] = {}
    for name, value in arguments.items():
        shape = _shape(value)
        if shape is None:
            continue
        try:
            np.broadcast_shapes(*seen.values(), shape)
        except ValueError:
            first = ", ".join(f"{n} (shape {s})" for n, s in seen.items())
            raise InputError(f"{name} (shape {shape}) does not broadcast with {first}") from None
        seen[name] = shape


def vectorised(func):
    """Decorate a vectorised closed form: array arguments must broadcast together.

    Without it numpy would raise a bare ValueError (``operands could not be broadcast``)
    from inside the formula; with it the caller gets an InputError naming the arguments.
    """
    signature = inspect.signature(func)

    @functools.wraps(func)
    def checked(*args, **kwargs):
        try:
            bound = signature.bind(*args, **kwargs)
        except TypeError:
            return func(*args, **kwargs)  # a wrong call: Python's own message
        check_broadcast(**bound.arguments)
        return func(*args, **kwargs)

    return checked
