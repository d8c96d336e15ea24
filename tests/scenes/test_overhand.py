"""Overhand-knot pulls: parameter sets, a short pull (default run), physics checks (slow).

Slow checks (coated-rod paper, sec. 4; Jawed et al. PRL 115, 118302 (2015)):
higher mu -> higher pull force at the same end-to-end length; the knot type is unchanged
after pulling (no pass-through); the force follows the Jawed braid law in the long-braid
regime within 25 %.
"""

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.scenes.overhand import coated_setup, imc_setup, inversion_points, overhand


def test_imc_setup_is_the_papers():
    """Choi, Tong & Jawed 2021, option file: E, rho, dt, delta, nu, speed, times."""
    s = imc_setup(1)
    assert (s.rod_length, s.n_nodes, s.rod_radius) == (1.0, 301, 1.6e-3)
    assert (s.youngs_modulus, s.density, s.poisson_ratio) == (0.18e6, 1180.0, 0.5)
    assert (s.dt, s.contact_distance, s.slip_speed) == (2.5e-3, 5e-4, 1e-4)
    assert (s.pull_speed, s.wait_time, s.pull_time, s.pull_both_ends) == (6e-3, 2.0, 60.0, True)
    assert s.end_to_end_length == 0.280 and imc_setup(3).end_to_end_length == 0.330
    assert s.bending_stiffness == pytest.approx(0.18e6 * np.pi * 1.6e-3**4 / 4)


def test_coated_setup_is_the_papers():
    """Coated-rod paper: d = 1.59 mm, E = 1.83 MPa, 200 mm/min, table 1 lengths."""
    s1, s3 = coated_setup(1), coated_setup(3)
    assert s1.rod_length == pytest.approx(0.300) and s3.rod_length == pytest.approx(0.600)
    assert s1.rod_radius == pytest.approx(0.795e-3) and s1.youngs_modulus == 1.83e6
    assert s1.pull_speed == pytest.approx(0.2 / 60) and not s1.pull_both_ends
    assert (s1.end_to_end_length, s3.end_to_end_length) == (0.100, 0.250)


def test_short_pull_records_curves():
    """A quick pull: ends move apart exactly, the trefoil survives, curves are recorded."""
    v, wait, pull = 0.03, 0.05, 0.25
    r = overhand(
        1,
        0.3,
        n_nodes=121,
        wait_time=wait,
        pull_time=pull,
        dt=5e-3,
        pull_speed=v,
        n_frames=11,
        n_snapshots=3,
    )
    assert r.status == "success"
    assert r.end_to_end[-1] - r.end_to_end[0] == pytest.approx(2 * v * pull, rel=1e-9)
    assert r.knot_start == r.knot_end == "3_1" and r.knot_preserved
    assert r.snapshots.shape == (3, 121, 3)
    assert np.all(np.isfinite(r.pull_force))
    # the loop is found and shrinks by about the pulled length in its arc
    assert np.all(np.isfinite(r.loop_diameter))
    assert r.loop_diameter[-1] < r.loop_diameter[0]
    d = r.to_dict()
    assert d["knot_preserved"] and len(d["pull_force"]) == 11


def test_inversion_points_synthetic():
    """A 40 % drop is found at its peak; a +-10 % stick-slip ripple is not an inversion."""
    e = np.linspace(0.1, 0.3, 401)
    rising = 0.01 * np.exp(10 * (e - 0.1))
    ripple = rising * (1 + 0.1 * np.sign(np.sin(2 * np.pi * np.arange(e.size) / 4)))
    assert inversion_points(e, ripple).size == 0
    dropped = np.where(e < 0.2, rising, 0.6 * rising)
    found = inversion_points(e, dropped)
    assert found.size == 1 and found[0] == pytest.approx(0.2, abs=0.005)  # within the window
    with pytest.raises(InputError):
        inversion_points(e, rising, window=4)


def test_bad_input():
    with pytest.raises(InputError):
        overhand(5, 0.3)
    with pytest.raises(InputError):
        overhand(1, -0.1)
    with pytest.raises(InputError):
        overhand(1, 0.3, params="nope")
    with pytest.raises(InputError):
        overhand(1, 0.3, pull_speed=0.0)


