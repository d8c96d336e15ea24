"""Parsing quantities with units at the command-line edge (knotmech.units)."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from knotmech.errors import InputError
from knotmech.units import parse_quantity


@pytest.mark.parametrize(
    ("text", "kind", "expected"),
    [
        ("4mm", "length", 0.004),
        ("4 mm", "length", 0.004),
        ("3cm", "length", 0.03),
        ("0.004", "length", 0.004),  # bare number: SI
        ("360deg", "angle", 2 * math.pi),
        ("2pi", "angle", 2 * math.pi),
        ("6.28rad", "angle", 6.28),
        ("1.5turn", "angle", 3 * math.pi),
        ("1.47N", "force", 1.47),
        ("0N", "force", 0.0),
        ("7gf", "force", 7e-3 * 9.80665),
        ("1kgf", "force", 9.80665),
        ("1.3MPa", "pressure", 1.3e6),
        ("0.3", "dimensionless", 0.3),
    ],
)
def test_parse_quantity_to_si(text, kind, expected):
    assert parse_quantity(text, kind) == pytest.approx(expected, rel=1e-12, abs=0)


def test_numbers_pass_through():
    assert parse_quantity(0.25, "length") == 0.25
    assert parse_quantity(3, "force") == 3.0


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
        ("nan", "length", "finite"),
        ("nan mm", "length", "finite"),
        ("inf N", "force", "finite"),
        ("abc", "length", "cannot read"),
        ("4 mm)", "length", "cannot read"),
        ("", "length", "empty"),
        ("__import__('os')", "length", "cannot read"),
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
