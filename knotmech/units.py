"""Quantities with units at the edges (command line, files): parse to plain SI floats.

Inside knotmech every number is a plain float in SI units (m, N, rad, Pa, ...).
:func:`parse_quantity` turns user text such as ``"4mm"``, ``"1.47N"``, ``"7gf"``,
``"360deg"``, ``"2pi"`` or ``"1.5turn"`` into that float, using pint. A bare number
is taken as already in SI units. Errors are :class:`knotmech.errors.InputError`
with a one-line message naming the argument.
"""

from __future__ import annotations

import math
from functools import lru_cache

from knotmech.errors import InputError

__all__ = ["KINDS", "parse_quantity", "format_quantity"]

#: kind -> (SI unit pint converts to, pint dimensionality string, examples)
KINDS: dict[str, tuple[str, str, str]] = {
    "length": ("meter", "[length]", "4mm, 0.004, 3cm"),
    "force": ("newton", "[length] * [mass] / [time] ** 2", "1.47N, 150gf, 0.2kgf"),
    "angle": ("radian", "dimensionless", "360deg, 2pi, 6.28rad, 1.5turn"),
    "pressure": ("pascal", "[mass] / [length] / [time] ** 2", "1.3MPa, 1.3e6"),
    "mass": ("kilogram", "[mass]", "150g, 0.15"),
    "time": ("second", "[time]", "2s, 10ms"),
    "velocity": ("meter / second", "[length] / [time]", "1mm/s"),
    "dimensionless": ("dimensionless", "dimensionless", "0.3"),
}


@lru_cache(maxsize=1)
def _registry():
    import pint

    return pint.UnitRegistry(autoconvert_offset_to_baseunit=True)


def parse_quantity(text, kind: str, *, name: str = "value") -> float:
    """Parse a quantity with optional units into an SI float.

    Parameters
    ----------
    text : str or float
        E.g. ``"4mm"``, ``"1.47 N"``, ``"360deg"``, ``"2pi"``, ``"1.5turn"``; a bare
        number (``"0.004"``, ``0.004``) is taken in SI units (radians for angles).
    kind : str
        One of :data:`KINDS` (``length``, ``force``, ``angle``, ...).
    name : str
        Argument name used in error messages (e.g. ``"--rod-diameter"``).

    Returns
    -------
    float
        The value in SI units (m, N, rad, Pa, kg, s, m/s).

    Raises
    ------
    InputError
        Unknown kind, unparsable text, a unit of the wrong dimension, NaN or infinity.

    Examples
    --------
    >>> parse_quantity("4mm", "length")
    0.004
    >>> round(parse_quantity("360deg", "angle"), 6)
    6.283185
    """
    if kind not in KINDS:
        raise InputError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    unit, _, examples = KINDS[kind]
    if isinstance(text, bool):
        raise InputError(f"{name} must be {_article(kind)} {kind} such as {examples}, got {text!r}")
    if isinstance(text, (int, float)):
        value = float(text)
    else:
        s = str(text).strip()
        if not s:
            raise InputError(f"{name} is empty; give a {kind} such as {examples}")
        try:
            value = float(s)  # bare number: SI
        except ValueError:
            value = _parse_with_units(s, kind, unit, name, examples)
    if not math.isfinite(value):
        raise InputError(f"{name} must be finite (got {text!r})")
    return value


def _parse_with_units(s: str, kind: str, unit: str, name: str, examples: str) -> float:
    import pint

    ureg = _registry()
    try:
        q = ureg.Quantity(s)
    except (pint.errors.PintError, ValueError, TypeError, SyntaxError, AttributeError):
        raise InputError(f"{name}: cannot read {s!r} as a {kind} (e.g. {examples})") from None
    except Exception:  # pint's parser may raise other errors on garbage
        raise InputError(f"{name}: cannot read {s!r} as a {kind} (e.g. {examples})") from None
    if not isinstance(q, ureg.Quantity):  # a plain number after evaluation, e.g. "2*3"
        return float(q)
    try:
        if kind == "dimensionless":
            return float(q.to("dimensionless").magnitude)
        return float(q.to(unit).magnitude)
    except pint.errors.DimensionalityError:
        raise InputError(
            f"{name}: {s!r} is not {_article(kind)} {kind} (its dimension is {q.dimensionality}); "
            f"use e.g. {examples}"
        ) from None
    except (TypeError, ValueError):
        raise InputError(f"{name}: cannot read {s!r} as a {kind} (e.g. {examples})") from None


def _article(word: str) -> str:
    return "an" if word[:1] in "aeiou" else "a"


def format_quantity(value: float, kind: str) -> str:
    """Short human-readable form of an SI value (``0.004, "length"`` -> ``"4 mm"``)."""
    v = float(value)
    if kind == "length":
        return f"{v * 1e3:.4g} mm" if abs(v) < 1 else f"{v:.4g} m"
    if kind == "force":
        return f"{v:.4g} N"
    if kind == "angle":
        return f"{math.degrees(v):.4g} deg ({v / (2 * math.pi):.4g} turns)"
    return f"{v:.4g}"
