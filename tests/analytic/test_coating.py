"""Coated rods: mu and coverage vs particle volume fraction (coated-rod paper), and the inverse."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from knotmech.analytic import coating
from knotmech.errors import InputError

phi = st.floats(0.0, 0.13)
mu = st.floats(0.2, 0.9)


def test_reproduces_the_paper_data():
    """Coated-rod paper, sec. 4 and Fig. 12: 0, 1, 4, 7, 13 % -> mu = 0.2, 0.5, 0.6, 0.7, 0.9;
    Fig. 7 / text: coverage 4.61 % at 1 %, 29.02 % at 13 %."""
    np.testing.assert_allclose(
        coating.coated_rod_mu([0.0, 0.01, 0.04, 0.07, 0.13]), [0.2, 0.5, 0.6, 0.7, 0.9], rtol=1e-14
    )
    np.testing.assert_allclose(coating.coated_rod_coverage([0.01, 0.13]), [0.0461, 0.2902])
    np.testing.assert_allclose(
        coating.coated_rod_volume_fraction([0.2, 0.5, 0.6, 0.7, 0.9]),
        [0.0, 0.01, 0.04, 0.07, 0.13],
        atol=1e-12,
    )


@settings(max_examples=60, deadline=None)
@given(phi, phi)
def test_monotone(p1, p2):
    lo, hi = min(p1, p2), max(p1, p2)
    if hi - lo < 1e-9:
        return
    assert coating.coated_rod_mu(lo) < coating.coated_rod_mu(hi)
    assert coating.coated_rod_coverage(lo) < coating.coated_rod_coverage(hi)


def test_monotone_on_a_dense_grid_and_bounded_by_the_data():
    grid = np.linspace(0.0, 0.13, 5001)
    m = coating.coated_rod_mu(grid)
    assert np.all(np.diff(m) > 0)
    assert m.min() == pytest.approx(0.2) and m.max() == pytest.approx(0.9)
    # PCHIP does not overshoot between data points
    for lo, hi, mlo, mhi in zip(
        coating.COATING_VOLUME_FRACTION[:-1],
        coating.COATING_VOLUME_FRACTION[1:],
        coating.COATING_MU[:-1],
        coating.COATING_MU[1:],
        strict=True,
    ):
        inside = m[(grid >= lo) & (grid <= hi)]
        assert inside.min() >= mlo - 1e-12 and inside.max() <= mhi + 1e-12


@settings(max_examples=60, deadline=None)
@given(phi, mu)
def test_round_trips(p, m):
    assert coating.coated_rod_volume_fraction(coating.coated_rod_mu(p)) == pytest.approx(
        p, abs=1e-12
    )
    assert coating.coated_rod_mu(coating.coated_rod_volume_fraction(m)) == pytest.approx(
        m, abs=1e-12
    )


def test_arrays_keep_their_shape():
    assert coating.coated_rod_mu(np.full((2, 3), 0.05)).shape == (2, 3)
    assert coating.coated_rod_volume_fraction(np.full((4,), 0.65)).shape == (4,)


@pytest.mark.parametrize("bad", [-0.01, 0.14, np.nan, 1.0])
def test_refuses_to_extrapolate_volume_fraction(bad):
    with pytest.raises(InputError, match="volume_fraction"):
        coating.coated_rod_mu(bad)
    with pytest.raises(InputError, match="volume_fraction"):
        coating.coated_rod_coverage(bad)


@pytest.mark.parametrize("bad", [0.19, 0.91, np.nan, -1.0])
def test_refuses_to_extrapolate_mu(bad):
    with pytest.raises(InputError, match="mu"):
        coating.coated_rod_volume_fraction(bad)
