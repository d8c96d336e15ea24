"""Quantities with units at the edges (command line, files): parse to plain SI floats.

Inside knotmech every number is a plain float in SI units (m, N, rad, Pa, ...).
:func:`parse_quantity` turns user text such as ``"4mm"``, ``"1.47N"``, ``"7gf"``,
``"360deg"``, ``"2pi"``, ``"1.5turn"``, ``"1200kg/m^3"`` or ``"1e-5N*m^2"`` into that
float, using pint. Errors are :class:`knotmech.errors.InputError` with a one-line
message naming the argument.

Text is read strictly, because a quantity read wrongly gives a confident wrong answer:

- a bare number in text (``"4"``) for a dimensional kind (length, force, angle, ...)
  is refused with a hint (``--rod-diameter 4: give a unit, e.g. 4mm``), unless the
  caller passes ``bare_si=True``; zero needs no unit. Python numbers (``0.004``) are
  taken as SI, as everywhere in the library;
- a dimensionless kind takes a plain number only (``--mu '0.3 deg'`` is refused,
  not read as 0.0052);
- a decimal comma (``4,0mm``), digit separators (``1_0``), and digits other than
  ASCII 0-9 (fullwidth, Arabic-Indic) are refused; the Unicode minus sign U+2212
  (``−4mm``) is read as a minus;
- counts (:func:`parse_count`) are whole numbers written with ASCII digits;
- magnitudes: NaN and infinity are refused, a number that overflows a float (``1e400mm``,
  or ``1e308km`` once in metres) is refused as such, and a non-zero number that underflows
  to zero (``1e-400mm``) is refused rather than read as 0; an angle beyond
  :data:`MAX_ANGLE_TURNS` turns (``1e300deg``) is refused: no input of knotmech is that large;
- text longer than :data:`MAX_TEXT` characters is refused, and a power (``^`` or ``**``)
  applies to a unit name with a whole exponent below 100 (``kg/m^3``), so that the text
  cannot make pint compute ``9**9**9`` for ever.

Every refusal is one line that names the argument (the option, e.g. ``--wrap-angle``).
"""

from __future__ import annotations

import math
import numbers
import re
import unicodedata
from functools import lru_cache

from knotmech.errors import InputError

__all__ = ["KINDS", "MAX_ANGLE_TURNS", "format_quantity", "parse_count", "parse_quantity"]

#: kind -> (SI unit pint converts to, pint dimensionality string, examples)
KINDS: dict[str, tuple[str, str, str]] = {
    "length": ("meter", "[length]", "4mm, 3cm, 0.5in"),
    "force": ("newton", "[length] * [mass] / [time] ** 2", "1.47N, 150gf, 0.2kgf"),
    "angle": ("radian", "dimensionless", "360deg, 2pi, 6.28rad, 1.5turn"),
    "pressure": ("pascal", "[mass] / [length] / [time] ** 2", "1.3MPa, 2GPa"),
    "mass": ("kilogram", "[mass]", "150g, 0.15kg"),
    "time": ("second", "[time]", "2s, 10ms"),
    "velocity": ("meter / second", "[length] / [time]", "1mm/s, 2cm/s"),
    "density": ("kilogram / meter ** 3", "[mass] / [length] ** 3", "1160kg/m^3, 1.16g/cm^3"),
    "bending_stiffness": (
        "newton * meter ** 2",
        "[length] ** 3 * [mass] / [time] ** 2",
        "1e-5N*m^2, 10N*mm^2",
    ),
    "dimensionless": ("dimensionless", "dimensionless", "0.3"),
}

#: the unit suggested after a bare number ("give a unit, e.g. 4mm")
HINT_UNITS: dict[str, str] = {
    "length": "mm",
    "force": "N",
    "angle": "deg",
    "pressure": "MPa",
    "mass": "g",
    "time": "s",
    "velocity": "mm/s",
    "density": "kg/m^3",
    "bending_stiffness": "N*m^2",
}

