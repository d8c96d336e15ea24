"""Elastic knots: Jawed et al. (2015) braid law and closure, Audoly et al. (2007) loose trefoil."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from knotmech.analytic import knots
from knotmech.errors import InputError
from knotmech.materials import IMC_YOUNGS_MODULUS

H = 1.6e-3
B = IMC_YOUNGS_MODULUS * np.pi * H**4 / 4  # IMC option file: E = 0.18 MPa, h = 1.6 mm
turns = st.integers(1, 6)
mu = st.floats(0.01, 1.0)
shortening = st.floats(60.0, 1e5)  # e / (n^2 h)


@settings(max_examples=40, deadline=None)
@given(st.floats(1e-3, 1.0), st.floats(1e-5, 1e-2))
def test_braid_wavenumber_eq3(r, h):
    k = knots.braid_wavenumber(loop_radius=r, rod_radius=h)
    assert h * k**2 * r == pytest.approx(1 / np.sqrt(12), rel=1e-12)


@settings(max_examples=40, deadline=None)
@given(st.floats(1.0, 1e4), turns, mu, st.floats(0.1, 10.0))
def test_braid_force_linear_in_mu_and_n(k, n, m, factor):
    kw = {"wavenumber": k, "rod_radius": H, "bending_stiffness": B}
    f = knots.braid_friction_force(turns=n, mu=m, **kw)
    assert f == pytest.approx(2 * np.pi * m * n * H * B * k**3, rel=1e-12)
    assert knots.braid_friction_force(turns=n, mu=factor * m, **kw) == pytest.approx(
        factor * f, rel=1e-12
    )
    assert knots.braid_friction_force(turns=3 * n, mu=m, **kw) == pytest.approx(3 * f, rel=1e-12)


@settings(max_examples=40, deadline=None)
@given(shortening, turns, mu, st.floats(0.1, 10.0))
def test_pull_force_linear_in_mu(s, n, m, factor):
    e = s * n**2 * H
    f = knots.overhand_pull_force(e, n, m, H, B)
    assert knots.overhand_pull_force(e, n, factor * m, H, B) == pytest.approx(factor * f, rel=1e-9)
    assert f > 0


@settings(max_examples=30, deadline=None)
@given(turns, mu)
def test_pull_force_decreases_with_shortening_and_grows_with_turns(n, m):
    e = np.geomspace(8 * n**2 * H, 1e4 * n**2 * H, 200)
    f = knots.overhand_pull_force(e, n, m, H, B)
    assert np.all(np.diff(f) < 0)
    e_fixed = 50 * 36 * H  # loose enough for n = 6
    f_n = knots.overhand_pull_force(e_fixed, np.arange(1, 7), m, H, B)
    assert np.all(np.diff(f_n) > 0)


@settings(max_examples=30, deadline=None)
@given(shortening, turns, mu)
def test_solution_satisfies_eqs_3_4_5(s, n, m):
    e = s * n**2 * H
    kn = knots.overhand_knot(
        end_to_end_shortening=e, turns=n, mu=m, rod_radius=H, bending_stiffness=B
    )
    r = kn.loop_radius
    # Eq. (3): wavenumber; braid length l = 2 pi n / k
    assert kn.wavenumber == pytest.approx(knots.braid_wavenumber(loop_radius=r, rod_radius=H))
    assert kn.braid_length == pytest.approx(2 * np.pi * n / kn.wavenumber, rel=1e-12)
    # Eq. (4)
    assert kn.force == pytest.approx(
        knots.braid_friction_force(
            wavenumber=kn.wavenumber, turns=n, mu=m, rod_radius=H, bending_stiffness=B
        ),
        rel=1e-12,
    )
    # closure: e = l + lambda with the elastica loop
    l_r, lam_r = knots.loop_closure(kn.elastica_parameter)
    assert kn.braid_length / r == pytest.approx(l_r, rel=1e-9)
    assert kn.loop_length / r == pytest.approx(lam_r, rel=1e-9)
    assert kn.braid_length + kn.loop_length == pytest.approx(e, rel=1e-8)
    # Eq. (5) master curve
    x, c = l_r, np.sqrt(3) * np.pi**2
    assert n**2 * H / e == pytest.approx(x**2 / (x + lam_r) / (8 * c), rel=1e-8)
    assert n**2 * kn.force * H**2 / B == pytest.approx(m * x**3 / (96 * c), rel=1e-8)


def test_loose_limit_is_a_circle_with_force_e_to_the_minus_three_halves():
    """As e/h -> infinity the loop becomes a circle, e -> 2 pi R, and
    F -> F_c = 2 pi mu n h B (sqrt(12) h e / (2 pi))^(-3/2). First correction: with
    x = l/R = 2 pi n 12^(1/4) sqrt(2 pi h/e), lambda/R = 2 pi + 2x + O(x^2), so
    e/R = 2 pi + 3x and F/F_c = 1 + 9x/(4 pi) + O(x^2): the remainder must shrink like x^2."""
    for n in (1, 3):
        for s in (1e6, 1e8, 1e10):
            e = s * H
            f = knots.overhand_pull_force(e, n, 0.3, H, B)
            f_c = 2 * np.pi * 0.3 * n * H * B * (np.sqrt(12) * H * e / (2 * np.pi)) ** -1.5
            x = 2 * np.pi * n * 12**0.25 * np.sqrt(2 * np.pi * H / e)
            assert abs(f / f_c - 1 - 9 * x / (4 * np.pi)) < 0.2 * x**2


def test_validity_flags():
    tight = knots.overhand_knot(
        end_to_end_shortening=30 * H, turns=1, mu=0.3, rod_radius=H, bending_stiffness=B
    )
    assert not tight.valid and "too tight" in tight.message
    weak = knots.overhand_knot(
        end_to_end_shortening=1e3 * H, turns=1, mu=0.001, rod_radius=H, bending_stiffness=B
    )
    assert not weak.valid and "loop pull" in weak.message
    good = knots.overhand_knot(
        end_to_end_shortening=300 * H, turns=2, mu=0.3, rod_radius=H, bending_stiffness=B
    )
    assert good.valid and good.message == ""


def test_audoly_loose_trefoil():
    r = np.geomspace(1e-3, 1.0, 7)
    f = knots.loose_knot_force(loop_radius=r, bending_stiffness=B)
    np.testing.assert_allclose(f * H**2 / B, (H / r) ** 2 / 2, rtol=1e-12)  # eps^4 / 2
    np.testing.assert_allclose(
        knots.loose_knot_force_from_shortening(
            end_to_end_shortening=2 * np.pi * r, bending_stiffness=B
        ),
        f,
        rtol=1e-12,
    )


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"turns": 1.5}, "turns"),
        ({"turns": 0}, "turns"),
        ({"mu": -0.1}, "mu"),
        ({"mu": np.nan}, "mu"),
        ({"rod_radius": -1e-3}, "rod_radius"),
        ({"end_to_end_shortening": 3 * H}, "long-braid limit"),
        ({"end_to_end_shortening": 0.0}, "end_to_end_shortening"),
    ],
)
def test_bad_input_raises(kwargs, match):
    base = {
        "end_to_end_shortening": 0.5,
        "turns": 2,
        "mu": 0.3,
        "rod_radius": H,
        "bending_stiffness": B,
    }
    with pytest.raises(InputError, match=match):
        knots.overhand_pull_force(**{**base, **kwargs})
