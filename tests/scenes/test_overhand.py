"""Overhand-knot pulls: parameter sets, a short pull (default run), physics checks (slow).

Slow checks (coated-rod paper, sec. 4; Jawed et al. PRL 115, 118302 (2015)):
higher mu -> higher pull force at the same end-to-end length; the knot type is unchanged
after pulling (no pass-through); the force follows the Jawed braid law in the long-braid
regime within 25 %.
"""

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.scenes.overhand import coated_setup, imc_setup, overhand


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


def test_bad_input():
    with pytest.raises(InputError):
        overhand(5, 0.3)
    with pytest.raises(InputError):
        overhand(1, -0.1)
    with pytest.raises(InputError):
        overhand(1, 0.3, params="nope")
    with pytest.raises(InputError):
        overhand(1, 0.3, pull_speed=0.0)