#: pint unit names that make a dimensionless quantity an angle
_ANGLE_UNITS = frozenset(
    ("radian", "milliradian", "degree", "arcminute", "arcsecond", "turn", "pi", "gradian")
)
#: non-ASCII characters accepted in a quantity (micro sign, Greek mu, degree, powers)
_ALLOWED_NON_ASCII = frozenset("\u00b5\u03bc\u00b0\u00b2\u00b3")
_MINUS_SIGNS = "\u2212\ufe63\uff0d"  # minus sign, small and fullwidth hyphen-minus
_BARE = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?|[+-]?(nan|inf|infinity)", re.I)
_COUNT = re.compile(r"[+-]?\d+")
_POWER = re.compile(r"\*\*|\^")
_EXPONENT = re.compile(r"\s*[+-]?\d{1,2}(?![\d.]|\s*(\*\*|\^))")
_LEADING_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)")

#: [turn] the largest angle accepted (a wrap of 1000 turns is already no knot)
MAX_ANGLE_TURNS = 1000.0
#: the longest text accepted for one quantity
MAX_TEXT = 100


_G = 9.80665  # [m/s^2] standard gravity (gram-force, kilogram-force)
_DEG = math.pi / 180.0
#: unit text -> (kind, factor to SI) for the common forms, read without pint: building
#: pint's registry takes about a second, which a command answering from a table should not
#: pay. Each entry is checked against pint in tests/test_units.py; any other text goes to
#: pint.
_FAST_UNITS: dict[str, tuple[str, float]] = {
    **{u: ("length", f) for u, f in (("m", 1.0), ("mm", 1e-3), ("cm", 1e-2), ("km", 1e3),
       ("um", 1e-6), ("\u00b5m", 1e-6), ("\u03bcm", 1e-6), ("in", 0.0254))},
    **{u: ("force", f) for u, f in (("N", 1.0), ("mN", 1e-3), ("kN", 1e3), ("gf", 1e-3 * _G),
       ("kgf", _G))},
    **{u: ("angle", f) for u, f in (("rad", 1.0), ("deg", _DEG), ("degree", _DEG),
       ("degrees", _DEG), ("\u00b0", _DEG), ("turn", 2 * math.pi), ("turns", 2 * math.pi))},
    **{u: ("pressure", f) for u, f in (("Pa", 1.0), ("kPa", 1e3), ("MPa", 1e6), ("GPa", 1e9))},
    **{u: ("mass", f) for u, f in (("kg", 1.0), ("g", 1e-3), ("mg", 1e-6))},
    **{u: ("time", f) for u, f in (("s", 1.0), ("ms", 1e-3), ("us", 1e-6), ("min", 60.0))},
    **{u: ("velocity", f) for u, f in (("m/s", 1.0), ("mm/s", 1e-3), ("cm/s", 1e-2))},
    **{u: ("density", f) for u, f in (("kg/m^3", 1.0), ("kg/m**3", 1.0), ("g/cm^3", 1e3))},
    **{u: ("bending_stiffness", f) for u, f in (("N*m^2", 1.0), ("N*mm^2", 1e-6))},
}  # fmt: skip
_NUMBER_UNIT = re.compile(r"([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?) ?(\S+)")


def _fast(s: str, kind: str) -> float | None:
    """``"4mm"`` -> 0.004 without pint, for the units of :data:`_FAST_UNITS`; else None."""
    m = _NUMBER_UNIT.fullmatch(s)
    if m is None:
        return None
    entry = _FAST_UNITS.get(m.group(2))
    if entry is None or entry[0] != kind:
        return None
    return float(m.group(1)) * entry[1]


@lru_cache(maxsize=1)
def _registry():
    import pint

    return pint.UnitRegistry(autoconvert_offset_to_baseunit=True)