# ---------------------------------------------------------------------------
# slow physics checks (about 1-2 CPU minutes per run)
# ---------------------------------------------------------------------------

QUICK_IMC = dict(n_nodes=151, pull_speed=0.03, dt=5e-3, wait_time=0.5, pull_time=8.0)


@pytest.fixture(scope="module")
def imc_n2_runs():
    """IMC knot n = 2 pulled 0.48 m at 30 mm/s per end, mu = 0.1 and 0.5 (151 nodes)."""
    return {mu: overhand(2, mu, n_frames=171, **QUICK_IMC) for mu in (0.1, 0.5)}


def _binned(r, edges):
    """Mean pull force in bins of the end-to-end shortening e = L - D."""
    e = r.end_to_end_shortening
    out = []
    for lo, hi in zip(edges[:-1], edges[1:], strict=True):
        sel = (e >= lo) & (e < hi)
        out.append(np.mean(r.pull_force[sel]))
    return np.array(out)


@pytest.mark.slow
def test_no_pass_through_when_pulled(imc_n2_runs):
    for r in imc_n2_runs.values():
        assert r.status == "success"
        assert r.knot_start == r.knot_end == "5_1"


@pytest.mark.slow
def test_higher_mu_higher_force(imc_n2_runs):
    """Coated-rod paper, sec. 4: the pull force grows with mu at every end-to-end length."""
    edges = np.linspace(0.20, 0.50, 7)
    f_low = _binned(imc_n2_runs[0.1], edges)
    f_high = _binned(imc_n2_runs[0.5], edges)
    # Jawed's law is linear in mu (ratio 5); measured 4.8-6.3
    assert np.all(f_high > 3.0 * f_low)


@pytest.mark.slow
@pytest.mark.parametrize("mu", [0.1, 0.5])
def test_force_follows_jawed_law(imc_n2_runs, mu):
    """Long-braid regime: F(e) within 25 % of Jawed et al. 2015 (knotmech.analytic.knots).

    Measured (151 nodes, 30 mm/s): F_sim/F_Jawed = 0.80-0.92 (mu = 0.1), 0.86-1.04 (mu = 0.5)
    for e = L - D in [0.20, 0.50] m.
    """
    knots = pytest.importorskip("knotmech.analytic.knots")
    r = imc_n2_runs[mu]
    edges = np.linspace(0.20, 0.50, 7)
    f_sim = _binned(r, edges)
    e_mid = 0.5 * (edges[1:] + edges[:-1])
    f_th = knots.overhand_pull_force(e_mid, 2, mu, r.setup.rod_radius, r.setup.bending_stiffness)
    assert np.all(np.abs(f_sim / f_th - 1) < 0.25)


QUICK_COATED_N3 = dict(n_nodes=151, pull_speed=0.03, dt=5e-3, wait_time=0.5, pull_time=9.0)


@pytest.mark.slow
def test_inversion_sooner_at_higher_mu():
    """Coated-rod paper, sec. 4 (n = 3): the pull force drops suddenly at the inversion point,
    and "the inversion point occurs sooner as the friction increase". Measured (151 nodes,
    30 mm/s, 5 ms; inversions as 20 % falls within 5 % of the range pulled, as in
    validation/overhand_knots.py): mu = 0.2 at an end-to-end length of 0.457 m, mu = 0.6 at
    0.446 m (mu = 0.9: 0.432 m), knot type 7_1 kept in all three.

    The paper also reports no inversion at mu = 0.6-0.9 for n = 3, 4 (its experiments); the
    DER pulls here invert at every mu (the full validation run too), so that half of the
    claim is not reproduced and not asserted.
    """
    found = {}
    for mu in (0.2, 0.6):
        r = overhand(3, mu, params="coated", n_frames=381, **QUICK_COATED_N3)
        assert r.status == "success", r.message
        assert r.knot_start == r.knot_end == "7_1"
        pulling = r.times > r.setup.wait_time + 0.2
        inv = inversion_points(r.end_to_end[pulling], r.pull_force[pulling], span=0.05)
        assert inv.size == 1
        found[mu] = inv[0]
    assert found[0.2] == pytest.approx(0.457, abs=0.01)
    assert found[0.6] < found[0.2]
