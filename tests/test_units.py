"""Parsing quantities with units at the command-line edge (knotmech.units)."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from knotmech.errors import InputError
from knotmech.units import HINT_UNITS, KINDS, parse_count, parse_quantity


@pytest.mark.parametrize(
    ("text", "kind", "expected"),
    [
        ("4mm", "length", 0.004),
        ("4 mm", "length", 0.004),
        ("3cm", "length", 0.03),
        ("4\u00b5m", "length", 4e-6),
        ("360deg", "angle", 2 * math.pi),
        ("360\u00b0", "angle", 2 * math.pi),
        ("2pi", "angle", 2 * math.pi),
        ("6.28rad", "angle", 6.28),
        ("1.5turn", "angle", 3 * math.pi),
        ("1.47N", "force", 1.47),
        ("0N", "force", 0.0),
        ("0", "force", 0.0),  # zero is zero in every unit
        ("7gf", "force", 7e-3 * 9.80665),
        ("1kgf", "force", 9.80665),
        ("1.3MPa", "pressure", 1.3e6),
        ("20ms", "time", 0.02),
        ("10mm/s", "velocity", 0.01),
        ("1200kg/m^3", "density", 1200.0),
        ("1.2g/cm^3", "density", 1200.0),
        ("1e-5N*m^2", "bending_stiffness", 1e-5),
        ("10N*mm^2", "bending_stiffness", 1e-5),
        ("0.3", "dimensionless", 0.3),
        ("\u22124mm", "length", -0.004),  # U+2212 MINUS SIGN is a minus, never dropped
        ("\u22120.3", "dimensionless", -0.3),
    ],
)
def test_parse_quantity_to_si(text, kind, expected):
    assert parse_quantity(text, kind) == pytest.approx(expected, rel=1e-12, abs=0)


def test_python_numbers_are_si():
    assert parse_quantity(0.25, "length") == 0.25
    assert parse_quantity(3, "force") == 3.0


def test_bare_si_only_when_asked():
    assert parse_quantity("0.004", "length", bare_si=True) == 0.004
    with pytest.raises(InputError, match=r"^--rod-diameter 4: give a unit, e.g. 4mm$"):
        parse_quantity("4", "length", name="--rod-diameter")


@pytest.mark.parametrize(
    ("kind", "hint"),
    [("length", "4mm"), ("force", "4N"), ("angle", "4deg"), ("pressure", "4MPa"),
     ("time", "4s"), ("velocity", "4mm/s"), ("density", "4kg/m^3"),
     ("bending_stiffness", "4N*m^2"), ("mass", "4g")],
)  # fmt: skip
def test_a_bare_number_is_never_silently_si(kind, hint):
    with pytest.raises(InputError, match="give a unit") as err:
        parse_quantity("4", kind, name="--x")
    assert str(err.value) == f"--x 4: give a unit, e.g. {hint}"
    # and the hint itself parses
    assert parse_quantity(hint, kind) > 0


def test_every_kind_has_a_hint_that_parses():
    for kind in KINDS:
        if kind != "dimensionless":
            assert parse_quantity("1" + HINT_UNITS[kind], kind) > 0


@settings(max_examples=30, deadline=None)
@given(st.floats(1e-6, 1e6))
def test_millimetres_round_trip(x):
    assert parse_quantity(f"{x!r} mm", "length") == pytest.approx(x * 1e-3, rel=1e-12)


@pytest.mark.parametrize(
    ("text", "kind", "match"),
    [
        ("4N", "length", "not a length"),
        ("4mm", "force", "not a force"),
        ("4mm", "angle", "not an angle"),
        ("4percent", "angle", "not an angle"),
        ("2*3", "angle", "give a unit"),
        ("0.004", "length", "give a unit"),
        ("360", "angle", "give a unit"),
        ("nan", "length", "finite"),
        ("nan mm", "length", "finite"),
        ("inf N", "force", "finite"),
        ("abc", "length", "cannot read"),
        ("4 mm)", "length", "cannot read"),
        ("", "length", "empty"),
        ("__import__('os')", "length", "cannot read"),
        # read wrongly by pint / float before: refused now
        ("4,0mm", "length", "comma"),  # was 40 mm
        ("0,3", "dimensionless", "comma"),
        ("1_0", "dimensionless", "'_'"),  # float('1_0') == 10
        ("1_0mm", "length", "'_'"),
        ("\uff14", "dimensionless", "non-ASCII digit"),  # fullwidth 4
        ("\uff14mm", "length", "non-ASCII digit"),
        ("\u0664mm", "length", "non-ASCII digit"),  # Arabic-Indic 4
        ("0.3 deg", "dimensionless", "plain number"),  # was 0.0052
        ("30%", "dimensionless", "plain number"),
        ("1200kg/m^3", "dimensionless", "plain number"),
        ("1200kg/m^3", "pressure", "not a pressure"),
        # magnitudes (issue 27): overflow, underflow, an angle of 1e300 deg, hanging powers
        ("1e400mm", "length", r"beyond the largest float \(1.8e308\)"),
        ("1e400", "dimensionless", "beyond the largest float"),
        ("1e308 km", "length", "beyond the largest float"),  # 1e311 m
        ("-1e400N", "force", "beyond the largest float"),
        ("1e-400mm", "length", r"too small for a float \(it would be read as 0\)"),
        ("1e-320 um", "length", "too small for a float"),
        ("1e300deg", "angle", r"is 2.78e\+297 turns; an angle must be within 1000 turns"),
        ("1001turn", "angle", "1e\\+03 turns; an angle must be within 1000 turns"),
        ("9**9**9 mm", "length", "a power applies to a unit name"),  # hung pint for ever
        ("10**400 mm", "length", "a power applies to a unit name"),
        ("mm^999", "length", "whole exponent below 100"),
        ("1" * 101 + "mm", "length", "103 characters long"),
        (" ", "length", "empty"),
    ],
)
def test_bad_quantities_name_the_argument(text, kind, match):
    with pytest.raises(InputError, match=match) as err:
        parse_quantity(text, kind, name="--rod-diameter")
    msg = str(err.value)
    assert "--rod-diameter" in msg
    assert "\n" not in msg


def test_unknown_kind():
    with pytest.raises(InputError, match="kind"):
        parse_quantity("1", "colour")


@pytest.mark.parametrize(("text", "expected"), [("151", 151), (" 8 ", 8), (120, 120), ("-3", -3)])
def test_counts(text, expected):
    value = parse_count(text, name="--n-nodes")
    assert value == expected and isinstance(value, int)


@pytest.mark.parametrize("text", ["1e2", "150.0", "1_0", "\u0661\u0662", "\uff11", "12mm", "",
                                  True, 1.5, None])  # fmt: skip
def test_bad_counts(text):
    # int() accepts "1_0", Arabic-Indic and fullwidth digits; a count must not
    with pytest.raises(InputError, match="--n-nodes") as err:
        parse_count(text, name="--n-nodes")
    assert "\n" not in str(err.value)


def test_units_read_without_pint_agree_with_pint():
    """The common units are read without building pint's registry (start-up time); each
    must give what pint gives."""
    from knotmech.units import _FAST_UNITS, _parse_with_units

    for unit, (kind, factor) in _FAST_UNITS.items():
        for number in ("4", "2.5e-3", "-0.75"):
            text = f"{number}{unit}"
            fast = parse_quantity(text, kind)
            assert fast == pytest.approx(float(number) * factor, rel=1e-15)
            assert fast == pytest.approx(_parse_with_units(text, kind, "x", ""), rel=1e-12)
            assert parse_quantity(f"{number} {unit}", kind) == fast


def test_a_fast_unit_of_the_wrong_kind_still_says_so():
    with pytest.raises(InputError, match="not a length"):
        parse_quantity("4N", "length", name="--d")


_ALPHABET = st.sampled_from(list("0123456789.,_-+eE mMNkgfdrsPa/^*()%°µ\u2212\uff14\u0664x")) | (
    st.characters()
)


@settings(max_examples=150, deadline=None, derandomize=True)
@given(text=st.text(_ALPHABET, max_size=12), kind=st.sampled_from(sorted(KINDS)))
def test_fuzz_any_text_is_a_finite_si_value_or_one_line_input_error(text, kind):
    """Whatever the user types, the answer is a finite float or a one-line InputError
    naming the option; never another exception."""
    try:
        value = parse_quantity(text, kind, name="--opt")
    except InputError as exc:
        assert "--opt" in str(exc) and "\n" not in str(exc)
    else:
        assert math.isfinite(value)


@settings(max_examples=100, deadline=None, derandomize=True)
@given(st.text(_ALPHABET, max_size=8))
def test_fuzz_counts(text):
    try:
        value = parse_count(text, name="--n")
    except InputError as exc:
        assert "--n" in str(exc) and "\n" not in str(exc)
    else:
        assert isinstance(value, int) and str(abs(value)) in text.replace("\u2212", "-")


def test_the_largest_accepted_magnitudes_still_parse():
    """Edges of the magnitude checks: 1000 turns, 1e308 m, the smallest normal float, m^3."""
    assert parse_quantity("1000turn", "angle") == pytest.approx(2000 * math.pi, rel=1e-15)
    assert parse_quantity("-360000deg", "angle") == pytest.approx(-2000 * math.pi, rel=1e-15)
    assert parse_quantity("1e308 m", "length") == 1e308
    assert parse_quantity("2.3e-308 m", "length") == 2.3e-308
    assert parse_quantity("0e-400mm", "length") == 0.0
    assert parse_quantity("1 kg/m**3", "density") == 1.0
    assert parse_quantity(1e300, "length") == 1e300  # a Python number is SI: no angle here
    with pytest.raises(InputError, match="must be within 1000 turns"):
        parse_quantity(1e300, "angle", name="wrap_angle")