def parse_quantity(text, kind: str, *, name: str = "value", bare_si: bool = False) -> float:
    """Parse a quantity with units into an SI float.

    Parameters
    ----------
    text : str or float
        E.g. ``"4mm"``, ``"1.47 N"``, ``"360deg"``, ``"2pi"``, ``"1.5turn"``,
        ``"1200kg/m^3"``. A Python number (``0.004``) is taken in SI units. A bare
        number in text (``"0.004"``) is refused for a dimensional kind unless
        ``bare_si`` (zero is accepted: it is zero in every unit).
    kind : str
        One of :data:`KINDS` (``length``, ``force``, ``angle``, ``pressure``, ``mass``,
        ``time``, ``velocity``, ``density``, ``bending_stiffness``, ``dimensionless``).
    name : str
        Argument name used in error messages (e.g. ``"--rod-diameter"``).
    bare_si : bool
        Accept a bare number in text as SI (for inputs that document it, e.g. a
        file column whose header names the unit).

    Returns
    -------
    float
        The value in SI units (m, N, rad, Pa, kg, s, m/s, kg/m^3, N m^2).

    Raises
    ------
    InputError
        Unknown kind; unparsable text; a bare number for a dimensional kind; a unit of
        the wrong dimension (an angle unit for a dimensionless input included); a
        decimal comma, a digit separator or a non-ASCII digit; NaN or infinity.

    Examples
    --------
    >>> parse_quantity("4mm", "length")
    0.004
    >>> round(parse_quantity("360deg", "angle"), 6)
    6.283185
    >>> parse_quantity("0.3", "dimensionless")
    0.3
    """
    if kind not in KINDS:
        raise InputError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    _, _, examples = KINDS[kind]
    if isinstance(text, bool) or text is None:
        raise InputError(f"{name} must be {_article(kind)} {_label(kind)} such as {examples}, "
                         f"got {text!r}")  # fmt: skip
    if isinstance(text, numbers.Real):
        return _checked(float(text), repr(text), kind, name)
    s = _clean_text(text, name, kind)
    if _BARE.fullmatch(s):
        value = _checked(float(s), s, kind, name)
        if kind == "dimensionless" or bare_si or value == 0.0:
            return value
        raise InputError(f"{name} {s}: give a unit, e.g. {s}{HINT_UNITS[kind]}")
    if kind == "dimensionless":
        raise InputError(f"{name}: give a plain number such as 0.3 (no unit), got {s!r}")
    value = _fast(s, kind)
    if value is None:
        value = _parse_with_units(s, kind, name, examples)
    return _checked(value, s, kind, name)


def _checked(value: float, s: str, kind: str, name: str) -> float:
    """``value`` (read from the text ``s``) unless NaN, inf, overflowed, underflowed, or an
    angle beyond :data:`MAX_ANGLE_TURNS`; else InputError naming ``name``."""
    if math.isnan(value) or (math.isinf(value) and re.search("inf", s, re.I)):
        raise InputError(f"{name} must be a finite number, got {s!r}")
    if math.isinf(value):
        raise InputError(f"{name}: {s!r} is beyond the largest float (1.8e308) in SI units")
    leading = _LEADING_NUMBER.match(s)
    if value == 0.0 and leading and re.search("[1-9]", leading.group()):
        raise InputError(f"{name}: {s!r} is too small for a float (it would be read as 0)")
    if kind == "angle" and abs(value) > MAX_ANGLE_TURNS * 2 * math.pi * (1 + 1e-12):
        raise InputError(
            f"{name}: {s!r} is {value / (2 * math.pi):.3g} turns; an angle must be within "
            f"{MAX_ANGLE_TURNS:g} turns ({MAX_ANGLE_TURNS * 360:g} deg)"
        )
    return value


def parse_count(text, *, name: str = "value") -> int:
    """Parse a count (number of nodes, elements, turns): a whole number in ASCII digits.

    Parameters
    ----------
    text : str or int
        ``"151"``; an ``int`` passes through. ``"1e2"``, ``"150.0"``, ``"1_0"`` and
        non-ASCII digits are refused.
    name : str
        Argument name used in error messages (e.g. ``"--n-nodes"``).

    Returns
    -------
    int
        The count; its range is checked by the function that uses it.

    Raises
    ------
    InputError
        Anything but a whole number.
    """
    if isinstance(text, bool) or text is None:
        raise InputError(f"{name} must be a whole number such as 151, got {text!r}")
    if isinstance(text, numbers.Integral):
        return int(text)
    s = _clean_text(text, name, "count")
    if not _COUNT.fullmatch(s):
        raise InputError(f"{name} must be a whole number such as 151, got {s!r}")
    return int(s)


