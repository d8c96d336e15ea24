"""The rule of knotmech.errors for a physical quantity (issue 27), on the closed forms."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from knotmech.analytic import capstan_ratio, effective_modulus, hertz_crossed_cylinders, mu_eff
from knotmech.errors import InputError, check_bending_scale, check_positive, check_range

MU_EFF_03_2 = 0.19615242270663188  # mu_eff(0.3, D/d = 2); the clove-hitch paper's 0.196


@pytest.mark.parametrize(
    ("mu", "d_over_d", "message"),
    [
        (True, 2.0, "mu must be a number or an array of numbers, got the bool True"),
        (np.bool_(False), 2.0, "mu must be a number or an array of numbers, got the bool False"),
        ("0.3", 2.0, "mu must be a number or an array of numbers, got the string '0.3'"),
        (b"0.3", 2.0, "got the string b'0.3'"),
        (None, 2.0, "mu must be a number or an array of numbers, got None"),
        (0.3 + 0j, 2.0, "got the complex number (0.3+0j)"),
        (np.complex128(0.3), 2.0, "got the complex number"),
        (0.3, [2.0, True], "D_over_d must be a number or an array of numbers, got the bool True"),
        (0.3, [2.0, "x"], "got the string 'x' in a list"),
        (0.3, [2.0, None], "got None in a list"),
        (0.3, [], "D_over_d must be a number or an array of numbers, got an empty array"),
        (0.3, [[1.0], [1.0, 2.0]], "(not a regular array)"),
        (0.3, np.array([True]), "got an array of dtype bool"),
        (0.3, np.array(["2"]), "got an array of dtype <U1"),
        (float("nan"), 2.0, "mu must be a finite number >= 0, got nan"),
        (0.3, float("inf"), "D_over_d must be a finite number > 0, got inf"),
        (0.3, [2.0, -float("inf")], "D_over_d must be a finite number > 0, got -inf"),
        (0.3, {"D": 2.0}, "D_over_d must be a number or an array of numbers, got {'D': 2.0} (a"),
    ],
)  # fmt: skip
def test_a_wrong_kind_of_value_is_one_line_naming_the_argument(mu, d_over_d, message):
    with pytest.raises(InputError) as e:
        mu_eff(mu, d_over_d)
    assert message in str(e.value)
    assert "\n" not in str(e.value)


@pytest.mark.parametrize(
    "d_over_d", [2, 2.0, np.float32(2.0), np.int64(2), Fraction(2), np.array(2.0), [2.0], (2,)]
)
def test_every_kind_of_real_number_gives_the_same_value(d_over_d):
    """Ints, numpy scalars, fractions, 0-d arrays and lists keep their value (vectorised)."""
    assert np.allclose(mu_eff(0.3, d_over_d), MU_EFF_03_2, rtol=0, atol=0)


def test_a_long_array_is_shown_in_one_short_line():
    with pytest.raises(InputError) as e:
        mu_eff(0.3, np.full((30, 30), "2"))
    assert "\n" not in str(e.value) and len(str(e.value)) < 120


def test_scalar_refuses_a_list_in_one_line_and_returns_a_float():
    with pytest.raises(
        InputError, match=r"^rod_diameter must be one number, got a list \[0.004, 0.005\]$"
    ):
        check_positive("rod_diameter", [0.004, 0.005], scalar=True)
    with pytest.raises(InputError, match="rod_diameter must be a number, got the string '4mm'"):
        check_positive("rod_diameter", "4mm", scalar=True)
    value = check_positive("rod_diameter", np.float32(0.5), scalar=True)
    assert type(value) is float and value == 0.5
    assert check_positive("rod_diameter", np.array(0.25), scalar=True) == 0.25


def test_range_and_infinity_where_allowed():
    with pytest.raises(InputError, match=r"poisson_ratio must lie in \[0, 0.5\], got 0.6"):
        check_range("poisson_ratio", 0.6, 0.0, 0.5)
    with pytest.raises(
        InputError, match=r"poisson_ratio must be a finite number in \[0, 0.5\], got nan"
    ):
        check_range("poisson_ratio", float("nan"), 0.0, 0.5)
    # a rigid counterface: E_2 = inf is the default and gives E* = E/(1 - nu^2)
    assert effective_modulus(1.0e6, 0.5, np.inf) == pytest.approx(1.0e6 / 0.75, rel=1e-15)
    with pytest.raises(
        InputError, match=r"youngs_modulus_2 must be a number in \(0, inf\], got nan"
    ):
        effective_modulus(1.0e6, 0.5, float("nan"))
    with pytest.raises(InputError, match="youngs_modulus_2 must be a number or an array of numb"):
        effective_modulus(1.0e6, 0.5, "inf")


def test_bending_scale_refuses_bools_and_strings():
    assert check_bending_scale(0.01) == 0.01
    for bad in (True, "0.5", None, 0.0, 1.5, float("nan")):
        with pytest.raises(InputError, match=r"^bending_scale must be a number in \(0, 1\], got"):
            check_bending_scale(bad)


def test_an_overflowing_capstan_ratio_is_refused_not_inf():
    """exp(mu theta) beyond 1.8e308 (mu theta > 709.78) is refused; just below it is finite."""
    assert np.isfinite(capstan_ratio(1.0, 709.0))
    with pytest.raises(InputError, match=r"exp\(mu\*wrap_angle\) is beyond the largest float"):
        capstan_ratio(1.0, 710.0)


def test_a_hertz_ellipse_too_slender_for_the_solver_is_refused():
    """Radii 1e24 apart gave a silently wrong ellipse (the solver saturates near 1e14)."""
    kw = dict(normal_force=1.0, youngs_modulus=1e6, poisson_ratio=0.5)
    ok = hertz_crossed_cylinders(radius_1=1e-5, radius_2=1e5, **kw)  # ratio 1e10: accepted
    assert np.isfinite(ok.semi_major) and ok.semi_minor < ok.semi_major
    with pytest.raises(InputError, match=r"radius_1/radius_2 = 1e\+24 is beyond 1e\+10"):
        hertz_crossed_cylinders(radius_1=1e-12, radius_2=1e12, **kw)
