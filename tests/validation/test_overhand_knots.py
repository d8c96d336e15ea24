"""Validation case 6 (overhand knots): force curves ordered in mu, mu recovered by fitting.

Default run: the inverse-problem machinery (misfit, parabola fit) on force curves from
the closed form of Jawed, Dieleman, Audoly & Reis, PRL 115, 118302 (2015)
(knotmech.analytic.knots.overhand_pull_force), where F is proportional to mu, so the
misfit is exactly a parabola in mu. Slow: the DER quick case (coated-rod paper, sec. 4,
Fig. 10; recover a known mu within 0.05).
"""

import json
from pathlib import Path

import numpy as np
import pytest

from knotmech.cli.validate import load_case
from knotmech.errors import InputError

case = load_case("overhand_knots")


def _jawed_curve(e, mu):
    knots = pytest.importorskip("knotmech.analytic.knots")
    h = 0.795e-3  # coated-rod paper: d = 1.59 mm, E = 1.83 MPa
    B = 1.83e6 * np.pi * h**4 / 4
    return knots.overhand_pull_force(e, 1, mu, h, B) * h**2 / B


def test_fit_mu_recovers_mu_from_jawed_curves():
    e = np.linspace(0.08, 0.18, 60)
    grid = (0.2, 0.5, 0.9)
    rng = np.random.default_rng(0)
    clean = _jawed_curve(e, 0.65)
    # F is linear in mu in Jawed's law: ratio at mu = 0.65 and 0.2 is 3.25
    np.testing.assert_allclose(clean / _jawed_curve(e, 0.2), 3.25, rtol=1e-9)
    noisy = clean + 0.03 * clean.max() * rng.standard_normal(e.size)
    mis = [case.misfit(e, noisy, e, _jawed_curve(e, m)) for m in grid]
    assert int(np.argmin(mis)) == 1
    assert case.fit_mu(grid, mis) == pytest.approx(0.65, abs=0.02)
    # without noise the misfit is an exact parabola in mu: the vertex is mu itself
    exact = [case.misfit(e, clean, e, _jawed_curve(e, m)) for m in grid]
    assert case.fit_mu(grid, exact) == pytest.approx(0.65, abs=1e-6)


def test_fit_mu_interpolated_on_a_curve_not_linear_in_mu():
    """Curves F = mu^1.5 f(e) (not linear in mu): the parabola through grid misfits is
    biased on the coarse grid (0.2, 0.5, 0.9); interpolating the curves in mu is not."""
    e = np.linspace(0.08, 0.18, 60)
    grid = (0.2, 0.5, 0.9)
    shape = _jawed_curve(e, 1.0)

    def curve(m):
        return m**1.5 * shape

    rng = np.random.default_rng(1)
    noisy = curve(0.65) + 0.03 * curve(0.65).max() * rng.standard_normal(e.size)
    sims = [(e, curve(m)) for m in grid]
    mu, cost = case.fit_mu_interpolated(e, noisy, grid, sims, return_cost=True)
    assert mu == pytest.approx(0.65, abs=0.02)
    assert cost(mu) <= min(cost(m) for m in grid)
    parabola = case.fit_mu(grid, [case.misfit(e, noisy, x, y) for x, y in sims])
    assert abs(parabola - 0.65) > abs(mu - 0.65)
    with pytest.raises(InputError):
        case.fit_mu_interpolated(e, noisy, grid[:2], sims[:2])


def test_fit_mu_edges_and_errors():
    # minimum at the grid's end: clipped to the range
    assert case.fit_mu([0.2, 0.5, 0.9], [1.0, 2.0, 3.0]) == pytest.approx(0.2)
    # three points that do not bracket a minimum fall back to the best grid value
    assert case.fit_mu([0.2, 0.5, 0.9], [1.0, 0.5, 0.6]) == pytest.approx(0.5, abs=0.4)
    with pytest.raises(InputError):
        case.fit_mu([0.2, 0.5], [1.0, 2.0])
    with pytest.raises(InputError):
        case.misfit([5.0, 6.0, 7.0], [1, 1, 1], [0.0, 1.0], [0.0, 1.0])


@pytest.mark.slow
def test_quick_case_der(tmp_path):
    """DER quick case: n = 1, mu in {0.2, 0.5, 0.9}, measurement at mu = 0.65 + noise."""
    r = case.run(quick=True, out_dir=tmp_path)
    assert r["verdict"] == "pass", r["checks"]
    n = r["numbers"]
    assert n["failed_runs"] == []
    assert all(n["knots_preserved"].values())
    f = n["mean_normalized_force_second_half"]["n=1"]
    assert f[0] < f[1] < f[2]
    assert n["force_increases_with_mu"]["n=1"] is True
    # measured: 0.647 (parabola through the three grid misfits alone: 0.595)
    assert abs(n["mu_recovered"] - 0.65) < 0.05
    assert len(r["figures"]) == 2
    png = Path(r["figures"][0])
    assert json.loads((png.parent / "overhand_knots.json").read_text())["numbers"] == n