def _clean_text(text, name: str, kind: str) -> str:
    """Strip, read a Unicode minus as '-', refuse what would be read wrongly."""
    s = str(text)
    for ch in _MINUS_SIGNS:
        s = s.replace(ch, "-")
    s = "".join(" " if ch.isspace() else ch for ch in s).strip()
    if not s:
        raise InputError(f"{name} is empty; give {_article(kind)} {_label(kind)} such as "
                         f"{KINDS[kind][2] if kind in KINDS else '151'}")  # fmt: skip
    for ch in s:
        if ord(ch) > 127 and ch not in _ALLOWED_NON_ASCII:
            what = "digit" if unicodedata.category(ch) == "Nd" else "character"
            raise InputError(
                f"{name}: {s!r} contains the non-ASCII {what} {ch!r} "
                f"(U+{ord(ch):04X}); write numbers with the digits 0-9"
            )
    if "," in s:
        raise InputError(f"{name}: {s!r} contains a comma; write the decimal point as '.' "
                         f"(e.g. {s.replace(',', '.', 1)}) and no thousands separator")  # fmt: skip
    if len(s) > MAX_TEXT:
        raise InputError(f"{name}: the text is {len(s)} characters long (at most {MAX_TEXT})")
    if re.search(r"\d_|_\d", s):
        raise InputError(f"{name}: {s!r} contains '_' in a number; write the digits without "
                         f"separators (e.g. {s.replace('_', '')})")  # fmt: skip
    return s


def _parse_with_units(s: str, kind: str, name: str, examples: str) -> float:
    import pint

    _check_powers(s, name)
    ureg = _registry()
    unit = KINDS[kind][0]
    try:
        q = ureg.Quantity(s)
    except Exception:  # pint's parser raises many kinds of errors on garbage
        raise InputError(f"{name}: cannot read {s!r} as {_article(kind)} {_label(kind)} "
                         f"(e.g. {examples})") from None  # fmt: skip
    units = dict(q.unit_items()) if isinstance(q, ureg.Quantity) else {}
    if not units:  # a plain number after evaluation, e.g. "2*3"
        raise InputError(f"{name} {s}: give a unit, e.g. {s}{HINT_UNITS[kind]}")
    if kind == "angle" and not set(units) <= _ANGLE_UNITS:
        raise InputError(f"{name}: {s!r} is not an angle; use e.g. {examples}")
    try:
        return float(q.to(unit).magnitude)
    except pint.errors.DimensionalityError:
        raise InputError(
            f"{name}: {s!r} is not {_article(kind)} {_label(kind)} (its dimension is "
            f"{q.dimensionality}); use e.g. {examples}"
        ) from None
    except (TypeError, ValueError, OverflowError):
        raise InputError(f"{name}: cannot read {s!r} as {_article(kind)} {_label(kind)} "
                         f"(e.g. {examples})") from None  # fmt: skip


def _check_powers(s: str, name: str) -> None:
    """Refuse a power of a number or a large or chained exponent (``9**9**9`` would never end)."""
    for m in _POWER.finditer(s):
        left = s[: m.start()].rstrip()
        if not (left and left[-1].isalpha() and _EXPONENT.match(s, m.end())):
            raise InputError(
                f"{name}: {s!r}: a power applies to a unit name with a whole exponent "
                "below 100 (e.g. kg/m^3)"
            )


def _label(kind: str) -> str:
    return {"bending_stiffness": "bending stiffness", "velocity": "speed",
            "dimensionless": "number"}.get(kind, kind)  # fmt: skip


def _article(word: str) -> str:
    return "an" if _label(word)[:1] in "aeiou" else "a"


def format_quantity(value: float, kind: str) -> str:
    """Short human-readable form of an SI value (``0.004, "length"`` -> ``"4 mm"``)."""
    v = float(value)
    if kind == "length":
        return f"{v * 1e3:.4g} mm" if abs(v) < 1 else f"{v:.4g} m"
    if kind == "force":
        return f"{v:.4g} N"
    if kind == "angle":
        turns = v / (2 * math.pi)
        return f"{math.degrees(v):.4g} deg ({turns:.4g} turn{'' if turns == 1 else 's'})"
    if kind == "pressure":
        return f"{v / 1e6:.4g} MPa"
    if kind == "time":
        return f"{v * 1e3:.4g} ms" if abs(v) < 1 else f"{v:.4g} s"
    if kind == "velocity":
        return f"{v * 1e3:.4g} mm/s"
    if kind == "density":
        return f"{v:.4g} kg/m^3"
    if kind == "bending_stiffness":
        return f"{v:.4g} N m^2"
    return f"{v:.4g}"
